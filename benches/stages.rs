//! `cargo bench`: median frame times of every stage, on one thread, as #13 asks to
//! measure before optimising: the box at 500x500 and 2000x2000, and the box split
//! 16 x 16 and 183 x 183 (a million triangles) at 1920x1080, depth-only and lit,
//! with each rasterizer. Criterion reports medians; Mpixel/s and Mtriangles/s
//! follow from the throughput it is given.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use rasterlab::app::Settings;
use rasterlab::measure::figure::Raster;
use rasterlab::scene::{cornell_box, subdivide};
use rasterlab::{Figure, Frame, Mesh, StageName};

fn bench(c: &mut Criterion, group: &str, mesh: &Mesh, size: (u32, u32), figures: &[Figure]) {
    let settings = Settings {
        width: size.0,
        height: size.1,
        focal: size.1 as f32,
        ..Settings::default()
    };
    let (camera, uniforms) = (settings.camera(), settings.uniforms());
    let mut g = c.benchmark_group(group);
    g.sample_size(20);
    g.throughput(Throughput::Elements((size.0 * size.1) as u64));
    for &figure in figures {
        for raster in [Raster::Rows, Raster::Edge] {
            let figure = figure.with_raster(raster);
            let mut pipeline = figure.pipeline_for(mesh);
            let mut frame = Frame::default();
            g.bench_function(figure.label(), |b| {
                b.iter(|| pipeline.render(mesh, &camera, &uniforms, &mut frame))
            });
        }
    }
    g.finish();
}

fn stages(c: &mut Criterion) {
    let box_ = cornell_box();
    bench(c, "box 500x500", &box_, (500, 500), &Figure::FIGURES);
    bench(c, "box 2000x2000", &box_, (2000, 2000), &Figure::FIGURES);
    let lit_and_depth = [
        Figure::of(StageName::Depth),
        Figure::of(StageName::PixelLight),
    ];
    bench(
        c,
        "cornell:16 1920x1080",
        &subdivide(&box_, 16),
        (1920, 1080),
        &lit_and_depth,
    );
    bench(
        c,
        "cornell:183 1920x1080",
        &subdivide(&box_, 183),
        (1920, 1080),
        &lit_and_depth,
    );
}

criterion_group!(benches, stages);
criterion_main!(benches);
