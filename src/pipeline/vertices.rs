//! The mesh's vertices as one frame sees them, made before any face is drawn:
//! each taken to camera space (eq. 8) and projected (eq. 3 and 4) once however
//! many faces share it, and where they all lie, which spares each triangle the
//! tests that the whole mesh makes needless. The work is split in parts that a
//! [`Join`] may run on two threads.

use super::bands::{chunk_rows, FaceGroups, CHUNK, GROUP};
use super::camera::{Camera, Projection};
use super::clip::{Rect, ScreenVertex};
use super::interpolate::Nothing;
use super::mesh::Mesh;
use super::raster::{SharedPlacing, Viewport};
use super::stage::Primitive;
use glam::Vec3;

/// Where a whole mesh lies, found once per frame from its vertices. A triangle
/// lies within its corners' projections (all in front of the camera), so when
/// the whole mesh fits, no triangle needs a cut or a view test.
#[derive(Clone, Copy, Default)]
pub(super) struct Fit {
    /// Every point is in front of the near plane (or there is none).
    pub(super) in_front: bool,
    /// Every point projects inside the screen, so no triangle needs a view test.
    pub(super) inside: bool,
}

/// The mesh's vertices as one frame sees them, before any face is drawn: each
/// in camera space (eq. 8, once however many faces share it) and where all of
/// them lie, which spares each triangle the tests the whole mesh makes needless.
#[derive(Default)]
pub struct Vertices {
    /// How many points the mesh had.
    pub(super) points: usize,
    /// Each vertex in camera space (eq. 8), unless the frame draws filled faces
    /// of a mesh in full view ([`Vertices::keeps_camera_space`]); left as it
    /// was then.
    pub(super) camera_space: Vec<Vec3>,
    /// Whether the frames draw filled faces ([`Vertices::draw_as`]).
    polygons: bool,
    /// Each vertex projected (eq. 3 and 4, from the screen's centre, and 1/z)
    /// when the whole mesh is in view, so that a corner shared by many faces is
    /// projected once; empty otherwise.
    screen: Vec<ScreenVertex<Nothing>>,
    pub(super) fit: Fit,
    /// The mesh's faces in groups, for a caller that draws it in bands frame
    /// after frame ([`Vertices::group_faces`]), and the rows each chunk of
    /// vertices lies in this frame, when the groups fit the mesh and it is in
    /// full view; empty otherwise.
    groups: FaceGroups,
    rows: Vec<(f32, f32)>,
    /// The rows each group of faces lies in this frame, from its chunks', when
    /// `rows` is not empty; empty otherwise.
    group_rows: Vec<(f32, f32)>,
    /// How the frames' vertices are placed for the rasterizer in the pass that
    /// projects them ([`Vertices::place_as`]), and this frame's places, when
    /// the mesh is in full view; empty otherwise.
    placing: Option<SharedPlacing>,
    places: Vec<(i32, i32)>,
}

impl Vertices {
    /// Every vertex projected, when the whole mesh is in view, so that a caller
    /// can see where the triangles are; empty otherwise.
    pub fn screen(&self) -> &[ScreenVertex<Nothing>] {
        &self.screen
    }

    /// Says what the frames prepared from now on draw: filled faces of a mesh
    /// in full view are drawn from the projections alone, so no points in
    /// camera space are kept for them; points and lines keep them.
    pub fn draw_as(&mut self, primitive: Primitive) {
        self.polygons = primitive == Primitive::Polygons;
    }

    /// Says how the frames prepared from now on place their vertices for the
    /// rasterizer ([`Rasterizer::SHARED`]), so that every band reads the same
    /// places; none to leave it to the bands.
    pub fn place_as(&mut self, placing: Option<SharedPlacing>) {
        self.placing = placing;
    }

    /// This frame's places, made as `placing` says, if they were.
    pub fn places(&self, placing: SharedPlacing) -> Option<&[(i32, i32)]> {
        let made = self.placing == Some(placing)
            && !self.screen.is_empty()
            && self.places.len() == self.screen.len();
        made.then_some(&self.places[..])
    }

