//! The handout's `Draw` and `DrawPolygon`: every face of the mesh goes through the
//! stage's vertex shader and the camera, is clipped, projected and rasterized, and
//! every pixel goes through the depth test (for stages that have one) and the
//! stage's pixel shader into the render target.

use super::bands::{halfway_row, reaches, GROUP};
use super::camera::{Camera, Projection};
use super::clip::{
    clip_near, clip_rect, clip_segment_near, clip_segment_rect, CameraVertex, Polygon, Rect,
    ScreenVertex,
};
use super::interpolate::{Interpolation, Perspective, Pixel, Varying};
use super::mesh::Mesh;
use super::raster::{Bounds, Lines, Placed, Rasterizer, RowRaster, Viewport};
use super::stage::{Primitive, Stage, Surface};
use super::target::{pack, Frame, Target};
use super::vertices::{Fit, Vertices};
use std::marker::PhantomData;
use std::mem::take;
use std::ops::Range;

/// How far the guard band reaches beyond each side of the screen, in screen
/// sizes: primitives are cut there, so none costs more than a few screens.
pub const GUARD_BAND: f32 = 1.0;

/// The core for stages whose per-pixel struct is `V`, interpolated the way `I`
/// says and rasterized by `R`, with the scratch buffers it reuses from one
/// triangle and one frame to the next. The stage itself is handed to each draw.
pub struct Pipeline<V: Varying, I: Interpolation = Perspective, R: Rasterizer = RowRaster> {
    /// Which faces to leave out by the way they face the camera.
    pub cull: Cull,
    /// How lines and the rows' polygon edges are walked.
    pub lines: Lines,
    /// Whether visible pixels are shaded together in batches ([`Visible`]: a
    /// batch holds the pixels of consecutive faces that shade alike) rather
    /// than one by one as they are found (the default): the same pixels and
    /// colours either way. Worth it for a pixel
    /// shader heavy enough to gain from running over plain arrays, which the
    /// compiler vectorises (light per pixel); a cost for a light one.
    pub batch_shading: bool,
    /// What covers the pixels of each primitive.
    pub raster: R,
    scratch: R::Scratch<V>,
    /// The mesh's vertices as this frame sees them, when [`Pipeline::draw`]
    /// prepares them itself.
    vertices: Vertices,
    /// Each vertex as the rasterizer places it ([`Rasterizer::place`]), when the
    /// mesh is in full view.
    places: Vec<R::Place>,
    /// The faces a band of a frame in full view draws, as runs of face indices
    /// (each with whether its faces may lie beyond the band: [`FaceGroups`]).
    runs: Vec<(Range<usize>, bool)>,
    visible: Visible<I::Kept<V>>,
    stats: Stats,
    interpolation: PhantomData<I>,
}

/// Another thread drawing a band of the same frame, which may take some of
/// this band's rows once it has none of its own left
/// ([`Pipeline::draw_sharing`]): the threads then end together when one band
/// holds more work than its share (its rows were weighed wrong, or the machine
/// slowed its thread).
pub trait Handover<'t>: Sync {
    /// Whether the other thread waits for rows.
    fn wanted(&self) -> bool;

    /// Gives the other thread `rows`, with every face before face `from`
    /// drawn in them: it draws the faces from `from` on
    /// ([`Pipeline::draw_given`]).
    fn hand_over(&self, rows: Target<'t>, from: usize);
}

/// How many faces a band draws between two looks at whether another thread
/// waits for rows: a few microseconds of a million-triangle frame.
const HANDOVER_EVERY: usize = 512;

/// The fewest faces left in a band for it to hand over about half of them:
/// these take about 0.4 ms on one core, and a thread given rows spends about
/// 0.1 ms choosing its groups before its first face.
const LEAST_HANDED: usize = 1 << 14;

/// The fewest rows a hand-over leaves on either side.
const LEAST_ROWS: i32 = 4;

/// The faces a pipeline draws: those of `mesh` from face `from` on, as
/// `camera` sees them, with the frame's `vertices`, beside the thread
/// `handover` names, if any.
#[derive(Clone, Copy)]
struct Faces<'a, 't> {
    mesh: &'a Mesh,
    camera: &'a Camera,
    vertices: &'a Vertices,
    from: usize,
    handover: Option<&'a dyn Handover<'t>>,
}

/// Faces left out by the way they face the camera: a face is back-facing when its
/// normal points away from the camera C, `(C - v0) · n < 0`, front-facing when
/// that is `> 0`; a face seen exactly edge-on is neither.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Cull {
    /// Draw every face (the handout).
    #[default]
    None,
    Back,
    Front,
}

/// What the last frame did, for `--stats`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    pub triangles: u64,
    /// Left out by `cull`.
    pub culled: u64,
    /// Wholly off the screen, or wholly behind the near plane.
    pub outside: u64,
    /// Cut by the near plane or the guard band.
    pub clipped: u64,
    /// Handed to the rasterizer (for points and lines: every triangle not culled;
    /// their corners and edges are cut one by one).
    pub drawn: u64,
    /// Pixels that passed the depth test (or had none) and were written.
    pub pixels_written: u64,
    /// Pixels a nearer surface had already covered: overdraw avoided.
    pub depth_rejected: u64,
    /// The whole mesh was in front of the near plane, so no triangle was checked
    /// against it.
    pub near_plane_skipped: bool,
    /// The whole mesh was inside the view, so no triangle was tested against the
    /// screen or the guard band.
    pub view_tests_skipped: bool,
}

/// The pixels that passed the depth test, shaded together later: the shading
/// loop then runs over plain arrays, which the compiler vectorises. The pixels
/// of consecutive faces that shade alike ([`Stage::shades_alike`]: for light per
/// pixel, the faces of one wall of a split mesh) wait in one batch, shaded when
/// a face that shades otherwise comes, when the batch is full and when the
/// faces are done. The colours go to the target in the order the pixels came,
/// so a pixel covered twice ends as the later face left it: the target ends up
/// exactly as if each pixel were shaded at once. The arrays hold
/// [`BATCH_PIXELS`] pixels, made in the first frame: however the bands are
/// split, no later frame allocates.
struct Visible<K> {
    /// Where each pixel goes in the target: 32 bits, half the traffic of a
    /// `usize` (a larger target is shaded pixel by pixel).
    index: Vec<u32>,
    /// What each pixel keeps for its shading ([`Interpolation::keep`]).
    kept: Vec<K>,
    /// How many pixels wait, and the surface of the faces they are on.
    waiting: usize,
    surface: Surface,
}

/// The most pixels [`Visible`] shades at once.
const BATCH_PIXELS: usize = 1 << 14;

