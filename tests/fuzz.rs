//! Property tests over the parsers that read what strangers send (issue #18):
//! OBJ and MTL files, `check rows` printouts, image files, `--scene` specs,
//! `map_Kd` statements and the command line's values. Arbitrary bytes, and
//! bytes shaped like the real thing, must give a result or a one-line error:
//! never a panic, a hang or an allocation past the bounds. (`fuzz/` holds the
//! coverage-guided `cargo fuzz` targets of the same parsers.)

use crate::common;
use proptest::prelude::*;
use rasterlab::app::parse;
use rasterlab::measure::check::rows::parse_rows;
use rasterlab::scene::obj::TextureMap;
use std::fs;

fn one_line(e: &str) -> bool {
    !e.is_empty() && !e.contains('\n')
}

/// Lines shaped like OBJ statements, with numbers and indices that go wrong in
/// every way (zero, negative, past the end, huge, NaN, fractions).
fn obj_like() -> impl Strategy<Value = String> {
    let number = prop_oneof![
        any::<f32>().prop_map(|x| x.to_string()),
        (-5i64..5).prop_map(|i| i.to_string()),
        Just("nan".to_string()),
        Just("1e39".to_string()),
        Just("x".to_string()),
        Just("4294967296".to_string()),
        Just("-9223372036854775808".to_string()),
    ];
    let corner = (
        number.clone(),
        proptest::option::of(number.clone()),
        proptest::option::of(number.clone()),
    )
        .prop_map(|(v, t, n)| match (t, n) {
            (None, None) => v,
            (Some(t), None) => format!("{v}/{t}"),
            (None, Some(n)) => format!("{v}//{n}"),
            (Some(t), Some(n)) => format!("{v}/{t}/{n}"),
        });
    let keyword = prop_oneof![
        Just("v"),
        Just("vt"),
        Just("vn"),
        Just("f"),
        Just("l"),
        Just("p"),
        Just("o"),
        Just("g"),
        Just("s"),
        Just("usemtl"),
        Just("mtllib"),
        Just("#"),
        Just("vp"),
    ];
    let line = (keyword, proptest::collection::vec(corner, 0..6))
        .prop_map(|(k, words)| format!("{k} {}", words.join(" ")));
    proptest::collection::vec(line, 0..40).prop_map(|lines| lines.join("\n"))
}

