//! Finding the camera of a screenshot taken after walking around (issue #22):
//! the pose (position, yaw, pitch) whose view of the box puts each wall's
//! colour where the screenshot has it.
//!
//! The score of a pose is the share of sampled pixels that agree with the depth
//! stage's flat colours drawn from it: both black, or both lit with the same
//! chromaticity (the colour over its largest channel, within 0.2), which light
//! scales but does not change, so one score serves every filled stage, lit or
//! not.
//!
//! A pose is searched as an orbit about the box's centre: where the centre is
//! seen (its camera-space x/z and y/z), how far it is along the view, and the
//! yaw and pitch. Walking sideways while turning back keeps the picture almost
//! the same; in these coordinates that is one coordinate (the turn with the
//! centre held in place), so a search along the axes follows it.
//!
//! The search starts from the given pose and a grid of 1,800 orbits (8
//! distances, 5 yaws, 3 pitches, the centre at 15 places), drawn at about 160
//! pixels on the image's shorter side; the best few are refined by a pattern
//! search there, and the best of those again at each finer size up to the
//! image's own, where the steps end at 0.001 units and 1/64 degree; a last
//! pattern search then moves along the camera's own position, yaw and pitch,
//! where an orbit's coordinates bend (the box's centre far aside). That grid
//! holds cameras that stepped back and turned a little; where its best pose
//! leaves walls out of place, a second grid of 6,075 places and turns a walk
//! reaches (up to past the box's centre, 60 degrees aside, 24 up or down),
//! drawn at about 80 pixels, is searched the same way. A search whose best pose
//! is far from explaining the screenshot before its full size stops there
//! (`LEAST_TO_REFINE`): an image that is not of the box is not refined.

use crate::pipeline::target::unpack;
use crate::pipeline::{Camera, Depth, Frame, Mesh, Nothing, Pipeline};
use crate::scene::cornell_box;
use glam::Vec3;

/// A fitted pose and its score (the share of pixels that agree).
#[derive(Clone, Copy, Debug)]
pub struct Pose {
    pub camera: Camera,
    pub score: f64,
}

/// The colour over its largest channel; `None` for black.
fn chroma(c: u32) -> Option<[f32; 3]> {
    let p = unpack(c).map(|v| v as f32);
    let m = p[0].max(p[1]).max(p[2]);
    (m >= 8.0).then(|| p.map(|v| v / m))
}

fn agree(a: Option<[f32; 3]>, b: Option<[f32; 3]>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => (0..3).all(|k| (a[k] - b[k]).abs() <= 0.2),
        _ => false,
    }
}

/// How many of the best starting poses are refined.
const STARTS: usize = 4;

/// The shorter side, in pixels, of the images the grid is drawn at.
const COARSE_SIDE: u32 = 160;

/// An orbit: the box centre's camera-space x/z and y/z, its distance along
/// the view, then yaw and pitch in degrees.
type Orbit = [f32; 5];

/// The first steps of the pattern search, per coordinate of an [`Orbit`].
const FIRST_STEPS: Orbit = [0.05, 0.05, 0.25, 4.0, 4.0];

/// The camera an orbit describes, with `base`'s image size and focal length.
fn camera_of(p: Orbit, base: &Camera) -> Camera {
    let mut camera = Camera {
        yaw: p[3].to_radians(),
        pitch: p[4].to_radians(),
        ..*base
    };
    // The centre at (a d, b d, d) in camera space: C = -(that, in world axes).
    let [right, down, forward] = camera.axes();
    let centre = Vec3::new(p[0] * p[2], p[1] * p[2], p[2]);
    camera.position = -(right * centre.x + down * centre.y + forward * centre.z);
    camera
}

/// A camera's place and turns: its position's x, y and z, then yaw and pitch
/// in degrees.
type Place = [f32; 5];

/// The first steps of the last pattern search, in a [`Place`]'s coordinates.
const PLACE_STEPS: Place = [0.02, 0.02, 0.02, 0.5, 0.5];

/// The camera at `place`, with `base`'s image size and focal length.
fn camera_at(place: Place, base: &Camera) -> Camera {
    Camera {
        position: Vec3::new(place[0], place[1], place[2]),
        yaw: place[3].to_radians(),
        pitch: place[4].to_radians(),
        ..*base
    }
}