impl<K: Copy + Default> Visible<K> {
    /// The arrays at their full length, if they are not already.
    fn reserve(&mut self) {
        if self.index.len() < BATCH_PIXELS {
            self.index.resize(BATCH_PIXELS, 0);
            self.kept.resize(BATCH_PIXELS, K::default());
        }
    }
}

/// A batch of [`Visible`] pixels to shade: the stage and surface they are
/// shaded with, where each goes and what it keeps.
struct Batch<'a, S: Stage, I: Interpolation> {
    stage: &'a S,
    surface: &'a Surface,
    index: &'a [u32],
    kept: &'a [I::Kept<S::Varying>],
}

/// The handout's `PixelShader` for a batch of pixels, then each colour into its
/// place (`index`). Kept out of line: a small function of its own keeps the
/// light's values in registers, and the shading loop vectorises: sixteen pixels
/// at a time on a CPU with AVX-512, eight with AVX2, found at run time, four
/// otherwise. The same operations in the same order either way (Rust never
/// fuses a multiply and an add by itself), so the same bytes.
#[inline(never)]
fn shade<S: Stage, I: Interpolation>(batch: Batch<S, I>, color: &mut [u32]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx512f") {
        // SAFETY: the CPU has AVX-512, as just checked.
        return unsafe { shade_avx512::<S, I>(batch, color) };
    }
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, as just checked.
        return unsafe { shade_avx2::<S, I>(batch, color) };
    }
    shade_loop::<S, I, 8>(batch, color)
}

/// [`shade_loop`] compiled for AVX2. Only this loop: compiled so, the
/// rasterizer's loop in `fill` was slower, its helpers no longer inlined.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn shade_avx2<S: Stage, I: Interpolation>(batch: Batch<S, I>, color: &mut [u32]) {
    shade_loop::<S, I, 8>(batch, color)
}

/// [`shade_loop`] compiled for AVX-512, sixteen pixels at a time.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn shade_avx512<S: Stage, I: Interpolation>(batch: Batch<S, I>, color: &mut [u32]) {
    shade_loop::<S, I, 16>(batch, color)
}

/// [`shade`]'s work, inlined into each of its compilations: `LANES` pixels at
/// a time into a small array, written to the target from there.
#[inline(always)]
fn shade_loop<S: Stage, I: Interpolation, const LANES: usize>(
    batch: Batch<S, I>,
    color: &mut [u32],
) {
    let Batch {
        stage,
        surface,
        index,
        kept,
    } = batch;
    let colour = |&k: &I::Kept<S::Varying>| pack(stage.pixel_shader(&I::decode_kept(k), surface));
    let (index, kept) = (
        index.chunks_exact(LANES),
        kept[..index.len()].chunks_exact(LANES),
    );
    let rest = index.remainder().iter().zip(kept.remainder());
    for (index, kept) in index.zip(kept) {
        let mut shaded = [0u32; LANES];
        for (c, q) in shaded.iter_mut().zip(kept) {
            *c = colour(q);
        }
        // Pixels of one row of one triangle, as most are in a large one, go
        // to the target in one store: each place is written once either way,
        // so the target's bytes are the same.
        let first = index[0];
        let in_a_row = (0..LANES as u32).fold(true, |all, k| {
            all & (index[k as usize] == first.wrapping_add(k))
        });
        match color.get_mut(first as usize..first as usize + LANES) {
            Some(row) if in_a_row => row.copy_from_slice(&shaded),
            _ => {
                for (&i, &c) in index.iter().zip(&shaded) {
                    color[i as usize] = c;
                }
            }
        }
    }
    for (&i, q) in rest {
        color[i as usize] = colour(q);
    }
}

impl<V: Varying, I: Interpolation, R: Rasterizer> Default for Pipeline<V, I, R> {
    fn default() -> Self {
        Pipeline {
            cull: Cull::None,
            lines: Lines::Interpolate,
            batch_shading: false,
            raster: R::default(),
            scratch: Default::default(),
            vertices: Vertices::default(),
            places: Vec::new(),
            runs: Vec::new(),
            visible: Visible {
                index: Vec::new(),
                kept: Vec::new(),
                waiting: 0,
                surface: Surface::default(),
            },
            stats: Stats::default(),
            interpolation: PhantomData,
        }
    }
}

impl<V: Varying, I: Interpolation, R: Rasterizer> Pipeline<V, I, R> {
    pub fn new() -> Self {
        Self::default()
    }

    /// What the last `draw` did.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Sizes `frame` to the camera's image and draws `mesh` into all of it.
    pub fn render<S: Stage<Varying = V>>(
        &mut self,
        stage: &S,
        mesh: &Mesh,
        camera: &Camera,
        frame: &mut Frame,
    ) {
        frame.resize(camera.width, camera.height, S::DEPTH_TEST);
        self.draw(stage, mesh, camera, &mut frame.target());
    }

    /// The handout's `Draw`: clear the target, then draw every face of `mesh`
    /// with `stage`'s shaders.
    ///
    /// With `camera.near` set, each primitive is clipped at the near plane before
    /// projection and at a guard band around the screen after it (see `clip`).
    /// A triangle in full view goes through neither cut, so its pixels are
    /// exactly the handout's.
    pub fn draw<S: Stage<Varying = V>>(
        &mut self,
        stage: &S,
        mesh: &Mesh,
        camera: &Camera,
        target: &mut Target,
    ) {
        // Taken out of `self` while the faces are drawn, and put back for the next frame.
        let mut vertices = take(&mut self.vertices);
        vertices.draw_as(S::PRIMITIVE);
        vertices.place_as(R::SHARED);
        vertices.prepare(mesh, camera);
        self.draw_prepared(stage, mesh, camera, &vertices, target);
        self.vertices = vertices;
    }

    /// [`Pipeline::draw`] with the frame's vertices already taken to camera space
    /// ([`Vertices::prepare`]): the bands of one frame share them, so the
    /// per-vertex work is done once however many threads draw.
    pub fn draw_prepared<S: Stage<Varying = V>>(
        &mut self,
        stage: &S,
        mesh: &Mesh,
        camera: &Camera,
        vertices: &Vertices,
        target: &mut Target,
    ) {
        self.draw_sharing(stage, mesh, camera, vertices, target, None)
    }