    /// Groups `mesh`'s faces ([`FaceGroups`]), so that each band of the frames
    /// prepared from now on passes over the faces wholly above or below it
    /// without reading them. For a caller that draws the same mesh frame after
    /// frame (or a mesh with its vertices and its first faces): the groups are
    /// checked against a frame's mesh by its sizes only.
    pub fn group_faces(&mut self, mesh: &Mesh) {
        self.groups = FaceGroups::of(mesh);
    }

    /// The rows each chunk of [`CHUNK`] vertices lies in this frame, when the
    /// faces are grouped and the mesh is in full view; empty otherwise.
    pub fn chunk_rows(&self) -> &[(f32, f32)] {
        &self.rows
    }

    /// The groups of faces and this frame's rows of each group, when the mesh is
    /// grouped and in full view.
    pub(super) fn grouped(&self) -> Option<(&FaceGroups, &[(f32, f32)])> {
        let rows = &self.group_rows[..];
        (!rows.is_empty()).then_some((&self.groups, rows))
    }

    /// Takes every vertex of `mesh` to `camera`'s space and looks at where they
    /// all lie; the buffers are kept for the next frame.
    pub fn prepare(&mut self, mesh: &Mesh, camera: &Camera) {
        self.prepare_split(mesh, camera, &InTurn)
    }

    /// [`Vertices::prepare`], the work split in parts that `join` may run at
    /// once.
    pub fn prepare_split(&mut self, mesh: &Mesh, camera: &Camera, join: &impl Join) {
        let n = mesh.positions.len();
        self.points = n;
        // Room for the points in camera space, for a frame that keeps them
        // (`keeps_camera_space`): made once, so that no later frame allocates,
        // and not written unless needed.
        self.camera_space
            .reserve(n.saturating_sub(self.camera_space.len()));
        self.screen.resize(n, ScreenVertex::default());
        let chunks = if self.groups.fit(mesh) {
            n.div_ceil(CHUNK)
        } else {
            0
        };
        self.rows.resize(chunks, (0.0, 0.0));
        let view = (camera.projection(), camera.near, camera.screen_rect());
        // Frames follow each other closely: when the last one kept the points
        // in camera space, they are written in the same pass as the projections
        // (and afterwards, apart, if this one needs them after all).
        let written = self.keeps_camera_space();
        if written {
            self.camera_space.resize(n, Vec3::ZERO);
        }
        let camera_space = match written {
            true => &mut self.camera_space[..],
            false => &mut [],
        };
        let placing = self.placing.filter(|_| self.polygons);
        self.places.resize(placing.map_or(0, |_| n), (0, 0));
        let placed = placing.map(|p| (p, Viewport::of(camera)));
        let mut fit = project_all(
            &mesh.positions,
            (
                camera_space,
                &mut self.screen,
                &mut self.rows,
                &mut self.places,
            ),
            &view,
            placed.as_ref(),
            join,
        );
        fit.in_front |= camera.near.is_none();
        if !(fit.inside && fit.in_front) {
            self.screen.clear();
            self.rows.clear();
            self.places.clear();
        }
        self.fit = fit;
        if self.keeps_camera_space() && !written {
            self.camera_space.resize(n, Vec3::ZERO);
            to_camera_all(&mesh.positions, &mut self.camera_space, &view.0, join);
        }
        let groups = match self.rows.is_empty() {
            true => 0,
            false => self.groups.count(),
        };
        self.group_rows.resize(groups, (0.0, 0.0));
        rows_of_groups(&self.groups, 0, &self.rows, &mut self.group_rows, join);
    }

    /// Whether the points in camera space are kept this frame: not for filled
    /// faces of a mesh in full view, which are drawn from `screen` alone.
    pub(super) fn keeps_camera_space(&self) -> bool {
        !(self.polygons && self.fit.inside && self.fit.in_front)
    }
}

/// Vertices handed to one piece of work at a time when the work is split.
const PART: usize = 1 << 15;

