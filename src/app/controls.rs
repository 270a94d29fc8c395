//! The viewer's controls as plain data: which key does what to the camera, the
//! light and the stage (the handout's `Update`). No window is needed here, so the
//! mapping is tested on its own and key scripts replay exactly.

use super::Settings;
use crate::app::figure::{Figure, Raster};
use glam::Vec3;

/// The keys the viewer reads, independent of the window library.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    Up,
    Down,
    Left,
    Right,
    PageUp,
    PageDown,
    Escape,
    /// A letter (lower case) or a digit.
    Char(char),
}

impl Key {
    /// Parses a key name as used in `--keys`: `up`, `down`, `left`, `right`,
    /// `pageup`, `pagedown`, `esc`, or one letter or digit.
    pub fn parse(name: &str) -> Option<Key> {
        Some(match name.to_ascii_lowercase().as_str() {
            "up" => Key::Up,
            "down" => Key::Down,
            "left" => Key::Left,
            "right" => Key::Right,
            "pageup" => Key::PageUp,
            "pagedown" => Key::PageDown,
            "esc" | "escape" => Key::Escape,
            s if s.len() == 1 && s.chars().all(|c| c.is_ascii_alphanumeric()) => {
                Key::Char(s.chars().next()?)
            }
            _ => return None,
        })
    }
}

/// What a key press (not a held key) asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// Show one of the seven figures (keys 1 to 7).
    Show(Figure),
    /// Switch between perspective-correct and affine interpolation (p).
    TogglePerspective,
    /// Switch between the handout's rows rasterizer and the exact one (x).
    ToggleRaster,
    /// Textures on or off (t): `--texture`'s, a model's own, or the checker.
    ToggleTexture,
    /// The normal map on or off (n): `--normal-map`'s, a model's own, or bumps.
    ToggleNormalMap,
    /// Parallax on or off (k), with the bumps.
    ToggleParallax,
    /// Nearest or bilinear texture filtering (b).
    ToggleFilter,
    /// Depth of field on or off (g).
    ToggleDepthOfField,
    /// Shadows: none, from the shadow map, filtered (m).
    CycleShadows,
    /// Save the current frame as a PNG (c).
    Save,
    /// Print the key list (h).
    Help,
    /// Quit (Esc).
    Quit,
}