    /// [`Pipeline::draw_prepared`] beside another thread, which may take the
    /// lower rows of the band once it has none of its own left
    /// ([`Handover`]): the faces left are then drawn into fewer rows here.
    pub fn draw_sharing<'t, S: Stage<Varying = V>>(
        &mut self,
        stage: &S,
        mesh: &Mesh,
        camera: &Camera,
        vertices: &Vertices,
        target: &mut Target<'t>,
        handover: Option<&dyn Handover<'t>>,
    ) {
        target.clear();
        let fit = vertices.fit;
        self.stats = Stats {
            triangles: mesh.faces.len() as u64,
            near_plane_skipped: fit.in_front && camera.near.is_some(),
            view_tests_skipped: fit.inside,
            ..Stats::default()
        };
        let faces = Faces {
            mesh,
            camera,
            vertices,
            from: 0,
            handover,
        };
        self.draw_from(stage, faces, target);
    }

    /// Draws the faces from face `from` on into `target`, rows another thread
    /// handed over ([`Handover::hand_over`]) with every earlier face drawn in
    /// them. The counts of triangles stay those of this pipeline's last frame;
    /// the pixels are added to them.
    pub fn draw_given<S: Stage<Varying = V>>(
        &mut self,
        stage: &S,
        mesh: &Mesh,
        camera: &Camera,
        vertices: &Vertices,
        target: &mut Target,
        from: usize,
    ) {
        let frame = take(&mut self.stats);
        let faces = Faces {
            mesh,
            camera,
            vertices,
            from,
            handover: None,
        };
        self.draw_from(stage, faces, target);
        self.stats = Stats {
            pixels_written: frame.pixels_written + self.stats.pixels_written,
            depth_rejected: frame.depth_rejected + self.stats.depth_rejected,
            ..frame
        };
    }

    /// `faces` drawn into `target` as it is.
    fn draw_from<'t, S: Stage<Varying = V>>(
        &mut self,
        stage: &S,
        faces: Faces<'_, 't>,
        target: &mut Target<'t>,
    ) {
        let Faces { mesh, vertices, .. } = faces;
        assert!(
            !S::DEPTH_TEST || target.depth.is_some(),
            "a stage with a depth test needs a depth buffer"
        );
        assert_eq!(
            vertices.points,
            mesh.positions.len(),
            "vertices prepared for another mesh"
        );
        assert!(
            S::PRIMITIVE == Primitive::Polygons || vertices.keeps_camera_space(),
            "vertices prepared for filled faces"
        );
        // Chosen once per frame, so that no loop over faces or pixels tests it.
        let batch = self.batch_shading
            && target
                .color
                .as_ref()
                .is_none_or(|c| c.len() <= u32::MAX as usize);
        match batch {
            true => self.draw_faces::<S, true>(stage, faces, target),
            false => self.draw_faces::<S, false>(stage, faces, target),
        }
    }

    /// Where `target`'s rows are drawn this frame: with nothing to cut at the
    /// near plane when every vertex is in front of it.
    fn view(&self, camera: &Camera, target: &Target, fit: Fit) -> View {
        let mut view = View::new(camera, target, self.lines);
        if fit.in_front {
            view.near = None; // nothing to cut: no test per triangle
        }
        view
    }

    /// Every face of `mesh` from `faces.from` on: culled, through the vertex
    /// shader, then drawn as the stage's primitive. A mesh in full view has
    /// nothing to cut or test, so its vertices are placed for the rasterizer
    /// once per frame ([`Rasterizer::place`]), whichever faces share them.
    fn draw_faces<'t, S: Stage<Varying = V>, const BATCH: bool>(
        &mut self,
        stage: &S,
        faces: Faces<'_, 't>,
        target: &mut Target<'t>,
    ) {
        let Faces {
            mesh,
            camera,
            vertices,
            from,
            handover,
        } = faces;
        let mut view = self.view(camera, target, vertices.fit);
        // Room, made in the first frame, for what any band of any later frame
        // holds: a batch of pixels, and a polygon's rows the image's height.
        if BATCH {
            self.visible.reserve();
        }
        self.raster
            .reserve(&mut self.scratch, camera.height as usize);
        let camera_space = &vertices.camera_space[..];
        // A band of a frame in full view passes over the triangles wholly above or
        // below its rows before any shading or setup (the band that holds them
        // draws them), so that threads share the per-triangle work. The rows are
        // widened by two, more than either rasterizer's rounding can reach.
        let centre = view.viewport.centre.1;
        let band_rows = |view: &View| {
            let rows = &view.viewport.bounds.y;
            (
                (rows.start - 2) as f32 - centre,
                (rows.end + 2) as f32 - centre,
            )
        };
        let (mut top, mut bottom) = band_rows(&view);
        let rows = &view.viewport.bounds.y;
        let whole = rows.start == 0 && rows.end >= camera.height as i32;
        // The whole mesh in view: every vertex was projected once for the frame.
        let screen = vertices.screen();
        let in_view = S::PRIMITIVE == Primitive::Polygons && !screen.is_empty();
        let pass_over = in_view && !whole;
        // Taken out of `self` while the faces are drawn, and put back for the next frame.
        let (mut places, mut runs) = (take(&mut self.places), take(&mut self.runs));
        runs.clear();
        // A band of a frame in full view whose faces are grouped passes over the
        // groups wholly above or below it without reading their faces. Culling
        // counts faces, so it reads them all.
        let grouped = vertices
            .grouped()
            .filter(|_| pass_over && self.cull == Cull::None);
        match grouped {
            Some((groups, rows)) => {
                let bounds = (top, bottom);
                self.stats.drawn += groups.select(mesh.faces.len(), rows, bounds, &mut runs);
            }
            None => runs.push((0..mesh.faces.len(), pass_over)),
        }
        if from > 0 {
            runs.retain_mut(|(run, _)| {
                run.start = run.start.max(from);
                run.start < run.end
            });
        }
        // Rows are handed over only where the groups' rows say how the faces
        // left lie in them.
        let mut handover = handover.zip(grouped.map(|(_, rows)| rows));
        // Once rows are handed over the band is smaller than its runs were
        // chosen for: then each group's rows say again whether its faces lie
        // beyond the band, rather than every face being tested.
        let mut regrouped: Option<&[(f32, f32)]> = None;
        // Placed in the pass that projected them, for every band, if this
        // rasterizer's places can be (the built-in ones'); else here.
        let shared = R::SHARED
            .and_then(|placing| vertices.places(placing))
            .and_then(R::shared_places);
        if in_view && shared.is_none() {
            let v = &view.viewport;
            places.clear();
            places.extend(screen.iter().map(|s| self.raster.place(s.x, s.y, v)));
        }
        let placed_from = shared.unwrap_or(&places);
        for r in 0..runs.len() {
            let (run, beyond) = runs[r].clone();
            let mut start = run.start;
            while start < run.end {
                // In pieces while another thread may want rows.
                let mut end = match handover {
                    Some(_) => (start + HANDOVER_EVERY).min(run.end),
                    None => run.end,
                };
                let mut pass_over = beyond;
                if let Some(rows) = regrouped {
                    let group = start / GROUP;
                    end = end.min((group + 1) * GROUP);
                    let unbounded = (f32::NEG_INFINITY, f32::INFINITY);
                    let group_rows = rows.get(group).copied().unwrap_or(unbounded);
                    let Some(beyond) = reaches(group_rows, (top, bottom)) else {
                        // In full view: drawn by the band its rows are in.
                        self.stats.drawn += (end - start) as u64;
                        start = end;
                        continue;
                    };
                    pass_over = beyond;
                }
                for (index, face) in mesh.faces[start..end].iter().enumerate() {
                    let index = start + index;
                    if self.cull != Cull::None {
                        let v0 = mesh.positions[face.vertices[0] as usize];
                        let facing = (camera.position - v0).dot(face.normal);
                        let culled = match self.cull {
                            Cull::Back => facing < 0.0,
                            Cull::Front => facing > 0.0,
                            Cull::None => false,
                        };
                        if culled {
                            self.stats.culled += 1;
                            continue;
                        }
                    }
                    // A triangle the rasterizer says covers nothing (most of a fine
                    // mesh's, with the exact one), or nothing in this band's rows
                    // (the band its rows are in draws it), is passed over before
                    // its surface and vertices are shaded.
                    let placed = match in_view {
                        true => face.vertices.map(|v| placed_from[v as usize]),
                        false => Default::default(),
                    };
                    let v = &view.viewport;
                    let misses = in_view
                        && (self.raster.misses(placed, v)
                            || pass_over && self.raster.misses_rows(placed, &v.bounds.y));
                    if misses {
                        self.stats.drawn += 1;
                        continue;
                    }
                    let surface = Surface::of(mesh, index);
                    let varyings =
                        [0, 1, 2].map(|k| stage.vertex_shader(&mesh.vertex(face, k), &surface));
                    let at = |k: usize| face.vertices[k] as usize;
                    let in_camera_space = || {
                        [0, 1, 2].map(|k| CameraVertex {
                            position: camera_space[at(k)],
                            varying: varyings[k],
                        })
                    };
                    match S::PRIMITIVE {
                        Primitive::Points => {
                            self.stats.drawn += 1;
                            self.draw_points(stage, &view, &in_camera_space(), &surface, target)
                        }
                        Primitive::Lines => {
                            self.stats.drawn += 1;
                            self.draw_edges(stage, &view, &in_camera_space(), &surface, target)
                        }
                        Primitive::Polygons if in_view => {
                            let corners = [0, 1, 2].map(|k| {
                                let zinv = screen[at(k)].zinv;
                                Placed {
                                    place: placed[k],
                                    zinv,
                                    varying: I::encode(zinv, varyings[k]),
                                }
                            });
                            let corners = FaceCorners::InView(corners);
                            self.draw_polygon::<S, BATCH>(stage, &view, corners, &surface, target)
                        }
                        Primitive::Polygons => {
                            let corners = FaceCorners::InCameraSpace(in_camera_space());
                            self.draw_polygon::<S, BATCH>(stage, &view, corners, &surface, target)
                        }
                    }
                }
                start = end;
                let Some((other, group_rows)) = handover.filter(|(h, _)| h.wanted()) else {
                    continue;
                };
                // Another thread has no rows left: it takes the lower rows that
                // hold about half the faces left, if that is worth a hand-over.
                let rows = view.viewport.bounds.y.clone();
                let (row, left) = halfway_row(&runs[r..], start, group_rows, rows.clone(), centre);
                let (least, most) = (rows.start + LEAST_ROWS, rows.end - LEAST_ROWS);
                if left < LEAST_HANDED || row < least || row > most {
                    handover = None; // too little left: draw it here
                    continue;
                }
                // The batch may hold pixels of the rows handed over.
                if BATCH {
                    self.shade_waiting(stage, target);
                }
                let (kept, given) = take(target).split_at_row(row as u32);
                *target = kept;
                other.hand_over(given, start);
                view = self.view(camera, target, vertices.fit);
                (top, bottom) = band_rows(&view);
                regrouped = Some(group_rows);
            }
        }
        self.places = places;
        self.runs = runs;
        if BATCH {
            self.shade_waiting(stage, target);
        }
    }

    /// The handout's `DrawPolygon`: a triangle of a mesh in full view goes to the
    /// rasterizer as its corners were placed; any other is clipped at the near
    /// plane, projected, tested against the screen and cut at the guard band
    /// first. Then each pixel goes through the depth test and the pixel shader.
    fn draw_polygon<S: Stage<Varying = V>, const BATCH: bool>(
        &mut self,
        stage: &S,
        view: &View,
        corners: FaceCorners<V, R::Place>,
        surface: &Surface,
        target: &mut Target,
    ) {
        let corners = match corners {
            FaceCorners::InView(placed) => {
                self.stats.drawn += 1;
                return self.fill::<S, BATCH>(stage, view, placed, surface, target);
            }
            FaceCorners::InCameraSpace(corners) => corners,
        };
        let near_cut = view
            .near
            .is_some_and(|n| corners.iter().any(|c| !in_front(c, n)));
        let mut polygon = Polygon::from_slice(&corners);
        let mut clipped = near_cut;
        if near_cut {
            polygon = clip_near(&polygon, view.near.unwrap_or_default());
        }
        let mut projected = Polygon::default();
        for &c in polygon.as_slice() {
            // On the camera plane (possible only without clipping): nothing to draw.
            let Some(s) = project::<_, I>(&view.projection, c) else {
                return;
            };
            projected.push(s);
        }
        if projected.is_empty() || off_screen(projected.as_slice(), &view.rect) {
            self.stats.outside += 1;
            return;
        }
        if !projected.as_slice().iter().all(|s| view.band.contains(s)) {
            projected = clip_rect(&projected, &view.band);
            clipped = true;
        }
        self.stats.clipped += clipped as u64;
        self.stats.drawn += 1;
        let corners = projected.as_slice();
        self.fill::<S, BATCH>(stage, view, corners, surface, target);
    }

    /// The projected polygon rasterized, each pixel through the depth test and the
    /// pixel shader. Kept out of the loop over faces, whose values would otherwise
    /// crowd the pixel loop's registers.
    #[inline(never)]
    fn fill<S: Stage<Varying = V>, const BATCH: bool>(
        &mut self,
        stage: &S,
        view: &View,
        corners: impl Corners<V, R>,
        surface: &Surface,
        target: &mut Target,
    ) {
        if BATCH && !S::shades_alike(&self.visible.surface, surface) {
            self.shade_waiting(stage, target);
        }
        let (width, first_row) = (target.width as usize, target.rows.start as usize);
        // Empty unless the stage tests depth (`draw` checked it has a buffer then).
        let depth_buffer = target.depth.as_deref_mut().unwrap_or_default();
        let mut color = target.color.as_deref_mut();
        // Made full length in `draw_faces`, in the first frame.
        let Visible {
            index,
            kept,
            waiting,
            surface: waiting_on,
        } = &mut self.visible;
        if BATCH && *waiting == 0 {
            *waiting_on = *surface;
        }
        // Slices, not the vectors: the pixel loop keeps their addresses in
        // registers instead of reloading them after every store.
        let (index, kept) = (&mut index[..], &mut kept[..]);
        // The batch's pixels so far, always fewer than `BATCH_PIXELS`: a count
        // in a register, where `Vec::push` would reload the length each pixel.
        let (mut n, before) = (*waiting, *waiting);
        // Counted where it is cheap: a batch counts its own pixels.
        let (mut rejected, mut written) = (0u64, 0u64);
        let plot = |p: Pixel<V>| {
            let i = (p.y as usize - first_row) * width + p.x as usize;
            if BATCH {
                if !depth_test::<S>(depth_buffer, i, p.zinv) {
                    rejected += 1;
                    return;
                }
                // SAFETY: both arrays hold BATCH_PIXELS (`Visible::reserve`,
                // in `draw_faces`), and n < BATCH_PIXELS: it returns to 0 on
                // reaching it.
                unsafe {
                    *index.get_unchecked_mut(n) = i as u32;
                    *kept.get_unchecked_mut(n) = I::keep(p.zinv, p.varying);
                }
                n += 1;
                if n == BATCH_PIXELS {
                    // A triangle too large for one batch is shaded in parts.
                    written += BATCH_PIXELS as u64;
                    if let Some(color) = color.as_deref_mut() {
                        let batch = Batch {
                            stage,
                            surface: &*waiting_on,
                            index,
                            kept,
                        };
                        shade::<S, I>(batch, color);
                    }
                    n = 0;
                }
            } else if depth_test::<S>(depth_buffer, i, p.zinv) {
                written += 1;
                if let Some(color) = color.as_deref_mut() {
                    let varying = I::decode(p.zinv, p.varying);
                    color[i] = pack(stage.pixel_shader(&varying, surface));
                }
            } else {
                rejected += 1;
            }
        };
        corners.cover(&self.raster, &mut self.scratch, &view.viewport, plot);
        // The pixels of a full batch were counted as it was shaded.
        self.stats.pixels_written += written + n as u64 - before as u64;
        self.stats.depth_rejected += rejected;
        *waiting = n;
    }

    /// The pixels the batch holds, if any, shaded into the target.
    fn shade_waiting<S: Stage<Varying = V>>(&mut self, stage: &S, target: &mut Target) {
        let Visible {
            index,
            kept,
            waiting,
            surface,
        } = &mut self.visible;
        if let (1.., Some(color)) = (*waiting, target.color.as_deref_mut()) {
            let index = &index[..*waiting];
            let batch = Batch {
                stage,
                surface,
                index,
                kept,
            };
            shade::<S, I>(batch, color);
        }
        *waiting = 0;
    }

    /// Section 2: each corner in front of the near plane as one pixel.
    fn draw_points<S: Stage<Varying = V>>(
        &mut self,
        stage: &S,
        view: &View,
        corners: &[CameraVertex<V>; 3],
        surface: &Surface,
        target: &mut Target,
    ) {
        for &c in corners {
            if view.near.is_some_and(|n| !in_front(&c, n)) {
                continue;
            }
            let Some(s) = project::<_, I>(&view.projection, c).filter(|s| view.band.contains(s))
            else {
                continue;
            };
            let stats = &mut self.stats;
            self.raster.point(s, &view.viewport, |p| {
                stats.count(shade_pixel::<S, I>(stage, p, surface, target))
            });
        }
    }

    /// The handout's `DrawPolygonEdges`: a line from corner i to corner (i + 1) mod 3,
    /// each cut at the near plane and the guard band first.
    fn draw_edges<S: Stage<Varying = V>>(
        &mut self,
        stage: &S,
        view: &View,
        corners: &[CameraVertex<V>; 3],
        surface: &Surface,
        target: &mut Target,
    ) {
        for i in 0..3 {
            let (a, b) = (corners[i], corners[(i + 1) % 3]);
            let near_cut = match view.near {
                Some(n) => clip_segment_near(a, b, n),
                None => Some((a, b)),
            };
            let Some((a, b)) = near_cut else { continue };
            let project = |c| project::<_, I>(&view.projection, c);
            let (Some(a), Some(b)) = (project(a), project(b)) else {
                continue;
            };
            let banded = if view.band.contains(&a) && view.band.contains(&b) {
                Some((a, b))
            } else {
                clip_segment_rect(a, b, &view.band)
            };
            let Some((a, b)) = banded else { continue };
            let stats = &mut self.stats;
            self.raster.line(a, b, &view.viewport, |p| {
                stats.count(shade_pixel::<S, I>(stage, p, surface, target))
            });
        }
    }
}

