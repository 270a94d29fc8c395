//! `rasterlab check`: reading a student's screenshot or rows printout, running the
//! checker of [`crate::measure::check`], and writing its report and heat map.

use crate::app::image_io::{AllOrNone, WriteError};
use crate::app::progress::Progress;
use crate::app::streams::printable;
use crate::measure::check::check_image;
use crate::measure::check::image::{ImageCheck, Setup};
use crate::measure::check::locate::{
    blended_edges, cut_from_render, doubled, locate, locate_by_frame, pixel_doubled, shrunk,
};
use crate::measure::check::pose::{fit_pose, walls_in_place, MIN_POSE_SCORE};
use crate::measure::check::rows::{check_rows, parse_rows_skipping, RowsCheck};
use crate::measure::heat::heat_map_picture;
use crate::pipeline::target::unpack;
use crate::pipeline::StageName;
use crate::pipeline::{Camera, Frame};
use crate::scene::input::{read_image_with_format, read_text_bounded, read_text_file, ImageLimit};
use glam::Vec3;
use std::path::{Path, PathBuf};

/// Why a check could not be made: a usage error (an option that contradicts the
/// input) or a failure (an input that cannot be read, a file that cannot be
/// written). Each is one line naming the problem.
#[derive(Debug, PartialEq)]
pub enum CheckError {
    Usage(String),
    Run(String),
}

impl From<WriteError> for CheckError {
    fn from(e: WriteError) -> Self {
        CheckError::Run(e.to_string())
    }
}

/// What `check IMAGE` was asked; `None` where the command line gave nothing.
#[derive(Clone, Debug, Default)]
pub struct CheckOptions {
    pub stage: Option<StageName>,
    /// The size the image must have.
    pub size: Option<(u32, u32)>,
    pub focal: Option<f32>,
    pub camera: Option<Vec3>,
    /// Degrees.
    pub yaw: f32,
    /// Degrees.
    pub pitch: f32,
    pub light: Option<Vec3>,
    pub light_power: Option<f32>,
    pub indirect: Option<f32>,
    pub fit_light: bool,
    /// Folder for the heat map and the image the best explanation draws.
    pub out: Option<PathBuf>,
}

/// Reads a PNG, JPEG, BMP or GIF screenshot as a frame, on white where it is
/// transparent (as an image viewer shows it: a macOS window screenshot's shadow
/// and corners); one larger than [`MAX_CHECK_SIDE`] is refused from its header,
/// before it is decoded.
pub fn read_screenshot(path: &Path) -> Result<Frame, String> {
    read_screenshot_noting_jpeg(path).map(|(frame, _)| frame)
}

/// [`read_screenshot`], and whether the file is a JPEG.
fn read_screenshot_noting_jpeg(path: &Path) -> Result<(Frame, bool), String> {
    let limit = ImageLimit {
        max_side: MAX_CHECK_SIDE,
        what: "a screenshot of the lab",
    };
    let (img, format) = read_image_with_format(path, limit)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let rgba = img.to_rgba8();
    let mut frame = Frame::new(rgba.width(), rgba.height());
    // One alpha over the whole image says nothing of what was drawn: an
    // OpenGL or SDL window read back often has 0 everywhere. Its colours are
    // taken as they are; an image whose alpha varies is seen over white.
    let first = rgba.pixels().next().map_or(255, |p| p[3]);
    let opaque = rgba.pixels().all(|p| p[3] == first);
    for (c, p) in frame.color.iter_mut().zip(rgba.pixels()) {
        let a = if opaque { 255 } else { p[3] as u32 };
        let [r, g, b] = [p[0], p[1], p[2]].map(|v| (v as u32 * a + 255 * (255 - a) + 127) / 255);
        *c = r << 16 | g << 8 | b;
    }
    Ok((frame, format == Some(image::ImageFormat::Jpeg)))
}

/// Below this share of the walls' pixels in place from the given camera, the
/// camera is fitted before anything else: the handout's images from the
/// handout's pose have 99 % and more, even with a slip (a flip moves the
/// blocks only, a swap two walls).
const CAMERA_ELSEWHERE: f64 = 0.7;

/// The camera that puts the walls of `observed` in place, with its focal length
/// unless `options` give it (the height, as the handout has it, the width, or
/// rasterlab's 500), as the setup to check from and the note that says so;
/// `None` when no pose puts [`MIN_POSE_SCORE`] of them in place.
fn fit_camera(observed: &Frame, setup: &Setup, options: &CheckOptions) -> Option<(Setup, String)> {
    let (w, h) = (observed.width, observed.height);
    let mut focals = vec![setup.camera.focal];
    if options.focal.is_none() {
        for f in [w as f32, 500.0] {
            if !focals.contains(&f) {
                focals.push(f);
            }
        }
    }
    let pose = fit_pose(observed, setup.camera, &focals);
    // A pose that puts fewer walls in place is a search that found nothing.
    if pose.score < MIN_POSE_SCORE {
        return None;
    }
    let c = pose.camera;
    // The given place and turns with another focal length (a render on a
    // larger canvas, black around it): the handout's camera itself, so its
    // edges are exact.
    if !moved_from(&c, &setup.camera) {
        let given = Camera {
            focal: c.focal,
            ..setup.camera
        };
        let note = format!(
            "the camera is the handout's, but the image is drawn with focal length {}, not its height {h} ({:.1} % of the walls' colours in place); it was checked with --focal {}",
            c.focal,
            pose.score * 100.0,
            c.focal
        );
        let moved = Setup {
            camera: given,
            ..setup.clone()
        };
        return (c.focal != setup.camera.focal).then_some((moved, note));
    }
    let focal = match c.focal == h as f32 {
        true => String::new(),
        false => format!(" --focal {}", c.focal),
    };
    let note = format!(
        "the camera is not at the handout's place; fitted at --camera {},{},{} --yaw {} --pitch {}{focal} ({:.1} % of the walls' colours in place); no variant was looked for on its edges, which a fitted camera places only to a fraction of a pixel",
        round3(c.position.x),
        round3(c.position.y),
        round3(c.position.z),
        round3(c.yaw.to_degrees()),
        round3(c.pitch.to_degrees()),
        pose.score * 100.0
    );
    let moved = Setup {
        camera: c,
        edges_exact: false,
        ..setup.clone()
    };
    Some((moved, note))
}

