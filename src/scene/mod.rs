//! What builds meshes for the pipeline: the handout's Cornell box and its
//! subdivisions, procedural scenes (a sphere, a floor grid) and OBJ model files,
//! chosen by a scene spec (`parse_scene`).

pub mod cornell;
pub mod input;
pub mod obj;
pub mod procedural;
pub mod ray;
pub mod texture;

pub use cornell::{cornell_box, subdivide};
pub use obj::{load_obj, obj_text, read_obj};
pub use procedural::{grid, sphere};

use crate::extensions::texture::{Maps, Model};
use crate::pipeline::camera::DEFAULT_NEAR;
use crate::pipeline::{Camera, Light, Mesh};
use glam::Vec3;
use std::path::Path;

/// A mesh to draw, with what framing it needs.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The spec for a built-in scene (`cornell:4`), the file's name without its
    /// extension for a model (`bunny`).
    pub name: String,
    pub mesh: Mesh,
    /// The images its materials read beyond their colours (an OBJ's `map_Kd`,
    /// `--texture`, `--normal-map`).
    pub maps: Maps,
    /// The handout's box, possibly subdivided: drawn with the handout's default
    /// camera and light rather than framed by its bounding sphere.
    pub is_box: bool,
    /// The tilt it is looked at with unless the command line says (degrees,
    /// positive looks up): a floor grid is looked down on, not seen edge-on.
    pub pitch: f32,
    /// What a reader should know about how the file was read (see
    /// [`obj::read_obj`]).
    pub warnings: Vec<String>,
}

impl Scene {
    /// The mesh with its maps, as the stages draw it.
    pub fn model(&self) -> Model<'_> {
        Model {
            mesh: &self.mesh,
            maps: &self.maps,
        }
    }
}

impl<'a> From<&'a Scene> for Model<'a> {
    fn from(scene: &'a Scene) -> Self {
        scene.model()
    }
}

/// The tilt a grid is looked at with: from above, at an angle.
pub const GRID_PITCH: f32 = -35.0;

/// The scene a spec names: `cornell` (the default), `cornell:K` (the box with each
/// triangle split into K² by `subdivide`, K from 1 to 256), `sphere:N` (about N
/// triangles, N from 8 to 4 000 000), `grid:N` (about N triangles, N from 2 to
/// 4 000 000), or a path ending in `.obj` (any case). The error is one line.
pub fn parse_scene(spec: &str) -> Result<Scene, String> {
    if spec.to_lowercase().ends_with(".obj") {
        let path = Path::new(spec);
        let name = path.file_stem().unwrap_or_default().to_string_lossy();
        let (mesh, maps, warnings) = read_obj(path)?;
        return Ok(Scene {
            name: name.into_owned(),
            mesh,
            maps,
            is_box: false,
            pitch: 0.0,
            warnings,
        });
    }
    let (kind, count) = match spec.split_once(':') {
        Some((kind, count)) => (kind, Some(count)),
        None => (spec, None),
    };
    let number = |low: usize, high: usize| match count.map(|c| (c, c.parse::<usize>())) {
        Some((_, Ok(n))) if (low..=high).contains(&n) => Ok(n),
        Some((c, _)) => Err(format!(
            "scene {kind}:N needs a whole number N from {low} to {high}, not '{c}'"
        )),
        None => Err(format!("scene {kind} needs a count: {kind}:N")),
    };
    let (mesh, is_box) = match (kind, count) {
        ("cornell", None) => (cornell_box(), true),
        ("cornell", Some(_)) => {
            let k = number(1, 256)?;
            room_for_triangles(30 * k * k, spec)?;
            (subdivide(&cornell_box(), k as u32), true)
        }
        ("sphere", _) => {
            let n = number(8, 4_000_000)?;
            room_for_triangles(n, spec)?;
            (sphere(n), false)
        }
        ("grid", _) => {
            let n = number(2, 4_000_000)?;
            room_for_triangles(n, spec)?;
            (grid(n), false)
        }
        _ => {
            return Err(format!(
                "unknown scene '{spec}': expected cornell, cornell:K, sphere:N, grid:N or a file ending in .obj"
            ))
        }
    };
    Ok(Scene {
        name: spec.to_string(),
        mesh,
        maps: Maps::default(),
        is_box,
        pitch: if kind == "grid" { GRID_PITCH } else { 0.0 },
        warnings: Vec::new(),
    })
}

/// A sphere around every vertex: the centre of their axis-aligned bounding box and
/// the largest distance from it to a vertex; `(0, 0)` for a mesh without vertices.
pub fn bounding_sphere(mesh: &Mesh) -> (Vec3, f32) {
    let Some(&first) = mesh.positions.first() else {
        return (Vec3::ZERO, 0.0);
    };
    let (low, high) = mesh
        .positions
        .iter()
        .fold((first, first), |(low, high), &p| (low.min(p), high.max(p)));
    let centre = (low + high) / 2.0;
    let radius = mesh
        .positions
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0, f32::max);
    (centre, radius)
}

