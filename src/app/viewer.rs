//! `rasterlab view`: the handout's interactive program, a window that redraws the
//! scene every frame from the current camera and light (its `Update` and `Draw`
//! loop). Keys are read through [`super::controls`], so a key script replays the
//! same way a person's key presses do.

use super::controls::{self, action, pressed, Action, Controls, Key, MouseLook};
use super::image_io::write_image;
use super::parallel::Parallel;
use super::Settings;
use crate::app::figure::{Figure, Raster};
use crate::extensions::depth_of_field::DepthOfField;
use crate::extensions::shadow::Shadows;
use crate::extensions::texture::{Filter, MaterialMaps};
use crate::pipeline::Frame;
use crate::pipeline::StageName;
use crate::scene::texture::{apply_normal_map, apply_parallax, apply_texture, bumps, TextureSpec};
use crate::scene::Scene;
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How a viewer session runs.
#[derive(Clone, Debug)]
pub struct Options {
    pub settings: Settings,
    /// What the window shows, and the `--scene` spec that named it.
    pub model: Scene,
    pub scene: String,
    /// The `--texture` spec the mesh was given, if any.
    pub texture: Option<String>,
    /// The `--normal-map` spec the mesh was given, if any.
    pub normal_map: Option<String>,
    pub view: Figure,
    /// Quit after this many frames.
    pub frames: Option<u64>,
    /// Save the last frame here when quitting.
    pub screenshot: Option<PathBuf>,
    /// Keys held in each of the first frames (`--keys`); live input follows.
    pub script: Vec<Vec<Key>>,
    /// Frames per second to aim for; 0 draws as fast as possible.
    pub fps: usize,
}

/// Seconds one scripted frame advances time by, so scripts replay exactly.
pub const SCRIPT_FRAME_SECONDS: f32 = 1.0 / 60.0;
/// Frames the title's median frame time is taken over.
pub const TITLE_FRAMES: usize = 30;

/// What a session did, for the closing lines on stderr.
#[derive(Clone, Debug)]
pub struct Summary {
    pub frames: u64,
    /// Median time from one frame to the next (draw, present, waiting).
    pub frame_median: Duration,
    /// Median time spent drawing.
    pub draw_median: Duration,
    pub settings: Settings,
    pub view: Figure,
    pub scene: String,
    /// The `--texture` spec that draws the last frame's textures, if it had any
    /// that the scene alone does not give.
    pub texture: Option<String>,
    /// The same for the normal map.
    pub normal_map: Option<String>,
    /// Whether the last frame had parallax.
    pub parallax: bool,
}

impl Summary {
    /// The render command that draws the last frame again.
    pub fn reproduce(&self) -> String {
        let mut command = command_for(self.view, &self.settings);
        if self.scene != "cornell" {
            command += &format!(" --scene {}", self.scene);
        }
        let lit = self.view.stage.is_lit();
        if let (Some(texture), true) = (&self.texture, lit) {
            command += &format!(" --texture {texture}");
        }
        if let (Some(map), StageName::PixelLight) = (&self.normal_map, self.view.stage) {
            command += &format!(" --normal-map {map}");
            if self.parallax {
                command += " --parallax";
            }
        }
        if self.settings.filter == Filter::Bilinear && lit {
            command += " --filter bilinear";
        }
        command
    }
}

/// Depth of field focused on what the image's centre pixel shows (the box's back
/// wall if it shows nothing or has no depth), with a lens a fiftieth of that
/// depth wide: enough to blur the near walls of the box.
fn autofocus(frame: &Frame) -> DepthOfField {
    let centre = (frame.height / 2 * frame.width + frame.width / 2) as usize;
    let zinv = frame.depth.get(centre).copied().unwrap_or(0.0);
    let focus = if zinv > 0.0 && (1.0 / zinv).is_finite() {
        1.0 / zinv
    } else {
        4.0
    };
    DepthOfField {
        focus,
        aperture: focus / 50.0,
    }
}

/// The scene the viewer draws: `given` with its textures and its normal map each
/// toggled when asked (`t`, `n`): taken off if it had them, else the checker or
/// the bumps put on (on the room for the box).
fn toggled(
    given: &Scene,
    texture: bool,
    normal_map: bool,
    parallax: bool,
) -> Result<Scene, String> {
    let mut scene = given.clone();
    if texture {
        let had = given.maps.materials.iter().any(|m| m.texture.is_some());
        let spec = if had {
            TextureSpec::None
        } else {
            TextureSpec::Checker
        };
        apply_texture(&mut scene, &spec)?;
    }
    if normal_map {
        if given.maps.materials.iter().any(|m| m.normal_map.is_some()) {
            scene
                .maps
                .materials
                .iter_mut()
                .for_each(|m| m.normal_map = None);
        } else {
            apply_normal_map(&mut scene, bumps());
        }
    }
    // Parallax reads the bumps' heights: on when asked and the bumps are there.
    scene
        .maps
        .materials
        .iter_mut()
        .for_each(|m| m.height_map = None);
    if parallax {
        apply_parallax(&mut scene);
    }
    Ok(scene)
}