/// Every point of `positions` projected (with the rows of each chunk of them,
/// if `rows` is not empty, and in camera space, if `camera_space` is not
/// empty), and where they all lie (before the near plane is taken into
/// account), in parts split by `join`.
fn project_all(
    positions: &[Vec3],
    (camera_space, screen, rows, places): PlacedOutputs,
    view: &(Projection, Option<f32>, Rect),
    placing: Option<&(SharedPlacing, Viewport)>,
    join: &impl Join,
) -> Fit {
    if positions.len() > PART {
        // Split between chunks, so that each part finds its own chunks' rows.
        let half = (positions.len() / 2).next_multiple_of(CHUNK);
        let (p, q) = positions.split_at(half);
        let (c, d) = camera_space.split_at_mut(half.min(camera_space.len()));
        let (s, t) = screen.split_at_mut(half);
        let (r, u) = rows.split_at_mut((half / CHUNK).min(rows.len()));
        let (a, b) = places.split_at_mut(half.min(places.len()));
        let (mut first, mut second) = (Fit::default(), Fit::default());
        join.join(
            || first = project_all(p, (c, s, r, a), view, placing, join),
            || second = project_all(q, (d, t, u, b), view, placing, join),
        );
        return Fit {
            in_front: first.in_front && second.in_front,
            inside: first.inside && second.inside,
        };
    }
    let fit = project_part(positions, (camera_space, &mut *screen, rows), view);
    // While the part's projections are in the cache; useless unless the whole
    // mesh is in view, as this part is.
    if let (Some((placing, viewport)), true) = (placing, fit.inside) {
        placing.place_all(screen, places, viewport);
    }
    fit
}

/// Where [`project_all`] writes: the points in camera space (or nothing), the
/// projections, and each chunk's rows (or nothing).
type Outputs<'a> = (
    &'a mut [Vec3],
    &'a mut [ScreenVertex<Nothing>],
    &'a mut [(f32, f32)],
);

/// [`Outputs`] and each point's place for the rasterizer (or nothing).
type PlacedOutputs<'a> = (
    &'a mut [Vec3],
    &'a mut [ScreenVertex<Nothing>],
    &'a mut [(f32, f32)],
    &'a mut [(i32, i32)],
);

/// [`project_all`]'s work on one part, compiled for the widest vectors the CPU
/// has, found at run time: the division and the products are exact in each
/// lane, and Rust never fuses a multiply and an add by itself, so the points
/// are the same bits however many are taken at once.
fn project_part(positions: &[Vec3], out: Outputs, view: &(Projection, Option<f32>, Rect)) -> Fit {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx512f") {
        // SAFETY: the CPU has AVX-512, as just checked.
        return unsafe { project_part_avx512(positions, out, view) };
    }
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, as just checked.
        return unsafe { project_part_avx2(positions, out, view) };
    }
    project_loop(positions, out, view)
}

/// [`project_loop`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn project_part_avx2(
    positions: &[Vec3],
    out: Outputs,
    view: &(Projection, Option<f32>, Rect),
) -> Fit {
    project_loop(positions, out, view)
}

/// [`project_loop`] compiled for AVX-512.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn project_part_avx512(
    positions: &[Vec3],
    out: Outputs,
    view: &(Projection, Option<f32>, Rect),
) -> Fit {
    project_loop(positions, out, view)
}

