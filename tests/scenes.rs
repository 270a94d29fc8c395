//! The scene layer: the procedural meshes, OBJ loading and writing by the design
//! notes' "Models" rules, the shipped models in docs/models, and scene specs.

use glam::{Vec2, Vec3};
use rasterlab::pipeline::mesh::face_normal;
use rasterlab::pipeline::{Mesh, Triangle};
use rasterlab::scene::{bounding_sphere, cornell_box, grid, load_obj, parse_scene, sphere};
use std::fs;
use std::path::{Path, PathBuf};

/// A folder of its own under the system's temporary folder, removed when dropped
/// (also when the test fails).
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("rasterlab-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    /// Writes `text` to `name` in the folder and returns its path.
    fn file(&self, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
        let path = self.0.join(name);
        fs::write(&path, text).unwrap();
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

fn bits3(v: Vec3) -> [u32; 3] {
    v.to_array().map(f32::to_bits)
}

fn bits2(v: Vec2) -> [u32; 2] {
    v.to_array().map(f32::to_bits)
}

/// Every number of a triangle as bits: -0 and 0 differ, as they must.
fn triangle_bits(t: &Triangle) -> Vec<[u32; 3]> {
    [t.v0, t.v1, t.v2, t.normal, t.color].map(bits3).to_vec()
}

fn assert_same_triangles(a: &Mesh, b: &Mesh) {
    let (a, b): (Vec<_>, Vec<_>) = (
        a.triangles().map(|t| triangle_bits(&t)).collect(),
        b.triangles().map(|t| triangle_bits(&t)).collect(),
    );
    assert_eq!(a.len(), b.len());
    for (i, (a, b)) in a.iter().zip(&b).enumerate() {
        assert_eq!(a, b, "triangle {i}");
    }
}

/// Positions, normals, texture coordinates, faces and colours, bit for bit.
fn assert_same_mesh(a: &Mesh, b: &Mesh) {
    let v3 = |v: &[Vec3]| v.iter().map(|&v| bits3(v)).collect::<Vec<_>>();
    let v2 = |v: &[Vec2]| v.iter().map(|&v| bits2(v)).collect::<Vec<_>>();
    let faces = |m: &Mesh| {
        m.faces
            .iter()
            .map(|f| (f.vertices, bits3(f.normal), f.material))
            .collect::<Vec<_>>()
    };
    let colors = |m: &Mesh| {
        m.materials
            .iter()
            .map(|m| bits3(m.color))
            .collect::<Vec<_>>()
    };
    assert_eq!(v3(&a.positions), v3(&b.positions), "positions");
    assert_eq!(v3(&a.normals), v3(&b.normals), "normals");
    assert_eq!(v2(&a.uvs), v2(&b.uvs), "texture coordinates");
    assert_eq!(faces(a), faces(b), "faces");
    assert_eq!(colors(a), colors(b), "colours");
}

fn round_trip(mesh: &Mesh, dir: &TempDir, name: &str) -> Mesh {
    let path = dir.0.join(name);
    rasterlab::app::export_obj(mesh, &path).unwrap();
    assert!(path.with_extension("mtl").is_file());
    load_obj(&path).unwrap()
}

#[test]
fn the_box_sphere_and_grid_survive_writing_and_loading() {
    let dir = TempDir::new("round-trip");
    let cornell = cornell_box();
    assert_same_triangles(&round_trip(&cornell, &dir, "box.obj"), &cornell);
    for mesh in [sphere(960), sphere(50), grid(200), grid(2)] {
        assert_same_mesh(&round_trip(&mesh, &dir, "mesh.obj"), &mesh);
    }
    // Nothing left behind but the two files.
    let mut names: Vec<_> = fs::read_dir(&dir.0)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["box.mtl", "box.obj", "mesh.mtl", "mesh.obj"]);
}

/// docs/models/NAME.obj and .mtl are what `write_obj` writes now; with
/// RASTERLAB_UPDATE_MODELS=1 the test rewrites them instead.
#[test]
fn the_shipped_models_are_current() {
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/models");
    let dir = TempDir::new("models");
    for (name, mesh) in [("cornell", cornell_box()), ("sphere", sphere(960))] {
        if std::env::var_os("RASTERLAB_UPDATE_MODELS").is_some() {
            rasterlab::app::export_obj(&mesh, &models.join(format!("{name}.obj"))).unwrap();
        }
        rasterlab::app::export_obj(&mesh, &dir.0.join(format!("{name}.obj"))).unwrap();
        for ext in ["obj", "mtl"] {
            let file = format!("{name}.{ext}");
            let shipped = fs::read(models.join(&file)).unwrap_or_default();
            assert!(
                shipped == fs::read(dir.0.join(&file)).unwrap(),
                "docs/models/{file} is stale: run RASTERLAB_UPDATE_MODELS=1 cargo test --release --test suite scenes::"
            );
        }
    }
    let loaded = load_obj(&models.join("cornell.obj")).unwrap();
    assert_same_triangles(&loaded, &cornell_box());
    assert_same_mesh(&load_obj(&models.join("sphere.obj")).unwrap(), &sphere(960));
}

#[test]
fn bad_files_are_one_line_errors() {
    let dir = TempDir::new("bad");
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    // After three vertices (lines 1 to 3), each case's lines.
    let mut cases: Vec<(&str, Vec<u8>, &str)> = [
        ("points", "p 1\nl 1 2\nf 1 2\n", "no faces"),
        ("number", "v 1 x 0\n", "line 4: position parse error"),
        (
            "face",
            "f 1 2 x\n",
            "line 4: face corner 'x' is not v, v/vt, v//vn or v/vt/vn",
        ),
        (
            "slashes",
            "f 1 2 3/3/3/3\n",
            "line 4: face corner '3/3/3/3' is not",
        ),
        ("letter", "f 1 2 3x\n", "line 4: face corner '3x' is not"),
        (
            "huge",
            "f 1 2 99999999999999999999\n",
            "line 4: index 99999999999999999999 is out of range",
        ),
        (
            "range",
            "f 1 2 3\nf 1 2 4\nf 3 2 1\n",
            "line 5: index 4 is past the end: the file has 3 positions",
        ),
        ("zero", "f 0 1 2\n", "line 4: index 0 is out of range"),
        ("back", "f -1 -2 -4\n", "line 4: index -4 is out of range"),
        ("normal", "vn 0 0 1\nf 1//1 2//0 3//1\n", "line 5: index 0"),
        ("nan", "v nan 0 0\nf 1 2 4\n", "line 4: a number is NaN"),
        (
            "inf",
            "v 1e39 0 0\nf 1 2 4\n",
            "line 4: 1e39 is past the largest number",
        ),
        ("w", "v 1 1 1 1e-45\nf 1 2 4\n", "NaN or infinite"),
        ("uv", "vt inf 0\nf 1 2 3\n", "line 4: a number is NaN"),
    ]
    .map(|(name, rest, expected)| (name, format!("{tri}{rest}").into_bytes(), expected))
    .into();
    cases.push(("nothing", vec![], "no faces"));
    // 201 polygons of 50 000 corners: 10 049 799 triangles.
    let polygon = format!("f{}\n", " 1".repeat(50_000));
    let big = format!("{tri}{}", polygon.repeat(201));
    cases.push(("big", big.into_bytes(), "too large"));
    for (name, bytes, expected) in &cases {
        let path = dir.file(&format!("{name}.obj"), bytes);
        let err = load_obj(&path).expect_err(name);
        assert!(
            err.starts_with(&format!("{}: ", path.display())),
            "{name}: {err}"
        );
        assert!(err.contains(expected), "{name}: {err}");
        assert!(!err.contains('\n'), "{name}: {err}");
    }
    let missing = dir.0.join("missing.obj");
    let err = load_obj(&missing).unwrap_err();
    assert!(
        err.contains("missing.obj") && err.contains("cannot open"),
        "{err}"
    );

    // Material libraries: missing, or broken in a way tobj reports or panics on.
    let uses = |mtl: &str| format!("mtllib {mtl}\n{tri}usemtl a\nf 1 2 3\n");
    for (name, mtl, expected) in [
        (
            "short",
            "newmtl a\nKd 0.5 0.5\n",
            "line 2: Kd needs three numbers",
        ),
        (
            "word",
            "newmtl a\nKd 0.5 red 0.5\n",
            "line 2: material parse error",
        ),
        (
            "nan",
            "newmtl a\nKd 0.5 NaN 0.5\n",
            "line 2: a number is NaN",
        ),
    ] {
        dir.file(&format!("{name}.mtl"), mtl);
        let path = dir.file(&format!("{name}.obj"), uses(&format!("{name}.mtl")));
        let err = load_obj(&path).unwrap_err();
        let library = format!(
            "material library {}",
            dir.0.join(format!("{name}.mtl")).display()
        );
        assert!(err.contains(&library), "{name}: {err}");
        assert!(err.contains(expected), "{name}: {err}");
    }
    // A library that is not there (a model shared without it): its faces grey,
    // with warnings that say so; one in another case is read, with a warning.
    let path = dir.file("absent.obj", uses("absent.mtl"));
    let (mesh, _, warnings) = rasterlab::scene::obj::read_obj(&path).unwrap();
    assert_eq!(mesh.faces.len(), 1);
    assert_eq!(mesh.material(&mesh.faces[0]).color, Vec3::splat(0.75));
    let shown = path.display();
    assert_eq!(
        warnings,
        [
            format!("{shown}: material library absent.mtl is not there: its materials are left out"),
            format!("{shown}: line 5: usemtl a: no material of that name in the material libraries: its faces are grey"),
        ]
    );
    dir.file("Cased.MTL", "newmtl a\nKd 1 0 0\n");
    let path = dir.file("cased.obj", uses("cased.mtl"));
    let (mesh, _, warnings) = rasterlab::scene::obj::read_obj(&path).unwrap();
    assert_eq!(mesh.material(&mesh.faces[0]).color, Vec3::X);
    assert_eq!(
        warnings,
        [format!(
            "{}: material library cased.mtl is not there: read {} instead",
            path.display(),
            dir.0.join("Cased.MTL").display()
        )]
    );
}

/// The colour of each triangle of the model at `path`, and its warnings.
fn colours_and_warnings(path: &Path) -> (Vec<Vec3>, Vec<String>) {
    let (mesh, _, warnings) = rasterlab::scene::obj::read_obj(path).unwrap();
    (mesh.triangles().map(|t| t.color).collect(), warnings)
}

#[test]
fn text_that_is_not_utf8_is_read_as_latin1() {
    let dir = TempDir::new("latin1");
    // Written on Windows: a comment and a material name in its Western
    // encoding in the OBJ (0xE9 is é), the same name in UTF-8 in the MTL.
    dir.file("m.mtl", "newmtl Mat\u{e9}riau\nKd 1 0 0\n");
    let obj: &[u8] = b"# Cr\xe9\xe9 par 3ds Max\nmtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Mat\xe9riau\nf 1 2 3\ng Bo\xeete\nf 1 2 3\n";
    let path = dir.file("m.obj", obj);
    let (colors, warnings) = colours_and_warnings(&path);
    assert_eq!(colors, [Vec3::X, Vec3::X]);
    // The comment needs no warning; the name and the group do.
    assert_eq!(
        warnings,
        [format!(
            "{}: line 6: not UTF-8: read as Latin-1, a character a byte (and 1 more such lines)",
            path.display()
        )]
    );
}

#[test]
fn a_byte_order_mark_and_a_one_number_colour_are_read() {
    let dir = TempDir::new("bom");
    // As Notepad saves UTF-8: a byte-order mark before the first keyword.
    dir.file("m.mtl", "\u{feff}newmtl a\nKd 1 0 0\nnewmtl b\nKd 0.25\n");
    let path = dir.file(
        "m.obj",
        "\u{feff}mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\n",
    );
    let (colors, warnings) = colours_and_warnings(&path);
    assert_eq!(colors, [Vec3::X, Vec3::splat(0.25)]);
    assert!(warnings.is_empty(), "{warnings:?}");
    let path = dir.file("v.obj", "\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert_eq!(load_obj(&path).unwrap().positions.len(), 3);
}

#[test]
fn mtllib_names_several_libraries_or_one_with_spaces_and_tga_textures_load() {
    let dir = TempDir::new("mtllib");
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
    dir.file("a1.mtl", "newmtl a\nKd 1 0 0\n");
    dir.file("a2.mtl", "newmtl b\nKd 0 1 0\nnewmtl a\nKd 0 0 1\n");
    let path = dir.file(
        "two.obj",
        format!("mtllib a1.mtl a2.mtl missing.mtl\n{tri}usemtl b\nf 1 2 3\nusemtl a\nf 1 2 3\n"),
    );
    let (colors, warnings) = colours_and_warnings(&path);
    // The first library to define a name gives its material.
    assert_eq!(colors, [Vec3::Y, Vec3::X]);
    assert_eq!(
        warnings,
        [format!(
            "{}: material library missing.mtl is not there: its materials are left out",
            path.display()
        )]
    );
    // Blender names the library after the model, spaces and all; a TGA
    // texture (no mark of its own: read by its name) of one blue texel.
    let tga = [
        0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 0, 24, 0, 255, 0, 0,
    ];
    dir.file("wood.TGA", tga);
    dir.file("my model.mtl", "newmtl w\nKd 1 1 1\nmap_Kd wood.TGA\n");
    let path = dir.file(
        "my model.obj",
        format!("mtllib my model.mtl\n{tri}usemtl w\nf 1/1 2/2 3/3\n"),
    );
    let (mesh, maps, warnings) = rasterlab::scene::obj::read_obj(&path).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(mesh.triangles().next().unwrap().color, Vec3::ONE);
    assert_eq!(maps.images.len(), 1);
    let nearest = rasterlab::extensions::texture::Filter::Nearest;
    let texel = maps.images[0].sample(Vec2::splat(0.5), nearest);
    assert_eq!(texel, Vec3::Z);
}

#[test]
fn polygons_are_fans_from_their_first_vertex_before_the_half_turn() {
    let dir = TempDir::new("fan");
    let path = dir.file(
        "quad.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -0.5 0.5 0\nvn 0 0 2\nf 1//1 2//1 3//1 4//1\nf 1//1 2//1 3//1 4//1 5//1\n",
    );
    let mesh = load_obj(&path).unwrap();
    let faces: Vec<[u32; 3]> = mesh.faces.iter().map(|f| f.vertices).collect();
    // (0, 1, 2), (0, 2, 3) in the file; each turned into (a, c, b). tobj numbers
    // the second polygon's vertices on from the first's (the same vertices).
    assert_eq!(
        faces,
        [[0, 2, 1], [0, 3, 2], [0, 2, 1], [0, 3, 2], [0, 4, 3]]
    );
    let flip = |x: f32, y: f32, z: f32| Vec3::new(x, -y, -z);
    assert_eq!(
        mesh.positions[..4],
        [
            flip(0.0, 0.0, 0.0),
            flip(1.0, 0.0, 0.0),
            flip(1.0, 1.0, 0.0),
            flip(0.0, 1.0, 0.0),
        ]
    );
    // Counter-clockwise seen from +z in the file: facing the camera (toward -z)
    // here, and the vertex normal (0, 0, 2) mapped and renormalised.
    for f in &mesh.faces {
        assert_eq!(f.normal, Vec3::NEG_Z);
        assert_eq!(
            f.normal,
            face_normal(f.vertices.map(|i| mesh.positions[i as usize]))
        );
    }
    assert!(mesh.normals.iter().all(|&n| n == Vec3::NEG_Z));
    assert!(mesh.uvs.is_empty());
}

#[test]
fn colours_are_kd_clamped_or_grey() {
    let dir = TempDir::new("kd");
    dir.file(
        "m.mtl",
        "newmtl hot\nKd 1.5 -0.25 0.5\nnewmtl plain\nKa 1 1 1\n",
    );
    let path = dir.file(
        "m.obj",
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl hot\nf 1 2 3\nusemtl unknown\nf 1 2 3\nusemtl plain\nf 1 2 3\n",
    );
    let mesh = load_obj(&path).unwrap();
    let colors: Vec<Vec3> = mesh.triangles().map(|t| t.color).collect();
    let grey = Vec3::splat(0.75);
    assert_eq!(colors, [grey, Vec3::new(1.0, 0.0, 0.5), grey, grey]);
}

#[test]
fn the_sphere_is_round_and_faces_outward() {
    for n in [8, 100, 960, 20_000] {
        let mesh = sphere(n);
        let count = mesh.faces.len();
        assert!(count >= 48, "{n}: {count}");
        if n >= 100 {
            assert!((count as f32 / n as f32 - 1.0).abs() < 0.1, "{n}: {count}");
        }
        assert_eq!(mesh.normals.len(), mesh.positions.len());
        assert_eq!(mesh.uvs.len(), mesh.positions.len());
        for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
            assert!((n.length() - 1.0).abs() < 1e-6, "{n}");
            assert!((p.length() - 1.0).abs() < 1e-6, "{p}");
            assert!(n.dot(*p) > 0.999, "{n} at {p}");
        }
        for t in mesh.triangles() {
            let centre = (t.v0 + t.v1 + t.v2) / 3.0;
            assert!((t.normal.length() - 1.0).abs() < 1e-5, "degenerate: {t:?}");
            assert!(t.normal.dot(centre.normalize()) > 0.9, "{t:?}");
        }
        for uv in &mesh.uvs {
            assert!(
                uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all(),
                "{uv}"
            );
        }
        // v is 1 at the top (y = -1: y points down) and 0 at the bottom.
        for (p, uv) in mesh.positions.iter().zip(&mesh.uvs) {
            assert!(((1.0 - p.y) / 2.0 - uv.y).abs() < 0.2, "{p} {uv}");
        }
    }
}

#[test]
fn the_grid_is_a_green_floor_facing_up() {
    for (n, squares) in [(2, 1), (200, 10), (5000, 50)] {
        let mesh = grid(n);
        assert_eq!(mesh.faces.len(), 2 * squares * squares);
        assert_eq!(
            mesh.positions.len(),
            (squares + 1) * (squares + 1),
            "shared vertices"
        );
        for t in mesh.triangles() {
            assert!(t.normal.abs_diff_eq(Vec3::NEG_Y, 1e-6), "{}", t.normal);
            assert_eq!(t.color, Vec3::new(0.15, 0.75, 0.15));
            for v in t.vertices() {
                assert!(v.y == 1.0 && v.x.abs() <= 1.0 && v.z.abs() <= 1.0, "{v}");
            }
        }
        assert!(mesh.normals.iter().all(|&n| n == Vec3::NEG_Y));
        let (low, high) = mesh
            .uvs
            .iter()
            .fold((Vec2::ONE, Vec2::ZERO), |(l, h), &t| (l.min(t), h.max(t)));
        assert_eq!((low, high), (Vec2::ZERO, Vec2::ONE));
    }
}

#[test]
fn scene_specs() {
    let cornell = parse_scene("cornell").unwrap();
    assert!(cornell.is_box && cornell.name == "cornell");
    assert_eq!(cornell.mesh, cornell_box());
    let sub = parse_scene("cornell:3").unwrap();
    assert!(sub.is_box && sub.mesh.faces.len() == 30 * 9);
    let s = parse_scene("sphere:960").unwrap();
    assert!(!s.is_box && s.mesh == sphere(960));
    assert_eq!(parse_scene("grid:2").unwrap().mesh, grid(2));
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/models");
    let file = parse_scene(models.join("cornell.obj").to_str().unwrap()).unwrap();
    assert!(!file.is_box && file.name == "cornell");
    let dir = TempDir::new("spec");
    dir.file("UPPER.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert_eq!(
        parse_scene(dir.0.join("UPPER.OBJ").to_str().unwrap())
            .unwrap()
            .mesh
            .faces
            .len(),
        1
    );

    for (spec, expected) in [
        ("", "unknown scene"),
        ("cube", "unknown scene"),
        ("cornell:0", "from 1 to 256"),
        ("cornell:257", "from 1 to 256"),
        ("cornell:x", "'x'"),
        ("sphere", "needs a count"),
        ("sphere:7", "from 8 to 4000000"),
        ("sphere:4000001", "from 8 to 4000000"),
        ("grid:1", "from 2 to 4000000"),
        ("grid:-5", "'-5'"),
        ("nowhere/missing.obj", "cannot open"),
    ] {
        let err = parse_scene(spec).map(|s| s.name).unwrap_err();
        assert!(
            err.contains(expected) && !err.contains('\n'),
            "{spec}: {err}"
        );
    }
}

#[test]
fn bounding_spheres() {
    let (centre, radius) = bounding_sphere(&cornell_box());
    assert!(centre.abs().max_element() < 1e-6, "{centre}");
    assert!((radius - 3f32.sqrt()).abs() < 1e-5, "{radius}");
    let (centre, radius) = bounding_sphere(&grid(8));
    assert_eq!(centre, Vec3::new(0.0, 1.0, 0.0));
    assert!((radius - 2f32.sqrt()).abs() < 1e-6);
    assert_eq!(bounding_sphere(&Mesh::default()), (Vec3::ZERO, 0.0));
}

#[test]
fn framing_fills_the_view_and_scales_the_light() {
    use rasterlab::scene::{framed_view, parse_scene};
    use rasterlab::{Camera, Light};
    let looking = Camera::handout(500, 500);
    let frame = |scene: &rasterlab::scene::Scene| framed_view(scene, &looking);
    assert_eq!(
        frame(&parse_scene("cornell:2").unwrap()).unwrap(),
        (looking, Light::handout())
    );
    // A unit sphere: half the view is atan(250 / 500); the sphere's radius fills
    // 90 % of it.
    let sphere = parse_scene("sphere:960").unwrap();
    let (p, p_light) = frame(&sphere).unwrap();
    let expected = 1.0 / (0.9 * (0.5f32).atan().sin());
    assert!(
        (p.position - glam::Vec3::new(0.0, 0.0, -expected)).length() < 1e-4,
        "{p:?}"
    );
    // The same sphere 1000 times larger: everything scales, power by a million.
    let mut big = sphere.clone();
    big.mesh = big.mesh.map_positions(|v| v * 1000.0);
    let (q, q_light) = frame(&big).unwrap();
    assert!((q.position / 1000.0 - p.position).length() < 1e-3, "{q:?}");
    assert!((q_light.position / 1000.0 - p_light.position).length() < 1e-3);
    assert!((q_light.power.x / p_light.power.x / 1e6 - 1.0).abs() < 1e-3);
    // A unit sphere and a larger one keep the handout's near plane.
    assert_eq!((p.near, q.near), (Some(0.01), Some(0.01)));
    // The same sphere 1000 times smaller: the near plane shrinks with it, so
    // the camera, 1/1000 of the unit sphere's distance away, does not cut it.
    let mut small = sphere.clone();
    small.mesh = small.mesh.map_positions(|v| v / 1000.0);
    let (t, _) = frame(&small).unwrap();
    assert!((t.position * 1000.0 - p.position).length() < 1e-3, "{t:?}");
    assert!(t.near.unwrap() < -t.position.z - 1e-3, "{t:?}");
    // Without clipping (--no-clip) the framed camera still does not clip.
    let unclipped = Camera {
        near: None,
        ..looking
    };
    assert_eq!(framed_view(&sphere, &unclipped).unwrap().0.near, None);
    // Sizes f32 cannot frame are refused.
    for factor in [1e30f32, 1e-12] {
        let mut odd = sphere.clone();
        odd.mesh = odd.mesh.map_positions(|v| v * factor);
        let e = frame(&odd).unwrap_err();
        assert!(e.contains("than f32 can frame"), "{e}");
    }
    // The box's place for the light is inside a closed sphere: the light moves out
    // along the same direction to 0.5 box units (scaled) beyond the sphere.
    let scale = 1.0 / 3f32.sqrt();
    let outside = glam::Vec3::new(0.0, -0.5, -0.7).normalize() * (1.0 + 0.5 * scale);
    assert!((p_light.position - outside).length() < 1e-3, "{p_light:?}");
    // The box read from its OBJ is a room open towards the camera: the light
    // keeps the box's place, since no wall lies between it and the camera.
    let room = parse_scene(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/docs/models/cornell.obj"
    ))
    .unwrap();
    let (_, r) = frame(&room).unwrap();
    assert_eq!(r.position, Light::handout().position);
    assert_eq!(r.power, Light::handout().power);
}