/// A face's corners as `DrawPolygon` gets them: placed for the rasterizer (a
/// mesh in full view), or in camera space, to be cut and projected.
enum FaceCorners<V, P> {
    InView([Placed<P, V>; 3]),
    InCameraSpace([CameraVertex<V>; 3]),
}

/// A polygon's corners as the rasterizer is handed them: projected (and
/// clipped), or a triangle in full view whose vertices it placed once per frame.
/// A trait, not an enum, so that each kind has its own pixel loop.
trait Corners<V: Varying, R: Rasterizer> {
    fn cover(
        self,
        raster: &R,
        scratch: &mut R::Scratch<V>,
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    );
}

impl<V: Varying, R: Rasterizer> Corners<V, R> for &[ScreenVertex<V>] {
    #[inline]
    fn cover(
        self,
        raster: &R,
        scratch: &mut R::Scratch<V>,
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    ) {
        raster.polygon(scratch, self, viewport, plot)
    }
}

impl<V: Varying, R: Rasterizer> Corners<V, R> for [Placed<R::Place, V>; 3] {
    #[inline]
    fn cover(
        self,
        raster: &R,
        scratch: &mut R::Scratch<V>,
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    ) {
        raster.triangle(scratch, self, viewport, plot)
    }
}

/// Whether a vertex is at or beyond the near plane `z = near` (false for NaN).
#[inline]
fn in_front<V>(c: &CameraVertex<V>, near: f32) -> bool {
    c.position.z >= near
}