/// [`project_part`]'s work, inlined into each of its compilations.
#[inline(always)]
fn project_loop(
    positions: &[Vec3],
    (camera_space, screen, rows): Outputs,
    view: &(Projection, Option<f32>, Rect),
) -> Fit {
    let (projection, near, rect) = view;
    let near = near.unwrap_or(f32::MIN_POSITIVE);
    let (mut in_front, mut inside) = (true, true);
    // Without a branch per point (`&`, not `&&`), so that the compiler may take
    // several points at once. A point off the screen is written too: the caller
    // reads the screen only if every point is on it.
    let mut project = |p: Vec3, s: &mut ScreenVertex<Nothing>| {
        let v = projection.to_camera(p);
        let (x, y, zinv) = projection.project_centred_or_not_finite(v);
        *s = ScreenVertex {
            x,
            y,
            zinv,
            varying: Nothing {},
        };
        let front = (v.z >= near) & v.z.is_finite();
        in_front &= front;
        // The rectangle's bounds hold no infinity or NaN, so neither do x and y.
        inside &= front
            & zinv.is_finite()
            & (x >= rect.left)
            & (x <= rect.right)
            & (y >= rect.top)
            & (y <= rect.bottom);
        v
    };
    // A loop each, so that neither tests per point whether to keep it.
    match camera_space.is_empty() {
        true => {
            for (&p, s) in positions.iter().zip(screen.iter_mut()) {
                project(p, s);
            }
        }
        false => {
            for ((&p, s), c) in positions.iter().zip(screen.iter_mut()).zip(camera_space) {
                *c = project(p, s);
            }
        }
    }
    let fit = Fit { in_front, inside };
    if fit.inside && !rows.is_empty() {
        chunk_rows(screen, rows);
    }
    fit
}

/// Every point of `positions` in camera space, in parts split by `join`.
fn to_camera_all(
    positions: &[Vec3],
    camera_space: &mut [Vec3],
    projection: &Projection,
    join: &impl Join,
) {
    if positions.len() > PART {
        let half = positions.len() / 2;
        let (p, q) = positions.split_at(half);
        let (c, d) = camera_space.split_at_mut(half);
        join.join(
            || to_camera_all(p, c, projection, join),
            || to_camera_all(q, d, projection, join),
        );
        return;
    }
    for (&p, c) in positions.iter().zip(camera_space) {
        *c = projection.to_camera(p);
    }
}

/// The rows of each group of faces from `first` on, into `out`, in parts split
/// by `join`.
fn rows_of_groups(
    groups: &FaceGroups,
    first: usize,
    rows: &[(f32, f32)],
    out: &mut [(f32, f32)],
    join: &impl Join,
) {
    if out.len() > PART / GROUP {
        let half = out.len() / 2;
        let (a, b) = out.split_at_mut(half);
        join.join(
            || rows_of_groups(groups, first, rows, a, join),
            || rows_of_groups(groups, first + half, rows, b, join),
        );
        return;
    }
    groups.group_rows(first, rows, out);
}

/// Two pieces of work that may run at once: on two threads for the threads that
/// draw bands (the application's helpers), one after the other ([`InTurn`])
/// otherwise. The pipeline starts
/// no threads of its own.
pub trait Join: Sync {
    fn join<A: FnOnce() + Send, B: FnOnce() + Send>(&self, a: A, b: B);
}

/// Work done on the calling thread, one piece after the other.
pub struct InTurn;

