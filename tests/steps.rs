//! The plain step programs in steps/ and the core prove each other: each program's
//! drawing equals the core's stage, byte for byte. (Clipping and the guard band,
//! which only the core has, never act on the default view, so nothing differs.)

use rasterlab::app::{self, Settings};
use rasterlab::{cornell_box, Figure, StageName};

use crate::plain::{depth, filled, pixel_light, points, vertex_light, wireframe};

fn core(figure: Figure) -> Vec<u8> {
    app::render(figure, &cornell_box(), &Settings::default(), None)
        .0
        .to_rgb8()
}

/// Asserts two 500 x 500 RGB images are equal, naming the first difference.
fn assert_same(name: &str, plain: &[u8], core: &[u8]) {
    assert_eq!(plain.len(), core.len(), "{name}");
    let differing: Vec<usize> = (0..plain.len() / 3)
        .filter(|&i| plain[3 * i..3 * i + 3] != core[3 * i..3 * i + 3])
        .collect();
    if let Some(&i) = differing.first() {
        panic!(
            "{name}: {} pixels differ, first at ({}, {}): plain {:?}, core {:?}",
            differing.len(),
            i % 500,
            i / 500,
            &plain[3 * i..3 * i + 3],
            &core[3 * i..3 * i + 3]
        );
    }
}

#[test]
fn every_step_program_draws_the_cores_figure_byte_for_byte() {
    use StageName::*;
    let lit = |p: bool| pixel_light::draw(p).to_rgb8();
    for (name, plain, figure) in [
        ("2-points", points::draw().to_rgb8(), Figure::of(Points)),
        (
            "3-wireframe",
            wireframe::draw().to_rgb8(),
            Figure::of(Wireframe),
        ),
        ("4-filled", filled::draw().to_rgb8(), Figure::of(Filled)),
        ("5-depth", depth::draw().to_rgb8(), Figure::of(Depth)),
        (
            "6-vertex-light",
            vertex_light::draw().to_rgb8(),
            Figure::of(VertexLight),
        ),
        ("7-pixel-light", lit(true), Figure::of(PixelLight)),
        (
            "7-pixel-light --affine",
            lit(false),
            Figure::with_interpolation(PixelLight, Some(true)),
        ),
    ] {
        assert_same(name, &plain, &core(figure));
    }
}

/// Each steps/ page shows its program's difference from the previous step's, as a
/// unified diff between `<!-- diff: A B -->` and `<!-- end diff -->`. With
/// `RASTERLAB_UPDATE_STEPS=1` the test rewrites the blocks instead of checking them.
#[test]
fn each_page_shows_its_sections_diff() {
    let steps = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("steps");
    let update = std::env::var_os("RASTERLAB_UPDATE_STEPS").is_some();
    let programs = [
        "2-points",
        "3-wireframe",
        "4-filled",
        "5-depth",
        "6-vertex-light",
        "7-pixel-light",
    ];
    for pair in programs.windows(2) {
        let (before, after) = (pair[0], pair[1]);
        let read = |name: &str| std::fs::read_to_string(steps.join(name)).unwrap();
        let (a, b) = (read(&format!("{before}.rs")), read(&format!("{after}.rs")));
        let diff = similar::TextDiff::from_lines(&a, &b)
            .unified_diff()
            .context_radius(2)
            .header(&format!("steps/{before}.rs"), &format!("steps/{after}.rs"))
            .to_string();
        let block =
            format!("<!-- diff: {before}.rs {after}.rs -->\n```diff\n{diff}```\n<!-- end diff -->");
        let page_path = steps.join(format!("{after}.md"));
        let page = std::fs::read_to_string(&page_path).unwrap();
        let start = page
            .find(&format!("<!-- diff: {before}.rs {after}.rs -->"))
            .unwrap_or_else(|| panic!("{after}.md has no diff block"));
        let end = page[start..].find("<!-- end diff -->").unwrap() + start + 17;
        if update {
            let new = format!("{}{block}{}", &page[..start], &page[end..]);
            std::fs::write(&page_path, new).unwrap();
        } else {
            assert!(
                page[start..end] == block,
                "{after}.md's diff is stale: run RASTERLAB_UPDATE_STEPS=1 cargo test --release --test suite steps::"
            );
        }
    }
}

/// docs/handout-map.md points at lines of the step programs: "`steps/F.rs`
/// `function`, lines A-B" must name lines inside that function, and "`code`
/// (line N)" a line that holds that code. A step program that changes moves the
/// map's lines with it, or this fails.
#[test]
fn the_handout_maps_step_lines_are_where_it_says() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let map = std::fs::read_to_string(root.join("docs/handout-map.md")).unwrap();
    let read = |file: &str| -> Vec<String> {
        let text = std::fs::read_to_string(root.join(file)).expect(file);
        text.lines().map(str::to_owned).collect()
    };
    let mut checked = 0;
    // The first table's rows: | handout | section | step | rasterlab | file |
    for row in map
        .lines()
        .filter(|l| l.starts_with('|') && l.matches(" | ").count() == 4)
    {
        let step_cell = row.split(" | ").nth(2).unwrap_or("");
        // One program per cell part, split where the next program is named.
        for part in step_cell
            .split("; `steps/")
            .map(|p| p.trim_start_matches("`steps/"))
        {
            let Some((file, rest)) = part.split_once(".rs`") else {
                continue;
            };
            if !file.chars().all(|c| c.is_ascii_alphanumeric() || c == '-') {
                continue;
            }
            let file = file.rsplit("steps/").next().unwrap();
            let lines = read(&format!("steps/{file}.rs"));
            // "`function`, lines A-B"
            if let Some((before, range)) = rest.split_once(", lines ") {
                let function = before.trim().trim_matches('`');
                let range: String = range
                    .chars()
                    .take_while(|c| c.is_ascii_digit() || *c == '-')
                    .collect();
                let (a, b) = range.split_once('-').unwrap();
                let (a, b): (usize, usize) = (a.parse().unwrap(), b.parse().unwrap());
                let start = lines[..a - 1]
                    .iter()
                    .rposition(|l| l.starts_with("fn ") || l.starts_with("pub fn "))
                    .unwrap();
                assert!(
                    lines[start].contains(&format!("fn {function}(")),
                    "docs/handout-map.md: steps/{file}.rs lines {a}-{b} are in `{}`, not `{function}`",
                    lines[start]
                );
                assert!(
                    !lines[a..b].iter().any(|l| l.starts_with('}')),
                    "docs/handout-map.md: steps/{file}.rs lines {a}-{b} leave `{function}`"
                );
                checked += 1;
            }
            // "`code` (line N)"
            let mut rest = rest;
            while let Some(at) = rest.find(" (line ") {
                let code = rest[..at].trim_end().rsplit('`').nth(1).unwrap();
                let n: String = rest[at + 7..]
                    .chars()
                    .take_while(char::is_ascii_digit)
                    .collect();
                let n: usize = n.parse().unwrap();
                assert!(
                    lines[n - 1].contains(code),
                    "docs/handout-map.md: steps/{file}.rs line {n} is `{}`, without `{code}`",
                    lines[n - 1].trim()
                );
                checked += 1;
                rest = &rest[at + 7..];
            }
        }
    }
    assert_eq!(checked, 5, "the map's line references found");
}