/// The place of a camera (inverse of [`camera_at`]).
fn place_of(camera: &Camera) -> Place {
    let p = camera.position;
    [
        p.x,
        p.y,
        p.z,
        camera.yaw.to_degrees(),
        camera.pitch.to_degrees(),
    ]
}

/// The orbit of a camera (inverse of [`camera_of`]).
fn orbit_of(camera: &Camera) -> Orbit {
    let c = camera.to_camera(Vec3::ZERO);
    let d = if c.z.abs() < 1e-3 { 1e-3 } else { c.z };
    [
        c.x / d,
        c.y / d,
        d,
        camera.yaw.to_degrees(),
        camera.pitch.to_degrees(),
    ]
}

/// Hooke and Jeeves' pattern search, maximising `score` from `start`: each
/// coordinate up and down by its step, then a jump on along the way the pose
/// moved while that helps; the steps halve when nothing helps, `halvings` times.
fn refine(
    start: (Orbit, f64),
    steps: Orbit,
    halvings: u32,
    score: &dyn Fn(Orbit) -> f64,
) -> (Orbit, f64) {
    let explore = |from: (Orbit, f64), steps: &Orbit| {
        let mut best = from;
        for k in 0..5 {
            for sign in [1.0, -1.0] {
                let mut p = best.0;
                p[k] += sign * steps[k];
                let e = score(p);
                if e > best.1 + 1e-9 {
                    best = (p, e);
                    break;
                }
            }
        }
        best
    };
    let mut base = start;
    let mut steps = steps;
    let mut left = halvings;
    loop {
        let mut next = explore(base, &steps);
        if next.1 <= base.1 + 1e-9 {
            if left == 0 {
                return base;
            }
            left -= 1;
            for s in &mut steps {
                *s /= 2.0;
            }
            continue;
        }
        loop {
            let jump: Orbit = std::array::from_fn(|k| 2.0 * next.0[k] - base.0[k]);
            base = next;
            let beyond = explore((jump, score(jump)), &steps);
            if beyond.1 > base.1 + 1e-9 {
                next = beyond;
            } else {
                break;
            }
        }
    }
}

/// How far, in pixels of a level, a wall drawn where the screenshot has
/// another still earns part of a pixel: the score falls off linearly over it,
/// so a wall a few pixels out of place is nearer than one far out, and the
/// search has a slope to climb where a plain count of agreeing pixels is flat.
const REACH: f32 = 6.0;

/// Nelder and Mead's simplex search, maximising `score` from `start` with a
/// first simplex of `steps` along each coordinate, for at most `budget`
/// scores: it turns along a ridge where moves along the axes stall.
fn simplex(
    start: (Orbit, f64),
    steps: Orbit,
    budget: usize,
    score: &dyn Fn(Orbit) -> f64,
) -> (Orbit, f64) {
    let mut points: Vec<(Orbit, f64)> = vec![start];
    for k in 0..5 {
        let mut p = start.0;
        p[k] += steps[k];
        points.push((p, score(p)));
    }
    let mut used = 5;
    let along = |a: &Orbit, b: &Orbit, t: f32| -> Orbit {
        std::array::from_fn(|k| a[k] + t * (b[k] - a[k]))
    };
    while used < budget {
        points.sort_by(|a, b| b.1.total_cmp(&a.1));
        let worst = points[5];
        let centre: Orbit =
            std::array::from_fn(|k| points[..5].iter().map(|p| p.0[k]).sum::<f32>() / 5.0);
        let reflected = along(&centre, &worst.0, -1.0);
        let r = score(reflected);
        used += 1;
        if r > points[0].1 {
            let expanded = along(&centre, &worst.0, -2.0);
            let e = score(expanded);
            used += 1;
            points[5] = if e > r { (expanded, e) } else { (reflected, r) };
        } else if r > points[4].1 {
            points[5] = (reflected, r);
        } else {
            let contracted = along(&centre, &worst.0, 0.5);
            let c = score(contracted);
            used += 1;
            if c > worst.1 {
                points[5] = (contracted, c);
            } else {
                let best = points[0].0;
                for p in &mut points[1..] {
                    p.0 = along(&best, &p.0, 0.5);
                    p.1 = score(p.0);
                }
                used += 5;
            }
        }
    }
    points
        .into_iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("six points")
}

