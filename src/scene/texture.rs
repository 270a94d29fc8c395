//! Textures for a scene (`--texture checker|PATH`): a procedural checker, images
//! read with `image`, and texture coordinates from a mesh's own geometry where it
//! has none.

use super::Scene;
use crate::extensions::texture::Texture;
use crate::pipeline::Mesh;
use glam::{Vec2, Vec3};
use std::path::Path;

/// Squares along each side of the checker: one texel each, so nearest and
/// bilinear sampling differ visibly.
pub const CHECKER_SQUARES: u32 = 8;

/// How dark the checker's dark squares are, as a fraction of the colour.
const CHECKER_DARK: f32 = 0.25;

/// What `--texture` names.
#[derive(Clone, Debug, PartialEq)]
pub enum TextureSpec {
    /// Each textured material gets a checker of its own colour and a darker one.
    Checker,
    /// An image file, the same for every textured material.
    Image(std::path::PathBuf),
    /// No textures, not even a model's own `map_Kd`: each face's `Kd`.
    None,
}

impl TextureSpec {
    pub fn parse(spec: &str) -> TextureSpec {
        match spec {
            "checker" => TextureSpec::Checker,
            "none" => TextureSpec::None,
            path => TextureSpec::Image(path.into()),
        }
    }
}

/// A checker of [`CHECKER_SQUARES`]² texels in `color` and a darker shade of it.
pub fn checker(color: Vec3) -> Texture {
    let n = CHECKER_SQUARES;
    let texels = (0..n * n)
        .map(|i| {
            let dark = (i % n + i / n) % 2 == 1;
            if dark {
                color * CHECKER_DARK
            } else {
                color
            }
        })
        .collect();
    Texture::new(n, n, texels).expect("a non-empty square")
}

/// The longest side of a texture read from a file.
pub const MAX_TEXTURE_SIDE: u32 = 16384;

/// The image at `path` as a texture of linear reflectances (each 8-bit channel
/// over 255). The error is one line naming the file.
pub fn load_texture(path: &Path) -> Result<Texture, String> {
    use image::{DynamicImage, GenericImageView};
    let shown = path.display();
    let limit = super::input::ImageLimit {
        max_side: MAX_TEXTURE_SIDE,
        what: "a texture",
    };
    let (width, height) = limit
        .allowed_size(path)
        .map_err(|e| format!("texture {shown}: {e}"))?;
    let n = width as usize * height as usize;
    // The decoded image (at most 8 bytes a pixel) and the texels, asked for
    // before decoding: an allocation the decoder cannot make aborts.
    let out_of_memory = |bytes: usize| {
        let need = crate::pipeline::target::megabytes(bytes);
        format!("texture {shown}: out of memory: its {width}x{height} texels need {need}")
    };
    let both = n * (8 + std::mem::size_of::<Vec3>());
    Vec::<u8>::new()
        .try_reserve_exact(both)
        .map_err(|_| out_of_memory(both))?;
    let image =
        super::input::read_image(path, limit).map_err(|e| format!("texture {shown}: {e}"))?;
    let mut texels = Vec::new();
    texels
        .try_reserve_exact(n)
        .map_err(|_| out_of_memory(n * std::mem::size_of::<Vec3>()))?;
    let texel = |c: [u8; 3]| Vec3::from(c.map(|c| c as f32 / 255.0));
    // Converted a pixel at a time: a converted copy of a large image is one
    // more allocation that could abort.
    match &image {
        DynamicImage::ImageRgb8(rgb) => texels.extend(rgb.pixels().map(|p| texel(p.0))),
        other => texels.extend(other.pixels().map(|(_, _, p)| texel([p[0], p[1], p[2]]))),
    }
    Texture::new(width, height, texels)
        .ok_or_else(|| format!("texture {shown}: the image is empty"))
}

/// Gives `scene` the texture `spec` names: on the Cornell box its walls, floor
/// and ceiling (the blocks keep their colours); on any other scene every
/// material. A mesh without texture coordinates gets them from its geometry
/// ([`planar_uvs`]).
pub fn apply_texture(scene: &mut Scene, spec: &TextureSpec) -> Result<(), String> {
    let image = match spec {
        TextureSpec::Checker => None,
        TextureSpec::Image(path) => Some(load_texture(path)?),
        TextureSpec::None => {
            scene
                .maps
                .materials
                .iter_mut()
                .for_each(|m| m.texture = None);
            return Ok(());
        }
    };
    let textured = surfaces_to_map(scene);
    let maps = &mut scene.maps;
    let shared = image.map(|t| maps.push(t));
    for (i, (material, textured)) in scene.mesh.materials.iter().zip(textured).enumerate() {
        if !textured {
            continue;
        }
        let index = match shared {
            Some(index) => index,
            None => maps.push(checker(material.color)),
        };
        maps.of_mut(i).texture = Some(index);
    }
    Ok(())
}

