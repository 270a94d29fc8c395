//! Model files: Wavefront OBJ with its MTL materials, read with the `tobj` crate
//! and written back, by the rules of the design notes' "Models" section.
//!
//! - A file is y up and right-handed, a model faces +z and its front faces are
//!   counter-clockwise seen from the front. Loading turns it half a turn about x:
//!   every position and normal `(x, y, z)` becomes `(x, -y, -z)` (y down, facing a
//!   camera that looks along +z), and every face `(a, b, c)` becomes `(a, c, b)`,
//!   so that the handout's normal `(v2 - v0) x (v1 - v0)` is the front face's.
//!   Writing applies the same two maps, which are their own inverses.
//! - A polygon becomes a fan from its first vertex, `(v0, v1, v2), (v0, v2, v3),
//!   ...`, before that map: tobj's `triangulate` splits polygons exactly so.
//! - One index addresses a vertex's position, normal and texture coordinate (tobj's
//!   `single_index`); tobj numbers the vertices of each object, group or material
//!   run in order of first use and drops the unused ones.
//! - A face's colour is its material's `Kd` clamped to [0, 1]. A face without a
//!   material, whose material the MTL files do not define, or whose material has no
//!   `Kd` is (0.75, 0.75, 0.75).
//! - A material library that the OBJ names but that cannot be read is an error
//!   naming it: silently grey models would hide a missing file.
//! - Vertex normals are kept (renormalised) when every vertex has one, texture
//!   coordinates (v up, as written) when every vertex has one; otherwise none are,
//!   and the face normals light the model. A zero vertex normal takes the normal of
//!   the first face that uses it.
//! - A material's `map_Kd` image (read relative to the OBJ file's folder) is its
//!   texture: where the model has texture coordinates, ρ is read from it instead
//!   of `Kd`. An image that cannot be read is an error naming it.
//! - Errors are one line naming the file and, where it is known, the line.
//!   Points and lines (`f 1`, `f 1 2`, `l 1 2`) are skipped.

