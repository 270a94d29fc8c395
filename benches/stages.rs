//! `cargo bench --features bench`: median frame times of every stage, on one thread, as #13 asks to
//! measure before optimising: the box at 500x500 and 2000x2000, and the box split
//! 16 x 16 and 183 x 183 (a million triangles) at 1920x1080, depth-only and lit,
//! with each rasterizer. Criterion reports medians; Mpixel/s and Mtriangles/s
//! follow from the throughput it is given (benches/threads.rs draws with two
//! threads). `RASTERLAB_RECORD=1` writes the medians to docs/bench/.

mod common;
#[path = "common/criterion.rs"]
mod medians;

use criterion::{Criterion, Throughput};
use medians::short;
use rasterlab::app::figure::Inputs;
use rasterlab::app::figure::Raster;
use rasterlab::app::Settings;
use rasterlab::pipeline::raster::rows::walk_line;
use rasterlab::pipeline::raster::Lines;
use rasterlab::scene::{cornell_box, subdivide};
use rasterlab::Pixel;
use rasterlab::{Figure, Frame, Mesh, StageName};
use std::hint::black_box;

fn bench(
    c: &mut Criterion,
    ids: &mut Vec<String>,
    group: &str,
    mesh: &Mesh,
    size: (u32, u32),
    figures: &[Figure],
) {
    let settings = common::settings(size);
    let (camera, uniforms) = (settings.camera, Inputs::lit(settings.light));
    let mut g = c.benchmark_group(group);
    short(&mut g, 20);
    g.throughput(Throughput::Elements((size.0 * size.1) as u64));
    for &figure in figures {
        for raster in [Raster::Rows, Raster::Edge] {
            let figure = figure.with_raster(raster);
            let mut pipeline = figure.pipeline_for(mesh);
            let mut frame = Frame::default();
            ids.push(format!("{group}/{}", figure.label()));
            g.bench_function(figure.label(), |b| {
                b.iter(|| pipeline.render(&uniforms, mesh, &camera, &mut frame))
            });
        }
    }
    g.finish();
}

fn stages(c: &mut Criterion, ids: &mut Vec<String>) {
    let box_ = cornell_box();
    bench(c, ids, "box 500x500", &box_, (500, 500), &Figure::FIGURES);
    bench(
        c,
        ids,
        "box 2000x2000",
        &box_,
        (2000, 2000),
        &Figure::FIGURES,
    );
    let lit_and_depth = [
        Figure::of(StageName::Depth),
        Figure::of(StageName::PixelLight),
    ];
    bench(
        c,
        ids,
        "cornell:16 1920x1080",
        &subdivide(&box_, 16),
        (1920, 1080),
        &lit_and_depth,
    );
    bench(
        c,
        ids,
        "cornell:183 1920x1080",
        &subdivide(&box_, 183),
        (1920, 1080),
        &lit_and_depth,
    );
}

/// `--lines bresenham` against the handout's `Interpolate`: walking every line
/// from (0, 0) to |dx|, |dy| <= 64 (Mpixel/s of line), and the wireframe and
/// filled box at 500x500 drawn each way (rows rasterizer).
fn lines(c: &mut Criterion, ids: &mut Vec<String>) {
    let mut g = c.benchmark_group("lines");
    short(&mut g, 20);
    let ends: Vec<(i32, i32)> = (-64..=64)
        .flat_map(|x| (-64..=64).map(move |y| (x, y)))
        .collect();
    let pixels: u64 = ends
        .iter()
        .map(|&(x, y)| x.abs().max(y.abs()) as u64 + 1)
        .sum();
    g.throughput(Throughput::Elements(pixels));
    for lines in [Lines::Interpolate, Lines::Bresenham] {
        let name = format!("walk every line, {lines:?}");
        ids.push(format!("lines/{name}"));
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut sum = 0i64;
                for &(x, y) in &ends {
                    walk_line(lines, Pixel::at(0, 0), Pixel::at(x, y), |p| {
                        sum += (p.x ^ p.y) as i64
                    });
                }
                black_box(sum)
            })
        });
    }
    let mesh = cornell_box();
    let settings = Settings::default();
    let (camera, uniforms) = (settings.camera, Inputs::lit(settings.light));
    g.throughput(Throughput::Elements(500 * 500));
    for stage in [StageName::Wireframe, StageName::Filled] {
        for lines in [Lines::Interpolate, Lines::Bresenham] {
            let figure = Figure::of(stage).with_lines(lines);
            let mut pipeline = figure.pipeline_for(&mesh);
            let mut frame = Frame::default();
            let name = format!("box 500x500, {}", figure.label());
            ids.push(format!("lines/{name}"));
            g.bench_function(name, |b| {
                b.iter(|| pipeline.render(&uniforms, &mesh, &camera, &mut frame))
            });
        }
    }
    g.finish();
}

fn main() {
    medians::run_and_record("stages", |c, ids| {
        stages(c, ids);
        lines(c, ids);
    });
}