/// MTL statements with the same kinds of values.
fn mtl_like() -> impl Strategy<Value = String> {
    let value = prop_oneof![
        any::<f32>().prop_map(|x| x.to_string()),
        Just("-s".to_string()),
        Just("-o".to_string()),
        Just("-bm".to_string()),
        Just("nan".to_string()),
        Just("tex.png".to_string()),
        Just("".to_string()),
    ];
    let keyword = prop_oneof![
        Just("newmtl"),
        Just("Kd"),
        Just("Ka"),
        Just("Ks"),
        Just("Ke"),
        Just("Ns"),
        Just("d"),
        Just("illum"),
        Just("map_Kd"),
        Just("map_Bump"),
    ];
    let line = (keyword, proptest::collection::vec(value, 0..5))
        .prop_map(|(k, words)| format!("{k} {}", words.join(" ")));
    proptest::collection::vec(line, 0..20).prop_map(|lines| lines.join("\n"))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn obj_bytes_load_or_fail_in_one_line(bytes in proptest::collection::vec(any::<u8>(), 0..2000)) {
        let dir = common::temp_dir("fuzz-obj-bytes");
        let path = dir.join("m.obj");
        fs::write(&path, &bytes).unwrap();
        if let Err(e) = rasterlab::scene::read_obj(&path) {
            prop_assert!(one_line(&e), "{e}");
        }
    }

    #[test]
    fn obj_and_mtl_statements_load_or_fail_in_one_line(obj in obj_like(), mtl in mtl_like()) {
        let dir = common::temp_dir("fuzz-obj-lines");
        fs::write(dir.join("m.mtl"), &mtl).unwrap();
        let obj = format!("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Kd\n{obj}\nf 1 2 3\n");
        let path = dir.join("m.obj");
        fs::write(&path, &obj).unwrap();
        match rasterlab::scene::read_obj(&path) {
            Ok((mesh, _, warnings)) => {
                prop_assert!(!mesh.faces.is_empty());
                let n = mesh.positions.len() as u32;
                prop_assert!(mesh.faces.iter().all(|f| f.vertices.iter().all(|&i| i < n)));
                prop_assert!(mesh.positions.iter().all(|p| p.is_finite()));
                prop_assert!(mesh.materials.iter().all(|m| (0.0..=1.0).contains(&m.color.x)));
                prop_assert!(warnings.iter().all(|w| one_line(w)));
            }
            Err(e) => prop_assert!(one_line(&e), "{e}"),
        }
    }

    #[test]
    fn rows_printouts_parse_or_fail_in_one_line(text in "[ -~\n]{0,400}") {
        if let Err(e) = parse_rows(&text) {
            prop_assert!(one_line(&e), "{e}");
        }
    }

    #[test]
    fn rows_with_fractions_or_exponents_name_the_first(
        rows in proptest::collection::vec(proptest::collection::vec(prop_oneof![
            3 => "-?[0-9]{1,9}",
            1 => "-?[0-9]{1,3}(\\.[0-9]{1,3}|[eE][-+]?[0-9]{1,2})",
        ], 4), 1..10)
    ) {
        let text: String = rows
            .iter()
            .map(|r| format!("Start: ({},{}). End: ({},{}).\n", r[0], r[1], r[2], r[3]))
            .collect();
        let first_not_whole = rows.iter().flatten().find(|t| t.parse::<i32>().is_err());
        match (parse_rows(&text), first_not_whole) {
            (Ok(parsed), None) => {
                let expected: Vec<[i32; 4]> = rows
                    .iter()
                    .map(|r| [0, 1, 2, 3].map(|i| r[i].parse().unwrap()))
                    .collect();
                prop_assert_eq!(parsed, expected);
            }
            (Err(e), Some(token)) => {
                prop_assert!(e.ends_with(&format!("'{token}' is not a whole number of pixels")), "{e}");
            }
            (result, token) => prop_assert!(false, "{result:?} for {token:?}"),
        }
    }

    #[test]
    fn image_bytes_decode_or_fail_in_one_line(
        bytes in proptest::collection::vec(any::<u8>(), 0..600),
        header in prop_oneof![
            Just(b"\x89PNG\r\n\x1a\n".to_vec()),
            Just(b"BM".to_vec()),
            Just(b"GIF89a".to_vec()),
            Just(Vec::new()),
        ],
    ) {
        let dir = common::temp_dir("fuzz-image");
        let path = dir.join("x.png");
        fs::write(&path, [header, bytes].concat()).unwrap();
        if let Err(e) = rasterlab::app::check::read_screenshot(&path) {
            prop_assert!(one_line(&e), "{e}");
        }
        if let Err(e) = rasterlab::scene::texture::load_texture(&path) {
            prop_assert!(one_line(&e), "{e}");
        }
    }

    #[test]
    fn png_headers_of_any_size_are_refused_or_read(w in any::<u32>(), h in any::<u32>()) {
        let dir = common::temp_dir("fuzz-png-size");
        let path = dir.join("x.png");
        let mut ihdr = b"IHDR".to_vec();
        ihdr.extend(w.to_be_bytes());
        ihdr.extend(h.to_be_bytes());
        ihdr.extend([8, 2, 0, 0, 0]);
        let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
        png.extend(13u32.to_be_bytes());
        png.extend(&ihdr);
        png.extend(common::crc32(&ihdr).to_be_bytes());
        fs::write(&path, png).unwrap();
        if let Err(e) = rasterlab::app::check::read_screenshot(&path) {
            prop_assert!(one_line(&e), "{e}");
        }
    }

    #[test]
    fn values_and_specs_parse_or_fail_in_one_line(s in "\\PC{0,40}") {
        let errors = [
            parse::size(&s).err(),
            parse::vec3(&s).err(),
            parse::dof(&s).err(),
            parse::focal(&s).err(),
            parse::non_negative(&s).err(),
            parse::point(&s).err(),
            parse::point_f32(&s).err(),
            parse::whole(&s, 1, 100).err(),
            parse::stage(&s).err(),
            // Specs ending in .obj name files: these do not exist.
            rasterlab::scene::parse_scene(&s).err(),
        ];
        for e in errors.iter().flatten() {
            prop_assert!(one_line(e), "{e}");
        }
        if let Ok((w, h)) = parse::size(&s) {
            prop_assert!((1..=parse::MAX_SIDE).contains(&w) && (1..=parse::MAX_SIDE).contains(&h));
        }
    }

    #[test]
    fn map_kd_options_never_eat_the_file_name(
        options in proptest::collection::vec(prop_oneof![
            (1usize..4, -9.0f32..9.0).prop_map(|(n, x)| format!("-s{}", format!(" {x}").repeat(n))),
            (1usize..4, -9.0f32..9.0).prop_map(|(n, x)| format!("-o{}", format!(" {x}").repeat(n))),
            Just("-bm 0.5".to_string()),
            Just("-clamp on".to_string()),
            Just("-mm 0 1".to_string()),
            Just("-imfchan r".to_string()),
        ], 0..5),
        name in "[a-z][a-z ]{0,10}[a-z]\\.png",
    ) {
        let m = TextureMap::parse(&format!("{} {name}", options.join(" ")));
        prop_assert_eq!(&m.file, &name);
        let named = options.iter().filter(|o| !o.starts_with("-s") && !o.starts_with("-o")).count();
        prop_assert_eq!(m.ignored.len(), named);
    }
}

#[test]
fn map_kd_options_are_read_by_the_mtl_format() {
    let m = TextureMap::parse("-s 2 3 1 -o 0.5 -clamp on -mm 0 1 brick wall.png");
    assert_eq!(m.file, "brick wall.png");
    assert_eq!(
        (m.scale, m.offset),
        (glam::Vec2::new(2.0, 3.0), glam::Vec2::new(0.5, 0.0))
    );
    assert_eq!(m.ignored, ["-clamp", "-mm"]);
    assert_eq!(TextureMap::parse("plain.png").file, "plain.png");
    let quoted = TextureMap::parse("-s 2 \"brick wall.png\"");
    assert_eq!(
        (quoted.file.as_str(), quoted.scale.x),
        ("brick wall.png", 2.0)
    );
    assert_eq!(TextureMap::parse("\"\"").file, "\"\"");
}