use super::cornell::WHITE;
use super::input::{open_regular, shortened};
use crate::extensions::texture::Maps;
use crate::pipeline::mesh::{face_normal, Face, Material, Mesh};
use glam::{Vec2, Vec3};
use std::cell::RefCell;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::io::{self, BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

/// The largest model loaded; a larger one is refused before tobj stores it.
pub const MAX_TRIANGLES: usize = 10_000_000;

/// The most positions (and, each, texture coordinates and normals) a model may
/// list: three for each of the most triangles, none shared.
pub const MAX_VERTICES: usize = 3 * MAX_TRIANGLES;

/// The most an OBJ file may hold (blank lines, comments and all): a model of
/// the most triangles, written with normals and texture coordinates, takes
/// about 1.6 GB and 40 million lines.
pub const MAX_OBJ_BYTES: u64 = 4 << 30;
pub const MAX_OBJ_LINES: u64 = 1 << 26;

/// The most an MTL file may hold.
pub const MAX_MTL_BYTES: u64 = 64 << 20;
pub const MAX_MTL_LINES: u64 = 1 << 22;

/// The longest line read: a line is held whole, so a file without newlines
/// (`/dev/zero`, a binary file) must not be.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// The most material libraries a model may name, and materials they may define
/// in all.
pub const MAX_LIBRARIES: usize = 64;
pub const MAX_MATERIALS: usize = 65_536;

/// The most texels a model's textures may hold in all: as many as the
/// largest one texture ([`super::texture::MAX_TEXTURE_SIDE`] a side).
pub const MAX_MODEL_TEXELS: u64 = 16384 * 16384;

/// The half turn about x between a file's axes and ours; its own inverse.
fn flip(v: Vec3) -> Vec3 {
    Vec3::new(v.x, -v.y, -v.z)
}

/// Reads an OBJ file (and the MTL files it names) into a mesh: its geometry
/// and colours, without the images [`read_obj`] also gives.
pub fn load_obj(path: &Path) -> Result<Mesh, String> {
    read_obj(path).map(|(mesh, _, _)| mesh)
}

/// The memory loading and drawing a model holds, in bytes a byte of its OBJ
/// file: measured, 2.2 (210 MB resident for a grid of a million triangles
/// written by `export`, 94 MB), with room for files of shorter lines.
const OBJ_BYTES_A_BYTE: usize = 4;

/// [`load_obj`], with the images its materials read and the warnings a reader should see: what the file asks for
/// that is drawn otherwise (a material that is not defined, a colour outside
/// [0, 1], a face with fewer than three corners, a `map_Kd` option not used).
pub fn read_obj(path: &Path) -> Result<(Mesh, Maps, Vec<String>), String> {
    let fail = |why: String| format!("{}: {why}", path.display());
    let file = open_regular(path).map_err(fail)?;
    // Before tobj reads it, whose allocations abort when memory runs out.
    let size = file.metadata().map_or(0, |m| m.len()) as usize;
    let bytes = size.saturating_mul(OBJ_BYTES_A_BYTE);
    if !crate::pipeline::target::memory_for(bytes) {
        return Err(fail(format!(
            "out of memory: its {} need about {} to load",
            crate::pipeline::target::megabytes(size),
            crate::pipeline::target::megabytes(bytes)
        )));
    }
    let mut reader = Lines::new(BufReader::new(file), Kind::Obj);
    let dir = path.parent().unwrap_or(Path::new(""));
    let mtl_error = RefCell::new(None);
    let mtl_warnings = RefCell::new(Vec::new());
    // Each library read once, however often it is named (tobj would keep
    // every reading's materials), and at most MAX_LIBRARIES of them.
    let read_libraries = RefCell::new(Vec::<PathBuf>::new());
    let materials_left = RefCell::new(MAX_MATERIALS);
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let loaded = tobj::load_obj_buf(&mut reader, &options, |name| {
        let name = name.to_string_lossy();
        let name = unquoted(&name);
        // A library that is not there leaves its materials undefined: their
        // faces are drawn grey, as the usemtl warnings say (models are often
        // shared without theirs).
        let mut warnings = mtl_warnings.borrow_mut();
        let libraries = libraries_named(dir, name, &mut warnings);
        let (mut materials, mut names) = (Vec::new(), HashMap::new());
        for (part, found) in libraries {
            let Some(found) = found else {
                warnings.push(format!(
                    "material library {} is not there: its materials are left out",
                    shortened(part)
                ));
                continue;
            };
            let mut read = read_libraries.borrow_mut();
            if read.contains(&found) {
                continue;
            }
            if read.len() == MAX_LIBRARIES {
                warnings.push(format!(
                    "material library {}: more than {MAX_LIBRARIES} libraries: left out",
                    shortened(part)
                ));
                continue;
            }
            read.push(found.clone());
            let mut left = materials_left.borrow_mut();
            let (more, more_names) = load_mtl(&found, &mut left, &mut warnings).map_err(|why| {
                mtl_error.borrow_mut().get_or_insert(why);
                tobj::LoadError::GenericFailure
            })?;
            for (material, index) in more_names {
                names.entry(material).or_insert(materials.len() + index);
            }
            materials.extend(more);
        }
        Ok((materials, names))
    });
    let (models, materials) = loaded.map_err(|e| {
        use tobj::LoadError::*;
        match reader.stop.take() {
            Some(why) => fail(why),
            // Found when tobj gathers an object's faces, after reading on: the
            // current line is not theirs, the largest index's line is.
            None if matches!(
                e,
                FaceVertexOutOfBounds | FaceTexCoordOutOfBounds | FaceNormalOutOfBounds
            ) =>
            {
                fail(reader.index_past_the_end().unwrap_or_else(|| e.to_string()))
            }
            None if matches!(e, FaceColorOutOfBounds | InvalidPolygon) => fail(e.to_string()),
            None => fail(format!("line {}: {e}", reader.line)),
        }
    })?;
    if let Some(why) = mtl_error.into_inner() {
        return Err(fail(why));
    }
    let materials = materials.unwrap_or_default();
    let maps: Vec<Option<TextureMap>> = materials
        .iter()
        .map(|m| m.diffuse_texture.as_deref().map(TextureMap::parse))
        .collect();
    let mesh = to_mesh(&models, &materials, &maps).map_err(fail)?;
    let (images, found_elsewhere) = load_diffuse_textures(&materials, &maps, dir).map_err(fail)?;
    let mut warnings = mtl_warnings.into_inner();
    warnings.extend(reader.warnings(&materials));
    // tobj reads a face's texture coordinates past the end of none as none.
    let (index, line) = reader.largest[1];
    if index > reader.counts[1] as u64 {
        warnings.push(format!(
            "line {line}: texture coordinate {index} is past the end: the file has {}: the faces' texture coordinates are left out",
            reader.counts[1]
        ));
    }
    let some_uvs = models.iter().any(|m| !m.mesh.texcoords.is_empty());
    if some_uvs && mesh.uvs.is_empty() && maps.iter().any(Option::is_some) {
        warnings.push(
            "texture coordinates on only some vertices: the map_Kd textures are not drawn (Kd is)"
                .into(),
        );
    }
    warnings.extend(found_elsewhere);
    for (m, map) in materials.iter().zip(&maps) {
        if let Some(kd) = m.diffuse {
            if kd.iter().any(|c| !(0.0..=1.0).contains(c)) {
                warnings.push(format!(
                    "material {}: Kd {} {} {} is outside [0, 1]: clamped to it",
                    m.name, kd[0], kd[1], kd[2]
                ));
            }
        }
        for option in map.iter().flat_map(|t| &t.ignored) {
            warnings.push(format!(
                "material {}: map_Kd option {option} is not supported: left out",
                m.name
            ));
        }
    }
    Ok((mesh, images, warnings.into_iter().map(fail).collect()))
}

/// A `map_Kd` statement: its options, then the file name (which may hold
/// spaces). `-s` scales and `-o` offsets the texture coordinates
/// (`uv * s + o`); the other options of the MTL format are read past and named
/// as not supported.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureMap {
    pub file: String,
    pub scale: Vec2,
    pub offset: Vec2,
    pub ignored: Vec<String>,
}