/// Whether `fitted` stands or turns otherwise than `given`, to the three
/// decimals a fitted camera is written with: a camera that only draws at
/// another focal length shows the handout's figure at another size.
fn moved_from(fitted: &Camera, given: &Camera) -> bool {
    let place = |c: &Camera| {
        [
            c.position.x,
            c.position.y,
            c.position.z,
            c.yaw.to_degrees(),
            c.pitch.to_degrees(),
        ]
        .map(round3)
    };
    place(fitted) != place(given)
}

/// How much larger a share of the walls' pixels undoing a slip must put in
/// place for the slip to be checked: a swap, a flip or a gamma undone where it
/// was not made moves walls out of place, and one undone where it was made puts
/// whole walls (a tenth of the image or more) back.
const SLIP_GAIN: f64 = 0.01;

/// `v` to three decimals, as the options that reproduce a pose are written.
fn round3(v: f32) -> f32 {
    (v * 1000.0).round() / 1000.0 + 0.0 // -0 is 0
}

/// `frame` with its red and blue channels exchanged.
fn swap_red_blue(frame: &Frame) -> Frame {
    let mut out = frame.clone();
    for c in &mut out.color {
        *c = (*c & 0x00ff00) | (*c >> 16 & 0xff) | (*c & 0xff) << 16;
    }
    out
}

/// A repair of a whole image: a slip undone.
type Undo = fn(&Frame) -> Frame;

/// The note for red and blue swapped back.
const SWAPPED: &str = "red and blue are swapped in this image (a pixel format read in the wrong byte order, a common SDL slip); it was checked with them swapped back";

/// The note for a gamma taken off.
const GAMMA: &str = "a gamma of 2.2 was applied to the colours (an sRGB conversion the handout does not make); it was checked with it taken off";

/// `frame` upside down: rows written bottom to top.
fn flip_rows(frame: &Frame) -> Frame {
    let mut out = frame.clone();
    let w = frame.width as usize;
    if w > 0 {
        for (row, source) in out.color.chunks_mut(w).zip(frame.color.chunks(w).rev()) {
            row.copy_from_slice(source);
        }
    }
    out
}

/// `frame` with a display gamma of 2.2 taken off each channel, `255 (c/255)^2.2`:
/// the image as it was before a gamma (an sRGB conversion) was applied to it.
fn remove_gamma(frame: &Frame) -> Frame {
    let table: Vec<u32> = (0..256)
        .map(|c| (255.0 * (c as f64 / 255.0).powf(2.2)).round() as u32)
        .collect();
    let mut out = frame.clone();
    for c in &mut out.color {
        let ch = |shift: u32| table[(*c >> shift & 0xff) as usize] << shift;
        *c = ch(16) | ch(8) | ch(0);
    }
    out
}

/// The colour of 99 % or more of the pixels (within 2/255, each channel), if
/// the image is one colour other than black (a black one has no walls to place
/// either way).
fn one_colour(frame: &Frame) -> Option<[u8; 3]> {
    let centre = (frame.height / 2 * frame.width + frame.width / 2) as usize;
    let colour = unpack(*frame.color.get(centre)?);
    let near = |&c: &u32| {
        unpack(c)
            .iter()
            .zip(colour)
            .all(|(&a, b)| a.abs_diff(b) <= 2)
    };
    let alike = frame.color.iter().filter(|c| near(c)).count();
    let black = colour.iter().all(|&c| c < 8);
    (!black && alike * 100 >= frame.color.len() * 99).then_some(colour)
}

/// The share of pixels within 8/255 of their right neighbour in every channel.
/// A render is made of surfaces lit smoothly (even through JPEG compression or
/// resizing, nearly every pixel is); noise or a photograph is not, and looking
/// for the camera such an image was taken from would take minutes for nothing.
fn smooth_share(frame: &Frame) -> f64 {
    let w = frame.width as usize;
    let pairs = frame.height as usize * w.saturating_sub(1);
    if pairs == 0 {
        return 1.0;
    }
    let near = |a: u32, b: u32| {
        unpack(a)
            .iter()
            .zip(unpack(b))
            .all(|(&a, b)| a.abs_diff(b) <= 8)
    };
    let smooth: usize = frame
        .color
        .chunks_exact(w)
        .map(|row| row.windows(2).filter(|p| near(p[0], p[1])).count())
        .sum();
    smooth as f64 / pairs as f64
}

