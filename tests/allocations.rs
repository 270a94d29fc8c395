//! After the first frame, drawing allocates nothing: no heap allocation per
//! triangle, row or pixel. A counting allocator watches a second frame of every
//! figure, with both rasterizers, on the box and on a finer mesh.

use rasterlab::app::figure::Inputs;
use rasterlab::app::figure::Raster;
use rasterlab::app::Settings;
use rasterlab::scene::{cornell_box, subdivide};
use rasterlab::{Figure, Frame};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: the caller's contract is passed on unchanged.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_frame_after_the_first_allocates_nothing() {
    let s = Settings::default();
    let (camera, uniforms) = (s.camera, Inputs::lit(s.light));
    for mesh in [cornell_box(), subdivide(&cornell_box(), 8)] {
        for figure in Figure::FIGURES {
            for raster in [Raster::Rows, Raster::Edge] {
                let figure = figure.with_raster(raster);
                let mut pipeline = figure.pipeline_for(&mesh);
                let mut frame = Frame::default();
                // The first frame allocates its buffers: the counter sees them.
                ALLOCATIONS.store(0, Ordering::Relaxed);
                COUNTING.store(true, Ordering::Relaxed);
                pipeline.render(&uniforms, &mesh, &camera, &mut frame);
                COUNTING.store(false, Ordering::Relaxed);
                assert!(ALLOCATIONS.load(Ordering::Relaxed) > 0);
                ALLOCATIONS.store(0, Ordering::Relaxed);
                COUNTING.store(true, Ordering::Relaxed);
                pipeline.render(&uniforms, &mesh, &camera, &mut frame);
                COUNTING.store(false, Ordering::Relaxed);
                let n = ALLOCATIONS.load(Ordering::Relaxed);
                assert_eq!(n, 0, "{} on {} triangles", figure.label(), mesh.faces.len());
            }
        }
    }
}