impl TextureMap {
    pub fn parse(statement: &str) -> TextureMap {
        let mut map = TextureMap {
            file: String::new(),
            scale: Vec2::ONE,
            offset: Vec2::ZERO,
            ignored: Vec::new(),
        };
        let mut words = statement.split_whitespace().peekable();
        let mut rest = statement.trim_start();
        while let Some(&word) = words.peek() {
            // Options and their counts of values, by the MTL format.
            let values = match word {
                "-s" | "-o" | "-t" => 3,
                "-mm" => 2,
                "-blendu" | "-blendv" | "-bm" | "-boost" | "-cc" | "-clamp" | "-imfchan"
                | "-texres" | "-type" => 1,
                _ => break,
            };
            words.next();
            let mut read = Vec::new();
            while read.len() < values {
                let Some(&next) = words.peek() else { break };
                // -s, -o and -t take one to three numbers (a NaN or an infinity
                // among them is read, then taken as its default); the others
                // take words.
                let number = next.parse::<f32>().ok();
                if values == 3 && number.is_none() {
                    break;
                }
                read.push((next, number.filter(|x| x.is_finite())));
                words.next();
            }
            let number = |i: usize, default: f32| read.get(i).and_then(|r| r.1).unwrap_or(default);
            match word {
                "-s" => map.scale = Vec2::new(number(0, 1.0), number(1, 1.0)),
                "-o" => map.offset = Vec2::new(number(0, 0.0), number(1, 0.0)),
                _ => map.ignored.push(word.to_string()),
            }
            // What is left of the statement after this option and its values.
            for w in std::iter::once(word).chain(read.iter().map(|r| r.0)) {
                rest = rest[rest.find(w).map_or(0, |i| i + w.len())..].trim_start();
            }
        }
        map.file = unquoted(rest.trim_end()).to_string();
        map
    }
}

/// Each material's `map_Kd` image, read relative to the OBJ file's folder, as
/// that material's texture (shared by the materials that name the same file),
/// and the warnings of [`file_beside`] and for each one not there at all.
fn load_diffuse_textures(
    materials: &[tobj::Material],
    maps: &[Option<TextureMap>],
    dir: &Path,
) -> Result<(Maps, Vec<String>), String> {
    let mut warnings = Vec::new();
    let mut images = Maps::default();
    // Each file named, found once (with the warnings of `file_beside`, and for
    // each one not there at all: a model shared without its textures still
    // draws). Each texel is held as three floats, so the textures in all are
    // bounded, as one texture's sides are, from their headers before any is read.
    let mut found: HashMap<&str, Option<PathBuf>> = HashMap::new();
    let mut texels = 0u64;
    for (m, map) in materials.iter().zip(maps) {
        let Some(name) = map.as_ref().map(|t| t.file.as_str()) else {
            continue;
        };
        if name.is_empty() {
            // Options alone, as a bare map_Kd: its Kd is drawn.
            warnings.push(format!(
                "material {}: map_Kd names no file, only options: left out",
                m.name
            ));
            continue;
        }
        if found.contains_key(name) {
            continue;
        }
        let what = format!("material {}: map_Kd", m.name);
        let path = file_beside(dir, name, &what, &mut warnings);
        match &path {
            None => warnings.push(format!(
                "{what} {} is not there: its Kd is drawn instead",
                shortened(name)
            )),
            Some(path) => {
                let (w, h) = super::input::image_size(path).unwrap_or((0, 0));
                texels += w as u64 * h as u64;
                if texels > MAX_MODEL_TEXELS {
                    return Err(format!(
                        "{what} {}: the model's textures would hold more than {MAX_MODEL_TEXELS} texels in all: refused",
                        shortened(name)
                    ));
                }
            }
        }
        found.insert(name, path);
    }
    let mut loaded: HashMap<&str, u32> = HashMap::new();
    for (i, (m, map)) in materials.iter().zip(maps).enumerate() {
        let Some(name) = map.as_ref().map(|t| t.file.as_str()) else {
            continue;
        };
        let Some(Some(path)) = found.get(name) else {
            continue;
        };
        let index = match loaded.get(name) {
            Some(&index) => index,
            None => {
                let texture = super::texture::load_texture(path)
                    .map_err(|e| format!("material {}: map_Kd: {e}", m.name))?;
                let index = images.push(texture);
                loaded.insert(name, index);
                index
            }
        };
        images.of_mut(i).texture = Some(index);
    }
    Ok((images, warnings))
}

/// Where the file an `mtllib` or a `map_Kd` names is, as models made on another
/// machine name it: the path as written if something is there; else with `\` read as `/` (a
/// Windows path); else the longest tail of it found below `dir` (an absolute
/// path from the author's disk, `C:\Users\...\textures\wood.jpg`, is
/// `textures/wood.jpg` or `wood.jpg` beside the model); each tail also matched
/// without regard to case (`Wood.JPG` for `wood.jpg`). `None` when none is there.
/// A file found elsewhere than written gets a warning naming it, after `what`.
fn file_beside(dir: &Path, name: &str, what: &str, warnings: &mut Vec<String>) -> Option<PathBuf> {
    // Whatever is there as written is read (or refused, a FIFO say) as it is.
    let as_written = dir.join(name);
    if as_written.exists() {
        return Some(as_written);
    }
    let found = elsewhere(dir, name)?;
    warnings.push(format!(
        "{what} {} is not there: read {} instead",
        shortened(name),
        found.display()
    ));
    Some(found)
}