/// Below this [`smooth_share`], an image is not searched for a camera: the
/// lab's renders and screenshots of them have 0.9 and more, uniform noise about
/// 0.0003.
const LEAST_SMOOTH: f64 = 0.5;

/// Whether `check` found a lab 3 image.
fn lab3(check: &ImageCheck) -> bool {
    check.fitted.is_some()
}

/// Whether `check` explains its image well: a lab 3 image whose differences, if
/// any, lie on edges.
fn explained(check: &ImageCheck) -> bool {
    check.fitted.is_some() && matches!(check.remaining.summary(), "none" | "edges")
}

/// Whether `searched`, checked from a light searched for, explains its image
/// better than `given`, from the light given: a lab 3 image from a light
/// elsewhere whose interiors are at most half as far off (RMSE). A shade that
/// differs for another reason (a formula written otherwise) moves the light a
/// little and gains little; a light moved by a few key presses leaves tens of
/// levels that its position takes to nearly nothing.
fn light_explains(searched: &ImageCheck, given: &ImageCheck) -> bool {
    let Some(s) = &searched.fitted else {
        return false;
    };
    s.light != given.closest.light
        && given
            .fitted
            .as_ref()
            .is_none_or(|g| s.errors.interior_rmse <= 0.5 * g.errors.interior_rmse)
}

/// The most memory a check holds at once, in bytes a pixel of the screenshot:
/// measured, 67 to 73 (the peak resident size checking a window's render
/// after the camera moved, 1600x1000, and a blue desktop, 1280x1024), with a
/// tenth more for room.
const CHECK_BYTES_A_PIXEL: usize = 80;

/// The largest side checked: a screenshot is a window, and each hypothesis draws
/// several frames of its size.
pub const MAX_CHECK_SIDE: u32 = 4096;

/// `check IMAGE`: the report and the files written into `options.out`.
pub fn check_image_file(
    path: &Path,
    options: &CheckOptions,
) -> Result<(ImageCheck, Vec<PathBuf>), CheckError> {
    let stem = path
        .file_stem()
        .map_or("image".into(), |s| s.to_string_lossy().into_owned());
    check_image_named(path, &stem, options)
}

/// [`check_image_file`], with the files written named after `stem`.
fn check_image_named(
    path: &Path,
    stem: &str,
    options: &CheckOptions,
) -> Result<(ImageCheck, Vec<PathBuf>), CheckError> {
    // A JPEG's blocks blur every edge and move every colour a little: checked
    // as an image resampled, and its pixels not held to 2/255.
    let (observed, lossy) = read_screenshot_noting_jpeg(path).map_err(CheckError::Run)?;
    check_screenshot(observed, lossy, path, stem, options)
}

