//! Drawing on several cores: the image split into bands of rows, one pipeline
//! per band, each thread owning its pixels (no locks, no atomics per pixel). A
//! band draws exactly its part of the whole image, so the result is the same, byte
//! for byte, for any number of threads. The bands are cut where the last frames'
//! times say the work splits evenly; when one still holds more (the machine
//! slowed its thread), the thread beside it takes its lower rows part of the way
//! through its faces ([`Exchange`]), and the two end together.
//!
//! The threads beside the caller are [`Helpers`]: each waits for the second half
//! of a [`Join`], spinning a little before it sleeps, so handing a frame over
//! costs well under a microsecond when frames follow each other. (rayon's pool,
//! entered from outside, sends the caller to sleep and wakes it again: about
//! 24 us a frame here, a fifth of a 2000x2000 clear.) The caller draws the first
//! half itself and takes the second back if no helper has started it, so a join
//! is never slower than the two halves in turn by more than a few atomic
//! operations.

use crate::app::figure::{Figure, Inputs, Prepared, Render};
use crate::extensions::normal_map::TangentFrame;
use crate::extensions::texture::Model;
use crate::pipeline::bands::CHUNK;
use crate::pipeline::clip::ScreenVertex;
use crate::pipeline::draw::{Handover, Stats};
use crate::pipeline::vertices::{InTurn, Join, Vertices};
use crate::pipeline::{Camera, Frame, Mesh, Target};
use std::any::Any;
use std::cell::UnsafeCell;
use std::ops::Range;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::{JoinHandle, Thread};
use std::time::{Duration, Instant};

/// A figure drawn in `threads` bands.
pub struct Parallel {
    pipelines: Vec<Box<dyn Render>>,
    helpers: Helpers,
    stats: Stats,
    /// The faces' tangent frames, for a figure with a normal map.
    frames: Vec<TangentFrame>,
    /// The mesh's vertices as the frame sees them, prepared once per frame for
    /// every band.
    vertices: Vertices,
    /// Each block of rows' work this frame, and where the bands end (kept
    /// between frames).
    work: Vec<f64>,
    ends: Vec<u32>,
    /// How much each block's work costs compared with the others, as the
    /// bands' drawing times have shown, and each band's time in the last frame.
    weight: Vec<f64>,
    times: Vec<f64>,
}

/// Draws `target` with `pipelines`, the band of pipeline `i` ending before row
/// `ends[i]` (the last at the target's bottom): the two halves of the pipelines on
/// the two sides of a [`Join`], whose jobs live on the stack, so a frame
/// allocates nothing for its threads. Two bands side by side share their
/// rows ([`Exchange`]). Every pipeline draws, an empty band too, so that each
/// one's counts are this frame's.
fn draw_bands(
    pipelines: &mut [Box<dyn Render>],
    (ends, times): (&[u32], &mut [f64]),
    target: Target,
    prepared: Prepared,
    join: &impl Join,
) {
    match pipelines {
        [] => {}
        [only] => {
            let (mut target, start) = (target, Instant::now());
            only.draw_sharing(prepared, &mut target, None);
            times[0] = start.elapsed().as_secs_f64();
        }
        [first, second] => {
            let (top, bottom) = target.split_at_row(ends[0]);
            let exchange = Exchange::new();
            let (first_time, second_time) = times.split_at_mut(1);
            join.join(
                || exchange.draw(first, 0, top, prepared, &mut first_time[0]),
                || exchange.draw(second, 1, bottom, prepared, &mut second_time[0]),
            );
            // Rows handed over count for the band they were cut from.
            let taken = exchange.taken();
            times[0] += taken[0];
            times[1] += taken[1];
        }
        _ => {
            let half = pipelines.len() / 2;
            let (top, bottom) = target.split_at_row(ends[half - 1]);
            let (first, second) = pipelines.split_at_mut(half);
            let (ends, later) = ends.split_at(half);
            let (times, later_times) = times.split_at_mut(half);
            join.join(
                || draw_bands(first, (ends, times), top, prepared, join),
                || draw_bands(second, (later, later_times), bottom, prepared, join),
            );
        }
    }
}

