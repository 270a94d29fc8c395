//! Finding the camera of a screenshot taken after walking around (issue #22):
//! the pose (position, yaw, pitch) whose view of the box puts each wall's
//! colour where the screenshot has it.
//!
//! The score of a pose is the share of sampled pixels that agree with the depth
//! stage's flat colours drawn from it: both black, or both lit with the same
//! chromaticity (the colour over its largest channel, within 0.2), which light
//! scales but does not change, so one score serves every filled stage, lit or
//! not. The search starts from the given pose and a grid of 360 (8 distances
//! back along z, 3 places along x, 5 yaws, 3 pitches), refines the best 4 by a
//! pattern search from 0.25 units and 4 degrees down to 0.001 units and 1/64
//! degree on every third pixel, then the best of those on every pixel.

use crate::pipeline::target::unpack;
use crate::pipeline::{Camera, Depth, Frame, Pipeline};
use crate::scene::cornell_box;
use glam::Vec3;

/// Every [`STRIDE`]th pixel is scored while searching; every pixel at the end.
const STRIDE: usize = 3;

/// A fitted pose and its score (the share of sampled pixels that agree).
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

/// Hooke and Jeeves' pattern search, maximising `score` from `start`: each
/// coordinate up and down by its step (0.25 units, 4 degrees), and x with yaw
/// and y with pitch diagonally, then a jump on
/// along the way the pose moved while that helps; the steps halve when nothing
/// helps, down to 0.001 units and 1/64 degree.
fn refine(start: ([f32; 5], f64), score: &dyn Fn([f32; 5]) -> f64) -> ([f32; 5], f64) {
    // Moves along each coordinate, then along x with yaw and y with pitch
    // together: moving sideways and turning back shift the view alike, so the
    // best pose often lies along such a diagonal.
    let moves: Vec<[f32; 5]> = (0..5)
        .flat_map(|k| {
            [1.0, -1.0].map(|sign| std::array::from_fn(|i| if i == k { sign } else { 0.0 }))
        })
        .chain([(0, 3), (1, 4)].into_iter().flat_map(|(a, b)| {
            [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)].map(|(sa, sb)| {
                std::array::from_fn(|i| match i {
                    i if i == a => sa,
                    i if i == b => sb,
                    _ => 0.0,
                })
            })
        }))
        .collect();
    let explore = |from: ([f32; 5], f64), steps: &[f32; 5]| {
        let mut best = from;
        for m in &moves {
            let p: [f32; 5] = std::array::from_fn(|k| best.0[k] + m[k] * steps[k]);
            let e = score(p);
            if e > best.1 + 1e-9 {
                best = (p, e);
            }
        }
        best
    };
    let mut base = start;
    let mut steps = [0.25f32, 0.25, 0.25, 4.0, 4.0];
    while steps[0] >= 0.001 {
        let mut next = explore(base, &steps);
        if next.1 <= base.1 + 1e-9 {
            for s in &mut steps {
                *s /= 2.0;
            }
            continue;
        }
        loop {
            let jump: [f32; 5] = std::array::from_fn(|k| 2.0 * next.0[k] - base.0[k]);
            base = next;
            let beyond = explore((jump, score(jump)), &steps);
            if beyond.1 > base.1 + 1e-9 {
                next = beyond;
            } else {
                break;
            }
        }
    }
    base
}

/// The pose that best explains `observed`, searched from `start` (whose image
/// size and focal length are kept).
pub fn fit_pose(observed: &Frame, start: Camera) -> Pose {
    let seen: Vec<Option<[f32; 3]>> = observed.color.iter().map(|&c| chroma(c)).collect();
    let mesh = cornell_box();
    // One pipeline and one frame for the whole search, drawn into again and
    // again (a few thousand poses).
    let pipeline = std::cell::RefCell::new(Pipeline::<_>::new());
    let frame = std::cell::RefCell::new(Frame::default());
    let score_at = |camera: &Camera, stride: usize| -> f64 {
        let mut drawn = frame.borrow_mut();
        pipeline
            .borrow_mut()
            .render(&Depth, &mesh, camera, &mut drawn);
        let pairs = drawn.color.iter().zip(&seen).step_by(stride);
        let (mut same, mut all) = (0usize, 0usize);
        for (&c, &s) in pairs {
            same += agree(chroma(c), s) as usize;
            all += 1;
        }
        same as f64 / all as f64
    };
    let score = |camera: &Camera| score_at(camera, STRIDE);
    // Position x, y, z, then yaw and pitch in degrees.
    let pose_of = |p: [f32; 5]| Camera {
        position: Vec3::new(p[0], p[1], p[2]),
        yaw: p[3].to_radians(),
        pitch: p[4].to_radians(),
        ..start
    };
    let s = start.position;
    let given = [
        s.x,
        s.y,
        s.z,
        start.yaw.to_degrees(),
        start.pitch.to_degrees(),
    ];
    let mut starts = vec![(given, score(&start))];
    for z in [-3.001, -3.5, -4.0, -5.0, -6.0, -8.0, -11.0, -15.0] {
        for x in [-0.5, 0.0, 0.5] {
            for yaw in [-20.0, -10.0, 0.0, 10.0, 20.0] {
                for pitch in [-8.0, 0.0, 8.0] {
                    let p = [x, 0.0, z, yaw, pitch];
                    starts.push((p, score(&pose_of(p))));
                }
            }
        }
    }
    starts.sort_by(|a, b| b.1.total_cmp(&a.1));
    // The best few starts refined; the best refined pose wins.
    let best = starts
        .iter()
        .take(STARTS)
        .map(|&start| refine(start, &|p| score(&pose_of(p))))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("at least one start");
    // The last digits against every pixel.
    let best = refine((best.0, score_at(&pose_of(best.0), 1)), &|p| {
        score_at(&pose_of(p), 1)
    });
    Pose {
        camera: pose_of(best.0),
        score: best.1,
    }
}