/// The screenshot as seen at one size: for each class of colour (black, then
/// each of the box's chromaticities), how far each pixel of an image `scale`
/// times smaller is from the nearest pixel of that class.
struct Level {
    /// How many times smaller than the screenshot.
    scale: f32,
    camera: Camera,
    /// Per class, per pixel: the distance in pixels, at most [`REACH`]; made
    /// when first asked for ([`Level::near`]), as a search may stop before
    /// the screenshot's full size.
    near: std::sync::OnceLock<Vec<Vec<f32>>>,
    /// Per pixel: its class, if any.
    class: Vec<Option<u8>>,
    /// How many classes there are.
    classes: usize,
}

/// The classes of colour a drawn or seen pixel can be: black, or like one of
/// the box's materials.
pub(super) struct Classes(Vec<[f32; 3]>);

impl Classes {
    pub(super) fn of(mesh: &crate::pipeline::Mesh) -> Classes {
        let mut out: Vec<[f32; 3]> = Vec::new();
        for m in &mesh.materials {
            let c = chroma(crate::pipeline::target::pack(m.color)).unwrap_or([0.0; 3]);
            if !out.iter().any(|&o| agree(Some(o), Some(c))) {
                out.push(c);
            }
        }
        Classes(out)
    }

    /// 0 for black, 1 + k for the k-th chromaticity, `None` for neither.
    fn class(&self, c: u32) -> Option<u8> {
        match chroma(c) {
            None => Some(0),
            seen => (self.0.iter().position(|&o| agree(Some(o), seen))).map(|k| k as u8 + 1),
        }
    }

    /// Whether `c` is like one of the materials that are not grey (one
    /// channel well below the largest): the walls a desktop rarely has.
    pub(super) fn coloured(&self, c: u32) -> bool {
        match self.class(c) {
            Some(k) if k > 0 => self.0[k as usize - 1].iter().any(|&v| v < 0.5),
            _ => false,
        }
    }

    fn len(&self) -> usize {
        self.0.len() + 1
    }
}

impl Level {
    fn new(observed: &Frame, start: &Camera, scale: u32, classes: &Classes) -> Level {
        // The focal length is each pose's own, divided by `scale` as drawn.
        let camera = Camera {
            width: (start.width / scale).max(1),
            height: (start.height / scale).max(1),
            ..*start
        };
        // Pixel i's centre, measured from the small image's centre, scaled up
        // and measured from the screenshot's.
        let full = |i: u32, small: u32, big: u32| {
            let at = (i as f32 + 0.5 - (small / 2) as f32) * scale as f32 + (big / 2) as f32;
            (at.max(0.0) as u32).min(big - 1)
        };
        let (w, h) = (camera.width as usize, camera.height as usize);
        let mut class = Vec::with_capacity(w * h);
        for j in 0..camera.height {
            let y = full(j, camera.height, observed.height);
            for i in 0..camera.width {
                let x = full(i, camera.width, observed.width);
                class.push(classes.class(observed.color[(y * observed.width + x) as usize]));
            }
        }
        Level {
            scale: scale as f32,
            camera,
            near: std::sync::OnceLock::new(),
            class,
            classes: classes.len(),
        }
    }

    /// Per class, per pixel: the distance in pixels to the nearest pixel of
    /// that class, at most [`REACH`].
    fn near(&self) -> &[Vec<f32>] {
        self.near.get_or_init(|| {
            let (w, h) = (self.camera.width as usize, self.camera.height as usize);
            (0..self.classes)
                .map(|k| distances(&self.class, w, h, k as u8))
                .collect()
        })
    }
}