/// The projection part of the handout's `VertexShader`: eq. 3 and 4 (relative to
/// the screen centre, before the rasterizer places it on a pixel) and 1/z, with
/// the varying encoded for interpolation. `None` if the vertex lies on
/// the camera plane and cannot be projected.
#[inline]
fn project<V: Varying, I: Interpolation>(
    projection: &Projection,
    c: CameraVertex<V>,
) -> Option<ScreenVertex<V>> {
    let (x, y, zinv) = projection.project_centred(c.position)?;
    let varying = I::encode(zinv, c.varying);
    Some(ScreenVertex {
        x,
        y,
        zinv,
        varying,
    })
}

/// The depth test of section 5 for pixel `i`: true, with the depth buffer updated,
/// if the pixel is nearer than what is there (or the stage has no depth test).
#[inline(always)]
fn depth_test<S: Stage>(buffer: &mut [f32], i: usize, zinv: f32) -> bool {
    if !S::DEPTH_TEST {
        return true;
    }
    // Nearer means larger 1/z. A NaN compares false, so it is never drawn: one
    // comparison per pixel, no separate test for NaN.
    let nearer = zinv > buffer[i];
    if !nearer {
        return false;
    }
    buffer[i] = zinv;
    true
}

impl Stats {
    /// Counts one pixel that was written or, if not, rejected by the depth test.
    fn count(&mut self, written: bool) {
        self.pixels_written += written as u64;
        self.depth_rejected += !written as u64;
    }
}

