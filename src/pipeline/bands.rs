//! Faces in groups, so that a band of rows finds the faces wholly above or below
//! it without reading them: each thread of a frame drawn in bands then reads and
//! sets up only its own triangles (and those it shares with a neighbour).
//!
//! The faces are taken in groups of [`GROUP`] in the mesh's order, and the
//! vertices in chunks of [`CHUNK`]. Once per mesh, each group records the chunks
//! that hold the vertices its faces name; once per frame, each chunk records the
//! lowest and highest row its vertices project to. A group's triangles lie within
//! its corners' rows, so within its chunks' rows. A mesh whose faces name nearby
//! vertices (a grid, a subdivided wall, most model files) names few chunks per
//! group, so its rows are tight; a group that names too many is drawn as before,
//! every face tested.

use super::clip::ScreenVertex;
use super::interpolate::Nothing;
use super::mesh::Mesh;
use std::ops::Range;

/// Faces in a group.
pub const GROUP: usize = 32;

/// Vertices in a chunk.
pub const CHUNK: usize = 16;

/// A group naming more chunks than this is drawn face by face.
const MOST_CHUNKS: usize = 12;

/// For each group of a mesh's faces, the chunks of vertices its faces name.
#[derive(Clone, Debug, Default)]
pub struct FaceGroups {
    /// Each group's chunks, in order, one after the other; none for a group
    /// that names too many.
    chunks: Vec<u32>,
    /// Where each group's chunks start in `chunks`, and where the last ends.
    starts: Vec<u32>,
    faces: usize,
    vertices: usize,
}

impl FaceGroups {
    /// `mesh`'s faces in groups.
    pub fn of(mesh: &Mesh) -> FaceGroups {
        let mut groups = FaceGroups {
            faces: mesh.faces.len(),
            vertices: mesh.positions.len(),
            ..FaceGroups::default()
        };
        let mut named = Vec::with_capacity(3 * GROUP);
        groups.starts.push(0);
        for group in mesh.faces.chunks(GROUP) {
            named.clear();
            named.extend(
                group
                    .iter()
                    .flat_map(|f| f.vertices.map(|v| v / CHUNK as u32)),
            );
            named.sort_unstable();
            named.dedup();
            if named.len() <= MOST_CHUNKS {
                groups.chunks.extend(&named);
            }
            groups.starts.push(groups.chunks.len() as u32);
        }
        groups
    }

    /// Whether these groups hold for `mesh`: made from it, or from a mesh with
    /// the same vertices whose first faces are its faces. Only the sizes are
    /// compared: looking at the faces would read them all.
    pub fn fit(&self, mesh: &Mesh) -> bool {
        self.starts.len() > 1
            && mesh.positions.len() == self.vertices
            && mesh.faces.len() <= self.faces
    }