/// Which of `scene`'s materials a texture or normal map goes on: the box's room
/// (its walls, floor and ceiling), or every material of another scene. Gives the
/// mesh texture coordinates from its geometry if it has none.
fn surfaces_to_map(scene: &mut Scene) -> Vec<bool> {
    let mesh = &mut scene.mesh;
    if mesh.uvs.is_empty() {
        *mesh = planar_uvs(mesh);
    }
    if scene.is_box {
        // The room is the box's first ten faces, in colours no block uses.
        let room = super::cornell_box();
        let colours: Vec<Vec3> = room.faces[..10]
            .iter()
            .map(|f| room.material(f).color)
            .collect();
        mesh.materials
            .iter()
            .map(|m| colours.contains(&m.color))
            .collect()
    } else {
        vec![true; mesh.materials.len()]
    }
}

/// Bumps across a surface, [`BUMPS`] to a side: a tangent-space normal map of
/// round domes, each normal `(-dh/du, -dh/dv, 1)` normalised and stored as
/// `(n + 1) / 2`.
pub fn bumps() -> Texture {
    bump_texture(|_, dh_du, dh_dv| {
        let n = Vec3::new(-dh_du, -dh_dv, 1.0).normalize();
        (n + Vec3::ONE) / 2.0
    })
}

/// The heights of [`bumps`]' domes, 0 on the flat and 1 at a dome's top, grey:
/// the height map `--parallax` reads.
pub fn bump_heights() -> Texture {
    bump_texture(|h, _, _| Vec3::splat(h / DOME_TOP))
}

/// A dome's top, in cells: `0.5 sqrt(R²)` for R = 0.4.
const DOME_TOP: f32 = 0.2;

/// A texture of the bumps: each texel `texel(h, dh/du, dh/dv)` for the height h
/// of the domes there (in cells), a dome `0.5 sqrt(R² - r²)` of radius R = 0.4
/// cell around each cell's centre.
fn bump_texture(texel: impl Fn(f32, f32, f32) -> Vec3) -> Texture {
    let size = 16 * BUMPS;
    let cell = size as f32 / BUMPS as f32;
    let texels = (0..size * size)
        .map(|i| {
            // Column and row from the top; v points up, so dh/dv is -dh/drow.
            let (x, y) = ((i % size) as f32 + 0.5, (i / size) as f32 + 0.5);
            let (dx, dy) = (x % cell / cell - 0.5, y % cell / cell - 0.5);
            let r2 = dx * dx + dy * dy;
            if r2 < 0.16 {
                let h = (0.16 - r2).sqrt();
                texel(0.5 * h, -0.5 * dx / h, 0.5 * dy / h)
            } else {
                texel(0.0, 0.0, 0.0)
            }
        })
        .collect();
    Texture::new(size, size, texels).expect("a non-empty square")
}

/// Gives the surfaces with a normal map the bumps' heights, for parallax. The
/// heights belong to the bumps: another map has none to give.
pub fn apply_parallax(scene: &mut Scene) {
    let maps = &mut scene.maps;
    if !maps.materials.iter().any(|m| m.normal_map.is_some()) {
        return;
    }
    let index = maps.push(bump_heights());
    for material in maps.materials.iter_mut().filter(|m| m.normal_map.is_some()) {
        material.height_map = Some(index);
    }
}

/// Bumps along each side of [`bumps`].
pub const BUMPS: u32 = 8;

/// What `--normal-map` names: `bumps` or an image file.
pub fn parse_normal_map(spec: &str) -> Result<Texture, String> {
    match spec {
        "bumps" => Ok(bumps()),
        path => load_texture(Path::new(path)),
    }
}

/// Gives `scene` the normal map `map`, on the surfaces a texture would go on.
pub fn apply_normal_map(scene: &mut Scene, map: Texture) {
    let mapped = surfaces_to_map(scene);
    let index = scene.maps.push(map);
    for (i, mapped) in mapped.into_iter().enumerate() {
        if mapped {
            scene.maps.of_mut(i).normal_map = Some(index);
        }
    }
}

