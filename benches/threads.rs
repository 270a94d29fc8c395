//! `cargo bench --features bench --bench threads`: the same frame drawn by one
//! thread and by two, in bands (`--threads`), as issue #20 measures it: every stage
//! of the box at 2000x2000, pixel-light at 500x500, and a million triangles with
//! the exact rasterizer; and a 2000x2000 frame with no faces, the clear alone,
//! which bounds what two threads can gain on the stages whose frame is mostly
//! the clear. Run it with two cores free (benches/sitting.sh pins it to
//! cores 0 and 1). `RASTERLAB_RECORD=1` writes the medians to docs/bench/.
//!
//! Criterion measures one thread, then two, seconds apart; on a shared machine
//! the host can slow one of them and not the other. So every case is also drawn
//! in turns ([`alternating`]): one thread, two, two frames at once on a
//! thread each, which is as much as two cores here give, and the two threads'
//! bands one after the other on one thread, which is what the split itself
//! costs.

mod common;
#[path = "common/criterion.rs"]
mod medians;

use criterion::Criterion;
use rasterlab::app::figure::{Inputs, Raster};
use rasterlab::app::parallel::Parallel;
use rasterlab::scene::{cornell_box, subdivide};
use rasterlab::{Camera, Figure, Frame, Mesh, StageName};
use std::time::Instant;

/// The meshes the cases draw.
struct Meshes {
    box_: Mesh,
    million: Mesh,
    nothing: Mesh,
}

/// One case: its name, mesh, image size and figure.
type Case<'m> = (String, &'m Mesh, (u32, u32), Figure);

impl Meshes {
    fn new() -> Meshes {
        let box_ = cornell_box();
        let million = subdivide(&box_, 183);
        Meshes {
            box_,
            million,
            nothing: Mesh::default(),
        }
    }

    /// Every stage of the box at 2000x2000, pixel-light at 500x500, a million
    /// triangles (depth and pixel-light, exact rasterizer), and the clear alone.
    fn cases(&self) -> Vec<Case<'_>> {
        let mut cases: Vec<Case> = Figure::FIGURES
            .iter()
            .map(|&f| {
                let name = format!("box 2000x2000, {}", f.label());
                (name, &self.box_, (2000, 2000), f)
            })
            .collect();
        let lit = Figure::of(StageName::PixelLight);
        let name = format!("box 500x500, {}", lit.label());
        cases.push((name, &self.box_, (500, 500), lit));
        for stage in [StageName::Depth, StageName::PixelLight] {
            let figure = Figure::of(stage).with_raster(Raster::Edge);
            let name = format!("cornell:183 1920x1080, {}", figure.label());
            cases.push((name, &self.million, (1920, 1080), figure));
        }
        let nothing = Figure::of(StageName::Points);
        let name = "2000x2000, the clear alone".to_string();
        cases.push((name, &self.nothing, (2000, 2000), nothing));
        cases
    }
}

/// Each case drawn by one thread and by two, in bands (`--threads`).
fn threads(c: &mut Criterion, ids: &mut Vec<String>, meshes: &Meshes) {
    let mut g = c.benchmark_group("threads");
    medians::short(&mut g, 20);
    for (name, mesh, size, figure) in meshes.cases() {
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

/// Rounds of frames each way.
const ROUNDS: usize = 16;
const FRAMES: usize = 8;

/// Each case four ways in turns: drawn by one thread, by two (in bands), as
/// two frames at once, each by one thread of its own (what the host lets two
/// cores do side by side: the ceiling for two threads), and as two threads'
/// bands drawn one after the other on one thread (the work of the split,
/// apart from the second core: [`Parallel::render_in_turn`]). [`ROUNDS`]
/// rounds of [`FRAMES`] frames each way, the ways' order turning each round,
/// after a round to warm up; each frame timed alone, and the median frame of
/// each way.
fn alternating(meshes: &Meshes) -> Vec<(String, Vec<f64>)> {
    let mut rows = Vec::new();
    for (name, mesh, size, figure) in meshes.cases() {
        let settings = common::settings(size);
        let (inputs, camera) = (&Inputs::lit(settings.light), &settings.camera);
        let new = |threads| Parallel::new(figure, mesh, threads).expect("threads");
        let mut one = (new(1), Frame::default());
        let mut two = (new(2), Frame::default());
        let mut side = [(new(1), Frame::default()), (new(1), Frame::default())];
        let mut in_turn = (new(2), Frame::default());
        let mut times = [(); 4].map(|_| Vec::with_capacity(2 * ROUNDS * FRAMES));
        // FRAMES frames, each timed, drawn by `render`.
        let draw =
            |(parallel, frame): &mut (Parallel, Frame),
             times: &mut Vec<f64>,
             render: fn(&mut Parallel, &Inputs, &Mesh, &Camera, &mut Frame)| {
                for _ in 0..FRAMES {
                    let start = Instant::now();
                    render(parallel, inputs, mesh, camera, frame);
                    times.push(start.elapsed().as_secs_f64() * 1e3);
                }
            };
        let render = Parallel::render;
        for round in 0..=ROUNDS {
            for way in (0..4).map(|k| (k + round) % 4) {
                let [t1, t2, t3, t4] = &mut times;
                match way {
                    0 => draw(&mut one, t1, render),
                    1 => draw(&mut two, t2, render),
                    3 => draw(&mut in_turn, t4, Parallel::render_in_turn),
                    _ => {
                        let [a, b] = &mut side;
                        let mut other = Vec::with_capacity(FRAMES);
                        std::thread::scope(|s| {
                            s.spawn(|| draw(b, &mut other, render));
                            draw(a, t3, render);
                        });
                        t3.extend(other);
                    }
                }
            }
            if round == 0 {
                times.iter_mut().for_each(Vec::clear); // warming up
            }
        }
        let [one, two, side, in_turn] = times.map(|mut t| {
            t.sort_by(f64::total_cmp);
            t[t.len() / 2]
        });
        eprintln!(
            "threads, in turns: {name}: 1 thread {one:.3} ms, 2 threads {two:.3} ms ({:.2} times), \
             two frames at once {side:.3} ms each (the host allows {:.2} times), \
             two bands in turn {in_turn:.3} ms ({:.2} times one thread's work)",
            one / two,
            2.0 * one / side,
            in_turn / one
        );
        rows.push((name, vec![one, two, side, in_turn]));
    }
    rows
}

fn main() {
    let meshes = Meshes::new();
    medians::run_and_record("threads", |c, ids| threads(c, ids, &meshes));
    // Only a whole run of the bench: not `cargo test`'s pass, nor a filter.
    let whole = std::env::args().skip(1).all(|a| a.starts_with('-'));
    if std::env::args().any(|a| a == "--bench") && whole {
        let rows = alternating(&meshes);
        if common::recording() {
            let columns = [
                "one_thread_ms",
                "two_threads_ms",
                "two_frames_at_once_ms",
                "two_bands_in_turn_ms",
            ];
            common::record("threads_alternating", &columns, &rows);
        }
    }
}