/// [`check_image_named`] of the screenshot read from `path`.
fn check_screenshot(
    mut observed: Frame,
    lossy: bool,
    path: &Path,
    stem: &str,
    options: &CheckOptions,
) -> Result<(ImageCheck, Vec<PathBuf>), CheckError> {
    // Refused before any hypothesis draws a frame of its size.
    let bytes =
        (observed.width as usize * observed.height as usize).saturating_mul(CHECK_BYTES_A_PIXEL);
    if !crate::pipeline::target::memory_for(bytes) {
        return Err(CheckError::Run(format!(
            "cannot check {}: out of memory: a {}x{} screenshot needs about {} to check",
            crate::app::image_io::describe(path),
            observed.width,
            observed.height,
            crate::pipeline::target::megabytes(bytes)
        )));
    }
    // The screenshot as given, kept while a part of it (or a render it is part
    // of) is checked instead.
    let mut given = None;
    // A window screenshot: the render inside it, unless the command line fixes
    // the size or the camera (then the image is taken as it is).
    let fixed = options.size.is_some() || options.focal.is_some() || options.camera.is_some();
    // A render with a few rows or columns cut off: checked in its place in
    // the handout's 500 x 500 render.
    let cut = match fixed || lossy {
        true => None,
        false => cut_from_render(&observed),
    };
    if let Some(c) = &cut {
        given = Some(std::mem::replace(&mut observed, c.frame.clone()));
    }
    let mut located = None;
    if !fixed && cut.is_none() && observed.width != observed.height {
        // The handout's figures first; a camera moved elsewhere leaves the
        // window's frame to find the render by.
        located = locate(&observed, lossy).or_else(|| locate_by_frame(&observed));
    }
    if let Some(l) = &located {
        given = Some(std::mem::replace(&mut observed, l.frame.clone()));
    }
    // Shown at twice its size pixel for pixel (a HiDPI screen): checked at the
    // size it was drawn.
    let halved = match fixed || cut.is_some() {
        true => None,
        false => pixel_doubled(&observed),
    };
    let shown_doubled = halved.is_some();
    if let Some(h) = halved {
        observed = h;
    }
    // A screenshot shrunk to half: checked at the size it was drawn.
    let blended = !fixed && !lossy && cut.is_none() && shrunk(&observed);
    if blended {
        observed = doubled(&observed);
    }
    // Resized to another size, or anti-aliased: checked as it is, its edges
    // taken for no rasterizer's.
    let resized = !blended && (lossy || blended_edges(&observed));
    let (w, h) = (observed.width, observed.height);
    if let Some((sw, sh)) = options.size {
        if (sw, sh) != (w, h) {
            return Err(CheckError::Usage(format!(
                "{} is {w}x{h}, not the {sw}x{sh} --size gives",
                path.display()
            )));
        }
    }
    let mut setup = Setup::handout(w, h);
    setup.stage = options.stage;
    if let Some(f) = options.focal {
        setup.camera.focal = f;
    }
    if let Some(c) = options.camera {
        setup.camera.position = c;
    }
    setup.camera.yaw = options.yaw.to_radians();
    setup.camera.pitch = options.pitch.to_radians();
    if let Some(l) = options.light {
        setup.light = l;
    }
    setup.power = options.light_power;
    setup.indirect = options.indirect;
    setup.fit_light = options.fit_light;
    setup.edges_exact = !(blended || resized);
    setup.resampled = blended || resized;
    setup.lossy = lossy;
    // Mostly black: points, lines, or nothing; there are no walls to place.
    let lit = observed
        .color
        .iter()
        .filter(|&&c| c & 0x00f8_f8f8 != 0)
        .count();
    // One colour in nearly every pixel: a camera against a single wall draws
    // that in any stage, so no camera is fitted to it.
    let flat = one_colour(&observed);
    // Nor has it edges on which a variant would show: a search for one only
    // takes time (minutes at 4096x4096).
    setup.edges_exact &= flat.is_none();
    let has_walls = lit * 20 > observed.color.len()
        && flat.is_none()
        && smooth_share(&observed) >= LEAST_SMOOTH;
    let walls_before = match has_walls {
        true => walls_in_place(&observed, &setup.camera),
        false => 0.0,
    };
    // Walls far from where the given camera sees them: the camera is fitted
    // first, sparing a whole check from a pose the image was not taken from.
    // (rasterlab's own focal length of 500 from the handout's place is not
    // elsewhere: a later step names it.)
    let at_500 = Camera {
        focal: 500.0,
        ..setup.camera
    };
    let elsewhere = has_walls
        && options.camera.is_none()
        && walls_before < CAMERA_ELSEWHERE
        && (options.focal.is_some() || walls_in_place(&observed, &at_500) < CAMERA_ELSEWHERE);
    let early = elsewhere
        .then(|| fit_camera(&observed, &setup, options))
        .flatten()
        .map(|(moved, note)| (check_image(&observed, &moved), moved, note))
        .filter(|(check, _, _)| lab3(check));
    let mut check = match early {
        Some((mut check, moved, note)) => {
            check.notes.push(note);
            check.camera = Some(moved.camera);
            check.adjusted = moved_from(&moved.camera, &setup.camera);
            setup = moved;
            check
        }
        None => check_image(&observed, &setup),
    };
    // Slips that hide a lab 3 image, tried in turn; the first whose check
    // `accept`s is kept, with the image and setup it was checked with (so the
    // heat map and any later step see the same image). Where the image has
    // walls, a slip is checked only if undoing it puts more of them in place
    // (a frame drawn and compared, against a whole check).
    let attempt = |image: Frame,
                   tried: Setup,
                   note: String,
                   accept: fn(&ImageCheck) -> bool,
                   check: &mut ImageCheck| {
        if has_walls && walls_in_place(&image, &tried.camera) <= walls_before + SLIP_GAIN {
            return None;
        }
        let again = check_image(&image, &tried);
        if accept(&again) {
            *check = again;
            check.notes.push(note);
            Some((image, tried))
        } else {
            None
        }
    };
    // Red and blue swapped: an SDL surface read in the other byte order.
    if check.fitted.is_none() {
        let note = SWAPPED.to_string();
        if let Some((image, _)) = attempt(
            swap_red_blue(&observed),
            setup.clone(),
            note,
            lab3,
            &mut check,
        ) {
            observed = image;
            check.adjusted = true;
        }
    }
    // An image upside down (read back bottom row first, as OpenGL's
    // glReadPixels gives it), or with a gamma applied: tried while the image is
    // not explained, and kept when the slip explains it.
    let slips: [(Undo, &str); 2] = [
        (flip_rows, "the image is upside down (its rows written bottom to top, as glReadPixels gives them); it was checked flipped back"),
        (remove_gamma, GAMMA),
    ];
    for (undo, note) in slips {
        if explained(&check) {
            break;
        }
        let (image, note) = (undo(&observed), note.to_string());
        if let Some((image, _)) = attempt(image, setup.clone(), note, explained, &mut check) {
            observed = image;
            check.adjusted = true;
        }
    }
    // rasterlab's own focal length of 500 on an image that is not 500 high.
    if check.fitted.is_none() && options.focal.is_none() && h != 500 {
        let mut ours = setup.clone();
        ours.camera.focal = 500.0;
        let note = format!("checked with focal length 500, rasterlab's default, not the image's height {h}: give --focal to say which");
        if let Some((_, tried)) = attempt(observed.clone(), ours, note, lab3, &mut check) {
            setup = tried;
        }
    }
    // A screenshot taken after walking around: the camera fitted to the
    // walls' colours, then the whole check from there (not on an image almost
    // all black: there are no walls to place).
    // (Not again where it was fitted first and found nothing better.)
    if !elsewhere && !explained(&check) && options.camera.is_none() && has_walls {
        if let Some((moved, note)) = fit_camera(&observed, &setup, options) {
            let c = moved.camera;
            if let Some((_, tried)) = attempt(observed.clone(), moved, note, lab3, &mut check) {
                check.camera = Some(c);
                check.adjusted = moved_from(&c, &setup.camera);
                setup = tried;
            }
        }
    }
    // A colour slip and a walk together: neither the given camera nor one
    // fitted to the walls' colours as they are finds the walls, so the slip
    // is undone first and the camera fitted to the image then.
    if check.fitted.is_none() && has_walls && options.camera.is_none() {
        let colour_slips: [(Undo, &str); 2] = [(swap_red_blue, SWAPPED), (remove_gamma, GAMMA)];
        for (undo, note) in colour_slips {
            let image = undo(&observed);
            let Some((moved, pose)) = fit_camera(&image, &setup, options) else {
                continue;
            };
            let again = check_image(&image, &moved);
            if lab3(&again) {
                check = again;
                check.notes.extend([note.to_string(), pose]);
                check.camera = Some(moved.camera);
                check.adjusted = true;
                setup = moved;
                observed = image;
                break;
            }
        }
    }
    // The skeleton's camera at z = -3.001 typed as -3: the same picture but for
    // a pixel here and there along the edges, which names it.
    let handout_camera = setup.camera.position == Camera::handout(w, h).position;
    if handout_camera && options.camera.is_none() && check.remaining.summary() == "edges" {
        let mut at_3 = setup.clone();
        at_3.camera.position.z = -3.0;
        let again = check_image(&observed, &at_3);
        if again.fitted.is_some() && again.remaining.total * 2 < check.remaining.total {
            let before = check.remaining.total;
            check = again;
            check.notes.push(format!(
                "the camera is at z = -3, not the handout's -3.001: drawn from there {} pixels differ instead of {before}",
                check.remaining.total
            ));
            check.camera = Some(at_3.camera);
            check.adjusted = true;
            setup = at_3;
        }
    }
    // A light moved (the handout's Update moves it with a, w, s and d): the
    // shade inside the surfaces is off while their edges fit, and under the
    // wrong light another stage or a variant can look best. The light is then
    // searched for, as --fit-light does, unless the command line places it.
    if !setup.fit_light && options.light.is_none() && check.shade_differs() {
        let mut searched = setup.clone();
        searched.fit_light = true;
        let again = check_image(&observed, &searched);
        if light_explains(&again, &check) {
            let l = again.closest.light;
            let mut notes = std::mem::take(&mut check.notes);
            notes.push(format!(
                "the shade inside the surfaces is not that of the handout's light at (0, -0.5, -0.7): the light was searched for (as --fit-light does) and found at ({}, {}, {}); give --light to check from a light you know",
                round3(l.x), round3(l.y), round3(l.z)
            ));
            check = ImageCheck {
                notes,
                camera: check.camera,
                adjusted: check.adjusted,
                ..again
            };
            setup = searched;
        } else {
            check.light_searched_in_vain = true;
        }
    }
    // A frame found around something that is no lab image (a photo's edges)
    // held no render: the image is checked whole, as it was given.
    if let Some(given) = given.filter(|_| check.fitted.is_none()) {
        let as_given = CheckOptions {
            size: Some((given.width, given.height)),
            ..options.clone()
        };
        return check_screenshot(given, lossy, path, stem, &as_given);
    }
    // A lit stage asked for on an image without direct light is contradicted,
    // not forced: P = 0 would call any flat image "Figure 7".
    let unlit = |c: &ImageCheck| {
        c.fitted
            .as_ref()
            .is_some_and(|f| f.hypothesis.lit() && f.shading.power <= 1e-3)
    };
    if let Some(stage) = options.stage.filter(|_| unlit(&check)) {
        let mut any = setup.clone();
        any.stage = None;
        let again = check_image(&observed, &any);
        let name = stage.name();
        check = again;
        check.notes.push(format!(
            "--stage {name} does not fit this image: the best {name} explanation has no direct light at all (P = 0); it was checked against every stage instead"
        ));
    }
    if let Some([r, g, b]) = flat {
        check.notes.insert(0, format!(
            "the image is one colour, ({r}, {g}, {b}), in 99 % or more of its pixels: a camera against a single wall draws that in any stage, so no camera was fitted to it"
        ));
    }
    if blended {
        check.notes.insert(0, format!(
            "the image was shrunk to half its size (the colours either side of each edge are blended, as a 2 x 2 mean makes them); it was checked doubled, at {w}x{h}, and no variant was looked for on its edges"
        ));
    }
    if shown_doubled {
        check.notes.insert(0, format!("the image is its render at twice the size, each pixel a 2 x 2 block (as a HiDPI screen shows a window); it was checked halved, at {w}x{h}"));
    }
    if lossy {
        check.notes.insert(0, "the image is a JPEG, whose compression blurs every edge and moves colours by a few levels: it was checked as it is, its pixels not held to 2/255, and no variant was looked for on its edges or in half a level (truncated colours); save the screenshot as PNG to check it to the pixel".to_string());
    } else if resized {
        check.notes.insert(0, "the colours either side of the image's edges are blended, which no rasterizer without anti-aliasing draws: it was resized (to a size other than half) or drawn anti-aliased; it was checked as it is, and no variant was looked for on its edges".to_string());
    }
    if let Some(c) = cut {
        check.notes.insert(0, c.note);
    }
    if let Some(l) = located {
        check.notes.insert(0, l.note);
        check.crop = Some(l.crop);
    }
    let mut written = Vec::new();
    if let Some(dir) = &options.out {
        // Kept even if this file's pictures cannot be written: the other
        // files, checked at the same time, write into it too.
        crate::app::create_folder(dir)?.keep();
        let title = match &check.fitted {
            Some(f) => format!("{stem} against Figure {} as fitted", f.hypothesis.figure()),
            None => format!("{stem}: not a lab 3 image; the closest stage"),
        };
        let heat_path = dir.join(format!("{stem}-heat.png"));
        let heat = heat_map_picture(&observed, &check.expected, &title)
            .map_err(|why| WriteError::new(&heat_path, why))?;
        let expected_path = dir.join(format!("{stem}-expected.png"));
        let mut files = AllOrNone::default();
        files.image(&heat, &heat_path)?;
        files.image(&check.expected, &expected_path)?;
        files.commit()?;
        written.extend([heat_path, expected_path]);
    }
    Ok((check, written))
}