/// Two bands drawn side by side: the thread that ends its own first takes
/// the lower rows of the other's, again and again while the other has enough
/// left ([`Handover`]), so that the two end together.
struct Exchange<'t> {
    state: Mutex<Handovers<'t>>,
    /// A thread waits for rows.
    wanted: AtomicBool,
}

struct Handovers<'t> {
    /// How many bands are being drawn by their own threads (only they hand
    /// rows over): a band counts from when its thread starts it, so that a
    /// band ended before the other started (the two joined in turn) waits for
    /// nothing.
    drawing: usize,
    /// Rows handed over and not yet taken: the rows, the first face not drawn
    /// in them, and the band they were cut from.
    offer: Option<(Target<'t>, usize, usize)>,
    /// How long each band's rows drawn by the other thread took.
    taken: [f64; 2],
    /// The thread waiting for rows, to be woken when some come or the other
    /// band ends.
    waiting: Option<Thread>,
}

/// One side of an [`Exchange`]: the band it draws.
struct Side<'e, 't> {
    exchange: &'e Exchange<'t>,
    band: usize,
}

impl<'t> Exchange<'t> {
    fn new() -> Self {
        Exchange {
            state: Mutex::new(Handovers {
                drawing: 0,
                offer: None,
                taken: [0.0; 2],
                waiting: None,
            }),
            wanted: AtomicBool::new(false),
        }
    }

    /// Nothing is drawn while the lock is held, so no panic can poison it.
    fn lock(&self) -> MutexGuard<'_, Handovers<'t>> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Band `band` drawn with `pipeline` into `target` (its time in `time`),
    /// handing rows over while the other thread wants them; then rows the other
    /// band hands over, until it has ended. If the other has not started (the
    /// two joined in turn: no helper was free), there is nothing to wait for.
    fn draw(
        &self,
        pipeline: &mut Box<dyn Render>,
        band: usize,
        mut target: Target<'t>,
        prepared: Prepared,
        time: &mut f64,
    ) {
        let start = Instant::now();
        {
            let _drawing = Drawing::new(self);
            let side = Side {
                exchange: self,
                band,
            };
            pipeline.draw_sharing(prepared, &mut target, Some(&side));
        }
        *time = start.elapsed().as_secs_f64();
        while let Some((mut rows, from, of)) = self.wait_for_rows() {
            let start = Instant::now();
            pipeline.draw_given(prepared, &mut rows, from);
            self.lock().taken[of] += start.elapsed().as_secs_f64();
        }
    }

    /// Rows the other thread hands over, or none once it has ended its band,
    /// waited for as a helper waits for a job ([`wait_until`]): the other band
    /// mostly ends within the spin, and waking a sleeping thread cost about
    /// 20 µs a frame.
    fn wait_for_rows(&self) -> Option<(Target<'t>, usize, usize)> {
        let mut offer = None;
        wait_until(
            || {
                let mut state = self.lock();
                offer = state.offer.take();
                if offer.is_some() || state.drawing == 0 {
                    state.waiting = None;
                    return true;
                }
                if state.waiting.is_none() {
                    state.waiting = Some(std::thread::current());
                }
                self.wanted.store(true, Ordering::Relaxed);
                false
            },
            HELPER_SPIN,
        );
        offer
    }

    /// The waiting thread woken, if one sleeps: `state` has changed.
    fn wake(state: &mut Handovers) {
        if let Some(thread) = state.waiting.take() {
            thread.unpark();
        }
    }

    fn taken(&self) -> [f64; 2] {
        self.lock().taken
    }
}

impl<'t> Handover<'t> for Side<'_, 't> {
    fn wanted(&self) -> bool {
        self.exchange.wanted.load(Ordering::Relaxed)
    }

    fn hand_over(&self, rows: Target<'t>, from: usize) {
        let mut state = self.exchange.lock();
        state.offer = Some((rows, from, self.band));
        self.exchange.wanted.store(false, Ordering::Relaxed);
        Exchange::wake(&mut state);
    }
}

