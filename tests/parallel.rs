//! Drawing in bands on several threads gives the image of drawing on one, byte
//! for byte, whatever the number of threads, the stage or the rasterizer.

use rasterlab::app::figure::Inputs;
use rasterlab::app::figure::Raster;
use rasterlab::app::parallel::Parallel;
use rasterlab::app::Settings;
use rasterlab::scene::parse_scene;
use rasterlab::{Figure, Frame};

#[test]
fn one_two_and_seven_threads_draw_the_same_bytes() {
    let sphere = parse_scene("sphere:100000").unwrap();
    let box_ = parse_scene("cornell").unwrap();
    let settings = Settings {
        camera: rasterlab::Camera {
            focal: 320.0,
            ..rasterlab::Camera::handout(320, 241) // bands of unequal height
        },
        ..Settings::default()
    };
    for (scene, position) in [
        (&box_, settings.camera.position),
        (&sphere, glam::Vec3::new(0.0, 0.0, -2.5)),
    ] {
        let s = Settings {
            camera: rasterlab::Camera {
                position,
                ..settings.camera
            },
            ..settings
        };
        let (camera, uniforms) = (s.camera, Inputs::lit(s.light));
        for figure in Figure::FIGURES {
            for raster in [Raster::Rows, Raster::Edge] {
                let figure = figure.with_raster(raster);
                let draw = |threads: usize| {
                    let mut p = Parallel::new(figure, &scene.mesh, threads).unwrap();
                    let mut frame = Frame::default();
                    p.render(&uniforms, &scene.mesh, &camera, &mut frame);
                    (frame, p.stats())
                };
                let (one, stats) = draw(1);
                // Something was drawn (the box's points light 18 pixels): equal
                // black frames would prove nothing.
                let drawn = one.color.iter().filter(|&&c| c != 0).count();
                assert!(
                    drawn >= 10 && stats.pixels_written > 0,
                    "{} {}: {drawn} pixels drawn",
                    scene.name,
                    figure.label()
                );
                for threads in [2, 7] {
                    let (many, many_stats) = draw(threads);
                    assert!(
                        one.color == many.color,
                        "{} {}: {threads} threads",
                        scene.name,
                        figure.label()
                    );
                    assert_eq!(stats, many_stats, "{} {}", scene.name, figure.label());
                }
            }
        }
    }
}