impl Join for InTurn {
    fn join<A: FnOnce() + Send, B: FnOnce() + Send>(&self, a: A, b: B) {
        a();
        b();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::raster::{EdgeRaster, Rasterizer};
    use crate::pipeline::RowRaster;

    /// A camera at the origin looking along z, 100 x 100 pixels, f = 100.
    fn camera() -> Camera {
        Camera {
            position: Vec3::ZERO,
            focal: 100.0,
            ..Camera::handout(100, 100)
        }
    }

    /// Small faces in front of [`camera`], more vertices than a part
    /// holds, round the view's axis at `reach` from it, going away.
    fn small_faces(reach: f32) -> Mesh {
        let mut mesh = Mesh::default();
        for k in 0..3 * PART / 2 {
            let t = k as f32 / PART as f32;
            let p = Vec3::new(t.sin() * reach, t.cos() * reach, 2.0 + t);
            mesh.push_triangle(
                [p, p + Vec3::X * 0.01, p + Vec3::Y * 0.01],
                -Vec3::Z,
                Vec3::ONE,
            );
        }
        mesh
    }

    #[test]
    fn vertices_prepared_in_parts_are_those_prepared_in_one() {
        // More vertices than a part holds, in view and then partly behind the
        // camera, prepared in one go and in parts run in the other order.
        struct Backwards;
        impl Join for Backwards {
            fn join<A: FnOnce() + Send, B: FnOnce() + Send>(&self, a: A, b: B) {
                b();
                a();
            }
        }
        let camera = camera();
        let mut mesh = small_faces(0.8);
        let seen = |mesh: &Mesh, split: bool| {
            let mut v = Vertices::default();
            v.draw_as(Primitive::Polygons);
            match split {
                false => v.prepare(mesh, &camera),
                true => v.prepare_split(mesh, &camera, &Backwards),
            }
            let screen: Vec<_> = v.screen.iter().map(|s| [s.x, s.y, s.zinv]).collect();
            let kept = v.keeps_camera_space();
            let camera_space = kept.then(|| v.camera_space.clone());
            (camera_space, kept, screen, v.fit.in_front, v.fit.inside)
        };
        let whole = seen(&mesh, false);
        // In view: projected, and nothing kept in camera space.
        assert_eq!((whole.1, whole.2.len()), (false, mesh.positions.len()));
        assert_eq!(seen(&mesh, true), whole);
        let last = mesh.positions.len() - 1;
        mesh.positions[last].z = -1.0;
        let behind = seen(&mesh, false);
        assert!(behind.1);
        assert!(behind.2.is_empty() && !behind.3 && !behind.4);
        assert_eq!(seen(&mesh, true), behind);
    }

    #[test]
    fn places_made_in_the_projecting_pass_are_the_rasterizers_own() {
        // More vertices than a part holds, so that the parts are placed apart,
        // over the whole 100 x 100 image.
        let camera = camera();
        let mesh = small_faces(0.9);
        let viewport = Viewport::of(&camera);
        let both = [SharedPlacing::Rows, SharedPlacing::Edge];
        for placing in both {
            let mut v = Vertices::default();
            v.draw_as(Primitive::Polygons);
            v.place_as(Some(placing));
            v.prepare_split(&mesh, &camera, &InTurn);
            let want: Vec<(i32, i32)> = (v.screen.iter())
                .map(|s| match placing {
                    SharedPlacing::Rows => RowRaster.place(s.x, s.y, &viewport),
                    SharedPlacing::Edge => EdgeRaster.place(s.x, s.y, &viewport),
                })
                .collect();
            assert_eq!(want.len(), mesh.positions.len());
            assert_eq!(v.places(placing), Some(&want[..]));
            let other = both[(placing == SharedPlacing::Rows) as usize];
            assert_eq!(v.places(other), None, "made as {placing:?}");
            // None for lines, nor for a mesh not wholly in view.
            v.draw_as(Primitive::Lines);
            v.prepare(&mesh, &camera);
            assert_eq!(v.places(placing), None);
            v.draw_as(Primitive::Polygons);
            let mut behind = mesh.clone();
            behind.positions[0].z = -1.0;
            v.prepare(&behind, &camera);
            assert_eq!(v.places(placing), None);
        }
    }

    #[test]
    fn projecting_many_points_at_a_time_gives_the_bits_of_one_at_a_time() {
        // The AVX2 and AVX-512 loops (each run here if the CPU has it) and the
        // plain one against each point projected alone: 4099 points (no
        // multiple of 16) over and around the screen, some behind the camera.
        let camera = camera();
        let camera = Camera {
            near: Some(0.1),
            ..camera
        };
        let view = (camera.projection(), camera.near, camera.screen_rect());
        let fraction = |k: usize, a: f32| (k as f32 * a).fract();
        let positions: Vec<Vec3> = (0..4099)
            .map(|k| {
                Vec3::new(
                    3.0 * fraction(k, 0.414_214) - 1.5,
                    3.0 * fraction(k, 0.732_051) - 1.5,
                    4.0 * fraction(k, 0.618_034) - 0.5,
                )
            })
            .collect();
        let alone: Vec<[u32; 3]> = positions
            .iter()
            .map(|&p| {
                let (x, y, zinv) = view.0.project_centred_or_not_finite(view.0.to_camera(p));
                [x, y, zinv].map(f32::to_bits)
            })
            .collect();
        let bits = |s: &[ScreenVertex<Nothing>]| -> Vec<[u32; 3]> {
            s.iter()
                .map(|s| [s.x, s.y, s.zinv].map(f32::to_bits))
                .collect()
        };
        let n = positions.len();
        let (mut screen, mut rows) = (vec![ScreenVertex::default(); n], vec![]);
        let fit = project_loop(&positions, (&mut [], &mut screen, &mut rows), &view);
        assert_eq!(bits(&screen), alone);
        assert!(!fit.inside && !fit.in_front);
        #[cfg(target_arch = "x86_64")]
        {
            let mut wide = |avx512: bool| {
                let mut screen = vec![ScreenVertex::default(); n];
                let out = (&mut [][..], &mut screen[..], &mut rows[..]);
                // SAFETY: the CPU has what each loop needs, as checked below.
                let fit = unsafe {
                    match avx512 {
                        true => project_part_avx512(&positions, out, &view),
                        false => project_part_avx2(&positions, out, &view),
                    }
                };
                assert_eq!(bits(&screen), alone);
                assert!(!fit.inside && !fit.in_front);
            };
            if std::arch::is_x86_feature_detected!("avx2") {
                wide(false);
            }
            if std::arch::is_x86_feature_detected!("avx512f") {
                wide(true);
            }
        }
    }

    #[test]
    fn the_fit_of_the_vertices_is_what_projecting_each_one_says() {
        // One point beside an inner triangle: on the screen's edges exactly and
        // just beyond them, on and around the near plane, on the camera plane,
        // behind, and not finite. The loop that projects them all tests without
        // a branch; each point is asked here as a corner would be.
        let camera = camera();
        let beyond = 0.5 + f32::EPSILON;
        let points = [
            (0.5, 0.5, 1.0),
            (-0.5, -0.5, 1.0),
            (beyond, 0.0, 1.0),
            (0.0, -beyond, 1.0),
            (0.0, 0.0, 0.5),
            (0.0, 0.0, 0.5 - f32::EPSILON),
            (0.0, 0.0, f32::MIN_POSITIVE),
            (0.0, 0.0, f32::MIN_POSITIVE / 2.0),
            (0.0, 0.0, 0.0),
            (0.0, 0.0, -1.0),
            (f32::NAN, 0.0, 1.0),
            (0.0, f32::INFINITY, 1.0),
            (0.0, 0.0, f32::INFINITY),
            (0.0, 0.0, f32::NAN),
            (1e30, 0.0, 1e-30),
        ];
        let mut fits = (0, 0);
        for near in [None, Some(0.5)] {
            let camera = Camera { near, ..camera };
            for p in points.map(Vec3::from) {
                let q = Vec3::new(0.0, 0.0, 2.0);
                let mut mesh = Mesh::default();
                mesh.push_triangle(
                    [q, q + Vec3::X * 0.1, q + Vec3::Y * 0.1],
                    -Vec3::Z,
                    Vec3::ONE,
                );
                mesh.push_triangle([p, q, q + Vec3::X * 0.1], -Vec3::Z, Vec3::ONE);
                let (projection, rect) = (camera.projection(), camera.screen_rect());
                let c = projection.to_camera(p);
                let in_front = c.z >= near.unwrap_or(f32::MIN_POSITIVE) && c.z.is_finite();
                let on_screen = in_front
                    && projection.project_centred(c).is_some_and(|(x, y, _)| {
                        (rect.left..=rect.right).contains(&x)
                            && (rect.top..=rect.bottom).contains(&y)
                    });
                let mut v = Vertices::default();
                v.prepare(&mesh, &camera);
                let want = (in_front || near.is_none(), on_screen);
                assert_eq!((v.fit.in_front, v.fit.inside), want, "{p:?}, near {near:?}");
                assert_eq!(
                    v.screen.len(),
                    if on_screen { mesh.positions.len() } else { 0 }
                );
                fits.0 += on_screen as usize;
                fits.1 += !on_screen as usize;
            }
        }
        // Both answers are asked about.
        assert_eq!(fits, (8, 22));
    }
}