/// [`file_beside`] of a file not where it is written.
fn elsewhere(dir: &Path, name: &str) -> Option<PathBuf> {
    let parts: Vec<&str> = name
        .split(['/', '\\'])
        .filter(|p| !p.is_empty() && !p.ends_with(':'))
        .collect();
    // A path from the author's disk ends in the few parts that can be beside
    // the model; each tail tried costs a look through its folders.
    let first = parts.len().saturating_sub(MAX_TAIL_PARTS);
    (first..parts.len()).find_map(|first| {
        let tail = &parts[first..];
        let exact = tail.iter().fold(dir.to_path_buf(), |p, part| p.join(part));
        if exact.is_file() {
            return Some(exact);
        }
        // Each part matched without regard to case, in the folders as they are.
        tail.iter()
            .try_fold(dir.to_path_buf(), |at, part| {
                // A model named without a folder is in the current one.
                let folder = match at.as_os_str().is_empty() {
                    true => Path::new("."),
                    false => at.as_path(),
                };
                std::fs::read_dir(folder)
                    .ok()?
                    .take(MAX_FOLDER_ENTRIES)
                    .flatten()
                    .find(|e| e.file_name().to_string_lossy().eq_ignore_ascii_case(part))
                    .map(|e| at.join(e.file_name()))
            })
            .filter(|p| p.is_file())
    })
}

/// How many of a name's last parts [`file_beside`] looks for beside the model.
const MAX_TAIL_PARTS: usize = 8;

/// How many entries of a folder [`file_beside`] looks through for a name.
const MAX_FOLDER_ENTRIES: usize = 10_000;

/// The files an `mtllib` line names, each with where it was found: the
/// format lets it name several, and a name with spaces in it, as Blender
/// writes a model's, is one when that file is there.
fn libraries_named<'n>(
    dir: &Path,
    name: &'n str,
    warnings: &mut Vec<String>,
) -> Vec<(&'n str, Option<PathBuf>)> {
    let what = "material library";
    if let Some(found) = file_beside(dir, name, what, warnings) {
        return vec![(name, Some(found))];
    }
    let parts: Vec<_> = name
        .split_whitespace()
        .map(|part| (part, file_beside(dir, part, what, warnings)))
        .collect();
    match parts.iter().any(|(_, found)| found.is_some()) {
        true => parts,
        false => vec![(name, None)],
    }
}

/// Reads one MTL file; the error names it and, where known, the line.
/// The statements it leaves out are named in `warnings`; it may define at most
/// `materials_left` materials, and takes those it defines from it.
fn load_mtl(
    path: &Path,
    materials_left: &mut usize,
    warnings: &mut Vec<String>,
) -> Result<(Vec<tobj::Material>, HashMap<String, usize>), String> {
    let fail = |why: String| format!("material library {}: {why}", path.display());
    let file = open_regular(path).map_err(fail)?;
    let mut reader = Lines::new(BufReader::new(file), Kind::Mtl);
    reader.materials_left = *materials_left;
    let loaded = tobj::load_mtl_buf(&mut reader).map_err(|e| {
        fail(
            reader
                .stop
                .take()
                .unwrap_or_else(|| format!("line {}: {e}", reader.line)),
        )
    })?;
    *materials_left = reader.materials_left;
    warnings.extend(reader.unsupported.iter().map(|w| fail(w.clone())));
    Ok(loaded)
}

/// Our mesh from tobj's models: the map to our axes, one material per MTL material
/// (plus the default grey when a face needs it).
fn to_mesh(
    models: &[tobj::Model],
    materials: &[tobj::Material],
    maps: &[Option<TextureMap>],
) -> Result<Mesh, String> {
    let mut mesh = Mesh {
        materials: materials
            .iter()
            .map(|m| {
                Material::new(
                    m.diffuse
                        .map_or(WHITE, |kd| Vec3::from(kd).clamp(Vec3::ZERO, Vec3::ONE)),
                )
            })
            .collect(),
        ..Mesh::default()
    };
    let mut default = None; // the grey material's index, once a face needs it
    let (mut all_normals, mut all_uvs) = (true, true);
    let vec3s = |xs: &[f32]| -> Vec<Vec3> {
        xs.chunks_exact(3)
            .map(|v| flip(Vec3::new(v[0], v[1], v[2])))
            .collect()
    };
    for model in models {
        let m = &model.mesh;
        let first = mesh.positions.len() as u32;
        mesh.positions.extend(vec3s(&m.positions));
        // tobj leaves out the normal or texture coordinate of a vertex that has
        // none, so the lists line up with the positions only when all have one.
        all_normals &= m.normals.len() == m.positions.len();
        all_uvs &= m.texcoords.len() / 2 == m.positions.len() / 3;
        if all_normals {
            mesh.normals.extend(vec3s(&m.normals));
        }
        if all_uvs {
            // A map_Kd -s or -o moves the coordinates of its material's faces;
            // tobj gives each material its own vertices.
            let (scale, offset) = match m.material_id.and_then(|i| maps.get(i)?.as_ref()) {
                Some(map) => (map.scale, map.offset),
                None => (Vec2::ONE, Vec2::ZERO),
            };
            mesh.uvs.extend(
                m.texcoords
                    .chunks_exact(2)
                    .map(|t| Vec2::new(t[0], t[1]) * scale + offset),
            );
        }
        let material = match m.material_id {
            Some(i) if i < materials.len() => i as u32,
            _ => *default.get_or_insert_with(|| {
                mesh.materials.push(Material::new(WHITE));
                mesh.materials.len() as u32 - 1
            }),
        };
        for t in m.indices.chunks_exact(3) {
            let vertices = [first + t[0], first + t[2], first + t[1]];
            let normal = face_normal(vertices.map(|i| mesh.positions[i as usize]));
            mesh.faces.push(Face {
                vertices,
                normal,
                material,
            });
        }
    }
    if !all_normals {
        mesh.normals.clear();
    }
    if !all_uvs {
        mesh.uvs.clear();
    }
    if mesh.faces.is_empty() {
        return Err("no faces: nothing to draw".into());
    }
    let finite = mesh
        .positions
        .iter()
        .chain(&mesh.normals)
        .all(|v| v.is_finite())
        && mesh.uvs.iter().all(|t| t.is_finite());
    if !finite {
        return Err("a coordinate is NaN or infinite".into());
    }
    // A normal that is already unit length (to f32 rounding) is kept bit for bit,
    // so a written mesh loads back unchanged.
    for n in &mut mesh.normals {
        let len2 = n.length_squared();
        if len2 > 0.0 && (len2 - 1.0).abs() > 1e-5 {
            *n /= len2.sqrt();
        }
    }
    if !mesh.normals.is_empty() {
        for f in &mesh.faces {
            for &i in &f.vertices {
                if mesh.normals[i as usize] == Vec3::ZERO {
                    mesh.normals[i as usize] = f.normal;
                }
            }
        }
    }
    Ok(mesh)
}