/// The handout's `PixelShader` for one pixel of a point or line: the depth test,
/// then the stage's colour into the target. Returns whether it was written.
#[inline(always)]
fn shade_pixel<S: Stage, I: Interpolation>(
    stage: &S,
    p: Pixel<S::Varying>,
    surface: &Surface,
    target: &mut Target,
) -> bool {
    let i = target.index(p.x, p.y);
    let depth_buffer = target.depth.as_deref_mut().unwrap_or_default();
    let written = depth_test::<S>(depth_buffer, i, p.zinv);
    if written {
        if let Some(color) = target.color.as_deref_mut() {
            color[i] = pack(stage.pixel_shader(&I::decode(p.zinv, p.varying), surface));
        }
    }
    written
}

/// True if every corner lies beyond one side of the screen by more than the
/// pixel or two that rounding and running sums can move a pixel.
fn off_screen<V>(corners: &[ScreenVertex<V>], screen: &Rect) -> bool {
    let m = 2.0;
    corners.iter().all(|v| v.x < screen.left - m)
        || corners.iter().all(|v| v.x > screen.right + m)
        || corners.iter().all(|v| v.y < screen.top - m)
        || corners.iter().all(|v| v.y > screen.bottom + m)
}

/// Where one frame is drawn: the camera's projection and near plane, the screen
/// and the guard band around it (in screen-centred coordinates), and the pixels
/// the target lets us write.
struct View {
    projection: Projection,
    near: Option<f32>,
    rect: Rect,
    band: Rect,
    viewport: Viewport,
}

impl View {
    fn new(camera: &Camera, target: &Target, lines: Lines) -> Self {
        let rect = camera.screen_rect();
        let g = camera.width.max(camera.height) as f32 * GUARD_BAND;
        View {
            projection: camera.projection(),
            near: camera.near,
            rect,
            band: Rect {
                left: rect.left - g,
                top: rect.top - g,
                right: rect.right + g,
                bottom: rect.bottom + g,
            },
            viewport: Viewport {
                bounds: Bounds {
                    x: 0..target.width.min(camera.width) as i32,
                    y: target.rows.start as i32..target.rows.end.min(camera.height) as i32,
                },
                lines,
                ..Viewport::of(camera)
            },
        }
    }
}

impl Viewport {
    /// Where `camera`'s vertices land, its whole image the bounds.
    pub(super) fn of(camera: &Camera) -> Viewport {
        Viewport {
            half_width: (camera.width / 2) as i32,
            half_height: (camera.height / 2) as i32,
            centre: (camera.width as f32 / 2.0, camera.height as f32 / 2.0),
            bounds: Bounds {
                x: 0..camera.width as i32,
                y: 0..camera.height as i32,
            },
            lines: Lines::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::mesh::face_normal;
    use crate::pipeline::raster::EdgeRaster;
    use crate::pipeline::stage::{Depth, PixelLight, Position};
    use crate::pipeline::{Affine, Light, Perspective};
    use glam::Vec3;

    /// A wall at z = 2 facing a camera at the origin, 100 x 100 pixels, f = 100.
    fn wall() -> (Mesh, Camera) {
        let mut mesh = Mesh::default();
        let [a, b, c, d] =
            [(-2.0, -2.0), (2.0, -2.0), (2.0, 2.0), (-2.0, 2.0)].map(|(x, y)| Vec3::new(x, y, 2.0));
        let grey = Vec3::splat(0.75);
        mesh.push_triangle([a, b, c], -Vec3::Z, grey);
        mesh.push_triangle([a, c, d], -Vec3::Z, grey);
        let camera = Camera {
            position: Vec3::ZERO,
            focal: 100.0,
            ..Camera::handout(100, 100)
        };
        (mesh, camera)
    }

    #[test]
    fn pixel_light_is_eq_10_and_11_at_each_pixels_point() {
        // The pipeline's colour against eq. 10 and 11 evaluated independently, in
        // f64, at the point of the wall each pixel shows: x = (px - W/2) z / f.
        let (mesh, camera) = wall();
        let light = Light {
            position: Vec3::new(0.3, -0.2, 1.0),
            power: Vec3::splat(2.0),
            indirect: Vec3::splat(0.2),
        };
        let mut frame = Frame::default();
        Pipeline::<_, Perspective>::new().render(&PixelLight { light }, &mesh, &camera, &mut frame);
        let mut worst = 0u8;
        for y in 0..100 {
            for x in 0..100 {
                let i = (y * 100 + x) as usize;
                assert!(frame.depth[i] > 0.0, "({x}, {y}) not drawn");
                let p = [(x as f64 - 50.0) * 0.02, (y as f64 - 50.0) * 0.02, 2.0];
                let l = light.position.to_array().map(f64::from);
                let r = [l[0] - p[0], l[1] - p[1], l[2] - p[2]];
                let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
                let cos = (-r[2] / r2.sqrt()).max(0.0); // the normal is -z
                let direct = 2.0 * cos / (4.0 * std::f64::consts::PI * r2);
                let expected = (0.75 * (direct + 0.2)).min(1.0) * 255.0;
                let got = frame.rgb(x, y)[0];
                worst = worst.max((got as f64 - expected).abs().round() as u8);
            }
        }
        // The rows rasterizer samples each pixel where its truncated corner puts
        // it, up to 1.5 pixels from (x, y): here at most 2 steps of 255.
        assert!(worst <= 2, "largest difference {worst}");
    }

    #[test]
    fn placing_each_vertex_once_draws_what_projecting_each_corner_draws() {
        // Random small and large triangles in full view, drawn twice: as they are
        // (every vertex placed once per frame), and with one more vertex, used by
        // no face, behind the camera, so that no vertex is placed ahead and each
        // corner is projected and placed for its face. Same bytes, both
        // rasterizers, depth and light per pixel.
        let (_, camera) = wall();
        let mut random = crate::pipeline::xorshift(0x2545_f491_4f6c_dd1du64);
        let mut next = || (random() >> 40) as f32 / (1u64 << 24) as f32;
        let mut mesh = Mesh::default();
        for k in 0..400 {
            // Within 0.8 of the axis at z >= 2: inside the 100-pixel screen.
            let size = if k % 10 == 0 { 1.0 } else { 0.08 };
            let mut at = || next() * (1.6 - size) - 0.8;
            let (x, y, z) = (at(), at(), 2.0 + next());
            let corners = [0, 1, 2]
                .map(|_| Vec3::new(x + size * next(), y + size * next(), z + 0.3 * next()));
            let color = Vec3::new(next(), next(), next());
            mesh.push_triangle(corners, face_normal(corners), color);
        }
        let mut stray = mesh.clone();
        stray.positions.push(Vec3::new(0.0, 0.0, -5.0));
        fn draw<S: Stage, R: Rasterizer>(stage: &S, mesh: &Mesh, camera: &Camera) -> Frame {
            let mut frame = Frame::default();
            Pipeline::<S::Varying, Perspective, R>::new().render(stage, mesh, camera, &mut frame);
            frame
        }
        fn same<S: Stage>(stage: &S, mesh: &Mesh, stray: &Mesh, camera: &Camera) {
            let placed = draw::<S, RowRaster>(stage, mesh, camera);
            assert!(placed.depth.iter().filter(|&&d| d > 0.0).count() > 2000);
            assert_eq!(placed, draw::<S, RowRaster>(stage, stray, camera));
            let placed = draw::<S, EdgeRaster>(stage, mesh, camera);
            assert_eq!(placed, draw::<S, EdgeRaster>(stage, stray, camera));
        }
        same(&Depth, &mesh, &stray, &camera);
        let light = Light::handout();
        same(&PixelLight { light }, &mesh, &stray, &camera);
        // The two paths were taken.
        let mut pipeline = Pipeline::<_, Perspective>::new();
        let mut frame = Frame::default();
        pipeline.render(&Depth, &mesh, &camera, &mut frame);
        assert!(pipeline.stats().view_tests_skipped);
        pipeline.render(&Depth, &stray, &camera, &mut frame);
        assert!(!pipeline.stats().view_tests_skipped);
    }

    /// Every hand-over a band offers taken at once, the rows kept.
    struct Eager<'t>(std::sync::Mutex<Vec<(Target<'t>, usize)>>);