/// The longest rows printout read: the handout's program prints a row in about
/// 40 bytes, and no image has a million rows.
pub const MAX_ROWS_BYTES: u64 = 64 << 20;

/// `check rows FILE X,Y ...`: reads the printout (`-` for standard input) and
/// compares it with the polygon's rows.
pub fn check_rows_file(path: &Path, vertices: &[(i32, i32)]) -> Result<RowsCheck, CheckError> {
    let text = if path.as_os_str() == "-" {
        read_text_bounded(std::io::stdin(), MAX_ROWS_BYTES)
            .map_err(|e| CheckError::Run(format!("cannot read standard input: {e}")))?
    } else {
        read_text_file(path, MAX_ROWS_BYTES)
            .map_err(|e| CheckError::Run(format!("cannot read {}: {e}", path.display())))?
    };
    let name = if path.as_os_str() == "-" {
        "standard input".to_string()
    } else {
        path.display().to_string()
    };
    let (rows, skipped) =
        parse_rows_skipping(&text).map_err(|e| CheckError::Run(format!("{name}: {e}")))?;
    Ok(RowsCheck {
        skipped,
        ..check_rows(vertices, rows)
    })
}

/// What `check` made of one file of a folder or a list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// The handout's figure within 2/255 at every pixel.
    Matches,
    /// A lab 3 image that differs from the handout's figure.
    Differs,
    /// Not an image of the lab.
    NotLab3,
    /// Not read: not an image, too large, a folder, a link to nothing.
    Unreadable,
}