/// `mesh` as the text of an OBJ file and of the MTL file `mtl_name` it names, by
/// the module's rules: loading them gives back the same positions, normals,
/// texture coordinates, faces and colours, bit for bit, for a mesh whose vertices
/// are numbered in order of first use as the file lists them and not shared
/// between materials (the box, `sphere`, `grid`). Returns (OBJ, MTL).
pub fn obj_text(mesh: &Mesh, mtl_name: &str) -> Result<(String, String), String> {
    let n = mesh.positions.len();
    let consistent = (mesh.normals.is_empty() || mesh.normals.len() == n)
        && (mesh.uvs.is_empty() || mesh.uvs.len() == n)
        && mesh.faces.iter().all(|f| {
            f.vertices.iter().all(|&i| (i as usize) < n)
                && (f.material as usize) < mesh.materials.len()
        });
    if !consistent {
        return Err("the mesh refers to vertices or materials it does not have".into());
    }
    let finite = mesh
        .positions
        .iter()
        .chain(&mesh.normals)
        .all(|v| v.is_finite())
        && mesh.uvs.iter().all(|t| t.is_finite())
        && mesh.materials.iter().all(|m| m.color.is_finite());
    if !finite {
        return Err("a coordinate or colour is NaN or infinite".into());
    }
    // `{}` prints an f32 with the fewest digits that read back as the same f32.
    let mut mtl = String::from("# rasterlab: the materials of the model beside it\n");
    for (i, m) in mesh.materials.iter().enumerate() {
        let c = m.color;
        let _ = writeln!(mtl, "newmtl m{i}\nKd {} {} {}", c.x, c.y, c.z);
    }
    let mut obj = String::from("# rasterlab: y up, front faces counter-clockwise\n");
    let _ = writeln!(obj, "mtllib {mtl_name}");
    for p in mesh.positions.iter().map(|&p| flip(p)) {
        let _ = writeln!(obj, "v {} {} {}", p.x, p.y, p.z);
    }
    for t in &mesh.uvs {
        let _ = writeln!(obj, "vt {} {}", t.x, t.y);
    }
    for v in mesh.normals.iter().map(|&v| flip(v)) {
        let _ = writeln!(obj, "vn {} {} {}", v.x, v.y, v.z);
    }
    let (uvs, normals) = (!mesh.uvs.is_empty(), !mesh.normals.is_empty());
    let mut material = None;
    for f in &mesh.faces {
        if material != Some(f.material) {
            material = Some(f.material);
            let _ = writeln!(obj, "usemtl m{}", f.material);
        }
        obj.push('f');
        let [a, b, c] = f.vertices;
        for i in [a, c, b].map(|i| i + 1) {
            let _ = match (uvs, normals) {
                (false, false) => write!(obj, " {i}"),
                (true, false) => write!(obj, " {i}/{i}"),
                (false, true) => write!(obj, " {i}//{i}"),
                (true, true) => write!(obj, " {i}/{i}/{i}"),
            };
        }
        obj.push('\n');
    }
    Ok((obj, mtl))
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Obj,
    Mtl,
}

/// A file name without the double quotes some exporters put around one with
/// spaces in it.
fn unquoted(name: &str) -> &str {
    let inside = name.strip_prefix('"').and_then(|n| n.strip_suffix('"'));
    inside.filter(|n| !n.is_empty()).unwrap_or(name)
}

