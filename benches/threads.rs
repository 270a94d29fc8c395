//! `cargo bench --features bench --bench threads`: the same frame drawn by one
//! thread and by two, in bands (`--threads`), as issue #20 measures it: every stage
//! of the box at 2000x2000, pixel-light at 500x500, and a million triangles with
//! the exact rasterizer; and a 2000x2000 frame with no faces, the clear alone,
//! which bounds what two threads can gain on the stages whose frame is mostly
//! the clear. Run it with two cores free (benches/sitting.sh pins it to
//! cores 0 and 1). `RASTERLAB_RECORD=1` writes the medians to docs/bench/.

mod common;
#[path = "common/criterion.rs"]
mod medians;

use criterion::Criterion;
use rasterlab::app::figure::{Inputs, Raster};
use rasterlab::app::parallel::Parallel;
use rasterlab::scene::{cornell_box, subdivide};
use rasterlab::{Figure, Frame, Mesh, StageName};

/// The same frame drawn by one thread and by two, in bands (`--threads`): every
/// stage of the box at 2000x2000, pixel-light at 500x500, and a million
/// triangles with the exact rasterizer.
fn threads(c: &mut Criterion, ids: &mut Vec<String>) {
    let box_ = cornell_box();
    let million = subdivide(&box_, 183);
    let nothing = Mesh::default();
    let mut cases: Vec<(String, &Mesh, (u32, u32), Figure)> = Figure::FIGURES
        .iter()
        .map(|&f| {
            (
                format!("box 2000x2000, {}", f.label()),
                &box_,
                (2000, 2000),
                f,
            )
        })
        .collect();
    let lit = Figure::of(StageName::PixelLight);
    cases.push((
        format!("box 500x500, {}", lit.label()),
        &box_,
        (500, 500),
        lit,
    ));
    for stage in [StageName::Depth, StageName::PixelLight] {
        let figure = Figure::of(stage).with_raster(Raster::Edge);
        let name = format!("cornell:183 1920x1080, {}", figure.label());
        cases.push((name, &million, (1920, 1080), figure));
    }
    cases.push((
        "2000x2000, the clear alone".into(),
        &nothing,
        (2000, 2000),
        Figure::of(StageName::Points),
    ));
    let mut g = c.benchmark_group("threads");
    medians::short(&mut g, 20);
    for (name, mesh, size, figure) in cases {
        let settings = common::settings(size);
        let inputs = Inputs::lit(settings.light);
        for threads in [1, 2] {
            let mut parallel = Parallel::new(figure, mesh, threads).expect("threads");
            let mut frame = Frame::default();
            let name = format!(
                "{name}, {threads} thread{}",
                if threads > 1 { "s" } else { "" }
            );
            ids.push(format!("threads/{name}"));
            g.bench_function(name, |b| {
                b.iter(|| parallel.render(&inputs, mesh, &settings.camera, &mut frame))
            });
        }
    }
    g.finish();
}

fn main() {
    medians::run_and_record("threads", threads);
}