/// A band drawn by its own thread until this is dropped, a panic's unwinding
/// too, so that the other thread never waits for rows that cannot come.
struct Drawing<'e, 't>(&'e Exchange<'t>);

impl<'e, 't> Drawing<'e, 't> {
    fn new(exchange: &'e Exchange<'t>) -> Self {
        exchange.lock().drawing += 1;
        Drawing(exchange)
    }
}

impl Drop for Drawing<'_, '_> {
    fn drop(&mut self) {
        let mut state = self.0.lock();
        state.drawing -= 1;
        Exchange::wake(&mut state);
    }
}

/// What setting up the triangles around one vertex costs, in pixels filled:
/// a mesh of small triangles is split into bands by its vertices, a few large
/// ones by their pixels.
const VERTEX_COST: usize = 64;

/// At most how many blocks of rows [`Parallel::balance`] weighs.
const BLOCKS: usize = 256;

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
        let helpers = Helpers::new(threads)?;
        let pipelines: Vec<_> = (0..threads).map(|_| figure.pipeline_for(model)).collect();
        let mut vertices = Vertices::default();
        vertices.draw_as(pipelines[0].primitive());
        vertices.place_as(pipelines[0].shared_placing());
        if threads > 1 {
            vertices.group_faces(model.mesh);
        }
        Ok(Parallel {
            pipelines,
            helpers,
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
        let helpers = std::mem::take(&mut self.helpers);
        self.prepare_and_draw(inputs, mesh, camera, frame, &helpers);
        self.helpers = helpers;
    }

    /// The frame [`Parallel::render`] draws, on the calling thread alone: the
    /// same split and the same bands, drawn one after the other, no rows handed
    /// over. What splitting the frame costs, apart from running on two cores
    /// (the threads bench's "two bands in turn").
    pub fn render_in_turn(
        &mut self,
        inputs: &Inputs,
        mesh: &Mesh,
        camera: &Camera,
        frame: &mut Frame,
    ) {
        self.prepare_and_draw(inputs, mesh, camera, frame, &InTurn);
    }

    /// The frame's vertices prepared, the bands balanced, each band drawn (the
    /// bands side by side as `join` runs them) and their counts summed.
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
        let prepared = Prepared {
            inputs,
            mesh,
            camera,
            vertices: &self.vertices,
        };
        let bands = (&self.ends[..], &mut self.times[..]);
        draw_bands(&mut self.pipelines, bands, frame.target(), prepared, join);
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
    /// for a mesh in view its vertices, each worth [`VERTEX_COST`] pixels, each
    /// row's work weighed by what the bands' times have shown it costs. Any
    /// split draws the same bytes; this one keeps both threads busy when the
    /// triangles crowd one part of the image, or one part's pixels cost more.
    /// Rows are weighed in at most [`BLOCKS`] blocks, since this runs on one
    /// thread before the bands start.
    fn balance(&mut self, camera: &Camera) {
        let (n, height) = (self.pipelines.len(), camera.height as usize);
        if n == 1 {
            self.ends.clear();
            self.ends.push(camera.height);
            return;
        }
        let block_rows = height.div_ceil(BLOCKS).max(1);
        // Each block's pixels (the last block may hold fewer rows).
        self.work.clear();
        self.work.extend(
            (0..height)
                .step_by(block_rows)
                .map(|top| (camera.width as usize * block_rows.min(height - top)) as f64),
        );
        let centre = camera.height as f32 / 2.0;
        let block =
            |y: f32| ((y + centre).max(0.0) as usize).min(height.saturating_sub(1)) / block_rows;
        let chunks = self.vertices.chunk_rows();
        if chunks.is_empty() {
            // A sample of the vertices is enough to see where they crowd.
            let screen = self.vertices.screen();
            let every = (screen.len() / VERTEX_SAMPLE).max(1);
            let cost = (VERTEX_COST * every) as f64;
            for &ScreenVertex { y, .. } in screen.iter().step_by(every) {
                self.work[block(y)] += cost;
            }
        } else {
            // The rows of each chunk of vertices, found as they were projected:
            // a sample of them, as of the vertices above.
            let every = (chunks.len() * CHUNK / VERTEX_SAMPLE).max(1);
            let cost = (VERTEX_COST * CHUNK * every) as f64;
            for &(low, high) in chunks.iter().step_by(every) {
                self.work[block((low + high) / 2.0)] += cost;
            }
        }
        self.learn_weights(height, block_rows);
        for (w, k) in self.work.iter_mut().zip(&self.weight) {
            *w *= k;
        }
        let total: f64 = self.work.iter().sum();
        let (mut done, mut b) = (0.0, 0usize);
        self.ends.clear();
        for band in 1..n {
            let share = total * band as f64 / n as f64;
            while b < self.work.len() && done + self.work[b] < share {
                done += self.work[b];
                b += 1;
            }
            // Within the block that holds the share's end, on the row where
            // its work, spread evenly over its rows, reaches it: one block
            // where the triangles crowd held 6 % of a million-triangle frame.
            let top = b * block_rows;
            let rows = block_rows.min(height.saturating_sub(top));
            let part = match self.work.get(b) {
                Some(&w) if w > 0.0 => ((share - done) / w).clamp(0.0, 1.0),
                _ => 0.0,
            };
            let end = top + (part * rows as f64).round() as usize;
            self.ends.push(end.min(height) as u32);
        }
        self.ends.push(camera.height);
    }

    /// Weighs the blocks (of `block_rows` rows) of each band of the last frame
    /// by how long the band took against how long its work, as weighed,
    /// foretold: a band slower than its share makes its rows dearer. Halfway (a
    /// square root) each frame, so that one frame's noise moves the bands little.
    fn learn_weights(&mut self, height: usize, block_rows: usize) {
        let blocks = self.work.len();
        if self.weight.len() != blocks || self.ends.last() != Some(&(height as u32)) {
            // A new size: nothing learnt yet.
            self.weight.clear();
            self.weight.resize(blocks, 1.0);
            return;
        }
        // Each band's blocks (a block that two bands share counts for both),
        // its work as weighed so far, and its time.
        let (work, weight) = (&self.work, &mut self.weight);
        let starts = std::iter::once(0).chain(self.ends.iter().map(|&e| e as usize));
        let bands = starts
            .zip(&self.ends)
            .map(|(start, &end)| start / block_rows..(end as usize).div_ceil(block_rows));
        let weighed =
            |weight: &[f64], b: Range<usize>| -> f64 { b.map(|b| work[b] * weight[b]).sum() };
        let all_work: f64 = weighed(weight, 0..blocks);
        let all_time: f64 = self.times.iter().sum();
        if all_time <= 0.0 || all_work <= 0.0 {
            return;
        }
        for (b, &time) in bands.zip(&self.times) {
            let band = weighed(weight, b.clone());
            if band <= 0.0 || time <= 0.0 {
                continue;
            }
            let dearer = ((time / all_time) / (band / all_work))
                .sqrt()
                .clamp(0.5, 2.0);
            for w in &mut weight[b] {
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

// The helper threads, and how a join hands its second half to one.

/// How long a helper keeps looking for work after its last job before it
/// sleeps: longer than the gap between two frames drawn back to back.
const HELPER_SPIN: Duration = Duration::from_micros(300);

/// How long the caller looks for the helper's half to finish before it sleeps.
const CALLER_SPIN: Duration = Duration::from_micros(50);

/// A slot's states: its helper is starting, idle, a caller is writing the job
/// into it, the job waits to be taken, the helper runs it, it has run (the
/// caller reads how and makes the slot idle again), or the helper should end.
const STARTING: u8 = 0;
const IDLE: u8 = 1;
const CLAIMED: u8 = 2;
const GIVEN: u8 = 3;
const RUNNING: u8 = 4;
const DONE: u8 = 5;
const STOP: u8 = 6;

/// The second half of a join, on the caller's stack, its lifetime erased while
/// it is handed over: the caller does not return before the slot is idle again.
type Job = *mut (dyn FnMut() + Send + 'static);
type Panic = Box<dyn Any + Send>;

/// What a caller and one helper share.
struct Slot {
    state: AtomicU8,
    /// Written by the caller while the slot is CLAIMED, read by the helper
    /// once it has moved the slot from GIVEN to RUNNING.
    job: UnsafeCell<Option<(Job, Thread)>>,
    /// Written by the helper while RUNNING, taken by the caller once DONE.
    panic: UnsafeCell<Option<Panic>>,
}

// SAFETY: the cells are only touched by whoever the state says owns the slot
// (see their fields), and every hand-over is a release store or exchange read
// with acquire.
unsafe impl Sync for Slot {}
unsafe impl Send for Slot {}

struct Helper {
    slot: Arc<Slot>,
    thread: Thread,
    handle: Option<JoinHandle<()>>,
}

/// `threads - 1` helper threads, so that a frame's bands are drawn by
/// `threads` threads with the caller's. None by default: every join in turn.
#[derive(Default)]
pub struct Helpers {
    helpers: Vec<Helper>,
}

impl Helpers {
    /// Starts `threads - 1` helpers, and returns once they have started: a
    /// thread sets itself up (and allocates) as it starts, which belongs to
    /// this call, not to the first frames.
    pub fn new(threads: usize) -> Result<Helpers, String> {
        let mut helpers = Vec::with_capacity(threads.saturating_sub(1));
        for i in 1..threads.max(1) {
            let slot = Arc::new(Slot::new(STARTING));
            let theirs = Arc::clone(&slot);
            let handle = std::thread::Builder::new()
                .name(format!("rasterlab band {i}"))
                .spawn(move || help(&theirs))
                .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
            helpers.push(Helper {
                slot,
                thread: handle.thread().clone(),
                handle: Some(handle),
            });
        }
        for h in &helpers {
            while h.slot.state.load(Ordering::Acquire) == STARTING {
                std::thread::yield_now();
            }
        }
        Ok(Helpers { helpers })
    }

    /// The first idle helper, now the caller's.
    fn claim(&self) -> Option<&Helper> {
        self.helpers.iter().find(|h| {
            h.slot
                .state
                .compare_exchange(IDLE, CLAIMED, Ordering::Acquire, Ordering::Relaxed)
                .is_ok()
        })
    }
}

impl Slot {
    fn new(state: u8) -> Slot {
        Slot {
            state: AtomicU8::new(state),
            job: UnsafeCell::new(None),
            panic: UnsafeCell::new(None),
        }
    }

    /// After the caller's half: the job run here if no helper took it, or its
    /// end awaited; the slot is idle again, and the job's panic returned.
    fn finish(&self, job: Job) -> Option<Panic> {
        let taken_back = self
            .state
            .compare_exchange(GIVEN, CLAIMED, Ordering::Acquire, Ordering::Relaxed)
            .is_ok();
        let panic = if taken_back {
            // SAFETY: the job is this caller's, alive on its stack, and no
            // helper will read the slot before it is given again.
            let run = catch_unwind(AssertUnwindSafe(|| unsafe { (*job)() }));
            unsafe { *self.job.get() = None };
            run.err()
        } else {
            wait_until(|| self.state.load(Ordering::Acquire) == DONE, CALLER_SPIN);
            // SAFETY: DONE, read with acquire: the helper has let go of the cells.
            unsafe { (*self.panic.get()).take() }
        };
        self.state.store(IDLE, Ordering::Release);
        panic
    }
}

impl Join for Helpers {
    fn join<A: FnOnce() + Send, B: FnOnce() + Send>(&self, a: A, b: B) {
        let Some(helper) = self.claim() else {
            a();
            b();
            return;
        };
        let mut b = Some(b);
        let mut second = || {
            if let Some(b) = b.take() {
                b()
            }
        };
        let second: *mut (dyn FnMut() + Send + '_) = &mut second;
        // SAFETY: only the lifetime changes; `finish` below returns only once
        // the job has run and the slot is idle, and `a`'s panic is caught so
        // that it cannot unwind past the job while a helper runs it.
        let job: Job = unsafe { std::mem::transmute(second) };
        let slot = &*helper.slot;
        // SAFETY: CLAIMED is this caller's alone.
        unsafe { *slot.job.get() = Some((job, std::thread::current())) };
        slot.state.store(GIVEN, Ordering::Release);
        helper.thread.unpark();
        let first = catch_unwind(AssertUnwindSafe(a));
        let second = slot.finish(job);
        if let Err(panic) = first {
            resume_unwind(panic);
        }
        if let Some(panic) = second {
            resume_unwind(panic);
        }
    }
}

impl Drop for Helpers {
    fn drop(&mut self) {
        // No join is running: each borrows the helpers.
        for h in &mut self.helpers {
            h.slot.state.store(STOP, Ordering::Release);
            h.thread.unpark();
            if let Some(handle) = h.handle.take() {
                let _ = handle.join();
            }
        }
    }
}

/// A helper's life: wait for a job, run it, say so, until told to stop.
fn help(slot: &Slot) {
    slot.state.store(IDLE, Ordering::Release);
    loop {
        let mut stop = false;
        wait_until(
            || match slot.state.load(Ordering::Acquire) {
                GIVEN => slot
                    .state
                    .compare_exchange(GIVEN, RUNNING, Ordering::Acquire, Ordering::Relaxed)
                    .is_ok(),
                STOP => {
                    stop = true;
                    true
                }
                _ => false,
            },
            HELPER_SPIN,
        );
        if stop {
            return;
        }
        // SAFETY: RUNNING is this helper's; the caller wrote the job before
        // giving it and waits for DONE before its stack frame ends.
        let (job, caller) = unsafe { (*slot.job.get()).take() }.expect("a given slot holds a job");
        let run = catch_unwind(AssertUnwindSafe(|| unsafe { (*job)() }));
        if let Err(panic) = run {
            unsafe { *slot.panic.get() = Some(panic) };
        }
        slot.state.store(DONE, Ordering::Release);
        // The caller may be asleep; it may also be gone already, which
        // `caller`, an owned handle, survives.
        caller.unpark();
    }
}

/// Waits until `ready`: spinning for about `spin`, yielding the core to other
/// threads after the first few microseconds, then asleep until unparked.
fn wait_until(mut ready: impl FnMut() -> bool, spin: Duration) {
    let start = Instant::now();
    let mut tries = 0u32;
    while !ready() {
        tries = tries.wrapping_add(1);
        if tries < 1024 {
            std::hint::spin_loop();
        } else if start.elapsed() < spin {
            std::thread::yield_now();
        } else {
            std::thread::park();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::figure::Inputs;
    use crate::pipeline::{Light, StageName};
    use crate::scene::cornell_box;
    use std::sync::atomic::AtomicUsize;
    use std::sync::Mutex;

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
        // A tall frame is weighed in blocks of rows, a band ending within
        // one where its share does.
        let tall = Camera::handout(200, 2001);
        parallel.balance(&tall);
        assert_eq!(parallel.work.len(), 251);
        assert_eq!(parallel.ends, [1001, 2001]);
    }

    /// Helpers whose one slot no thread serves: every join takes its second
    /// half back and runs it on the caller.
    fn unserved() -> Helpers {
        Helpers {
            helpers: vec![Helper {
                slot: Arc::new(Slot::new(IDLE)),
                thread: std::thread::current(),
                handle: None,
            }],
        }
    }

    /// A sum over 0..n split in halves down to single numbers, each half a join.
    fn split_sum(helpers: &Helpers, range: std::ops::Range<usize>, sum: &AtomicUsize) {
        if range.len() <= 1 {
            for i in range {
                sum.fetch_add(i, Ordering::Relaxed);
            }
            return;
        }
        let middle = range.start + range.len() / 2;
        helpers.join(
            || split_sum(helpers, range.start..middle, sum),
            || split_sum(helpers, middle..range.end, sum),
        );
    }

    /// Two bands that share their rows, joined in turn because no helper
    /// serves the join: the first ends without waiting for the second, which
    /// has not started, and the frame is one thread's.
    #[test]
    fn bands_joined_in_turn_draw_one_threads_frame() {
        let mesh = cornell_box();
        let camera = Camera::handout(120, 90);
        let inputs = Inputs::lit(Light::handout());
        let figure = Figure::of(StageName::PixelLight);
        let mut one = Frame::default();
        Parallel::new(figure, &mesh, 1)
            .unwrap()
            .render(&inputs, &mesh, &camera, &mut one);
        let mut two = Parallel::new(figure, &mesh, 2).unwrap();
        let mut frame = Frame::default();
        for _ in 0..3 {
            two.prepare_and_draw(&inputs, &mesh, &camera, &mut frame, &unserved());
            assert!(frame.color == one.color);
        }
        assert!(one.color.iter().filter(|&&c| c != 0).count() > 1000);
    }

    #[test]
    fn every_half_runs_once_nested_or_not_on_any_number_of_helpers() {
        for helpers in [
            Helpers::new(1).unwrap(),
            Helpers::new(2).unwrap(),
            Helpers::new(7).unwrap(),
            unserved(),
        ] {
            for round in 0..200 {
                let n = 1 + round % 37;
                let sum = AtomicUsize::new(0);
                split_sum(&helpers, 0..n, &sum);
                assert_eq!(sum.into_inner(), n * (n - 1) / 2, "{n}");
                for h in &helpers.helpers {
                    assert_eq!(h.slot.state.load(Ordering::Relaxed), IDLE);
                }
            }
        }
    }

    #[test]
    fn a_helper_draws_the_second_half_when_the_first_takes_a_while() {
        let helpers = Helpers::new(2).unwrap();
        let threads = Mutex::new(Vec::new());
        helpers.join(
            || {
                // Up to 5 s for the helper to start the second half, however
                // busy the machine.
                let start = Instant::now();
                while threads.lock().unwrap().is_empty() && start.elapsed().as_secs() < 5 {
                    std::thread::sleep(Duration::from_millis(1));
                }
                threads.lock().unwrap().push(std::thread::current().id());
            },
            || threads.lock().unwrap().push(std::thread::current().id()),
        );
        let threads = threads.into_inner().unwrap();
        assert_eq!(threads.len(), 2);
        assert_ne!(threads[0], threads[1]);
        // Taken back, the second half runs on the caller.
        let caller = Mutex::new(None);
        unserved().join(
            || {},
            || *caller.lock().unwrap() = Some(std::thread::current().id()),
        );
        assert_eq!(
            caller.into_inner().unwrap(),
            Some(std::thread::current().id())
        );
    }

    #[test]
    fn a_panic_in_either_half_reaches_the_caller_after_both_ended() {
        for helpers in [Helpers::new(2).unwrap(), unserved()] {
            let ended = AtomicUsize::new(0);
            let caught = catch_unwind(AssertUnwindSafe(|| {
                helpers.join(
                    || {
                        ended.fetch_add(1, Ordering::SeqCst);
                    },
                    || panic!("second"),
                )
            }));
            let said = caught.unwrap_err();
            assert_eq!(said.downcast_ref::<&str>(), Some(&"second"));
            assert_eq!(ended.load(Ordering::SeqCst), 1);
            let caught = catch_unwind(AssertUnwindSafe(|| {
                helpers.join(
                    || panic!("first"),
                    || {
                        std::thread::sleep(Duration::from_millis(20));
                        ended.fetch_add(1, Ordering::SeqCst);
                    },
                )
            }));
            let said = caught.unwrap_err();
            assert_eq!(said.downcast_ref::<&str>(), Some(&"first"));
            assert_eq!(ended.load(Ordering::SeqCst), 2);
            // And the helpers still work.
            let sum = AtomicUsize::new(0);
            split_sum(&helpers, 0..10, &sum);
            assert_eq!(sum.into_inner(), 45);
        }
    }
}
