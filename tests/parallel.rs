//! Drawing in bands on several threads gives the image of drawing on one, byte
//! for byte, whatever the number of threads, the stage or the rasterizer: with
//! the mesh wholly in view (each band passes over the triangles outside its
//! rows), partly out of it (every band looks at every triangle), and with a
//! million triangles; and the same bands drawn one after the other on one
//! thread, as the threads bench measures what the split costs.

use rasterlab::app::figure::Inputs;
use rasterlab::app::figure::Raster;
use rasterlab::app::parallel::Parallel;
use rasterlab::app::Settings;
use rasterlab::scene::parse_scene;
use rasterlab::{Figure, Frame, StageName};

#[test]
fn one_two_and_seven_threads_draw_the_same_bytes() {
    let sphere = parse_scene("sphere:100000").unwrap();
    let box_ = parse_scene("cornell").unwrap();
    let million = parse_scene("cornell:183").unwrap();
    let lit_and_depth = [
        Figure::of(StageName::Depth),
        Figure::of(StageName::PixelLight),
    ];
    let settings = Settings {
        camera: rasterlab::Camera {
            focal: 240.0,
            ..rasterlab::Camera::handout(320, 241) // bands of unequal height
        },
        ..Settings::default()
    };
    let handout = settings.camera.position;
    for (scene, position, yaw, in_view, figures) in [
        (&box_, handout, 0.0, true, &Figure::FIGURES[..]),
        (
            &sphere,
            glam::Vec3::new(0.0, 0.0, -2.5),
            0.0,
            true,
            &Figure::FIGURES,
        ),
        (
            &sphere,
            glam::Vec3::new(0.8, 0.3, -1.6),
            20.0,
            false,
            &Figure::FIGURES,
        ),
        (&million, handout, 0.0, true, &lit_and_depth),
    ] {
        let s = Settings {
            camera: rasterlab::Camera {
                position,
                yaw: f32::to_radians(yaw),
                ..settings.camera
            },
            ..settings
        };
        let (camera, uniforms) = (s.camera, Inputs::lit(s.light));
        for &figure in figures {
            for raster in [Raster::Rows, Raster::Edge] {
                let figure = figure.with_raster(raster);
                // On the threads, or (`in_turn`) the same bands one after the other.
                let draw = |threads: usize, in_turn: bool| {
                    let mut p = Parallel::new(figure, &scene.mesh, threads).unwrap();
                    let mut frame = Frame::default();
                    if in_turn {
                        p.render_in_turn(&uniforms, &scene.mesh, &camera, &mut frame)
                    } else {
                        p.render(&uniforms, &scene.mesh, &camera, &mut frame)
                    }
                    (frame, p.stats())
                };
                let (one, stats) = draw(1, false);
                // In view, each band passes over the triangles outside its rows.
                assert_eq!(stats.view_tests_skipped, in_view, "{}", scene.name);
                // Something was drawn (the box's points light 18 pixels): equal
                // black frames would prove nothing.
                let drawn = one.color.iter().filter(|&&c| c != 0).count();
                assert!(
                    drawn >= 10 && stats.pixels_written > 0,
                    "{} {}: {drawn} pixels drawn",
                    scene.name,
                    figure.label()
                );
                for (threads, in_turn) in [(2, false), (7, false), (2, true), (7, true)] {
                    let (many, many_stats) = draw(threads, in_turn);
                    assert!(
                        one.color == many.color,
                        "{} {}: {threads} threads, in turn: {in_turn}",
                        scene.name,
                        figure.label()
                    );
                    assert_eq!(stats, many_stats, "{} {}", scene.name, figure.label());
                }
            }
        }
    }
}

/// A band passes over groups of faces by the rows of the vertices they name,
/// found once per mesh: a mesh whose faces name vertices all over it, and a
/// prefix of the faces of the mesh the bands were made for (as `animate` draws),
/// still give one thread's bytes and counts.
#[test]
fn scattered_faces_and_a_prefix_of_the_faces_draw_the_same_bytes() {
    let grid = parse_scene("cornell:40").unwrap().mesh;
    let mut scattered = grid.clone();
    let n = grid.faces.len();
    // Face i takes face 7919 i mod n (a prime not dividing n, so each face once):
    // neighbours in the list lie far apart.
    assert_ne!(n % 7919, 0);
    for (i, face) in scattered.faces.iter_mut().enumerate() {
        *face = grid.faces[i * 7919 % n];
    }
    let mut prefix = grid.clone();
    prefix.faces.truncate(n * 2 / 5);
    let camera = rasterlab::Camera {
        focal: 240.0,
        ..rasterlab::Camera::handout(300, 257)
    };
    let uniforms = Inputs::lit(Settings::default().light);
    for figure in [
        Figure::of(StageName::Depth),
        Figure::of(StageName::PixelLight).with_raster(Raster::Edge),
    ] {
        for (made_for, drawn) in [(&scattered, &scattered), (&grid, &prefix)] {
            let draw = |threads: usize| {
                let mut p = Parallel::new(figure, made_for, threads).unwrap();
                let mut frame = Frame::default();
                p.render(&uniforms, drawn, &camera, &mut frame);
                (frame, p.stats())
            };
            let (one, stats) = draw(1);
            assert!(
                stats.view_tests_skipped && stats.pixels_written > 10_000,
                "{stats:?}"
            );
            assert_eq!(stats.triangles, drawn.faces.len() as u64);
            for threads in [2, 3] {
                let (many, many_stats) = draw(threads);
                assert!(
                    one.color == many.color,
                    "{}: {threads} threads",
                    figure.label()
                );
                assert_eq!(stats, many_stats, "{}", figure.label());
            }
        }
    }
}