/// The chamfer distance (1 along a row or column, 1.4 diagonally) from each
/// pixel to the nearest of class `k`, at most [`REACH`].
fn distances(class: &[Option<u8>], w: usize, h: usize, k: u8) -> Vec<f32> {
    let mut d: Vec<f32> = class
        .iter()
        .map(|&c| if c == Some(k) { 0.0 } else { REACH })
        .collect();
    let (straight, diagonal) = (1.0f32, std::f32::consts::SQRT_2);
    for y in 0..h {
        for x in 0..w {
            let mut v = d[y * w + x];
            if x > 0 {
                v = v.min(d[y * w + x - 1] + straight);
            }
            if y > 0 {
                v = v.min(d[(y - 1) * w + x] + straight);
                if x > 0 {
                    v = v.min(d[(y - 1) * w + x - 1] + diagonal);
                }
                if x + 1 < w {
                    v = v.min(d[(y - 1) * w + x + 1] + diagonal);
                }
            }
            d[y * w + x] = v;
        }
    }
    for y in (0..h).rev() {
        for x in (0..w).rev() {
            let mut v = d[y * w + x];
            if x + 1 < w {
                v = v.min(d[y * w + x + 1] + straight);
            }
            if y + 1 < h {
                v = v.min(d[(y + 1) * w + x] + straight);
                if x + 1 < w {
                    v = v.min(d[(y + 1) * w + x + 1] + diagonal);
                }
                if x > 0 {
                    v = v.min(d[(y + 1) * w + x - 1] + diagonal);
                }
            }
            d[y * w + x] = v.min(REACH);
        }
    }
    d
}

/// The share of `observed`'s pixels whose class of colour (black, or like one
/// of the box's walls) is the one the depth stage draws there from `camera`:
/// 1 when every wall is where the screenshot has it, whatever the light.
pub fn walls_in_place(observed: &Frame, camera: &Camera) -> f64 {
    let mesh = cornell_box();
    let classes = Classes::of(&mesh);
    let mut drawn = Frame::default();
    Pipeline::<_>::new().render(&Depth, &mesh, camera, &mut drawn);
    let same = drawn
        .color
        .iter()
        .zip(&observed.color)
        .filter(|&(&d, &o)| classes.class(d) == classes.class(o))
        .count();
    same as f64 / observed.color.len().max(1) as f64
}

/// The share of pixels whose walls a pose must put in place to be taken for the
/// screenshot's; the walked-around screenshots tried get 99.7 % and more.
pub const MIN_POSE_SCORE: f64 = 0.97;

/// The pose that best explains `observed`, searched from `start` (whose image
/// size is kept) with each of `focals`: each one gets the coarse grid and the
/// best starts of all are refined. The coarse grid can settle on a focal length
/// whose poses only look right at low resolution (a 640x480 window drawn with
/// f = 480 taken at f = 640); when the pose found is below [`MIN_POSE_SCORE`],
/// each other focal length is searched on its own and the best full-size score
/// kept. A pose found with another focal length than the first (the image's
/// height, as the handout sets it) is held against the first searched alone,
/// which wins a tie: a nearby focal length and distance frame the box almost
/// alike (480 x 480 drawn with f = 480 from z = -3.4 is f = 500 from z = -3.51
/// to 99.2 % of its walls' pixels), and only the full-size score tells them apart.
/// Where that leaves walls out of place ([`CLOSE_POSE_SCORE`]), the places
/// a walk reaches ([`Grid::Walked`]) are searched too, and the better pose kept.
pub fn fit_pose(observed: &Frame, start: Camera, focals: &[f32]) -> Pose {
    let mut pose = search(observed, start, focals, Grid::Orbits);
    // The focal lengths whose best pose is known: none searched twice.
    let mut tried = vec![pose.camera.focal];
    if let Some(&first) = focals.first().filter(|&&f| f != pose.camera.focal) {
        let alone = search(observed, start, &[first], Grid::Orbits);
        tried.push(first);
        if alone.score >= pose.score {
            pose = alone;
        }
    }
    if pose.score < MIN_POSE_SCORE {
        for f in focals.iter().filter(|f| !tried.contains(f)) {
            let alone = search(observed, start, std::slice::from_ref(f), Grid::Orbits);
            if alone.score > pose.score {
                pose = alone;
            }
        }
    }
    if pose.score < CLOSE_POSE_SCORE {
        let walked = search(observed, start, focals, Grid::Walked);
        if walked.score > pose.score {
            pose = walked;
        }
    }
    pose
}

/// The share of pixels below which a pose found from [`Grid::Orbits`] is
/// searched for again from [`Grid::Walked`]: every render from a pose either
/// grid reaches scores above it (a fitted camera misplaces edges by a fraction
/// of a pixel), and a pose caught on the wrong side of a wall below it.
const CLOSE_POSE_SCORE: f64 = 0.995;