impl Status {
    /// The word the table, the CSV and the JSON use.
    pub fn name(self) -> &'static str {
        match self {
            Status::Matches => "matches",
            Status::Differs => "differs",
            Status::NotLab3 => "not-lab3",
            Status::Unreadable => "unreadable",
        }
    }
}

/// One file checked: its status, the report (for an image that was read), its
/// first sentence or why the file was not read, and the files written for it.
#[derive(Debug)]
pub struct FileCheck {
    pub file: PathBuf,
    pub status: Status,
    /// The report's first sentence, or why the file was not read.
    pub summary: String,
    /// The report; `None` for a file that was not read.
    pub check: Option<ImageCheck>,
    pub written: Vec<PathBuf>,
}

/// The first sentence of `check`'s report on `file`.
fn first_sentence(check: &ImageCheck, file: &Path) -> String {
    let text = check.text(&file.display().to_string());
    let first = text
        .lines()
        .find(|l| !l.starts_with("Note: ") && !l.is_empty());
    first.unwrap_or("").to_string()
}

/// The most files one `check` reads from its folders: a course has hundreds
/// of submissions, not millions.
pub const MAX_CHECK_FILES: usize = 100_000;

/// How deep `check` looks into folders (a submission per folder, with some
/// folders inside).
const MAX_CHECK_DEPTH: usize = 16;

/// The files `check` is given: each FILE as it is, and each folder's files
/// (hidden ones left out), recursively, in name order, with the folders passed
/// over: more than [`MAX_CHECK_DEPTH`] folders down, or reached by a link
/// (never followed, so no loop is walked).
pub fn submission_files(inputs: &[PathBuf]) -> Result<(Vec<PathBuf>, Vec<PassedOver>), CheckError> {
    struct Found {
        files: Vec<PathBuf>,
        passed_over: Vec<PassedOver>,
    }
    fn walk(dir: &Path, depth: usize, found: &mut Found) -> Result<(), CheckError> {
        let read = std::fs::read_dir(dir).map_err(|e| {
            CheckError::Run(format!("cannot read the folder {}: {e}", dir.display()))
        })?;
        let mut entries: Vec<(PathBuf, bool)> = Vec::new();
        for entry in read {
            let entry = entry.map_err(|e| {
                CheckError::Run(format!("cannot read the folder {}: {e}", dir.display()))
            })?;
            if entry.file_name().to_string_lossy().starts_with('.') {
                continue;
            }
            let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
            // A link to a folder (`up -> ..`) is not walked into, as no
            // link is followed into a folder; nor is it a file to check.
            let linked_dir = entry.file_type().is_ok_and(|t| t.is_symlink())
                && std::fs::metadata(entry.path()).is_ok_and(|m| m.is_dir());
            if linked_dir {
                found.passed_over.push(PassedOver::Link(entry.path()));
                continue;
            }
            entries.push((entry.path(), is_dir));
            if found.files.len() + entries.len() > MAX_CHECK_FILES {
                return Err(CheckError::Run(format!(
                    "more than {MAX_CHECK_FILES} files under {}: check fewer at a time",
                    dir.display()
                )));
            }
        }
        entries.sort();
        for (path, is_dir) in entries {
            match is_dir {
                true if depth < MAX_CHECK_DEPTH => walk(&path, depth + 1, found)?,
                true => found.passed_over.push(PassedOver::TooDeep(path)),
                false => found.files.push(path),
            }
        }
        Ok(())
    }
    let mut found = Found {
        files: Vec::new(),
        passed_over: Vec::new(),
    };
    for input in inputs {
        // symlink_metadata: a link to a folder is checked as the file it is.
        match std::fs::symlink_metadata(input) {
            Ok(m) if m.is_dir() => walk(input, 0, &mut found)?,
            _ => found.files.push(input.clone()),
        }
    }
    Ok((found.files, found.passed_over))
}