    /// The groups of a mesh with `faces` faces: each group's range of faces, and
    /// the chunks its vertices are in (none if it names too many). The tests'
    /// view of them; `select` walks the same by index.
    #[cfg(test)]
    fn groups(&self, faces: usize) -> impl Iterator<Item = (Range<usize>, &[u32])> + '_ {
        self.starts
            .windows(2)
            .enumerate()
            .map(move |(g, ends)| {
                let from = g * GROUP;
                let chunks = &self.chunks[ends[0] as usize..ends[1] as usize];
                (from..(from + GROUP).min(faces), chunks)
            })
            .take_while(|(faces, _)| !faces.is_empty())
    }

    /// How many groups there are.
    pub fn count(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    /// The rows (from the screen's centre) of each group from `first` on, into
    /// `out`, from the rows its chunks lie in this frame (`rows`): every band of
    /// the frame reads them, so they are found once. A group that names too many
    /// chunks gets every row.
    pub fn group_rows(&self, first: usize, rows: &[(f32, f32)], out: &mut [(f32, f32)]) {
        let starts = &self.starts[first..];
        for (ends, out) in starts.windows(2).zip(out) {
            let chunks = &self.chunks[ends[0] as usize..ends[1] as usize];
            *out = rows_of_chunks(chunks, rows).unwrap_or((f32::NEG_INFINITY, f32::INFINITY));
        }
    }

    /// The faces of a band whose rows (from the screen's centre) are `bounds`,
    /// of a mesh with `faces` faces whose groups lie in `rows` this frame
    /// ([`FaceGroups::group_rows`]): as runs of faces in the mesh's order, each
    /// with whether its faces may lie beyond the band (to be tested one by one).
    /// Returns how many faces it passed over, wholly beyond the band.
    pub fn select(
        &self,
        faces: usize,
        rows: &[(f32, f32)],
        (top, bottom): (f32, f32),
        runs: &mut Vec<(Range<usize>, bool)>,
    ) -> u64 {
        runs.clear();
        runs.reserve(self.count()); // in the first frame: no later one allocates
        let mut passed = 0;
        let groups = faces.div_ceil(GROUP).min(rows.len());
        for (g, &group_rows) in rows[..groups].iter().enumerate() {
            let faces = g * GROUP..((g + 1) * GROUP).min(faces);
            let Some(beyond) = reaches(group_rows, (top, bottom)) else {
                passed += faces.len() as u64;
                continue;
            };
            match runs.last_mut() {
                Some((run, b)) if run.end == faces.start && *b == beyond => run.end = faces.end,
                _ => runs.push((faces, beyond)),
            }
        }
        passed
    }

    /// Whether some group names too many chunks for its rows to be bounded (it
    /// keeps none).
    #[cfg(test)]
    fn scattered(&self) -> bool {
        self.starts.windows(2).any(|s| s[0] == s[1])
    }
}

/// Whether a group whose faces lie in rows `(low, high)` reaches beyond a
/// band's rows `(top, bottom)`, or None if it lies wholly beyond them.
pub fn reaches((low, high): (f32, f32), (top, bottom): (f32, f32)) -> Option<bool> {
    let outside = high < top || low > bottom;
    (!outside).then_some(low < top || high > bottom)
}

/// Where a band of image rows `band` that still has the faces of `runs` from
/// face `from` on to draw is cut in two halves of them, as their groups' rows
/// this frame say (`rows`, from the screen's centre, which is at row
/// `centre`): the row the lower half starts at, and how many faces are left
/// in the band.
/// Each group counts at its middle row, in one of [`HALVING_PARTS`] parts of
/// the band; a group without bounded rows counts in the middle.
pub fn halfway_row(
    runs: &[(Range<usize>, bool)],
    from: usize,
    rows: &[(f32, f32)],
    band: Range<i32>,
    centre: f32,
) -> (i32, usize) {
    let mut parts = [0usize; HALVING_PARTS];
    let length = band.len().max(1) as f32;
    let part = |mid: f32| {
        let at = (mid + centre - band.start as f32) / length * HALVING_PARTS as f32;
        match at.is_finite() {
            true => (at.max(0.0) as usize).min(HALVING_PARTS - 1),
            false => HALVING_PARTS / 2,
        }
    };
    for run in runs {
        let faces = run.0.start.max(from)..run.0.end;
        let mut at = faces.start;
        while at < faces.end {
            let group = at / GROUP;
            let end = ((group + 1) * GROUP).min(faces.end);
            let (low, high) = rows.get(group).copied().unwrap_or((0.0, 0.0));
            // A group wholly beyond the band is passed over, not drawn.
            let beyond = high + centre < band.start as f32 || low + centre > band.end as f32;
            if !beyond {
                parts[part((low + high) / 2.0)] += end - at;
            }
            at = end;
        }
    }
    let left: usize = parts.iter().sum();
    let mut done = 0;
    for (k, &faces) in parts.iter().enumerate() {
        if 2 * (done + faces) >= left && faces > 0 {
            // Within the part, where its faces, spread evenly, reach half.
            let within = (left as f32 / 2.0 - done as f32) / faces as f32;
            let row = (k as f32 + within.clamp(0.0, 1.0)) * length / HALVING_PARTS as f32;
            return (band.start + row.round() as i32, left);
        }
        done += faces;
    }
    (band.start + band.len() as i32 / 2, left)
}