    impl<'t> Handover<'t> for Eager<'t> {
        fn wanted(&self) -> bool {
            true
        }
        fn hand_over(&self, rows: Target<'t>, from: usize) {
            self.0.lock().unwrap().push((rows, from));
        }
    }

    #[test]
    fn rows_handed_over_and_drawn_by_another_pipeline_keep_the_bytes_and_counts() {
        // A million-triangle frame in small: in full view, the faces grouped.
        let mesh = crate::scene::subdivide(&crate::scene::cornell_box(), 128);
        let camera = Camera {
            focal: 120.0,
            ..Camera::handout(160, 120)
        };
        fn both<S: Stage, R: Rasterizer>(stage: &S, batch: bool, mesh: &Mesh, camera: &Camera) {
            let new = || {
                let mut p = Pipeline::<S::Varying, Perspective, R>::new();
                p.batch_shading = batch;
                p
            };
            let (mut whole, mut one) = (Frame::default(), new());
            one.render(stage, mesh, camera, &mut whole);
            let mut vertices = Vertices::default();
            vertices.draw_as(S::PRIMITIVE);
            vertices.place_as(R::SHARED);
            vertices.group_faces(mesh);
            vertices.prepare(mesh, camera);
            let mut frame = Frame::default();
            frame.resize(camera.width, camera.height, S::DEPTH_TEST);
            let (mut top, mut bottom) = frame.target().split_at_row(30);
            let (mut upper, mut lower, mut helper) = (new(), new(), new());
            upper.draw_prepared(stage, mesh, camera, &vertices, &mut top);
            let eager = Eager(Default::default());
            lower.draw_sharing(stage, mesh, camera, &vertices, &mut bottom, Some(&eager));
            let given = eager.0.into_inner().unwrap();
            // Half the faces left each time, while enough are left.
            assert!(given.len() >= 3, "{} hand-overs", given.len());
            assert!(given.windows(2).all(|g| g[0].1 < g[1].1));
            assert!(given
                .iter()
                .all(|(rows, _)| rows.rows.len() >= LEAST_ROWS as usize));
            for (mut rows, from) in given {
                helper.draw_given(stage, mesh, camera, &vertices, &mut rows, from);
            }
            assert_eq!(frame.color, whole.color);
            assert_eq!(frame.depth, whole.depth);
            // The pixels are shared out; each band counts every triangle.
            let (one, bands) = (one.stats, [upper.stats, lower.stats, helper.stats]);
            let sum = |count: fn(&Stats) -> u64| bands.iter().map(count).sum::<u64>();
            assert_eq!(sum(|s| s.pixels_written), one.pixels_written);
            assert_eq!(sum(|s| s.depth_rejected), one.depth_rejected);
            for band in &bands[..2] {
                assert_eq!((band.triangles, band.drawn), (one.triangles, one.drawn));
            }
        }
        let light = Light::handout();
        both::<_, EdgeRaster>(&PixelLight { light }, true, &mesh, &camera);
        both::<_, RowRaster>(&Depth, false, &mesh, &camera);
    }

    #[test]
    fn faces_that_shade_alike_wait_in_one_batch_and_keep_the_image() {
        // The wall, then a nearer grey triangle facing the same way, whose pixels
        // join the wall's in the batch and must end on top; then a red one (the
        // grey wait is shaded first) and a grey one behind the wall (rejected).
        // At 100x100 all the grey pixels wait in one batch; at 200x200 (40 000
        // pixels) the batch fills in the middle of a face.
        let (mut mesh, camera) = wall();
        let grey = Vec3::splat(0.75);
        let near = [(-1.0, -1.0, 1.5), (1.0, -1.0, 1.5), (0.0, 1.0, 1.5)].map(Vec3::from);
        mesh.push_triangle(near, -Vec3::Z, grey);
        let red = [(0.0, 0.0, 1.2), (1.0, 0.0, 1.2), (0.0, 1.0, 1.2)].map(Vec3::from);
        mesh.push_triangle(red, -Vec3::Z, Vec3::new(0.75, 0.15, 0.15));
        let behind = [(-1.0, 1.0, 3.0), (1.0, 1.0, 3.0), (0.0, -1.0, 3.0)].map(Vec3::from);
        mesh.push_triangle(behind, -Vec3::Z, grey);
        let stage = PixelLight {
            light: Light::handout(),
        };
        let alike = |a, b| {
            PixelLight::<Light>::shades_alike(&Surface::of(&mesh, a), &Surface::of(&mesh, b))
        };
        assert!(alike(0, 2) && alike(2, 4) && !alike(2, 3));
        for size in [100, 200] {
            let camera = Camera {
                focal: size as f32,
                width: size,
                height: size,
                ..camera
            };
            let mut pipeline = Pipeline::<_>::new();
            let mut frames = [Frame::default(), Frame::default()];
            let mut stats = [Stats::default(); 2];
            for (k, batch) in [true, false].into_iter().enumerate() {
                pipeline.batch_shading = batch;
                pipeline.render(&stage, &mesh, &camera, &mut frames[k]);
                stats[k] = *pipeline.stats();
            }
            assert_eq!(frames[0].color, frames[1].color, "{size}");
            assert_eq!(stats[0], stats[1], "{size}");
            let pixels = (size * size) as u64;
            assert!(stats[0].pixels_written > pixels * 9 / 8, "{:?}", stats[0]);
            assert!(stats[0].depth_rejected > pixels / 40, "{:?}", stats[0]);
        }
    }

    #[test]
    fn shading_a_triangle_at_a_time_gives_the_image_of_shading_each_pixel() {
        // The wall, and in front of it a tilted triangle that hides part of it and
        // is itself partly hidden by one drawn after it: pixels overwritten, and
        // pixels rejected by the depth test, in both orders.
        let (mut mesh, camera) = wall();
        let red = Vec3::new(0.75, 0.15, 0.15);
        let tilted = [(-1.5, -1.0, 1.2), (1.0, -1.5, 1.8), (0.0, 1.5, 1.5)].map(Vec3::from);
        mesh.push_triangle(tilted, face_normal(tilted), red);
        let front = [(-1.0, 0.0, 1.0), (1.0, 0.2, 1.0), (0.0, 1.0, 1.0)].map(Vec3::from);
        mesh.push_triangle(front, -Vec3::Z, Vec3::ONE);
        let stage = PixelLight {
            light: Light::handout(),
        };
        for affine in [false, true] {
            let (mut batched, mut immediate) = (Frame::default(), Frame::default());
            fn both<I: Interpolation>(
                stage: &PixelLight,
                mesh: &Mesh,
                camera: &Camera,
                frames: [&mut Frame; 2],
            ) {
                let [batched, immediate] = frames;
                let mut pipeline = Pipeline::<_, I>::new();
                pipeline.batch_shading = true;
                pipeline.render(stage, mesh, camera, batched);
                pipeline.batch_shading = false;
                pipeline.render(stage, mesh, camera, immediate);
            }
            let frames = [&mut batched, &mut immediate];
            match affine {
                true => both::<Affine>(&stage, &mesh, &camera, frames),
                false => both::<Perspective>(&stage, &mesh, &camera, frames),
            }
            assert_eq!(batched.color, immediate.color, "affine: {affine}");
            let red_pixels = batched
                .color
                .iter()
                .filter(|&&c| c >> 16 > 2 * (c & 0xff))
                .count();
            assert!(red_pixels > 500, "the tilted triangle shows: {red_pixels}");
        }
    }

    #[test]
    fn shading_eight_or_sixteen_pixels_at_a_time_gives_the_bytes_of_four() {
        // The loop for AVX2 or AVX-512 is the one that runs here if the CPU has
        // it; the figures test it against bytes made before it existed. This
        // holds both to the plain loop pixel by pixel, over points nearer and
        // farther than the light, and a count that is no multiple of 16, for
        // what each interpolation keeps of a pixel.
        #[cfg(target_arch = "x86_64")]
        fn same_bytes<I: Interpolation>() {
            let stage = PixelLight {
                light: Light::handout(),
            };
            // The box's floor, lit from above, and points over it up to just
            // below the light.
            let surface = Surface {
                normal: -Vec3::Y,
                reflectance: Vec3::new(0.75, 0.15, 0.15),
                face: 0,
                material: 0,
            };
            let n = 4099;
            let fraction = |k: usize, a: f32| (k as f32 * a).fract();
            let kept: Vec<I::Kept<Position>> = (0..n)
                .map(|k| {
                    let world = Vec3::new(
                        2.0 * fraction(k, 0.414_214) - 1.0,
                        1.4 * fraction(k, 0.732_051) - 0.4,
                        2.0 * fraction(k, 0.618_034) - 1.0,
                    );
                    let zinv = 1.0 / (world.z + 3.0);
                    I::keep(zinv, I::encode(zinv, Position { world }))
                })
                .collect();
            // Every pixel in its own place, in reverse order, so that the
            // colours are compared pixel by pixel.
            let index: Vec<u32> = (0..n as u32).rev().collect();
            let batch = || Batch::<PixelLight, I> {
                stage: &stage,
                surface: &surface,
                index: &index,
                kept: &kept,
            };
            let (mut plain, mut wide) = (vec![0; n], vec![0; n]);
            shade_loop::<PixelLight, I, 8>(batch(), &mut plain);
            // SAFETY: the CPU has AVX2, as the caller checked.
            unsafe { shade_avx2::<PixelLight, I>(batch(), &mut wide) };
            assert_eq!(plain, wide);
            if std::arch::is_x86_feature_detected!("avx512f") {
                let mut widest = vec![0; n];
                // SAFETY: the CPU has AVX-512, as just checked.
                unsafe { shade_avx512::<PixelLight, I>(batch(), &mut widest) };
                assert_eq!(plain, widest);
            }
            let distinct: std::collections::HashSet<_> = plain.iter().collect();
            // 116 colours: the light's whole range, from the indirect term
            // alone to a full red.
            assert!(distinct.len() > 100, "{} colours", distinct.len());
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            same_bytes::<Perspective>();
            same_bytes::<Affine>();
        }
    }

    #[test]
    fn a_depth_only_pass_fills_depth_and_shades_nothing() {
        let (mesh, camera) = wall();
        let mut depth = vec![0.0f32; 100 * 100];
        let mut target = Target {
            width: 100,
            height: 100,
            rows: 0..100,
            color: None,
            depth: Some(&mut depth),
        };
        Pipeline::<_>::new().draw(&Depth, &mesh, &camera, &mut target);
        // 1/z = 1/2 everywhere, up to the running sums' rounding.
        assert!(
            depth.iter().all(|&z| (z - 0.5).abs() < 1e-6),
            "{:?}",
            &depth[..4]
        );
    }
}
