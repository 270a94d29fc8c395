//! `rasterlab check`: reading a student's screenshot or rows printout, running the
//! checker of [`crate::measure::check`], and writing its report and heat map.

use crate::app::image_io::{write_image, WriteError};
use crate::measure::check::check_image;
use crate::measure::check::image::{ImageCheck, Setup};
use crate::measure::check::locate::locate;
use crate::measure::check::pose::fit_pose;
use crate::measure::check::rows::{check_rows, parse_rows_skipping, RowsCheck};
use crate::measure::heat::heat_map_picture;
use crate::pipeline::Frame;
use crate::pipeline::StageName;
use crate::scene::input::{read_image, read_text_bounded, read_text_file, ImageLimit};
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

/// Reads a PNG or BMP screenshot as a frame (alpha is dropped); one larger than
/// [`MAX_CHECK_SIDE`] is refused from its header, before it is decoded.
pub fn read_screenshot(path: &Path) -> Result<Frame, String> {
    let limit = ImageLimit {
        max_side: MAX_CHECK_SIDE,
        what: "a screenshot of the lab",
    };
    let img =
        read_image(path, limit).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let rgb = img.to_rgb8();
    let mut frame = Frame::new(rgb.width(), rgb.height());
    for (c, p) in frame.color.iter_mut().zip(rgb.pixels()) {
        *c = (p[0] as u32) << 16 | (p[1] as u32) << 8 | p[2] as u32;
    }
    Ok(frame)
}

/// The share of pixels whose walls a fitted camera must put in place (see
/// [`crate::measure::check::pose`]); the walked-around screenshots tried get 99.7 %
/// and more.
const MIN_POSE_SCORE: f64 = 0.97;

/// `v` to three decimals, as the options that reproduce a pose are written.
fn round3(v: f32) -> f32 {
    (v * 1000.0).round() / 1000.0
}

/// `frame` with its red and blue channels exchanged.
fn swap_red_blue(frame: &Frame) -> Frame {
    let mut out = frame.clone();
    for c in &mut out.color {
        *c = (*c & 0x00ff00) | (*c >> 16 & 0xff) | (*c & 0xff) << 16;
    }
    out
}

/// The largest side checked: a screenshot is a window, and each hypothesis draws
/// several frames of its size.
pub const MAX_CHECK_SIDE: u32 = 4096;

/// `check IMAGE`: the report and the files written into `options.out`.
pub fn check_image_file(
    path: &Path,
    options: &CheckOptions,
) -> Result<(ImageCheck, Vec<PathBuf>), CheckError> {
    let mut observed = read_screenshot(path).map_err(CheckError::Run)?;
    // A window screenshot: the render inside it, unless the command line fixes
    // the size or the camera (then the image is taken as it is).
    let fixed = options.size.is_some() || options.focal.is_some() || options.camera.is_some();
    let mut located = None;
    if !fixed && observed.width != observed.height {
        located = locate(&observed);
    }
    if let Some(l) = &located {
        observed = l.frame.clone();
    }
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
    let mut check = check_image(&observed, &setup);
    // Slips that hide a lab 3 image, tried in turn while it is not one; the
    // first that explains it is kept, with the image and setup it was checked
    // with (so the heat map and any later step see the same image).
    let attempt = |image: Frame, tried: Setup, note: String, check: &mut ImageCheck| {
        let again = check_image(&image, &tried);
        if again.fitted.is_some() {
            *check = again;
            check.notes.push(note);
            Some((image, tried))
        } else {
            None
        }
    };
    // Red and blue swapped: an SDL surface read in the other byte order.
    if check.fitted.is_none() {
        let note = "red and blue are swapped in this image (a pixel format read in the wrong byte order, a common SDL slip); it was checked with them swapped back".to_string();
        if let Some((image, _)) = attempt(swap_red_blue(&observed), setup.clone(), note, &mut check)
        {
            observed = image;
        }
    }
    // rasterlab's own focal length of 500 on an image that is not 500 high.
    if check.fitted.is_none() && options.focal.is_none() && h != 500 {
        let mut ours = setup.clone();
        ours.camera.focal = 500.0;
        let note = format!("checked with focal length 500, rasterlab's default, not the image's height {h}: give --focal to say which");
        if let Some((_, tried)) = attempt(observed.clone(), ours, note, &mut check) {
            setup = tried;
        }
    }
    // A screenshot taken after walking around: the camera fitted to the
    // walls' colours, then the whole check from there (not on an image almost
    // all black: there are no walls to place).
    let lit = observed
        .color
        .iter()
        .filter(|&&c| c & 0x00f8_f8f8 != 0)
        .count();
    if check.fitted.is_none() && options.camera.is_none() && lit * 20 > observed.color.len() {
        let pose = fit_pose(&observed, setup.camera);
        // A pose that puts fewer walls in place is a search that found nothing.
        if pose.score >= MIN_POSE_SCORE {
            let mut moved = setup.clone();
            moved.camera = pose.camera;
            let c = pose.camera;
            let note = format!(
                "the camera is not at the handout's place; fitted at --camera {},{},{} --yaw {} --pitch {} ({:.1} % of the walls' colours in place)",
                round3(c.position.x),
                round3(c.position.y),
                round3(c.position.z),
                round3(c.yaw.to_degrees()),
                round3(c.pitch.to_degrees()),
                pose.score * 100.0
            );
            if let Some((_, tried)) = attempt(observed.clone(), moved, note, &mut check) {
                check.camera = Some(c);
                setup = tried;
            }
        }
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
    if let Some(l) = located {
        check.notes.insert(0, l.note);
        check.crop = Some(l.crop);
    }
    let mut written = Vec::new();
    if let Some(dir) = &options.out {
        crate::app::create_folder(dir)?;
        let stem = path
            .file_stem()
            .map_or("image".into(), |s| s.to_string_lossy().into_owned());
        let title = match &check.fitted {
            Some(f) => format!("{stem} against Figure {} as fitted", f.hypothesis.figure()),
            None => format!("{stem}: not a lab 3 image; the closest stage"),
        };
        let heat = heat_map_picture(&observed, &check.expected, &title)
            .expect("the expected image has the screenshot's size");
        let heat_path = dir.join(format!("{stem}-heat.png"));
        write_image(&heat, &heat_path)?;
        let expected_path = dir.join(format!("{stem}-expected.png"));
        write_image(&check.expected, &expected_path)?;
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