/// The angle in degrees that the command line turns back into `radians` exactly
/// (`--yaw` and `--pitch` are read in degrees): the nearest f32 to it in degrees,
/// or one a few steps away when that one rounds to a neighbour.
fn degrees_for(radians: f32) -> f32 {
    let nearest = radians.to_degrees();
    let mut candidate = nearest;
    for _ in 0..8 {
        if candidate.to_radians() == radians {
            return candidate;
        }
        let step = if candidate.to_radians() < radians {
            f32::next_up
        } else {
            f32::next_down
        };
        candidate = step(candidate);
    }
    nearest
}

/// `rasterlab <stage> [--affine] --size .. --camera ..`: every setting, written so
/// that it parses back to the same f32 values.
pub fn command_for(view: Figure, s: &Settings) -> String {
    let v = |v: glam::Vec3| format!("{},{},{}", v.x, v.y, v.z);
    let c = &s.camera;
    let mut command = format!(
        "rasterlab {}{} --size {}x{} --focal {} --camera {} --yaw {} --pitch {}",
        view.stage.name(),
        view.flags(),
        c.width,
        c.height,
        c.focal,
        v(c.position),
        degrees_for(c.yaw),
        degrees_for(c.pitch),
    );
    // Only the lit stages take the light (the others refuse options they ignore).
    if view.stage.is_lit() {
        command += &format!(
            " --light {} --light-power {} --indirect {}",
            v(s.light.position),
            s.light.power.x,
            s.light.indirect.x
        );
    }
    if let (Some(dof), true) = (s.dof, view.stage.has_depth()) {
        command += &format!(" --dof {},{}", dof.focus, dof.aperture);
    }
    match c.near {
        None => command += " --no-clip",
        Some(near) if near != crate::pipeline::camera::DEFAULT_NEAR => {
            command += &format!(" --near {near}")
        }
        Some(_) => {}
    }
    command
}

fn median(samples: impl Iterator<Item = Duration>) -> Duration {
    let v: Vec<Duration> = samples.collect();
    if v.is_empty() {
        Duration::ZERO
    } else {
        crate::measure::timing::summarize(v).median
    }
}

fn title(view: Figure, frame_times: &VecDeque<Duration>, draw: Duration) -> String {
    let interpolation = if !view.stage.interpolates() {
        "no interpolation"
    } else if view.affine {
        "affine"
    } else {
        "perspective-correct"
    };
    let raster = match view.raster {
        Raster::Rows => "rows",
        Raster::Edge => "edge",
    };
    format!(
        "rasterlab: {} ({}, {raster} rasterizer), frame {:.1} ms, draw {:.1} ms - h for keys",
        view.stage.name(),
        interpolation,
        median(frame_times.iter().copied()).as_secs_f64() * 1e3,
        draw.as_secs_f64() * 1e3
    )
}

fn to_key(k: minifb::Key) -> Option<Key> {
    use minifb::Key as M;
    let digit = |d: u8| Some(Key::Char((b'0' + d) as char));
    let index = k as u8;
    match k {
        M::Up => Some(Key::Up),
        M::Down => Some(Key::Down),
        M::Left => Some(Key::Left),
        M::Right => Some(Key::Right),
        M::PageUp => Some(Key::PageUp),
        M::PageDown => Some(Key::PageDown),
        M::Escape => Some(Key::Escape),
        // minifb numbers Key0..Key9 from 0 and A..Z right after.
        M::Key0
        | M::Key1
        | M::Key2
        | M::Key3
        | M::Key4
        | M::Key5
        | M::Key6
        | M::Key7
        | M::Key8
        | M::Key9 => digit(index - M::Key0 as u8),
        M::NumPad0 => digit(0),
        M::NumPad1 => digit(1),
        M::NumPad2 => digit(2),
        M::NumPad3 => digit(3),
        M::NumPad4 => digit(4),
        M::NumPad5 => digit(5),
        M::NumPad6 => digit(6),
        M::NumPad7 => digit(7),
        _ if (M::A as u8..=M::Z as u8).contains(&index) => {
            Some(Key::Char((b'a' + index - M::A as u8) as char))
        }
        _ => None,
    }
}

