//! After the first frame, drawing allocates nothing: no heap allocation per
//! triangle, row or pixel. A counting allocator watches a second frame of every
//! figure, with both rasterizers, on the box and on a finer mesh. It counts on the
//! drawing thread only, so the suite's other tests, running beside it, are not
//! counted.

use rasterlab::app::figure::Inputs;
use rasterlab::app::figure::Raster;
use rasterlab::app::Settings;
use rasterlab::scene::{cornell_box, subdivide};
use rasterlab::{Figure, Frame};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    // Const-initialised: reading them never allocates, which the allocator relies on.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    if COUNTING.get() {
        ALLOCATIONS.set(ALLOCATIONS.get() + 1);
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
    }
}