/// The key list `h` prints.
pub const HELP: &str = "\
keys: up/down move the camera forward/back, left/right turn it (yaw),
      pageup/pagedown or r/f look up/down (pitch), left mouse button + drag looks around;
      w/s move the light forward/back (+z/-z), a/d left/right, q/e up/down;
      1 points, 2 wireframe, 3 filled, 4 depth, 5 vertex-light, 6 pixel-light,
      7 pixel-light --affine; p toggles perspective-correct interpolation;
      x switches between the rows rasterizer and the exact edge rasterizer;
      t toggles textures (the checker, or the model's own), n the normal map
      (bumps, or --normal-map's), k parallax (with the bumps), b bilinear filtering,
      g depth of field (--dof's, or focused on what the centre pixel shows),
      m shadows: none, --shadows, --shadows --pcf;
      c saves the frame as a PNG; h prints this list; Esc quits.";

/// Speeds of held keys and of the mouse. Movement is per second, so it feels the
/// same at any frame rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controls {
    /// Camera movement, world units per second (the box is 2 wide).
    pub move_speed: f32,
    /// Yaw and pitch, degrees per second.
    pub turn_speed: f32,
    /// Light movement, world units per second.
    pub light_speed: f32,
    /// Mouse look, degrees per pixel of motion.
    pub mouse_degrees: f32,
}

impl Default for Controls {
    fn default() -> Self {
        Controls {
            move_speed: 1.0,
            turn_speed: 60.0,
            light_speed: 1.0,
            mouse_degrees: 0.25,
        }
    }
}

/// Pitch stops short of straight up or down, where yaw would lose its meaning.
pub const MAX_PITCH: f32 = 89.0;

impl Controls {
    /// Applies the keys held during one frame of `dt` seconds.
    pub fn apply_held(&self, held: &[Key], dt: f32, s: &mut Settings) {
        let forward = s.camera.axes()[2];
        let (step, turn, light) = (
            self.move_speed * dt,
            (self.turn_speed * dt).to_radians(),
            self.light_speed * dt,
        );
        let (camera, light_at) = (&mut s.camera, &mut s.light.position);
        for key in held {
            match key {
                Key::Up => camera.position += forward * step,
                Key::Down => camera.position -= forward * step,
                Key::Left => camera.yaw -= turn,
                Key::Right => camera.yaw += turn,
                Key::PageUp | Key::Char('r') => camera.pitch += turn,
                Key::PageDown | Key::Char('f') => camera.pitch -= turn,
                Key::Char('w') => *light_at += Vec3::Z * light,
                Key::Char('s') => *light_at -= Vec3::Z * light,
                Key::Char('a') => *light_at -= Vec3::X * light,
                Key::Char('d') => *light_at += Vec3::X * light,
                Key::Char('q') => *light_at -= Vec3::Y * light, // y points down
                Key::Char('e') => *light_at += Vec3::Y * light,
                _ => {}
            }
        }
        let max = MAX_PITCH.to_radians();
        camera.pitch = camera.pitch.clamp(-max, max);
    }

    /// Mouse look: `dx` pixels right turns right, `dy` pixels down looks down.
    pub fn apply_mouse(&self, dx: f32, dy: f32, s: &mut Settings) {
        let (c, max) = (&mut s.camera, MAX_PITCH.to_radians());
        c.yaw += (dx * self.mouse_degrees).to_radians();
        c.pitch = (c.pitch - (dy * self.mouse_degrees).to_radians()).clamp(-max, max);
    }
}

/// Mouse look's memory: where the pointer was in the last frame of a drag.
///
/// A drag's first frame reports no motion: with no previous position, the first
/// reading would be measured from wherever the pointer last was (or from 0, 0),
/// the large first jump one of the student reports worked around with a delay.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MouseLook {
    last: Option<(f32, f32)>,
}

impl MouseLook {
    /// Takes this frame's button state and pointer position; returns the motion
    /// to apply, in pixels, if the left button has been held since the last frame.
    pub fn update(
        &mut self,
        button_down: bool,
        position: Option<(f32, f32)>,
    ) -> Option<(f32, f32)> {
        if !button_down {
            self.last = None;
            return None;
        }
        let motion = match (self.last, position) {
            (Some((x0, y0)), Some((x1, y1))) => Some((x1 - x0, y1 - y0)),
            _ => None,
        };
        self.last = position;
        motion
    }
}

/// Whether holding or pressing `key` does anything in the viewer.
pub fn does_something(key: Key) -> bool {
    let held = matches!(
        key,
        Key::Up
            | Key::Down
            | Key::Left
            | Key::Right
            | Key::PageUp
            | Key::PageDown
            | Key::Char('r' | 'f' | 'w' | 's' | 'a' | 'd' | 'q' | 'e')
    );
    held || action(key).is_some()
}

/// What pressing `key` asks for, if anything.
pub fn action(key: Key) -> Option<Action> {
    match key {
        Key::Char(c @ '1'..='7') => Some(Action::Show(Figure::FIGURES[c as usize - '1' as usize])),
        Key::Char('p') => Some(Action::TogglePerspective),
        Key::Char('x') => Some(Action::ToggleRaster),
        Key::Char('t') => Some(Action::ToggleTexture),
        Key::Char('b') => Some(Action::ToggleFilter),
        Key::Char('n') => Some(Action::ToggleNormalMap),
        Key::Char('k') => Some(Action::ToggleParallax),
        Key::Char('g') => Some(Action::ToggleDepthOfField),
        Key::Char('m') => Some(Action::CycleShadows),
        Key::Char('c') => Some(Action::Save),
        Key::Char('h') => Some(Action::Help),
        Key::Escape => Some(Action::Quit),
        _ => None,
    }
}

/// `view` drawn by the other rasterizer.
pub fn toggle_raster(view: Figure) -> Figure {
    view.with_raster(match view.raster {
        Raster::Rows => Raster::Edge,
        Raster::Edge => Raster::Rows,
    })
}

/// `view` with interpolation switched, for stages that interpolate; others unchanged.
pub fn toggle_perspective(view: Figure) -> Figure {
    if view.stage.interpolates() {
        Figure {
            affine: !view.affine,
            ..view
        }
    } else {
        view
    }
}

/// A parsed `--keys` script: the keys held in each frame.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Script(pub Vec<Vec<Key>>);

impl std::str::FromStr for Script {
    type Err = String;
    fn from_str(s: &str) -> Result<Script, String> {
        parse_script(s).map(Script)
    }
}

/// A key script, `--keys "right*30,w*10,up+left*5"`: each item holds its keys
/// (joined by `+`) for a number of frames (default 1); `none*N` holds nothing.
/// Returns the keys held in each frame, in order.
pub fn parse_script(script: &str) -> Result<Vec<Vec<Key>>, String> {
    let mut frames = Vec::new();
    for item in script.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (keys, count) = match item.split_once('*') {
            Some((k, n)) => {
                let n: usize = n
                    .trim()
                    .parse()
                    .map_err(|_| format!("'{n}' is not a frame count in '{item}'"))?;
                (k, n)
            }
            None => (item, 1),
        };
        if count > 1_000_000 {
            return Err(format!("at most 1000000 frames per item, got '{item}'"));
        }
        let held: Vec<Key> = if keys.trim() == "none" {
            Vec::new()
        } else {
            keys.split('+')
                .map(|k| {
                    Key::parse(k.trim())
                        .filter(|&key| does_something(key))
                        .ok_or_else(|| {
                            format!(
                                "unknown key '{}' in '{item}': 'h' in the viewer lists the keys",
                                k.trim()
                            )
                        })
                })
                .collect::<Result<_, _>>()?
        };
        frames.extend(std::iter::repeat_n(held, count));
    }
    Ok(frames)
}