/// A folder [`submission_files`] does not look into.
#[derive(Debug, PartialEq)]
pub enum PassedOver {
    /// More than [`MAX_CHECK_DEPTH`] folders down.
    TooDeep(PathBuf),
    /// A link to a folder.
    Link(PathBuf),
}

/// Checks every file, on `threads` threads, in order: one [`FileCheck`] each,
/// whatever happens to the others. With `options.out`, each image's heat map is
/// named after its path (`a/shot.png` gives `a_shot-heat.png`), so two
/// students' `shot.png` do not overwrite each other. `progress` is told of each
/// file as it is done.
pub fn check_files(
    files: &[PathBuf],
    options: &CheckOptions,
    threads: usize,
    progress: &mut Progress,
) -> Vec<FileCheck> {
    use rayon::prelude::*;
    let common = common_folder(files);
    let names = unique(files.iter().map(|f| heat_name(f, &common)).collect());
    let files: Vec<(&PathBuf, &String)> = files.iter().zip(&names).collect();
    progress.begin(files.len());
    let progress = std::sync::Mutex::new(progress);
    let one = |&(file, name): &(&PathBuf, &String)| {
        let checked = check_one(file, name, options);
        if let Ok(mut p) = progress.lock() {
            p.step(&format!("{}: {}", file.display(), checked.status.name()));
        }
        checked
    };
    match rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()
    {
        Ok(pool) => pool.install(|| files.par_iter().map(one).collect()),
        Err(_) => files.iter().map(one).collect(),
    }
}

/// One file of [`check_files`], whatever happens to it.
fn check_one(file: &Path, name: &str, options: &CheckOptions) -> FileCheck {
    match check_image_named(file, name, options) {
        Ok((check, written)) => FileCheck {
            status: if check.is_handouts_figure(options.stage) {
                Status::Matches
            } else if check.fitted.is_some() {
                Status::Differs
            } else {
                Status::NotLab3
            },
            summary: first_sentence(&check, file),
            file: file.to_path_buf(),
            check: Some(check),
            written,
        },
        Err(CheckError::Usage(e) | CheckError::Run(e)) => FileCheck {
            file: file.to_path_buf(),
            status: Status::Unreadable,
            summary: e,
            check: None,
            written: Vec::new(),
        },
    }
}

/// `check DIR|FILES...`: every file checked on every core, the table (or with
/// `json` the JSON lines) to print, and the CSV written to `csv`. A CSV path that
/// is a folder, or inputs with no files, are refused before any checking.
pub fn check_many(
    inputs: &[PathBuf],
    options: &CheckOptions,
    json: bool,
    csv: Option<&Path>,
    progress: &mut Progress,
) -> Result<(Vec<FileCheck>, String), CheckError> {
    if let Some(csv) = csv.filter(|c| c.is_dir()) {
        return Err(CheckError::Run(format!(
            "cannot write {}: it is a folder",
            csv.display()
        )));
    }
    // `--csv *.png` takes the first screenshot as the table's name: refused
    // rather than written over.
    let named_csv = |c: &&Path| c.extension().is_some_and(|e| e.eq_ignore_ascii_case("csv"));
    if let Some(csv) = csv.filter(|c| !named_csv(c)) {
        return Err(CheckError::Usage(format!(
            "--csv {}: the table's file name must end in .csv",
            printable(&csv.display().to_string())
        )));
    }
    let (mut files, passed_over) = submission_files(inputs)?;
    let (deep, links): (Vec<&PassedOver>, Vec<&PassedOver>) = passed_over
        .iter()
        .partition(|p| matches!(p, PassedOver::TooDeep(_)));
    let warn = |paths: &[&PassedOver], what: &str| {
        if let Some(PassedOver::TooDeep(first) | PassedOver::Link(first)) = paths.first() {
            let more = match paths.len() {
                1 => String::new(),
                n => format!(" (and {} more such folders)", n - 1),
            };
            let first = printable(&first.display().to_string());
            crate::say!("warning: {first} {what}{more}");
        }
    };
    warn(
        &deep,
        &format!("is more than {MAX_CHECK_DEPTH} folders down: not looked into"),
    );
    warn(&links, "is a link to a folder: not followed");
    // The pictures an earlier `check --out` wrote into a folder being checked
    // are not a student's: checked, they would add a row (and a picture) a run.
    if let Some(out) = options.out.as_ref().and_then(|o| o.canonicalize().ok()) {
        let ours = |f: &PathBuf| {
            let name = f
                .file_name()
                .map_or(String::new(), |n| n.to_string_lossy().into_owned());
            (name.ends_with("-heat.png") || name.ends_with("-expected.png"))
                && f.canonicalize().is_ok_and(|f| f.starts_with(&out))
        };
        files.retain(|f| !ours(f));
    }
    let is_input = |csv: &Path| {
        let csv = csv.canonicalize();
        files.iter().any(|f| {
            csv.as_ref()
                .is_ok_and(|c| f.canonicalize().is_ok_and(|f| f == *c))
        })
    };
    if let Some(csv) = csv.filter(|c| is_input(c)) {
        return Err(CheckError::Usage(format!(
            "--csv {}: it is one of the files to check",
            printable(&csv.display().to_string())
        )));
    }
    if files.is_empty() {
        let names: Vec<String> = inputs.iter().map(|p| p.display().to_string()).collect();
        return Err(CheckError::Run(format!(
            "no files to check in {}",
            names.join(", ")
        )));
    }
    let checks = check_files(&files, options, crate::app::parallel::cores(), progress);
    let table = match json {
        true => files_json(&checks),
        false => files_text(&checks),
    };
    if let Some(csv) = csv {
        crate::app::image_io::write_text(csv, &files_csv(&checks))?;
    }
    Ok((checks, table))
}