/// An MTL colour given by one number, `Kd 0.5`, which the format allows
/// (green and blue then equal red), written out as three for tobj.
fn one_number_colour(line: &str) -> Option<String> {
    let mut words = line.split_whitespace();
    let first = words.next()?;
    let value = words.next()?;
    let colour = matches!(first, "Ka" | "Kd" | "Ks" | "Ke");
    (colour && words.next().is_none() && value.parse::<f32>().is_ok())
        .then(|| format!("{first} {value} {value} {value}\n"))
}

/// The file as tobj reads it, a line at a time: counts the lines, so that errors
/// can name one, and stops tobj, with the reason in `stop`, at a line it must not
/// read on: a number that is NaN or infinite, an index that tobj's arithmetic
/// would overflow on (a panic in builds with overflow checks), an MTL colour
/// without three values (tobj 4.0.5 panics on it), or more than MAX_TRIANGLES
/// triangles.
struct Lines<R> {
    inner: R,
    kind: Kind,
    /// Lines read so far.
    line: usize,
    /// `v`, `vt` and `vn` lines so far: a negative index counts back from these.
    counts: [usize; 3],
    triangles: usize,
    stop: Option<String>,
    /// The largest positive index of each kind, with its line.
    largest: [(u64, usize); 3],
    /// Faces with fewer than three corners: the first one's line, and how many.
    short_faces: (usize, usize),
    /// Each material name `usemtl` gives (the first [`MAX_NAMES`]), with its first line.
    usemtl: Vec<(String, usize)>,
    /// Lines other than comments read as Latin-1: the first one's number, and how many.
    latin1: (usize, usize),
    /// Polylines (`l`), which are not drawn: the first one's line, and how many.
    polylines: (usize, usize),
    /// In an MTL file: how many more materials it may define, and the
    /// statements of the MTL format it leaves out, each with its line.
    materials_left: usize,
    unsupported: Vec<String>,
    /// What was read so far, for the bounds on a whole file.
    bytes: u64,
    physical_lines: u64,
}

/// How many material names are remembered for the warnings.
const MAX_NAMES: usize = 256;

impl<R: BufRead> Lines<R> {
    fn new(inner: R, kind: Kind) -> Self {
        Lines {
            inner,
            kind,
            line: 0,
            counts: [0; 3],
            triangles: 0,
            stop: None,
            largest: [(0, 0); 3],
            short_faces: (0, 0),
            usemtl: Vec::new(),
            latin1: (0, 0),
            polylines: (0, 0),
            materials_left: MAX_MATERIALS,
            unsupported: Vec::new(),
            bytes: 0,
            physical_lines: 0,
        }
    }

    /// A line that is not UTF-8 read as Latin-1, a character a byte: files
    /// written on Windows carry comments and names in its Western encoding,
    /// whose letters are Latin-1's, and a name so read in both the OBJ and its
    /// MTL still matches (an MTL's `é` in UTF-8 is the OBJ's byte 0xE9 read so).
    fn latin1(&mut self, bytes: Vec<u8>, number: usize) -> String {
        let line: String = bytes.into_iter().map(char::from).collect();
        if !line.trim_start().starts_with('#') {
            if self.latin1.1 == 0 {
                self.latin1.0 = number;
            }
            self.latin1.1 += 1;
        }
        line
    }

    /// Which line has an index past the end of its list, and what it is.
    fn index_past_the_end(&self) -> Option<String> {
        let kinds = ["positions", "texture coordinates", "normals"];
        (0..3).find_map(|k| {
            let (index, line) = self.largest[k];
            (index > self.counts[k] as u64).then(|| {
                format!(
                    "line {line}: index {index} is past the end: the file has {} {}",
                    self.counts[k], kinds[k]
                )
            })
        })
    }

    /// The warnings gathered while reading, once the materials are known.
    fn warnings(&self, materials: &[tobj::Material]) -> Vec<String> {
        let mut out = Vec::new();
        for (name, line) in &self.usemtl {
            if !materials.iter().any(|m| &m.name == name) {
                out.push(format!(
                    "line {line}: usemtl {name}: no material of that name in the material libraries: its faces are grey"
                ));
            }
        }
        // The first line of a kind, and how many more there were.
        let first = |(line, n): (usize, usize), what: &str, such: &str| {
            let more = match n {
                1 => String::new(),
                n => format!(" (and {} more such {such})", n - 1),
            };
            (n > 0).then(|| format!("line {line}: {what}{more}"))
        };
        out.extend(first(
            self.short_faces,
            "a face needs at least three corners: left out",
            "faces",
        ));
        out.extend(first(
            self.latin1,
            "not UTF-8: read as Latin-1, a character a byte",
            "lines",
        ));
        out.extend(first(
            self.polylines,
            "a polyline (l) is not drawn: left out",
            "lines",
        ));
        out
    }