/// [`Grid::Walked`]'s places: from in front of the box to past its centre,
/// across it, and up and down.
const WALKED_Z: [f32; 9] = [-4.5, -3.5, -2.75, -2.0, -1.5, -1.0, -0.5, 0.0, 0.4];
const WALKED_X: [f32; 5] = [-0.7, -0.35, 0.0, 0.35, 0.7];
const WALKED_Y: [f32; 3] = [-0.5, 0.0, 0.5];
/// [`Grid::Walked`]'s turns and tilts, in degrees.
const WALKED_YAWS: [f32; 9] = [-60.0, -45.0, -30.0, -15.0, 0.0, 15.0, 30.0, 45.0, 60.0];
const WALKED_PITCHES: [f32; 5] = [-24.0, -12.0, 0.0, 12.0, 24.0];

/// Where a search starts.
#[derive(Clone, Copy)]
enum Grid {
    /// The given pose and 1,800 orbits around the box (stepped back, turned
    /// by up to 20 degrees).
    Orbits,
    /// The places and turns of a walk: cameras from z = -4.5, in front of
    /// the box, to 0.4, past its centre, across it, turned by up to 60
    /// degrees and tilted by up to 24.
    Walked,
}

impl Grid {
    /// The poses a search scores first, as orbits.
    fn poses(self, start: &Camera) -> Vec<Orbit> {
        let mut out = Vec::new();
        match self {
            Grid::Orbits => {
                out.push(orbit_of(start));
                for d in [4.0, 4.5, 5.0, 6.0, 7.0, 9.0, 12.0, 16.0] {
                    for yaw in [-20.0, -10.0, 0.0, 10.0, 20.0] {
                        for pitch in [-8.0, 0.0, 8.0] {
                            for a in [-0.3, -0.15, 0.0, 0.15, 0.3] {
                                for b in [-0.15, 0.0, 0.15] {
                                    out.push([a, b, d, yaw, pitch]);
                                }
                            }
                        }
                    }
                }
            }
            // The box's centre may be behind a camera (one that walked into
            // the box), but not level with it, where an orbit is undefined.
            Grid::Walked => {
                let places = WALKED_Z.iter().flat_map(|&z| {
                    (WALKED_X.iter()).flat_map(move |&x| WALKED_Y.map(|y| [x, y, z]))
                });
                let turns = WALKED_YAWS
                    .iter()
                    .flat_map(|&yaw| WALKED_PITCHES.map(|p| (yaw, p)));
                for [x, y, z] in places {
                    for (yaw, pitch) in turns.clone() {
                        let orbit = orbit_of(&camera_at([x, y, z, yaw, pitch], start));
                        if orbit[2].abs() >= 0.2 {
                            out.push(orbit);
                        }
                    }
                }
            }
        }
        out
    }

    /// The shorter side, in pixels, of the images the poses are scored at:
    /// [`Grid::Walked`] has more than twice as many, drawn at half the size.
    fn side(self) -> u32 {
        match self {
            Grid::Orbits => COARSE_SIDE,
            Grid::Walked => COARSE_SIDE / 2,
        }
    }

    /// How many of the best poses are refined: [`Grid::Walked`]'s steps are
    /// coarser, so the pose sought is further from its best ones.
    fn refined(self) -> usize {
        match self {
            Grid::Orbits => STARTS,
            Grid::Walked => 4 * STARTS,
        }
    }

    /// The sizes of the simplexes that end a search, in the last steps of
    /// the pattern search: near the box a step moves the picture more, and
    /// [`Grid::Walked`]'s last, smaller simplex settles what its first two
    /// leave a step away.
    fn simplex_sizes(self) -> &'static [f32] {
        match self {
            Grid::Orbits => &[16.0, 4.0],
            Grid::Walked => &[16.0, 4.0, 1.0],
        }
    }
}

/// The score below which a search stops before the screenshot's full size,
/// where most of its drawing is: the searches that went on to reach
/// [`MIN_POSE_SCORE`] had 0.977 and more there (the tests' screenshots, and
/// moved cameras from 500x500 to 1920x1080, resized or saved as JPEG down to
/// quality 25), and gained at most 0.01 at full size; the images that are not
/// of the box (a collage of figures, a heat map, a window with text over it)
/// had at most 0.93, and took 20 s to 2 min to search to the end.
const LEAST_TO_REFINE: f64 = 0.95;

/// A pipeline and the frame it draws into, drawn into again and again (a
/// search draws a few thousand poses): one for each thread.
struct Drawing {
    pipeline: Pipeline<Nothing>,
    frame: Frame,
}