/// Keys down now that were not down in the frame before: the presses.
pub fn pressed(now: &[Key], before: &[Key]) -> Vec<Key> {
    now.iter()
        .filter(|k| !before.contains(k))
        .copied()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::{Light, StageName};

    fn settings() -> Settings {
        Settings::default()
    }

    /// The camera's yaw and pitch in degrees, to 4 decimals.
    fn turned(s: &Settings) -> (f32, f32) {
        let deg = |r: f32| (r.to_degrees() * 1e4).round() / 1e4;
        (deg(s.camera.yaw), deg(s.camera.pitch))
    }

    #[test]
    fn arrows_move_along_the_view_and_turn() {
        let c = Controls::default();
        let mut s = settings();
        c.apply_held(&[Key::Up], 0.5, &mut s);
        assert_eq!(s.camera.position, Vec3::new(0.0, 0.0, -3.001 + 0.5));
        c.apply_held(&[Key::Right], 0.5, &mut s);
        assert_eq!(turned(&s).0, 30.0);
        // Facing 90 degrees right, forward is +x.
        s.camera.yaw = 90f32.to_radians();
        let before = s.camera.position;
        c.apply_held(&[Key::Down], 1.0, &mut s);
        assert!(
            (s.camera.position - (before - Vec3::X)).length() < 1e-6,
            "{}",
            s.camera.position
        );
    }

    #[test]
    fn movement_scales_with_frame_time() {
        let c = Controls::default();
        let (mut a, mut b) = (settings(), settings());
        for _ in 0..4 {
            c.apply_held(&[Key::Left, Key::Char('d')], 0.25, &mut a);
        }
        c.apply_held(&[Key::Left, Key::Char('d')], 1.0, &mut b);
        let (la, lb) = (a.light.position, b.light.position);
        assert!((a.camera.yaw - b.camera.yaw).abs() < 1e-6 && (la - lb).length() < 1e-6);
        assert_eq!(turned(&b).0, -60.0);
        assert_eq!(lb, Vec3::new(1.0, -0.5, -0.7));
    }

    #[test]
    fn light_keys_follow_lab_2() {
        let c = Controls::default();
        for (key, dir) in [
            ('w', Vec3::Z),
            ('s', -Vec3::Z),
            ('a', -Vec3::X),
            ('d', Vec3::X),
            ('q', -Vec3::Y),
            ('e', Vec3::Y),
        ] {
            let mut s = settings();
            c.apply_held(&[Key::Char(key)], 0.1, &mut s);
            assert!(
                (s.light.position - (Light::handout().position + dir * 0.1)).length() < 1e-6,
                "{key}"
            );
            assert_eq!(s.camera, Settings::default().camera);
        }
    }

    #[test]
    fn pitch_keys_and_mouse_are_clamped() {
        let c = Controls::default();
        let mut s = settings();
        c.apply_held(&[Key::PageUp], 1.0, &mut s);
        assert_eq!(turned(&s).1, 60.0);
        c.apply_held(&[Key::Char('r')], 1.0, &mut s);
        assert_eq!(turned(&s).1, MAX_PITCH);
        c.apply_mouse(40.0, 1000.0, &mut s);
        assert_eq!(turned(&s), (10.0, -MAX_PITCH));
    }

    #[test]
    fn presses_pick_figures_and_actions() {
        assert_eq!(
            action(Key::Char('1')),
            Some(Action::Show(Figure::of(StageName::Points)))
        );
        assert_eq!(
            action(Key::Char('7')),
            Some(Action::Show(Figure::with_interpolation(
                StageName::PixelLight,
                Some(true)
            )))
        );
        assert_eq!(action(Key::Char('8')), None);
        assert_eq!(action(Key::Char('p')), Some(Action::TogglePerspective));
        assert_eq!(action(Key::Char('x')), Some(Action::ToggleRaster));
        let edge = toggle_raster(Figure::of(StageName::Depth));
        assert_eq!(edge.raster, Raster::Edge);
        assert_eq!(toggle_raster(edge), Figure::of(StageName::Depth));
        assert_eq!(action(Key::Escape), Some(Action::Quit));
        assert!(toggle_perspective(Figure::of(StageName::PixelLight)).affine);
        assert!(!toggle_perspective(Figure::of(StageName::VertexLight)).affine);
        let depth = Figure::of(StageName::Depth);
        assert_eq!(
            toggle_perspective(depth),
            depth,
            "depth has nothing to correct"
        );
    }

    #[test]
    fn mouse_look_ignores_the_first_frame_of_a_drag() {
        let mut m = MouseLook::default();
        assert_eq!(m.update(false, Some((10.0, 10.0))), None);
        assert_eq!(
            m.update(true, Some((400.0, 300.0))),
            None,
            "first frame of a drag"
        );
        assert_eq!(m.update(true, Some((410.0, 295.0))), Some((10.0, -5.0)));
        assert_eq!(m.update(false, Some((0.0, 0.0))), None);
        assert_eq!(
            m.update(true, Some((50.0, 50.0))),
            None,
            "a new drag starts afresh"
        );
        assert_eq!(m.update(true, None), None, "pointer left the window");
        assert_eq!(m.update(true, Some((60.0, 50.0))), None);
    }

    #[test]
    fn scripts() {
        let f = parse_script("right*2, up+w ,none*2,p").unwrap();
        assert_eq!(
            f,
            vec![
                vec![Key::Right],
                vec![Key::Right],
                vec![Key::Up, Key::Char('w')],
                vec![],
                vec![],
                vec![Key::Char('p')],
            ]
        );
        assert_eq!(
            parse_script("jump*3").unwrap_err(),
            "unknown key 'jump' in 'jump*3': 'h' in the viewer lists the keys"
        );
        // Keys that do nothing in the viewer are refused too.
        assert!(parse_script("8")
            .unwrap_err()
            .starts_with("unknown key '8'"));
        assert!(parse_script("z").is_err());
        assert!(parse_script("7,c,h,esc").is_ok());
        assert!(parse_script("up*x").is_err());
        assert_eq!(
            pressed(&[Key::Up, Key::Char('p')], &[Key::Up]),
            vec![Key::Char('p')]
        );
    }
}
