//! Drawing on several cores: the image split into bands of rows, one pipeline
//! per band, each thread owning its pixels (no locks, no atomics per pixel). A
//! band draws exactly its part of the whole image, so the result is the same, byte
//! for byte, for any number of threads.

use crate::app::figure::{Figure, Inputs, Render};
use crate::extensions::normal_map::TangentFrame;
use crate::extensions::texture::Model;
use crate::pipeline::clip::ScreenVertex;
use crate::pipeline::draw::{Join, Stats, Vertices};
use crate::pipeline::{Camera, Frame, Mesh, Target};

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
    work: Vec<u64>,
    ends: Vec<u32>,
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
fn draw_bands(pipelines: &mut [Box<dyn Render>], ends: &[u32], target: Target, shared: Shared) {
    let Shared {
        inputs,
        mesh,
        camera,
        vertices,
    } = shared;
    match pipelines {
        [] => {}
        [only] => {
            let mut target = target;
            only.draw_prepared(inputs, mesh, camera, vertices, &mut target)
        }
        _ => {
            let half = pipelines.len() / 2;
            let (top, bottom) = target.split_at_row(ends[half - 1]);
            let (first, second) = pipelines.split_at_mut(half);
            rayon::join(
                || draw_bands(first, &ends[..half], top, shared),
                || draw_bands(second, &ends[half..], bottom, shared),
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
const VERTEX_COST: u64 = 64;

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
        })
    }

    /// Sizes `frame` to the camera's image and draws `mesh` into it, a band per
    /// thread, each with the stage made from `inputs` (and the faces' tangent
    /// frames, which this keeps). `mesh` is the model's, or one with its
    /// vertices and its first faces: the tangent frames and the groups of faces
    /// the bands pass over ([`Vertices::group_faces`]) were made from it.
    pub fn render(&mut self, inputs: &Inputs, mesh: &Mesh, camera: &Camera, frame: &mut Frame) {
        let vertices = &mut self.vertices;
        match &self.pool {
            None => vertices.prepare(mesh, camera),
            Some(pool) => pool.install(|| vertices.prepare_split(mesh, camera, &Rayon)),
        }
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
        let (pipelines, ends, target) = (&mut self.pipelines[..], &self.ends[..], frame.target());
        match &self.pool {
            None => draw_bands(pipelines, ends, target, shared),
            Some(pool) => pool.install(|| draw_bands(pipelines, ends, target, shared)),
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

    /// Ends the bands where each holds about the same work: a row's pixels, and
    /// for a mesh in view its vertices, each worth [`VERTEX_COST`] pixels. Any
    /// split draws the same bytes; this one keeps both threads busy when the
    /// triangles crowd one part of the image.
    fn balance(&mut self, camera: &Camera) {
        let (n, height) = (self.pipelines.len(), camera.height as usize);
        self.ends.clear();
        if n == 1 {
            self.ends.push(camera.height);
            return;
        }
        self.work.clear();
        self.work.resize(height, camera.width as u64);
        // A sample of the vertices is enough to see where they crowd.
        let screen = self.vertices.screen();
        let every = (screen.len() / VERTEX_SAMPLE).max(1);
        let (centre, cost) = (camera.height as f32 / 2.0, VERTEX_COST * every as u64);
        for &ScreenVertex { y, .. } in screen.iter().step_by(every) {
            let row = ((y + centre).max(0.0) as usize).min(height.saturating_sub(1));
            self.work[row] += cost;
        }
        let total: u64 = self.work.iter().sum();
        let (mut done, mut row) = (0u64, 0usize);
        for band in 1..n {
            let share = total * band as u64 / n as u64;
            while row < height && done + self.work[row] / 2 < share {
                done += self.work[row];
                row += 1;
            }
            self.ends.push(row as u32);
        }
        self.ends.push(camera.height);
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