/// The sizes (bounding-sphere radii) a scene may have to be framed: beyond them
/// f32 cannot hold what framing computes (the light's power grows with the size
/// squared, 1/z with the inverse of the distance).
pub const FRAMED_RADII: (f32, f32) = (1e-9, 1e12);

/// How far the box's light hangs below the ceiling (box units): a light moved out
/// of a closed model keeps this gap to the model's bounding sphere, scaled.
const LIGHT_GAP: f32 = 0.5;

/// The camera and the light that frame `scene` for `camera` (its direction,
/// focal length and image size; its position and near plane are replaced). The
/// box keeps the handout's (`Camera::handout`, `Light::handout`). Another scene's
/// bounding sphere fills 90 % of the image's shorter side; the light sits where
/// the box's sits relative to the box, scaled with the scene, and its power grows
/// with the size squared (eq. 10 falls off as 1/r²), so a model in millimetres is
/// lit as one in metres. The box's light is inside the room, which is open
/// towards the camera; inside a closed model it would light only the model's
/// inside, so when a surface lies between that place and the camera the light
/// moves out along the same direction from the centre to just outside the
/// bounding sphere ([`LIGHT_GAP`] from it, scaled). The near plane stays the
/// handout's 0.01 for a scene 1 unit across (its radius) or larger, and shrinks
/// with a smaller one, so that a model in millimetres is not cut away whole. A
/// scene whose size is outside [`FRAMED_RADII`] is refused.
pub fn framed_view(scene: &Scene, camera: &Camera) -> Result<(Camera, Light), String> {
    let handout = (
        Camera::handout(camera.width, camera.height),
        Light::handout(),
    );
    let near = |d: f32| camera.near.map(|_| d);
    if scene.is_box {
        let framed = Camera {
            position: handout.0.position,
            near: near(DEFAULT_NEAR),
            ..*camera
        };
        return Ok((framed, handout.1));
    }
    let (box_centre, box_radius) = bounding_sphere(&cornell_box());
    let (centre, radius) = bounding_sphere(&scene.mesh);
    let (low, high) = FRAMED_RADII;
    if !(centre.is_finite() && radius.is_finite() && radius <= high) {
        return Err(format!(
            "scene {} is more than {high:e} units across (its bounding sphere's radius): larger than f32 can frame: scale the model down",
            scene.name
        ));
    }
    if radius < low && !scene.mesh.positions.is_empty() {
        return Err(format!(
            "scene {} is {radius:e} units across (its bounding sphere's radius), smaller than f32 can frame (at least {low:e}): scale the model up",
            scene.name
        ));
    }
    let radius = if radius > 0.0 { radius } else { 1.0 };
    let half = camera.width.min(camera.height) as f32 / 2.0;
    let angle = (half / camera.focal).atan();
    let distance = radius / (0.9 * angle.sin()).min(1.0);
    let scale = radius / box_radius;
    let forward = camera.axes()[2];
    let position = centre - forward.normalize_or(Vec3::Z) * distance;
    let offset = (handout.1.position - box_centre) * scale;
    let mut light = centre + offset;
    if hides(&scene.mesh, light, position) {
        light = centre + offset.normalize() * (radius + LIGHT_GAP * scale);
    }
    let framed = Camera {
        position,
        near: near(DEFAULT_NEAR * radius.min(1.0)),
        ..*camera
    };
    let light = Light {
        position: light,
        power: handout.1.power * (scale * scale),
        ..handout.1
    };
    Ok((framed, light))
}

/// Whether a triangle of `mesh` lies on the segment from `light` to `camera`.
fn hides(mesh: &Mesh, light: Vec3, camera: Vec3) -> bool {
    mesh.triangles()
        .any(|tri| ray::intersect(light, camera - light, &tri, 0.0).is_some_and(|t| t < 1.0))
}

/// The memory a built-in scene of about `triangles` triangles holds while it
/// is made and drawn, a byte count a triangle: measured, 60 (65 MB resident
/// for sphere:1000000 and grid:1000000 at 64x64), with a third more for room.
const BYTES_A_TRIANGLE: usize = 80;

/// Refuses, before it is made, a scene whose triangles the memory there is
/// cannot hold.
fn room_for_triangles(triangles: usize, spec: &str) -> Result<(), String> {
    use crate::pipeline::target::{megabytes, memory_for};
    let bytes = triangles.saturating_mul(BYTES_A_TRIANGLE);
    match memory_for(bytes) {
        true => Ok(()),
        false => Err(format!(
            "out of memory: scene {spec} needs about {}",
            megabytes(bytes)
        )),
    }
}