    /// A statement as tobj is given it: in an OBJ file, a polyline left out
    /// (tobj would fill it as a face), so is a face of fewer than three
    /// corners, and a vertex's colour (`v x y z r g b`,
    /// which tobj wants on every vertex or none) dropped, a texture coordinate
    /// of u alone given its v of 0; in an MTL file, only
    /// what is drawn from (`newmtl`, `Kd`, `map_Kd`), so that a statement of
    /// the format read otherwise (`Ka spectral`, `d -halo`, `illum 2.0`) cannot
    /// stop the model loading. A statement left out stays as a comment, so
    /// that the lines keep their numbers.
    fn statement(&mut self, line: String, number: usize) -> String {
        let mut words = line.split_whitespace();
        let first = words.next().unwrap_or("");
        let comment = || "#\n".to_string();
        match (self.kind, first) {
            (Kind::Obj, "l") => {
                if self.polylines.1 == 0 {
                    self.polylines.0 = number;
                }
                self.polylines.1 += 1;
                comment()
            }
            // A comment after a vertex or a face (`v 1 2 3 # corner`), which
            // tobj would read as more numbers.
            (Kind::Obj, "v" | "vt" | "vn" | "f") if line.contains('#') => {
                let data = line.split('#').next().unwrap_or("");
                self.statement(format!("{}\n", data.trim_end()), number)
            }
            // Warned of as a short face: tobj refuses one with no corners
            // ("invalid polygon", without its line) and leaves out the rest.
            (Kind::Obj, "f") if words.clone().count() < 3 => {
                if self.short_faces.1 == 0 {
                    self.short_faces.0 = number;
                }
                self.short_faces.1 += 1;
                comment()
            }
            (Kind::Obj, "v") if words.clone().count() >= 6 => {
                let xyz: Vec<&str> = words.take(3).collect();
                format!("v {}\n", xyz.join(" "))
            }
            // The format lets a texture coordinate give u alone (v is then 0),
            // which tobj refuses.
            (Kind::Obj, "vt") if words.clone().count() == 1 => {
                format!("vt {} 0\n", words.next().unwrap_or("0"))
            }
            (Kind::Obj, _) => line,
            (Kind::Mtl, "map_Kd") if words.next().is_none() => {
                self.note_left_out(format!("line {number}: map_Kd names no file: left out"));
                comment()
            }
            (Kind::Mtl, "newmtl" | "map_Kd") => line,
            (Kind::Mtl, "Kd") => match words.next() {
                Some(form @ ("spectral" | "xyz")) => {
                    self.note_left_out(format!(
                        "line {number}: Kd {form} is not supported: left out"
                    ));
                    comment()
                }
                _ => one_number_colour(&line).unwrap_or(line),
            },
            (Kind::Mtl, _) if first.starts_with('#') || first.is_empty() => line,
            (Kind::Mtl, _) => comment(),
        }
    }

    /// Says why an MTL statement is left out (the first [`MAX_NAMES`] of them).
    fn note_left_out(&mut self, why: String) {
        if self.unsupported.len() < MAX_NAMES {
            self.unsupported.push(why);
        }
    }

    fn check(&mut self, line: &str) -> Result<(), String> {
        let mut words = line.split_whitespace();
        let first = words.next().unwrap_or("");
        match (self.kind, first) {
            (Kind::Obj, "f") => return self.check_face(words),
            (Kind::Obj, "usemtl") => {
                let name = line
                    .trim()
                    .split_once(char::is_whitespace)
                    .map_or("", |n| n.1);
                let name = name.trim();
                if self.usemtl.len() < MAX_NAMES && !self.usemtl.iter().any(|u| u.0 == name) {
                    self.usemtl.push((name.to_string(), self.line));
                }
                return Ok(());
            }
            (Kind::Obj, "v" | "vt" | "vn") => {
                let k = ["v", "vt", "vn"]
                    .iter()
                    .position(|&w| w == first)
                    .unwrap_or(0);
                self.counts[k] += 1;
                if self.counts[k] > MAX_VERTICES {
                    return Err(format!(
                        "more than {MAX_VERTICES} '{first}' lines: the model is too large to load"
                    ));
                }
            }
            (Kind::Mtl, "Kd") if words.clone().count() < 3 => {
                return Err(format!("{first} needs three numbers (or one, for a grey)"))
            }
            (Kind::Mtl, "Kd") => {}
            (Kind::Mtl, "newmtl") => {
                if self.materials_left == 0 {
                    return Err(format!(
                        "more than {MAX_MATERIALS} materials: the model is too large to load"
                    ));
                }
                self.materials_left -= 1;
                return Ok(());
            }
            _ => return Ok(()),
        }
        // Words that are not numbers at all are tobj's to report.
        // A number past f32's range (1e39) reads as infinite: said as such.
        match words.find(|w| w.parse::<f32>().is_ok_and(|x| !x.is_finite())) {
            Some(w) if crate::scene::input::past_f32(w) => Err(format!(
                "{} is past the largest number a coordinate holds (about 3.4e38)",
                crate::scene::input::shortened(w)
            )),
            Some(_) => Err("a number is NaN or infinite".into()),
            None => Ok(()),
        }
    }