impl Drawing {
    fn new() -> Drawing {
        Drawing {
            pipeline: Pipeline::new(),
            frame: Frame::default(),
        }
    }
}

/// The box, drawn by the depth stage, and the classes of its colours.
struct Scorer {
    mesh: Mesh,
    classes: Classes,
}

impl Scorer {
    /// The score of the box drawn from `p` on `level`: per pixel drawn, 1
    /// where the screenshot's pixel is of its class, falling to 0 at REACH
    /// pixels from the nearest one that is. With `count`, the plain share of
    /// pixels of the same class instead.
    fn draw_at(
        &self,
        drawing: &mut Drawing,
        level: &Level,
        p: Orbit,
        focal: f32,
        count: bool,
    ) -> f64 {
        #[cfg(test)]
        if level.scale == 1.0 {
            tests::FULL_SIZE_DRAWS.with(|n| n.set(n.get() + 1));
        }
        let at = Camera {
            focal: focal / level.scale,
            ..level.camera
        };
        let camera = camera_of(p, &at);
        let drawn = &mut drawing.frame;
        drawing.pipeline.render(&Depth, &self.mesh, &camera, drawn);
        // The depth stage draws a few flat colours: each one's class is worked
        // out once per run of it.
        let near = if count { &[][..] } else { level.near() };
        let (mut last, mut last_class) = (0u32, Some(0u8));
        let mut sum = 0.0f64;
        for (i, &c) in drawn.color.iter().enumerate() {
            if c != last {
                (last, last_class) = (c, self.classes.class(c));
            }
            sum += match last_class {
                Some(k) if count => (level.class[i] == Some(k)) as u8 as f64,
                Some(k) => (1.0 - near[k as usize][i] / REACH) as f64,
                None => 0.0,
            };
        }
        sum / level.class.len() as f64
    }
}