/// The first `rasterlab-<stage>-N.png` in the current folder that does not exist.
fn free_capture_path(view: Figure) -> PathBuf {
    let name = view.default_file();
    let stem = name.trim_end_matches(".png");
    (1..)
        .map(|n| PathBuf::from(format!("rasterlab-{stem}-{n}.png")))
        .find(|p| !p.exists())
        .expect("some number is free")
}

fn save(frame: &Frame, path: &Path) -> Result<(), String> {
    write_image(frame, path).map_err(|e| e.to_string())?;
    crate::say!("saved {}", path.display());
    Ok(())
}

/// Opens the window and runs until Esc, the window closing, or `frames`.
pub fn run(options: Options) -> Result<Summary, String> {
    if cfg!(target_os = "linux") && std::env::var_os("DISPLAY").is_none_or(|d| d.is_empty()) {
        return Err(
            "no display: DISPLAY is not set, so no window can open; run under a desktop or \
             `xvfb-run -a rasterlab view`, or render to files with `rasterlab all --out figures`"
                .into(),
        );
    }
    let (w, h) = (
        options.settings.camera.width as usize,
        options.settings.camera.height as usize,
    );
    let mut window = minifb::Window::new("rasterlab", w, h, minifb::WindowOptions::default())
        .map_err(|e| {
            format!(
                "cannot open a window ({e}); render to files instead with `rasterlab all --out figures`"
            )
        })?;
    window.set_target_fps(options.fps);

    // The mesh as given; `t` and `n` toggle its textures and normal map.
    let given = options.model.clone();
    let has = |pick: fn(&MaterialMaps) -> Option<u32>| {
        given.maps.materials.iter().any(|m| pick(m).is_some())
    };
    let had_texture = has(|m| m.texture);
    let had_normal_map = has(|m| m.normal_map);
    let (mut textured, mut bumped) = (had_texture, had_normal_map);
    let mut parallax = has(|m| m.height_map);
    // `g` switches between none and this: --dof's, or set at the first `g`.
    let mut dof = options.settings.dof;
    // Kept apart from the view, which drops them on stages without light.
    let mut shadows = options.view.shadows;
    let mut scene = given.clone();
    let controls = Controls::default();
    let mut settings = options.settings;
    let mut view = options.view;
    let threads = settings.threads;
    let mut pipeline = Parallel::new(view, &scene, threads)?;
    let mut frame = Frame::default();
    let mut held_before: Vec<Key> = Vec::new();
    let mut mouse = MouseLook::default();
    let mut frame_times: VecDeque<Duration> = VecDeque::with_capacity(TITLE_FRAMES);
    let (mut all_frames, mut all_draws) = (Vec::new(), Vec::new());
    let mut last_start = Instant::now();
    let mut count: u64 = 0;

    while window.is_open() && options.frames.is_none_or(|n| count < n) {
        let start = Instant::now();
        let scripted = options.script.get(count as usize);
        let (held, dt) = match scripted {
            Some(keys) => (keys.clone(), SCRIPT_FRAME_SECONDS),
            None => {
                let keys = window.get_keys().into_iter().filter_map(to_key).collect();
                let dt = if count == 0 {
                    0.0
                } else {
                    (start - last_start).as_secs_f32().min(0.1)
                };
                (keys, dt)
            }
        };
        if count > 0 {
            let ft = start - last_start;
            if frame_times.len() == TITLE_FRAMES {
                frame_times.pop_front();
            }
            frame_times.push_back(ft);
            all_frames.push(ft);
        }
        last_start = start;

        let mut quit = false;
        for key in pressed(&held, &held_before) {
            match action(key) {
                Some(Action::Show(v)) => {
                    // A figure key keeps the rasterizer, culling and shadows chosen.
                    view = v
                        .with_raster(view.raster)
                        .with_cull(view.cull)
                        .with_shadows(shadows);
                    pipeline = Parallel::new(view, &scene, threads)?;
                }
                Some(Action::TogglePerspective) => {
                    view = controls::toggle_perspective(view);
                    pipeline = Parallel::new(view, &scene, threads)?;
                }
                Some(Action::ToggleRaster) => {
                    view = controls::toggle_raster(view);
                    pipeline = Parallel::new(view, &scene, threads)?;
                }
                Some(
                    action @ (Action::ToggleTexture
                    | Action::ToggleNormalMap
                    | Action::ToggleParallax),
                ) => {
                    match action {
                        Action::ToggleTexture => textured = !textured,
                        Action::ToggleNormalMap => bumped = !bumped,
                        _ => {
                            // Parallax needs the bumps: k puts them on too.
                            parallax = !parallax;
                            bumped |= parallax;
                        }
                    }
                    parallax &= bumped;
                    scene = toggled(
                        &given,
                        textured != had_texture,
                        bumped != had_normal_map,
                        parallax,
                    )?;
                    pipeline = Parallel::new(view, &scene, threads)?;
                }
                Some(Action::CycleShadows) => {
                    shadows = match shadows {
                        Shadows::None => Shadows::Hard,
                        Shadows::Hard => Shadows::Pcf,
                        Shadows::Pcf => Shadows::None,
                    };
                    view = view.with_shadows(shadows);
                    pipeline = Parallel::new(view, &scene, threads)?;
                }
                Some(Action::ToggleDepthOfField) => {
                    if settings.dof.is_some() {
                        settings.dof = None;
                    } else {
                        let chosen = *dof.get_or_insert_with(|| autofocus(&frame));
                        settings.dof = Some(chosen);
                    }
                }
                Some(Action::ToggleFilter) => {
                    settings.filter = match settings.filter {
                        Filter::Nearest => Filter::Bilinear,
                        Filter::Bilinear => Filter::Nearest,
                    };
                }
                Some(Action::Save) => save(&frame, &free_capture_path(view))?,
                Some(Action::Help) => crate::say!("{}", controls::HELP),
                Some(Action::Quit) => quit = true,
                None => {}
            }
        }
        if quit {
            break;
        }
        held_before = held.clone();
        controls.apply_held(&held, dt, &mut settings);

        // Mouse look while the left button is held (not during a script).
        let button = scripted.is_none() && window.get_mouse_down(minifb::MouseButton::Left);
        let position = window.get_mouse_pos(minifb::MouseMode::Pass);
        if let Some((dx, dy)) = mouse.update(button, position) {
            controls.apply_mouse(dx, dy, &mut settings);
        }

        let draw_start = Instant::now();
        super::draw_frame(&mut pipeline, view, scene.model(), &settings, &mut frame);
        let draw = draw_start.elapsed();
        all_draws.push(draw);
        window
            .update_with_buffer(&frame.color, w, h)
            .map_err(|e| format!("cannot update the window: {e}"))?;
        if count.is_multiple_of(10) {
            window.set_title(&title(view, &frame_times, draw));
        }
        count += 1;
    }
    if let Some(path) = &options.screenshot {
        save(&frame, path)?;
    }
    Ok(Summary {
        frames: count,
        frame_median: median(all_frames.into_iter()),
        draw_median: median(all_draws.into_iter()),
        settings,
        view,
        scene: options.scene,
        // A texture the scene does not give by itself: --texture's, or the
        // checker toggled on.
        texture: match (textured, had_texture) {
            (true, true) => options.texture,
            (true, false) => Some("checker".into()),
            // A model's own map_Kd toggled off.
            (false, true) => Some("none".into()),
            (false, false) => None,
        },
        normal_map: match (bumped, had_normal_map) {
            (true, true) => options.normal_map,
            (true, false) => Some("bumps".into()),
            (false, _) => None,
        },
        parallax,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_map_from_the_window_library() {
        assert_eq!(to_key(minifb::Key::A), Some(Key::Char('a')));
        assert_eq!(to_key(minifb::Key::Z), Some(Key::Char('z')));
        assert_eq!(to_key(minifb::Key::Key7), Some(Key::Char('7')));
        assert_eq!(to_key(minifb::Key::NumPad3), Some(Key::Char('3')));
        assert_eq!(to_key(minifb::Key::PageUp), Some(Key::PageUp));
        assert_eq!(to_key(minifb::Key::F1), None);
    }

    #[test]
    fn the_reproducing_command_parses_back_exactly() {
        use crate::pipeline::Camera;
        let s = Settings {
            camera: Camera {
                yaw: (1.0f32 / 3.0).to_radians(),
                position: glam::Vec3::new(-0.1, 0.2, -2.9),
                ..Camera::handout(500, 500)
            },
            ..Settings::default()
        };
        let view = Figure::with_interpolation(StageName::PixelLight, Some(true));
        assert_eq!(
            command_for(view, &s),
            "rasterlab pixel-light --affine --size 500x500 --focal 500 --camera -0.1,0.2,-2.9 \
             --yaw 0.33333334 --pitch 0 --light 0,-0.5,-0.7 --light-power 1.1 --indirect 0.5"
        );
        let depth = Figure::of(StageName::Depth);
        assert_eq!(
            command_for(
                depth,
                &Settings {
                    camera: Camera {
                        near: None,
                        ..s.camera
                    },
                    ..s
                }
            ),
            "rasterlab depth --size 500x500 --focal 500 --camera -0.1,0.2,-2.9 \
             --yaw 0.33333334 --pitch 0 --no-clip"
        );
    }
}
