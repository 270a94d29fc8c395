//! Drawing on several cores: the image split into bands of rows, one pipeline
//! per band, each thread owning its pixels (no locks, no atomics per pixel). A
//! band draws exactly its part of the whole image, so the result is the same, byte
//! for byte, for any number of threads.

use crate::app::figure::{Figure, Inputs, Render};
use crate::extensions::normal_map::TangentFrame;
use crate::extensions::texture::Model;
use crate::pipeline::bands::CHUNK;
use crate::pipeline::clip::ScreenVertex;
use crate::pipeline::draw::{InTurn, Join, Stats, Vertices};
use crate::pipeline::{Camera, Frame, Mesh, Target};
use std::ops::Range;
use std::time::Instant;

/// A figure drawn in `threads` bands.
pub struct Parallel {
    pipelines: Vec<Box<dyn Render>>,
    pool: Option<rayon::ThreadPool>,
    stats: Stats,
    /// The faces' tangent frames, for a figure with a normal map.
    frames: Vec<TangentFrame>,
    /// The mesh's vertices in camera space, prepared once per frame for every band.
    vertices: Vertices,
    /// Each row's work this frame, and where the bands end (kept between frames).
    work: Vec<f64>,
    ends: Vec<u32>,
    /// How much each row's work costs compared with the others, as the bands'
    /// drawing times have shown, and each band's time in the last frame.
    weight: Vec<f64>,
    times: Vec<f64>,
}

/// What every band of a frame reads.
#[derive(Clone, Copy)]
struct Shared<'a> {
    inputs: &'a Inputs<'a>,
    mesh: &'a Mesh,
    camera: &'a Camera,
    vertices: &'a Vertices,
}

/// Draws `target` with `pipelines`, the band of pipeline `i` ending before row
/// `ends[i]` (the last at the target's bottom): the two halves of the pipelines on
/// the two sides of a `rayon::join`, whose jobs live on the stack, so a frame
/// allocates nothing for its threads. Every pipeline draws, an empty band too,
/// so that each one's counts are this frame's.
fn draw_bands(
    pipelines: &mut [Box<dyn Render>],
    (ends, times): (&[u32], &mut [f64]),
    target: Target,
    shared: Shared,
    join: &impl Join,
) {
    let Shared {
        inputs,
        mesh,
        camera,
        vertices,
    } = shared;
    match pipelines {
        [] => {}
        [only] => {
            let (mut target, start) = (target, Instant::now());
            only.draw_prepared(inputs, mesh, camera, vertices, &mut target);
            times[0] = start.elapsed().as_secs_f64();
        }
        _ => {
            let half = pipelines.len() / 2;
            let (top, bottom) = target.split_at_row(ends[half - 1]);
            let (first, second) = pipelines.split_at_mut(half);
            let (ends, later) = ends.split_at(half);
            let (times, later_times) = times.split_at_mut(half);
            join.join(
                || draw_bands(first, (ends, times), top, shared, join),
                || draw_bands(second, (later, later_times), bottom, shared, join),
            );
        }
    }
}

/// Work split between the pool's threads.
struct Rayon;

impl Join for Rayon {
    fn join<A: FnOnce() + Send, B: FnOnce() + Send>(&self, a: A, b: B) {
        rayon::join(a, b);
    }
}

/// What setting up the triangles around one vertex costs, in pixels filled:
/// a mesh of small triangles is split into bands by its vertices, a few large
/// ones by their pixels.
const VERTEX_COST: usize = 64;

/// About how many vertices [`Parallel::balance`] looks at.
const VERTEX_SAMPLE: usize = 1 << 16;

/// The number of cores, the default `--threads`.
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

