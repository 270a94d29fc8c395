//! After the first frame, drawing allocates nothing: no heap allocation per
//! triangle, row or pixel. A counting allocator watches a second frame of every
//! figure, with both rasterizers, on the box and on a finer mesh. It counts on the
//! drawing thread only, so the suite's other tests, running beside it, are not
//! counted. On two threads every thread is counted, in a process of its own.

use rasterlab::app::figure::Inputs;
use rasterlab::app::figure::Raster;
use rasterlab::app::parallel::Parallel;
use rasterlab::app::Settings;
use rasterlab::scene::{cornell_box, subdivide};
use rasterlab::{Figure, Frame};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

struct Counting;

thread_local! {
    // Const-initialised: reading them never allocates, which the allocator relies on.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Every thread's allocations, for a process that runs one test alone.
static COUNTING_ALL: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS_ALL: AtomicUsize = AtomicUsize::new(0);

fn count() {
    if COUNTING.get() {
        ALLOCATIONS.set(ALLOCATIONS.get() + 1);
    }
    // The harness's main thread only waits for the test, but may set up its
    // channel's wait the first time it does, at any moment: not ours.
    // SAFETY: both calls only read the calling thread's and process's ids.
    let harness = unsafe { libc::gettid() == libc::getpid() };
    if COUNTING_ALL.load(Ordering::Relaxed) && !harness {
        ALLOCATIONS_ALL.fetch_add(1, Ordering::Relaxed);
    }
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: the caller's contract is passed on unchanged.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Every figure with both rasterizers, on the box and on a finer mesh.
fn cases() -> Vec<(rasterlab::Mesh, Figure)> {
    let mut cases = Vec::new();
    for mesh in [cornell_box(), subdivide(&cornell_box(), 8)] {
        for figure in Figure::FIGURES {
            for raster in [Raster::Rows, Raster::Edge] {
                cases.push((mesh.clone(), figure.with_raster(raster)));
            }
        }
    }
    cases
}

#[test]
fn a_frame_after_the_first_allocates_nothing() {
    let s = Settings::default();
    let (camera, uniforms) = (s.camera, Inputs::lit(s.light));
    for (mesh, figure) in cases() {
        let mut pipeline = figure.pipeline_for(&mesh);
        let mut frame = Frame::default();
        // The first frame allocates its buffers: the counter sees them.
        ALLOCATIONS.set(0);
        COUNTING.set(true);
        pipeline.render(&uniforms, &mesh, &camera, &mut frame);
        COUNTING.set(false);
        assert!(ALLOCATIONS.get() > 0);
        ALLOCATIONS.set(0);
        COUNTING.set(true);
        pipeline.render(&uniforms, &mesh, &camera, &mut frame);
        COUNTING.set(false);
        let n = ALLOCATIONS.get();
        assert_eq!(n, 0, "{} on {} triangles", figure.label(), mesh.faces.len());
    }
}

/// The same on two threads, the second band drawn by a helper thread, over 200 frames:
/// every thread's allocations are counted, so the test runs in a process of its
/// own (this test binary again, with only this test), where no other test
/// allocates beside it.
#[test]
fn a_frame_on_two_threads_after_the_first_allocates_nothing() {
    const ALONE: &str = "RASTERLAB_ALLOCATIONS_ALONE";
    let name = "allocations::a_frame_on_two_threads_after_the_first_allocates_nothing";
    if std::env::var_os(ALONE).is_none() {
        let out = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--exact", name, "--test-threads", "1"])
            .env(ALONE, "1")
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&out.stdout) + String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{said}");
        assert!(
            said.contains("1 passed"),
            "the test did not run alone: {said}"
        );
        return;
    }
    let s = Settings::default();
    let uniforms = Inputs::lit(s.light);
    // The first frame sees the box from afar, small; the later ones near, and
    // moving up and down the image, while the split follows the bands' last
    // times: each band draws larger triangles, and other rows, than at first.
    let far = rasterlab::Camera {
        position: glam::Vec3::new(0.0, 0.0, -8.0),
        ..s.camera
    };
    let (near, up) = (
        s.camera,
        rasterlab::Camera {
            position: s.camera.position + glam::Vec3::new(0.0, 0.25, 0.0),
            ..s.camera
        },
    );
    for (mesh, figure) in cases() {
        let mut parallel = Parallel::new(figure, &mesh, 2).unwrap();
        let mut frame = Frame::default();
        parallel.render(&uniforms, &mesh, &far, &mut frame);
        ALLOCATIONS_ALL.store(0, Ordering::Relaxed);
        COUNTING_ALL.store(true, Ordering::Relaxed);
        for k in 0..FRAMES {
            let camera = if k % 2 == 0 { &up } else { &near };
            parallel.render(&uniforms, &mesh, camera, &mut frame);
        }
        COUNTING_ALL.store(false, Ordering::Relaxed);
        let n = ALLOCATIONS_ALL.load(Ordering::Relaxed);
        assert_eq!(
            n,
            0,
            "{} on {} triangles: {n} allocations in {FRAMES} frames",
            figure.label(),
            mesh.faces.len()
        );
    }
}

const FRAMES: usize = 200;