/// The mesh with texture coordinates from its geometry: each face is projected
/// on the axis plane its normal is closest to, the mesh's bounding box mapped to
/// [0, 1] on each axis, with v up (y points down). Faces get vertices of their
/// own, since a corner shared by faces facing different ways needs a coordinate
/// for each.
pub fn planar_uvs(mesh: &Mesh) -> Mesh {
    let Some(&first) = mesh.positions.first() else {
        return mesh.clone();
    };
    let (low, high) = mesh
        .positions
        .iter()
        .fold((first, first), |(l, h), &p| (l.min(p), h.max(p)));
    let extent = (high - low).max(Vec3::splat(f32::MIN_POSITIVE));
    let mut out = Mesh {
        materials: mesh.materials.clone(),
        ..Mesh::default()
    };
    for face in &mesh.faces {
        let n = face.normal.abs();
        let first = out.positions.len() as u32;
        for k in 0..3 {
            let vertex = mesh.vertex(face, k);
            let q = (vertex.position - low) / extent;
            let uv = if n.x >= n.y && n.x >= n.z {
                Vec2::new(q.z, 1.0 - q.y)
            } else if n.y >= n.z {
                Vec2::new(q.x, q.z)
            } else {
                Vec2::new(q.x, 1.0 - q.y)
            };
            out.positions.push(vertex.position);
            if !mesh.normals.is_empty() {
                out.normals.push(vertex.normal);
            }
            out.uvs.push(uv);
        }
        out.faces.push(crate::pipeline::Face {
            vertices: [first, first + 1, first + 2],
            ..*face
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::parse_scene;

    #[test]
    fn checker_alternates_its_colour_and_a_darker_one() {
        let t = checker(Vec3::ONE);
        let at =
            |x: f32, y: f32| t.sample(Vec2::new(x, y), crate::extensions::texture::Filter::Nearest);
        let step = 1.0 / CHECKER_SQUARES as f32;
        assert_eq!(at(0.5 * step, 1.0 - 0.5 * step), Vec3::ONE);
        assert_eq!(at(1.5 * step, 1.0 - 0.5 * step), Vec3::splat(CHECKER_DARK));
        assert_eq!(at(1.5 * step, 1.0 - 1.5 * step), Vec3::ONE);
    }

    #[test]
    fn the_box_gets_textured_walls_and_plain_blocks() {
        let mut scene = parse_scene("cornell").unwrap();
        apply_texture(&mut scene, &TextureSpec::Checker).unwrap();
        let mesh = &scene.mesh;
        assert_eq!(mesh.uvs.len(), mesh.positions.len());
        assert_eq!(
            scene.maps.images.len(),
            5,
            "floor, two walls, ceiling, back wall"
        );
        for (i, face) in mesh.faces.iter().enumerate() {
            let texture = scene.maps.of(face.material).texture;
            assert_eq!(texture.is_some(), i < 10, "face {i}");
        }
        // Every coordinate lies in [0, 1]: the box spans its own bounding box.
        assert!(mesh
            .uvs
            .iter()
            .all(|uv| (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)));
    }

    #[test]
    fn none_takes_every_texture_off() {
        let mut scene = parse_scene("cornell").unwrap();
        apply_texture(&mut scene, &TextureSpec::Checker).unwrap();
        apply_texture(&mut scene, &TextureSpec::parse("none")).unwrap();
        assert!(scene.maps.materials.iter().all(|m| m.texture.is_none()));
    }

    #[test]
    fn a_missing_or_bad_image_is_a_one_line_error_naming_it() {
        let mut scene = parse_scene("sphere:100").unwrap();
        let missing = TextureSpec::Image("/nonexistent/wood.png".into());
        let e = apply_texture(&mut scene, &missing).unwrap_err();
        assert!(e.starts_with("texture /nonexistent/wood.png: "), "{e}");
        assert!(!e.contains('\n'));
        let dir = std::env::temp_dir().join(format!("rasterlab-tex-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bad = dir.join("bad.png");
        std::fs::write(&bad, b"not a png").unwrap();
        let e = load_texture(&bad).unwrap_err();
        assert!(
            e.starts_with(&format!("texture {}: ", bad.display())),
            "{e}"
        );
        assert!(!e.contains('\n'));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