impl Parallel {
    /// `figure` of `mesh` on `threads` threads (1 draws on the calling thread).
    pub fn new<'a>(
        figure: Figure,
        model: impl Into<Model<'a>>,
        threads: usize,
    ) -> Result<Parallel, String> {
        let model = model.into();
        let threads = threads.max(1);
        let pool = if threads > 1 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
            Some(pool)
        } else {
            None
        };
        let mut vertices = Vertices::default();
        if threads > 1 {
            vertices.group_faces(model.mesh);
        }
        Ok(Parallel {
            pipelines: (0..threads).map(|_| figure.pipeline_for(model)).collect(),
            pool,
            stats: Stats::default(),
            frames: figure.tangent_frames(model),
            vertices,
            work: Vec::new(),
            ends: Vec::new(),
            weight: Vec::new(),
            times: vec![0.0; threads],
        })
    }

    /// Sizes `frame` to the camera's image and draws `mesh` into it, a band per
    /// thread, each with the stage made from `inputs` (and the faces' tangent
    /// frames, which this keeps). `mesh` is the model's, or one with its
    /// vertices and its first faces: the tangent frames and the groups of faces
    /// the bands pass over ([`Vertices::group_faces`]) were made from it.
    pub fn render(&mut self, inputs: &Inputs, mesh: &Mesh, camera: &Camera, frame: &mut Frame) {
        // The frame enters the pool once: each entry wakes its threads and
        // puts the caller to sleep, which costs more than a small frame draws.
        match self.pool.take() {
            None => self.prepare_and_draw(inputs, mesh, camera, frame, &InTurn),
            Some(pool) => {
                pool.install(|| self.prepare_and_draw(inputs, mesh, camera, frame, &Rayon));
                self.pool = Some(pool);
            }
        }
        // Each band decides about every triangle alike; pixels are its own.
        let mut stats = self.pipelines[0].stats();
        for p in &self.pipelines[1..] {
            let s = p.stats();
            stats.pixels_written += s.pixels_written;
            stats.depth_rejected += s.depth_rejected;
        }
        self.stats = stats;
    }

    /// The frame's vertices prepared, the bands balanced, and each band drawn,
    /// the bands side by side as `join` runs them.
    fn prepare_and_draw(
        &mut self,
        inputs: &Inputs,
        mesh: &Mesh,
        camera: &Camera,
        frame: &mut Frame,
        join: &impl Join,
    ) {
        self.vertices.prepare_split(mesh, camera, join);
        self.balance(camera);
        let inputs = &Inputs {
            frames: &self.frames,
            ..*inputs
        };
        let depth = self.pipelines[0].depth_test();
        frame.resize(camera.width, camera.height, depth);
        let shared = Shared {
            inputs,
            mesh,
            camera,
            vertices: &self.vertices,
        };
        let bands = (&self.ends[..], &mut self.times[..]);
        draw_bands(&mut self.pipelines, bands, frame.target(), shared, join);
    }

    /// Ends the bands where each holds about the same work: a row's pixels, and
    /// for a mesh in view its vertices, each worth [`VERTEX_COST`] pixels, each
    /// row's work weighed by what the bands' times have shown it costs. Any
    /// split draws the same bytes; this one keeps both threads busy when the
    /// triangles crowd one part of the image, or one part's pixels cost more.
    fn balance(&mut self, camera: &Camera) {
        let (n, height) = (self.pipelines.len(), camera.height as usize);
        if n == 1 {
            self.ends.clear();
            self.ends.push(camera.height);
            return;
        }
        self.work.clear();
        self.work.resize(height, camera.width as f64);
        let centre = camera.height as f32 / 2.0;
        let row = |y: f32| ((y + centre).max(0.0) as usize).min(height.saturating_sub(1));
        let chunks = self.vertices.chunk_rows();
        if chunks.is_empty() {
            // A sample of the vertices is enough to see where they crowd.
            let screen = self.vertices.screen();
            let every = (screen.len() / VERTEX_SAMPLE).max(1);
            let cost = (VERTEX_COST * every) as f64;
            for &ScreenVertex { y, .. } in screen.iter().step_by(every) {
                self.work[row(y)] += cost;
            }
        } else {
            // The rows of each chunk of vertices, found as they were projected.
            let cost = (VERTEX_COST * CHUNK) as f64;
            for &(low, high) in chunks {
                self.work[row((low + high) / 2.0)] += cost;
            }
        }
        self.learn_weights(height);
        for (w, k) in self.work.iter_mut().zip(&self.weight) {
            *w *= k;
        }
        let total: f64 = self.work.iter().sum();
        let (mut done, mut row) = (0.0, 0usize);
        self.ends.clear();
        for band in 1..n {
            let share = total * band as f64 / n as f64;
            while row < height && done + self.work[row] / 2.0 < share {
                done += self.work[row];
                row += 1;
            }
            self.ends.push(row as u32);
        }
        self.ends.push(camera.height);
    }

    /// Weighs the rows of each band of the last frame by how long the band took
    /// against how long its work, as weighed, foretold: a band slower than its
    /// share makes its rows dearer. Halfway (a square root) each frame, so that
    /// one frame's noise moves the bands little.
    fn learn_weights(&mut self, height: usize) {
        if self.weight.len() != height || self.ends.last() != Some(&(height as u32)) {
            // A new size: nothing learnt yet.
            self.weight.clear();
            self.weight.resize(height, 1.0);
            return;
        }
        // Each band's rows, its work as weighed so far, and its time.
        let (work, weight) = (&self.work, &mut self.weight);
        let starts = std::iter::once(0).chain(self.ends.iter().map(|&e| e as usize));
        let bands = starts
            .zip(&self.ends)
            .map(|(start, &end)| start..end as usize);
        let weighed =
            |weight: &[f64], rows: Range<usize>| -> f64 { rows.map(|r| work[r] * weight[r]).sum() };
        let all_work: f64 = weighed(weight, 0..height);
        let all_time: f64 = self.times.iter().sum();
        if all_time <= 0.0 || all_work <= 0.0 {
            return;
        }
        for (rows, &time) in bands.zip(&self.times) {
            let band = weighed(weight, rows.clone());
            if band <= 0.0 || time <= 0.0 {
                continue;
            }
            let dearer = ((time / all_time) / (band / all_work))
                .sqrt()
                .clamp(0.5, 2.0);
            for w in &mut weight[rows] {
                *w = (*w * dearer).clamp(1.0 / 64.0, 64.0);
            }
        }
    }

    /// Whether the figure tests depth, so its frames need a depth buffer.
    pub fn depth_test(&self) -> bool {
        self.pipelines[0].depth_test()
    }

    /// What the last frame did, summed over the bands.
    pub fn stats(&self) -> Stats {
        self.stats
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::figure::Inputs;
    use crate::pipeline::{Light, StageName};
    use crate::scene::cornell_box;

    #[test]
    fn a_band_slower_than_its_share_is_given_fewer_rows() {
        let mesh = cornell_box();
        let camera = Camera::handout(200, 300);
        let mut parallel = Parallel::new(Figure::of(StageName::Filled), &mesh, 2).unwrap();
        let mut frame = Frame::default();
        parallel.render(&Inputs::lit(Light::handout()), &mesh, &camera, &mut frame);
        // Equal times: the split stays where the pixels split.
        parallel.times = vec![1.0, 1.0];
        parallel.balance(&camera);
        let even = parallel.ends.clone();
        assert_eq!(even, [150, 300]);
        // The top band took three times as long: its rows cost more, and it
        // ends higher, further each frame, but never by a jump.
        let mut ends = vec![even[0]];
        for _ in 0..4 {
            parallel.times = vec![3.0, 1.0];
            parallel.balance(&camera);
            ends.push(parallel.ends[0]);
        }
        assert!(
            ends.windows(2).all(|e| e[1] < e[0] && e[0] - e[1] < 50),
            "{ends:?}"
        );
        // A new size learns afresh.
        let wide = Camera::handout(200, 240);
        parallel.balance(&wide);
        assert_eq!(parallel.ends, [120, 240]);
    }
}