/// In how many parts [`halfway_row`] weighs a band's rows.
const HALVING_PARTS: usize = 32;

/// The rows (from the screen's centre) that the vertices of each chunk of
/// `screen` lie in: the lowest and highest `y`.
pub fn chunk_rows(screen: &[ScreenVertex<Nothing>], rows: &mut [(f32, f32)]) {
    for (chunk, rows) in screen.chunks(CHUNK).zip(rows) {
        // Plain comparisons, not `f32::min`: the rows are those of vertices in
        // view, never NaN, and this compiles to one instruction each.
        *rows = chunk.iter().fold((f32::MAX, f32::MIN), |(lo, hi), s| {
            (
                if s.y < lo { s.y } else { lo },
                if s.y > hi { s.y } else { hi },
            )
        });
    }
}

/// The rows a group whose vertices are in `chunks` lies in, if it names any.
fn rows_of_chunks(chunks: &[u32], rows: &[(f32, f32)]) -> Option<(f32, f32)> {
    let (&first, rest) = chunks.split_first()?;
    let mut bounds = *rows.get(first as usize)?;
    for &c in rest {
        let &(a, b) = rows.get(c as usize)?;
        // Plain comparisons, as in `chunk_rows`: never NaN.
        bounds = (
            if a < bounds.0 { a } else { bounds.0 },
            if b > bounds.1 { b } else { bounds.1 },
        );
    }
    Some(bounds)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::mesh::Face;
    use glam::Vec3;

    #[test]
    fn a_band_is_cut_where_half_its_faces_left_lie() {
        // 64 groups, group g on image row g (the screen's centre on row 32).
        let rows: Vec<(f32, f32)> = (0..64)
            .map(|g| (g as f32 - 32.5, g as f32 - 31.5))
            .collect();
        let runs = [(0..64 * GROUP, false)];
        assert_eq!(halfway_row(&runs, 0, &rows, 0..64, 32.0), (32, 64 * GROUP));
        // Only the faces from `from` on are left.
        let from = 32 * GROUP;
        assert_eq!(
            halfway_row(&runs, from, &rows, 0..64, 32.0),
            (48, 32 * GROUP)
        );
        // Groups wholly beyond the band do not count: 17 reach rows 0 to 16.
        assert_eq!(halfway_row(&runs, 0, &rows, 0..16, 32.0), (8, 17 * GROUP));
        // A group with no bounded rows counts in the middle of the band.
        let mut scattered = rows.clone();
        scattered[0] = (f32::NEG_INFINITY, f32::INFINITY);
        let one = [(0..GROUP, false)];
        assert_eq!(halfway_row(&one, 0, &scattered, 0..64, 32.0), (33, GROUP));
    }

    /// A grid of `n` x `n` squares, two faces each, row by row.
    fn grid(n: u32) -> Mesh {
        let mut mesh = Mesh::default();
        for j in 0..=n {
            for i in 0..=n {
                mesh.positions.push(Vec3::new(i as f32, j as f32, 1.0));
            }
        }
        let at = |i: u32, j: u32| j * (n + 1) + i;
        for j in 0..n {
            for i in 0..n {
                let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                for vertices in [[a, b, c], [a, c, d]] {
                    mesh.faces.push(Face {
                        vertices,
                        normal: Vec3::Z,
                        material: 0,
                    });
                }
            }
        }
        mesh
    }

    /// Each vertex's `y` as its row.
    fn rows_of(mesh: &Mesh) -> Vec<(f32, f32)> {
        let screen: Vec<_> = mesh
            .positions
            .iter()
            .map(|p| ScreenVertex {
                x: p.x,
                y: p.y,
                zinv: 1.0,
                varying: Nothing {},
            })
            .collect();
        let mut rows = vec![(0.0, 0.0); screen.len().div_ceil(CHUNK)];
        chunk_rows(&screen, &mut rows);
        rows
    }

    #[test]
    fn a_group_lies_within_its_chunks_rows_and_a_grid_within_few() {
        let mesh = grid(90);
        let (groups, rows) = (FaceGroups::of(&mesh), rows_of(&mesh));
        assert!(!groups.scattered() && groups.fit(&mesh));
        let mut seen = 0;
        for (faces, chunks) in groups.groups(mesh.faces.len()) {
            let (low, high) = rows_of_chunks(chunks, &rows).expect("a grid names few chunks");
            // 32 faces are 16 squares of one row of squares, or of two: two or
            // three rows of vertices, and chunks run from one row to the next.
            assert!(high - low <= 3.0, "{low} to {high}");
            for face in &mesh.faces[faces] {
                for v in face.vertices {
                    let y = mesh.positions[v as usize].y;
                    assert!(low <= y && y <= high);
                    seen += 1;
                }
            }
        }
        assert_eq!(seen, 3 * mesh.faces.len());
        // A prefix of the faces fits; another mesh's vertices do not.
        let mut prefix = mesh.clone();
        prefix.faces.truncate(1000);
        assert!(groups.fit(&prefix));
        assert_eq!(
            groups.groups(1000).map(|(f, _)| f.len()).sum::<usize>(),
            1000
        );
        prefix.positions.pop();
        assert!(!groups.fit(&prefix));
    }

    /// `mesh` with every `nth` group's faces each naming a vertex of their own
    /// row and of the last: 16 squares of vertices in 3 rows name more than 12
    /// chunks.
    fn scatter(mut mesh: Mesh, nth: usize) -> Mesh {
        let last = mesh.positions.len() as u32 - 1;
        for (k, face) in mesh.faces.iter_mut().enumerate() {
            if (k / GROUP) % nth == 1 {
                face.vertices[0] = last - (k % GROUP) as u32 * CHUNK as u32;
            }
        }
        mesh
    }

    #[test]
    fn faces_naming_far_apart_vertices_are_not_bounded() {
        let mesh = scatter(grid(90), 2);
        let (groups, rows) = (FaceGroups::of(&mesh), rows_of(&mesh));
        assert!(groups.scattered());
        let bounded = groups
            .groups(mesh.faces.len())
            .filter(|(_, chunks)| rows_of_chunks(chunks, &rows).is_some())
            .count();
        assert_eq!(groups.groups(mesh.faces.len()).count(), 507);
        assert_eq!(bounded, 254);
    }

    #[test]
    fn a_band_passes_over_only_faces_beyond_it_and_tests_those_that_may_be() {
        for mesh in [grid(90), scatter(grid(90), 3)] {
            let groups = FaceGroups::of(&mesh);
            let mut rows = vec![(0.0, 0.0); groups.count()];
            groups.group_rows(0, &rows_of(&mesh), &mut rows);
            let mut runs = Vec::new();
            for (top, bottom) in [(20.5, 40.5), (-10.0, 0.5), (89.5, 200.0), (45.0, 45.0)] {
                let faces = mesh.faces.len();
                let passed = groups.select(faces, &rows, (top, bottom), &mut runs);
                let mut chosen = vec![None; faces];
                for (run, beyond) in &runs {
                    for k in run.clone() {
                        chosen[k] = Some(*beyond);
                    }
                }
                let left = chosen.iter().filter(|c| c.is_none()).count();
                assert_eq!(passed, left as u64);
                for (face, chosen) in mesh.faces.iter().zip(&chosen) {
                    let ys = face.vertices.map(|v| mesh.positions[v as usize].y);
                    let beyond = ys.iter().all(|&y| y < top) || ys.iter().all(|&y| y > bottom);
                    let within = ys.iter().all(|&y| top <= y && y <= bottom);
                    match chosen {
                        // Passed over: wholly beyond the band.
                        None => assert!(beyond, "{ys:?} in {top} to {bottom}"),
                        // Not tested: wholly within it.
                        Some(false) => assert!(within, "{ys:?} in {top} to {bottom}"),
                        Some(true) => {}
                    }
                }
                // A band within the grid passes over most of it.
                if bottom - top == 20.0 {
                    assert!(left > faces / 2 && left < faces, "{left} of {faces}");
                }
            }
        }
    }
}
