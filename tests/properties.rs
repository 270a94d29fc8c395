//! Property tests: random triangles and cameras, including degenerate triangles and
//! triangles behind or through the camera, never panic, never write outside the
//! frame, never leave NaN in the depth buffer; closed meshes have no cracks; the
//! same input always gives the same bytes.

use glam::Vec3;
use proptest::prelude::*;
use rasterlab::app::figure::Inputs;
use rasterlab::pipeline::Target;
use rasterlab::{Camera, Figure, Frame, Light, Mesh, StageName, Triangle};

fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -3.0f32..3.0,
        1 => Just(0.0f32),
        1 => -1e-6f32..1e-6,
        1 => -1e4f32..1e4,
    ]
}

fn vec3() -> impl Strategy<Value = Vec3> {
    (coord(), coord(), coord()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn triangle() -> impl Strategy<Value = Triangle> {
    prop_oneof![
        3 => (vec3(), vec3(), vec3()).prop_map(|(a, b, c)| Triangle::new(a, b, c, Vec3::new(0.7, 0.4, 0.2))),
        // Degenerate: a repeated vertex, or three points on a line.
        1 => (vec3(), vec3()).prop_map(|(a, b)| Triangle::new(a, b, a, Vec3::ONE)),
        1 => (vec3(), vec3(), 0.0f32..1.0).prop_map(|(a, b, t)| Triangle::new(a, b, a + (b - a) * t, Vec3::ONE)),
    ]
}

fn camera() -> impl Strategy<Value = Camera> {
    (
        vec3(),
        -180.0f32..180.0,
        -89.0f32..89.0,
        1.0f32..2000.0,
        1u32..64,
        1u32..64,
        prop::bool::ANY,
    )
        .prop_map(
            |(position, yaw, pitch, focal, width, height, clip)| Camera {
                position,
                yaw: yaw.to_radians(),
                pitch: pitch.to_radians(),
                focal,
                width,
                height,
                near: clip.then_some(0.01),
            },
        )
}

fn view() -> impl Strategy<Value = Figure> {
    prop::sample::select(Figure::FIGURES.to_vec())
}

fn uniforms() -> Inputs<'static> {
    Inputs::lit(Light::handout())
}

fn draw(view: Figure, scene: &[Triangle], camera: &Camera) -> Frame {
    view.render(&Mesh::from_triangles(scene), camera, Light::handout())
}

/// The same image drawn as two bands of rows, split at row `split`, each into
/// buffers of its own: what a thread drawing half the image would do.
fn draw_in_bands(view: Figure, scene: &[Triangle], camera: &Camera, split: u32) -> Frame {
    let mesh = Mesh::from_triangles(scene);
    let mut whole = Frame::default();
    let mut pipeline = view.pipeline_for(&mesh);
    pipeline.render(&uniforms(), &mesh, camera, &mut whole); // sizes the buffers
    let (w, h) = (camera.width, camera.height);
    let split = split.min(h);
    let has_depth = !whole.depth.is_empty();
    let n = (w * split) as usize;
    let (color_top, color_bottom) = whole.color.split_at_mut(n);
    let mut depth = whole.depth.clone();
    let (depth_top, depth_bottom) = depth.split_at_mut(if has_depth { n } else { 0 });
    for (rows, color, depth) in [
        (0..split, color_top, depth_top),
        (split..h, color_bottom, depth_bottom),
    ] {
        color.fill(0x00ab_cdef); // anything: the draw must clear its band
        let mut target = Target {
            width: w,
            height: h,
            rows,
            color: Some(color),
            depth: has_depth.then_some(depth),
        };
        pipeline.draw(&uniforms(), &mesh, camera, &mut target);
    }
    whole.depth = depth;
    whole
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn random_scenes_draw_safely_and_bands_agree(
        scene in prop::collection::vec(triangle(), 1..6),
        camera in camera(),
        view in view(),
        split in 0u32..64,
    ) {
        // An out-of-bounds write would panic on indexing.
        let frame = draw(view, &scene, &camera);
        prop_assert!(frame.depth.iter().all(|z| !z.is_nan()));
        // Two bands of rows drawn on their own make the same image, colour and depth.
        let banded = draw_in_bands(view, &scene, &camera, split);
        prop_assert_eq!(&frame.color, &banded.color);
        prop_assert_eq!(
            frame.depth.iter().map(|z| z.to_bits()).collect::<Vec<_>>(),
            banded.depth.iter().map(|z| z.to_bits()).collect::<Vec<_>>()
        );
    }

    /// Drawing depends on nothing but its input: not on what the frame held before,
    /// nor on what the pipeline drew last, nor on the thread it runs on.
    #[test]
    fn drawing_is_deterministic(
        scene in prop::collection::vec(triangle(), 1..4),
        other in prop::collection::vec(triangle(), 1..4),
        camera in camera(),
        view in view(),
    ) {
        let fresh = draw(view, &scene, &camera);
        let (mesh, other) = (Mesh::from_triangles(&scene), Mesh::from_triangles(&other));
        let reused = std::thread::scope(|s| {
            s.spawn(|| {
                let mut pipeline = view.pipeline_for(&mesh);
                let mut frame = Frame::default();
                let mut bigger = camera;
                bigger.width += 7;
                pipeline.render(&uniforms(), &other, &bigger, &mut frame);
                pipeline.render(&uniforms(), &mesh, &camera, &mut frame);
                frame
            })
            .join()
            .unwrap()
        });
        prop_assert_eq!(fresh.color, reused.color);
    }

    /// A cube seen from outside covers its silhouette without holes: every pixel
    /// whose centre is 1.5 pixels or more inside the convex hull of the projected
    /// corners is drawn.
    #[test]
    fn a_closed_cube_has_no_cracks(
        yaw in -180.0f32..180.0,
        pitch in -80.0f32..80.0,
        distance in 2.5f32..8.0,
        size in 0.2f32..1.0,
    ) {
        let scene = cube(size);
        let (w, h) = (96u32, 96u32);
        let (sy, cy) = yaw.to_radians().sin_cos();
        let (sp, cp) = pitch.to_radians().sin_cos();
        let forward = Vec3::new(sy * cp, -sp, cy * cp);
        let camera = Camera {
            position: -forward * distance,
            yaw: yaw.to_radians(),
            pitch: pitch.to_radians(),
            focal: 96.0,
            width: w,
            height: h,
            near: Some(0.01),
        };
        let frame = draw(Figure::of(StageName::Filled), &scene, &camera);
        let p = camera.projection();
        let corners: Vec<(f32, f32)> = cube_corners(size)
            .iter()
            .map(|&v| {
                let (x, y, _) = p.project_centred(p.to_camera(v)).unwrap();
                (x + (w / 2) as f32, y + (h / 2) as f32)
            })
            .collect();
        let hull = convex_hull(corners);
        let mut checked = 0;
        for y in 0..h {
            for x in 0..w {
                let c = (x as f32 + 0.5, y as f32 + 0.5);
                if inside_by(&hull, c, 1.5) {
                    checked += 1;
                    prop_assert!(frame.color[(y * w + x) as usize] != 0, "hole at ({}, {})", x, y);
                }
            }
        }
        // The cube is at least 0.4 wide and 8 away: over 4 pixels, so some
        // pixels are always deep inside (a guard against a vacuous test).
        prop_assert!(checked > 0, "no pixel checked; hull {:?}", hull);
    }
}

fn cube_corners(s: f32) -> [Vec3; 8] {
    let mut v = [Vec3::ZERO; 8];
    for (i, c) in v.iter_mut().enumerate() {
        *c = Vec3::new(
            if i & 1 == 0 { -s } else { s },
            if i & 2 == 0 { -s } else { s },
            if i & 4 == 0 { -s } else { s },
        );
    }
    v
}

fn cube(s: f32) -> Vec<Triangle> {
    let v = cube_corners(s);
    let faces = [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ];
    faces
        .iter()
        .flat_map(|f| {
            [
                Triangle::new(v[f[0]], v[f[1]], v[f[2]], Vec3::ONE),
                Triangle::new(v[f[0]], v[f[2]], v[f[3]], Vec3::ONE),
            ]
        })
        .collect()
}

/// Andrew's monotone chain, counter-clockwise in a y-down image.
fn convex_hull(mut p: Vec<(f32, f32)>) -> Vec<(f32, f32)> {
    p.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let cross = |o: (f32, f32), a: (f32, f32), b: (f32, f32)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f32, f32)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let points: Vec<_> = if pass == 0 {
            p.clone()
        } else {
            p.iter().rev().copied().collect()
        };
        for q in points {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// Whether `c` is inside the convex polygon `hull` by at least `margin`.
fn inside_by(hull: &[(f32, f32)], c: (f32, f32), margin: f32) -> bool {
    let n = hull.len();
    n >= 3
        && (0..n).all(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % n]);
            let (ex, ey) = (b.0 - a.0, b.1 - a.1);
            let len = (ex * ex + ey * ey).sqrt();
            len > 0.0 && (ex * (c.1 - a.1) - ey * (c.0 - a.0)) / len >= margin
        })
}