/// The box written as OBJ by the design notes' rules renders every stage, with
/// either rasterizer, byte for byte as the built-in box (drawn from the handout's
/// pose: a model is otherwise framed by its bounding sphere).
#[test]
fn the_boxs_obj_renders_every_stage_as_the_built_in_box() {
    use rasterlab::app::figure::Raster;
    use rasterlab::app::{self, Settings};
    use rasterlab::{cornell_box, Figure};
    let obj = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/models/cornell.obj");
    let loaded = rasterlab::scene::load_obj(&obj).unwrap();
    let built_in = cornell_box();
    let s = Settings::default();
    for raster in [Raster::Rows, Raster::Edge] {
        for figure in Figure::FIGURES {
            let figure = figure.with_raster(raster);
            let a = app::render(figure, &loaded, &s, None).0;
            let b = app::render(figure, &built_in, &s, None).0;
            assert!(a.color == b.color, "{}", figure.label());
        }
    }
    // And through the command line, with the pose given explicitly.
    let bin = env!("CARGO_BIN_EXE_rasterlab");
    let out = std::process::Command::new(bin)
        .args([
            "depth",
            "--scene",
            obj.to_str().unwrap(),
            "--camera",
            "0,0,-3.001",
            "-o",
            "-",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let png = out.stdout;
    let committed = std::fs::read(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("steps/fig5-depth.png"),
    )
    .unwrap();
    assert_eq!(png, committed, "depth --scene cornell.obj is Figure 5");
}

/// A model without --camera is framed and the pose is printed; the printed pose
/// reproduces the image.
#[test]
fn a_model_is_framed_and_the_printed_pose_reproduces_it() {
    let bin = env!("CARGO_BIN_EXE_rasterlab");
    let obj = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/models/sphere.obj");
    let run = |extra: &[&str]| {
        std::process::Command::new(bin)
            .args([
                "pixel-light",
                "--scene",
                obj.to_str().unwrap(),
                "--size",
                "96x96",
                "--focal",
                "96",
                "-o",
                "-",
            ])
            .args(extra)
            .output()
            .unwrap()
    };
    let framed = run(&[]);
    let err = String::from_utf8_lossy(&framed.stderr).into_owned();
    assert!(framed.status.success(), "{err}");
    let pose: Vec<String> = err
        .lines()
        .find_map(|l| l.split_once("): ").map(|(_, p)| p.to_string()))
        .expect("the pose is printed")
        .split_whitespace()
        .map(String::from)
        .collect();
    let pose: Vec<&str> = pose.iter().map(String::as_str).collect();
    let again = run(&pose);
    assert!(again.status.success());
    assert_eq!(
        framed.stdout, again.stdout,
        "the printed pose gives the same image"
    );
    // The sphere fills most of the view: a disc of lit pixels around the centre.
    let img = image::load_from_memory(&framed.stdout).unwrap().to_rgb8();
    let drawn = img.pixels().filter(|p| p.0 != [0, 0, 0]).count();
    let disc = std::f64::consts::PI * (0.9 * 48.0f64).powi(2);
    assert!(
        (drawn as f64 - disc).abs() < 0.1 * disc,
        "{drawn} pixels against {disc:.0}"
    );
}

#[test]
fn culling_back_faces_of_the_closed_box_changes_nothing_with_exact_coverage() {
    use rasterlab::app::figure::Raster;
    use rasterlab::app::{self, Settings};
    use rasterlab::pipeline::draw::Cull;
    use rasterlab::{cornell_box, Figure, StageName};
    let (mesh, s) = (cornell_box(), Settings::default());
    let depth = Figure::of(StageName::Depth);
    let draw = |f: Figure| app::render(f, &mesh, &s, None).0.color;
    // The edge rasterizer covers each pixel of a closed surface once: the
    // back-facing triangles only ever lose, and culling them changes no pixel.
    let edge = depth.with_raster(Raster::Edge);
    assert!(draw(edge) == draw(edge.with_cull(Cull::Back)));
    // The handout's rows truncate each triangle's corners on their own, so at
    // three block corners only a back face's row reaches a pixel; culling leaves
    // what lies behind. Measured: exactly those 3 of 250 000 pixels.
    let (a, b) = (draw(depth), draw(depth.with_cull(Cull::Back)));
    let differing = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert_eq!(differing, 3);
}

#[test]
fn rows_draw_shared_edges_twice_and_edges_do_not() {
    use rasterlab::app::explain::pixels_drawn_twice;
    use rasterlab::app::figure::Raster;
    use rasterlab::app::Settings;
    use rasterlab::{cornell_box, Figure, StageName};
    let (mesh, s) = (cornell_box(), Settings::default());
    let rows = pixels_drawn_twice(&mesh, &s, Raster::Rows);
    let edge = pixels_drawn_twice(&mesh, &s, Raster::Edge);
    // Measured on the default view (steps/8-models.md): the walls' and blocks'
    // diagonals and every shared edge, drawn by both halves.
    assert_eq!(edge, 0);
    assert_eq!(rows, 3080);
    let draw = |r: Raster| {
        let f = Figure::of(StageName::Depth).with_raster(r);
        rasterlab::app::render(f, &mesh, &s, None).0.color
    };
    let (a, b) = (draw(Raster::Rows), draw(Raster::Edge));
    let shifted = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    // Pixels where the two rasterizers show different surfaces: all along edges,
    // where truncation moves the rows rasterizer's corners by up to 1.5 pixels.
    assert_eq!(shifted, 3222);
}

#[test]
fn a_texture_coordinate_of_u_alone_has_a_v_of_0() {
    // The format allows `vt u`; tobj refused it ("vt 0.5" stopped the model).
    let dir = TempDir::new("vt-u");
    let obj = |vt: [&str; 3]| {
        format!(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt {}\nvt {}\nvt {}\nf 1/1 2/2 3/3\n",
            vt[0], vt[1], vt[2]
        )
    };
    let alone = load_obj(&dir.file("u.obj", obj(["0.25", "0.5", "0.75"]))).unwrap();
    let both = load_obj(&dir.file("uv.obj", obj(["0.25 0", "0.5 0", "0.75 0"]))).unwrap();
    assert_eq!(alone.uvs.len(), 3);
    assert_eq!(alone.uvs, both.uvs);
}

#[test]
fn what_exporters_write_that_tobj_would_misread_is_read_or_warned_of() {
    let dir = TempDir::new("fifth-obj");
    let tri = "v -1 -1 -1 # a corner\nv 1 0 0\nv 0 1 0\n";
    let warned = |name: &str, text: String| {
        let path = dir.file(name, text);
        let (mesh, _, warnings) = rasterlab::scene::obj::read_obj(&path).unwrap();
        let shown = path.display().to_string();
        let warnings: Vec<String> = warnings
            .iter()
            .map(|w| w.replacen(&format!("{shown}: "), "", 1))
            .collect();
        (mesh, warnings)
    };
    // A bare `f` stopped the model ("invalid polygon", no line); a comment
    // after a vertex was "color parse error".
    let (mesh, warnings) = warned("f.obj", format!("{tri}f\nf 1 2 3 # the face\nf 3 2 1#\n"));
    assert_eq!(mesh.positions[0], Vec3::new(-1.0, 1.0, 1.0));
    assert_eq!(mesh.faces.len(), 2);
    assert_eq!(
        warnings,
        ["line 4: a face needs at least three corners: left out"]
    );
    // Texture coordinates named and never given were dropped without a word.
    let (_, warnings) = warned("vt.obj", format!("{tri}f 1/1 2/1 3/2\n"));
    assert_eq!(
        warnings,
        ["line 4: texture coordinate 2 is past the end: the file has 0: the faces' texture coordinates are left out"]
    );
    // map_Kd with options only stopped the model, where a bare one is left
    // out; `-s nan nan nan` took the NaNs for the file's name.
    dir.file(
        "m.mtl",
        "newmtl a\nKd 1 0 0\nmap_Kd -s nan nan nan pal.png\nnewmtl b\nKd 0 1 0\nmap_Kd -clamp on\n",
    );
    let text =
        format!("mtllib m.mtl\n{tri}vt 0 0\nusemtl a\nf 1/1 2/1 3/1\nusemtl b\nf 1/1 2/1 3/1\n");
    let (_, warnings) = warned("m.obj", text);
    assert_eq!(
        warnings,
        [
            "material a: map_Kd pal.png is not there: its Kd is drawn instead",
            "material b: map_Kd names no file, only options: left out",
            "material b: map_Kd option -clamp is not supported: left out",
        ]
    );
}