    fn check_face<'a>(&mut self, corners: impl Iterator<Item = &'a str>) -> Result<(), String> {
        let mut n = 0;
        for corner in corners {
            n += 1;
            // position/texture/normal; a negative index counts back. tobj
            // takes nothing else (its "face parse error"): said here with the
            // corner.
            if corner.split('/').skip(3).any(|index| !index.is_empty()) {
                return Err(not_a_corner(corner));
            }
            for (k, index) in corner.split('/').take(3).enumerate() {
                if index.is_empty() {
                    continue; // v//vn, v/vt/
                }
                let Ok(i) = index.parse::<i64>() else {
                    return Err(match whole_number(index) {
                        true => format!("index {index} is out of range"),
                        false => not_a_corner(corner),
                    });
                };
                if i == 0
                    || i > u32::MAX as i64
                    || (i < 0 && i.unsigned_abs() > self.counts[k] as u64)
                {
                    return Err(format!("index {i} is out of range"));
                }
                if i > 0 && i as u64 > self.largest[k].0 {
                    self.largest[k] = (i as u64, self.line);
                }
            }
        }
        self.triangles += n.max(2) - 2;
        if self.triangles > MAX_TRIANGLES {
            return Err(format!(
                "more than {MAX_TRIANGLES} triangles: the model is too large to load"
            ));
        }
        Ok(())
    }
}

/// Reads one line of `inner` into `bytes`, ended by `\n`, `\r\n` or a lone
/// `\r` (as old Mac programs write them; read as `\n`), and stops once past
/// `limit` bytes. Returns how many bytes it put in `bytes`.
fn read_line_ending(
    inner: &mut impl BufRead,
    limit: usize,
    bytes: &mut Vec<u8>,
) -> io::Result<usize> {
    loop {
        let buf = inner.fill_buf()?;
        if buf.is_empty() || bytes.len() > limit {
            return Ok(bytes.len());
        }
        let Some(end) = buf.iter().position(|&b| b == b'\n' || b == b'\r') else {
            let n = buf.len();
            bytes.extend_from_slice(buf);
            inner.consume(n);
            continue;
        };
        let at_return = buf[end] == b'\r';
        bytes.extend_from_slice(&buf[..end]);
        inner.consume(end + 1);
        if at_return && inner.fill_buf()?.first() == Some(&b'\n') {
            inner.consume(1);
        }
        bytes.push(b'\n');
        return Ok(bytes.len());
    }
}

fn not_a_corner(corner: &str) -> String {
    format!("face corner '{corner}' is not v, v/vt, v//vn or v/vt/vn (whole-number indices)")
}

/// Digits, after at most one sign.
fn whole_number(text: &str) -> bool {
    let digits = text.strip_prefix(['-', '+']).unwrap_or(text);
    !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())
}

impl<R: BufRead> Read for Lines<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.inner.read(buf)
    }
}

impl<R: BufRead> BufRead for Lines<R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amount: usize) {
        self.inner.consume(amount)
    }

    /// tobj reads with `lines()`, which reads each line through this: at most
    /// [`MAX_LINE_BYTES`] of it.
    fn read_line(&mut self, text: &mut String) -> io::Result<usize> {
        let number = self.line + 1;
        let (most_bytes, most_lines) = match self.kind {
            Kind::Obj => (MAX_OBJ_BYTES, MAX_OBJ_LINES),
            Kind::Mtl => (MAX_MTL_BYTES, MAX_MTL_LINES),
        };
        if self.bytes > most_bytes || self.physical_lines > most_lines {
            let why = format!(
                "more than {} MB or {most_lines} lines: too large to load",
                most_bytes >> 20
            );
            self.stop = Some(format!("line {number}: {why}"));
            return Err(io::Error::other(why));
        }
        let mut line = String::new();
        let mut more = 0; // lines joined to the first by a closing backslash
        loop {
            let mut bytes = Vec::new();
            let read = read_line_ending(&mut self.inner, MAX_LINE_BYTES - line.len(), &mut bytes);
            self.physical_lines += 1;
            self.bytes += bytes.len() as u64;
            let part = match read {
                Err(e) => Err(e.to_string()),
                Ok(n) if line.len() + n > MAX_LINE_BYTES => Err(format!(
                    "longer than {MAX_LINE_BYTES} bytes: not a model file, or a broken one"
                )),
                Ok(_) => Ok(String::from_utf8(bytes)
                    .unwrap_or_else(|e| self.latin1(e.into_bytes(), number + more))),
            };
            match part {
                Ok(part) if line.is_empty() => line = part,
                Ok(part) => line.push_str(&part),
                Err(why) => {
                    self.stop = Some(format!("line {}: {why}", number + more));
                    return Err(io::Error::other(why));
                }
            }
            // `v 1 2 \` continues on the next line, as the format allows.
            match line.trim_end().strip_suffix('\\') {
                Some(joined) if !line.trim_start().starts_with('#') => {
                    line = format!("{joined} ");
                    more += 1;
                }
                _ => break,
            }
        }
        if more > 0 && !line.ends_with('\n') {
            line.push('\n');
        }
        // A byte-order mark, as Notepad saves UTF-8, would hide the first
        // line's keyword from tobj (a vertex or `newmtl` lost silently).
        if self.line == 0 && line.starts_with('\u{feff}') {
            line.drain(..'\u{feff}'.len_utf8());
        }
        let line = match line.is_empty() {
            true => line,
            false => self.statement(line, number),
        };
        if !line.is_empty() {
            self.line = number + more;
            if let Err(why) = self.check(&line) {
                self.stop = Some(format!("line {number}: {why}"));
                return Err(io::Error::other(why));
            }
        }
        text.push_str(&line);
        Ok(line.len())
    }
}