/// One search of [`fit_pose`] over all of `focals` at once, from `grid`. The
/// coarse grid's poses, and the refining of its best, are shared out among
/// the cores (the same poses found, in the same order, as on one).
fn search(observed: &Frame, start: Camera, focals: &[f32], grid: Grid) -> Pose {
    use rayon::prelude::*;
    let mesh = cornell_box();
    let classes = Classes::of(&mesh);
    let scorer = Scorer { mesh, classes };
    let drawing = std::cell::RefCell::new(Drawing::new());
    let draw_at = |level: &Level, p: Orbit, focal: f32, count: bool| {
        scorer.draw_at(&mut drawing.borrow_mut(), level, p, focal, count)
    };
    let score_at = |level: &Level, p: Orbit, focal: f32| draw_at(level, p, focal, false);
    let short = start.width.min(start.height);
    let mut scales = vec![1u32];
    while short / (scales[0] * 2) >= grid.side() {
        scales.insert(0, scales[0] * 2);
    }
    let levels: Vec<Level> = scales
        .iter()
        .map(|&s| Level::new(observed, &start, s, &scorer.classes))
        .collect();
    let coarse = &levels[0];
    let poses = grid.poses(&start);
    let grid_poses: Vec<(Orbit, f32)> = focals
        .iter()
        .flat_map(|&f| poses.iter().map(move |&p| (p, f)))
        .collect();
    let mut starts: Vec<(Orbit, f64, f32)> = grid_poses
        .par_iter()
        .map_init(Drawing::new, |drawing, &(p, f)| {
            (p, scorer.draw_at(drawing, coarse, p, f, false), f)
        })
        .collect();
    starts.sort_by(|a, b| b.1.total_cmp(&a.1));
    // The steps that finish one level start the next, finer one: each level
    // halves them as often as it is coarser than the last.
    let halvings = 2;
    let refined: Vec<((Orbit, f64), f32)> = starts[..grid.refined().min(starts.len())]
        .par_iter()
        .map_init(Drawing::new, |drawing, &(p, e, f)| {
            let drawing = std::cell::RefCell::new(drawing);
            let score = |p| scorer.draw_at(&mut drawing.borrow_mut(), coarse, p, f, false);
            (refine((p, e), FIRST_STEPS, halvings, &score), f)
        })
        .collect();
    let (best, focal) = refined
        .into_iter()
        .max_by(|a, b| a.0 .1.total_cmp(&b.0 .1))
        .expect("at least one start");
    let mut steps = FIRST_STEPS.map(|s| s / (1 << halvings) as f32);
    let mut best = best;
    let (full, between) = levels.split_last().expect("at least one level");
    let start = Camera { focal, ..start };
    let pose_at = |p: Orbit| Pose {
        camera: camera_of(p, &start),
        score: draw_at(full, p, focal, true),
    };
    let refine_at = |level: &Level, best: (Orbit, f64), steps: Orbit| {
        refine((best.0, score_at(level, best.0, focal)), steps, 1, &|p| {
            score_at(level, p, focal)
        })
    };
    for level in between.iter().skip(1) {
        best = refine_at(level, best, steps);
        steps = steps.map(|s| s / 2.0);
    }
    // The screenshot's full size, where most of the drawing is, only for a
    // pose that may come to explain it.
    if best.1 < LEAST_TO_REFINE {
        return pose_at(best.0);
    }
    if levels.len() > 1 {
        best = refine_at(full, best, steps);
        steps = steps.map(|s| s / 2.0);
    }
    // The last digits, on every pixel of the screenshot: down to 0.001 units.
    let left = (steps[2] / 0.001).log2().ceil().max(0.0) as u32;
    if levels.len() > 1 || left > 0 {
        best = refine((best.0, score_at(full, best.0, focal)), steps, left, &|p| {
            score_at(full, p, focal)
        });
    }
    // A simplex, restarted around its best: a fresh simplex turns to a ridge
    // the first one had flattened against.
    for &size in grid.simplex_sizes() {
        best = simplex(best, steps.map(|s| s * size), 150, &|p| {
            score_at(full, p, focal)
        });
    }
    // Last, along the camera's own position and turns: where the box's centre
    // is far aside, an orbit's coordinates bend, and a pose they leave on a
    // ridge a few hundredths of a unit away moves on along these.
    let base = Camera {
        focal,
        ..full.camera
    };
    let orbit_at = |q: Place| orbit_of(&camera_at(q, &base));
    let place = place_of(&camera_of(best.0, &base));
    let (place, score) = refine((place, best.1), PLACE_STEPS, 5, &|q| {
        score_at(full, orbit_at(q), focal)
    });
    if score > best.1 {
        best = (orbit_at(place), score);
    }
    pose_at(best.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::target::pack;

    thread_local! {
        /// Poses drawn at the screenshot's full size on this thread.
        pub(super) static FULL_SIZE_DRAWS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
    }

    /// `search` on `observed` from the handout's camera, and the poses it
    /// drew at full size.
    fn searched(observed: &Frame) -> (Pose, usize) {
        FULL_SIZE_DRAWS.with(|n| n.set(0));
        let start = Camera::handout(observed.width, observed.height);
        let pose = search(observed, start, &[start.focal], Grid::Orbits);
        (pose, FULL_SIZE_DRAWS.with(|n| n.get()))
    }

    #[test]
    fn a_moved_camera_is_refined_at_full_size() {
        let camera = Camera {
            position: Vec3::new(0.2, -0.1, -3.4),
            yaw: 6f32.to_radians(),
            ..Camera::handout(500, 500)
        };
        let mut observed = Frame::default();
        Pipeline::<_>::new().render(&Depth, &cornell_box(), &camera, &mut observed);
        let (pose, drawn) = searched(&observed);
        assert!(pose.score >= 0.995, "{pose:?}");
        assert!(
            (pose.camera.position - camera.position).length() < 0.02,
            "{pose:?}"
        );
        assert!(drawn > 100, "{drawn} poses drawn at full size");
    }

    #[test]
    fn an_image_not_of_the_box_is_not_refined() {
        // Stripes of the box's own colours, 25 pixels high: every pixel is of
        // a wall's class, but in no view's arrangement.
        let colours: Vec<u32> = cornell_box()
            .materials
            .iter()
            .map(|m| pack(m.color))
            .collect();
        let mut observed = Frame::new(500, 500);
        for (i, c) in observed.color.iter_mut().enumerate() {
            *c = colours[(i / 500 / 25) % colours.len()];
        }
        let (pose, drawn) = searched(&observed);
        assert!(pose.score < LEAST_TO_REFINE, "{pose:?}");
        assert_eq!(drawn, 1, "only the pose returned is drawn at full size");
    }
}