/// The folder every file is in, so that names are told apart by what follows.
fn common_folder(files: &[PathBuf]) -> PathBuf {
    let mut common: Option<PathBuf> = None;
    for f in files {
        let parent = f.parent().unwrap_or(Path::new("")).to_path_buf();
        common = Some(match common {
            None => parent,
            Some(c) => c
                .components()
                .zip(parent.components())
                .take_while(|(a, b)| a == b)
                .map(|(a, _)| a)
                .collect(),
        });
    }
    common.unwrap_or_default()
}

/// `names` with a number added to each that an earlier one already has
/// (`x.png` and `x.bmp` both give `x`: the second `x-2`).
fn unique(names: Vec<String>) -> Vec<String> {
    let mut taken = std::collections::HashSet::new();
    names
        .into_iter()
        .map(|name| {
            let mut candidate = name.clone();
            let mut n = 1;
            while !taken.insert(candidate.clone()) {
                n += 1;
                candidate = format!("{name}-{n}");
            }
            candidate
        })
        .collect()
}

/// `file`'s path below `common`, without its extension, with `_` for each
/// folder separator.
fn heat_name(file: &Path, common: &Path) -> String {
    let inner = file.strip_prefix(common).unwrap_or(file).with_extension("");
    let parts: Vec<String> = inner
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    match parts.join("_") {
        name if name.is_empty() => "image".to_string(),
        name => name,
    }
}

/// One row per file, tab-separated: its path, its status and the report's first
/// sentence; then the count of each status.
pub fn files_text(checks: &[FileCheck]) -> String {
    let mut out = String::new();
    for c in checks {
        out.push_str(&format!(
            "{}\t{}\t{}\n",
            printable(&c.file.display().to_string()),
            c.status.name(),
            printable(&c.summary)
        ));
    }
    let count = |s: Status| checks.iter().filter(|c| c.status == s).count();
    out.push_str(&format!(
        "{} files: matches {}, differs {}, not-lab3 {}, unreadable {}\n",
        checks.len(),
        count(Status::Matches),
        count(Status::Differs),
        count(Status::NotLab3),
        count(Status::Unreadable)
    ));
    out
}

/// One JSON object per line per file: `file` and `status`, then the report's
/// fields (or `error` for a file that was not read).
pub fn files_json(checks: &[FileCheck]) -> String {
    use crate::measure::check::report::json_string;
    let mut out = String::new();
    for c in checks {
        let head = format!(
            "{{\"file\":{},\"status\":{}",
            json_string(&c.file.display().to_string()),
            json_string(c.status.name())
        );
        match &c.check {
            Some(check) => {
                let report = check.json(&c.file.display().to_string());
                out.push_str(&format!("{head},{}\n", &report[1..]));
            }
            None => out.push_str(&format!("{head},\"error\":{}}}\n", json_string(&c.summary))),
        }
    }
    out
}

/// The table as CSV (RFC 4180): file, status, figure, stage, light power,
/// indirect light, variants and the report's first sentence.
pub fn files_csv(checks: &[FileCheck]) -> String {
    let cell = |s: &str| match s.contains([',', '"', '\n', '\r']) {
        true => format!("\"{}\"", s.replace('"', "\"\"")),
        false => s.to_string(),
    };
    let mut out = String::from("file,status,figure,stage,light_power,indirect,variants,summary\n");
    for c in checks {
        let fitted = c.check.as_ref().and_then(|k| k.fitted.as_ref());
        let (figure, stage, power, indirect, variants) = match fitted {
            Some(f) => {
                let lit = f.hypothesis.lit();
                let three = |v: f32| crate::measure::check::report::three_digits(v);
                (
                    f.hypothesis.figure().to_string(),
                    f.hypothesis.stage.name().to_string(),
                    if lit {
                        three(f.shading.power)
                    } else {
                        String::new()
                    },
                    if lit {
                        three(f.shading.indirect)
                    } else {
                        String::new()
                    },
                    f.variants().join(" "),
                )
            }
            None => Default::default(),
        };
        let row = [
            cell(&c.file.display().to_string()),
            c.status.name().to_string(),
            figure,
            stage,
            power,
            indirect,
            cell(&variants),
            cell(&c.summary),
        ];
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}
