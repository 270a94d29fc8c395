//! Faces in groups, so that a band of rows finds the faces wholly above or below
//! it without reading them: each thread of a frame drawn in bands then reads and
//! sets up only its own triangles (and those it shares with a neighbour).
//!
//! The faces are taken in groups of [`GROUP`] in the mesh's order, and the
//! vertices in chunks of [`CHUNK`]. Once per mesh, each group records the run of
//! chunks that holds every vertex its faces name; once per frame, each chunk
//! records the lowest and highest row its vertices project to. A group's
//! triangles lie within its corners' rows, so within its chunks' rows. A mesh
//! whose faces name nearby vertices (a grid, a subdivided wall, most model files)
//! has short runs and so tight rows; one that does not is drawn as before,
//! every face tested.

use super::clip::ScreenVertex;
use super::interpolate::Nothing;
use super::mesh::Mesh;
use std::ops::Range;

/// Faces in a group.
pub const GROUP: usize = 256;

/// Vertices in a chunk.
pub const CHUNK: usize = 64;

/// Longer runs than this many chunks are not worth looking at: such a group is
/// drawn face by face.
const LONGEST_RUN: u32 = 32;

/// For each group of a mesh's faces, the chunks of vertices its faces name.
#[derive(Clone, Debug, Default)]
pub struct FaceGroups {
    /// The first and last chunk of each group.
    runs: Vec<(u32, u32)>,
    /// Whether a group's run is too long to bound its rows.
    scattered: bool,
    faces: usize,
    vertices: usize,
}

impl FaceGroups {
    /// `mesh`'s faces in groups.
    pub fn of(mesh: &Mesh) -> FaceGroups {
        let runs: Vec<(u32, u32)> = mesh
            .faces
            .chunks(GROUP)
            .map(|group| {
                let named = group.iter().flat_map(|f| f.vertices);
                let (first, last) = named.fold((u32::MAX, 0), |(a, b), v| (a.min(v), b.max(v)));
                (first / CHUNK as u32, last / CHUNK as u32)
            })
            .collect();
        FaceGroups {
            scattered: runs.iter().any(|&(a, b)| b - a > LONGEST_RUN),
            runs,
            faces: mesh.faces.len(),
            vertices: mesh.positions.len(),
        }
    }

    /// Whether these groups hold for `mesh`: made from it, or from a mesh with
    /// the same vertices whose first faces are its faces. Only the sizes are
    /// compared: looking at the faces would read them all.
    pub fn fit(&self, mesh: &Mesh) -> bool {
        !self.runs.is_empty()
            && mesh.positions.len() == self.vertices
            && mesh.faces.len() <= self.faces
    }

    /// The groups' faces of a mesh with `faces` faces: each group's range of
    /// faces, and the range of chunks its vertices are in.
    pub fn groups(&self, faces: usize) -> impl Iterator<Item = (Range<usize>, Range<usize>)> + '_ {
        self.runs
            .iter()
            .enumerate()
            .map(move |(g, &(a, b))| {
                let from = g * GROUP;
                (from..(from + GROUP).min(faces), a as usize..b as usize + 1)
            })
            .take_while(|(faces, _)| !faces.is_empty())
    }

    /// Whether some group's vertices are too scattered for its rows to be
    /// bounded: a band then places every vertex.
    pub fn scattered(&self) -> bool {
        self.scattered
    }
}

/// The rows (from the screen's centre) that the vertices of each chunk of
/// `screen` lie in: the lowest and highest `y`.
pub fn chunk_rows(screen: &[ScreenVertex<Nothing>], rows: &mut [(f32, f32)]) {
    for (chunk, rows) in screen.chunks(CHUNK).zip(rows) {
        *rows = chunk.iter().fold((f32::MAX, f32::MIN), |(lo, hi), s| {
            (lo.min(s.y), hi.max(s.y))
        });
    }
}

/// The rows a group whose vertices are in `chunks` lies in, if its run is
/// short enough to look at.
pub fn group_rows(chunks: Range<usize>, rows: &[(f32, f32)]) -> Option<(f32, f32)> {
    if chunks.len() > LONGEST_RUN as usize + 1 {
        return None;
    }
    let rows = rows.get(chunks)?;
    Some(rows.iter().fold((f32::MAX, f32::MIN), |(lo, hi), &(a, b)| {
        (lo.min(a), hi.max(b))
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::mesh::Face;
    use glam::Vec3;

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
            let (low, high) = group_rows(chunks, &rows).expect("a grid's runs are short");
            // 256 faces are under two rows of 90 squares: three rows of vertices,
            // and a chunk's slack on either side.
            assert!(high - low <= 4.0, "{low} to {high}");
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
        assert_eq!(groups.groups(1000).map(|(f, _)| f.len()).sum::<usize>(), 1000);
        prefix.positions.pop();
        assert!(!groups.fit(&prefix));
    }

    #[test]
    fn faces_naming_far_apart_vertices_are_not_bounded() {
        let mut mesh = grid(90);
        // The last face of each group names the first vertex as well.
        for face in mesh.faces.iter_mut().skip(GROUP - 1).step_by(GROUP) {
            face.vertices[0] = 0;
        }
        let (groups, rows) = (FaceGroups::of(&mesh), rows_of(&mesh));
        assert!(groups.scattered());
        let bounded = groups
            .groups(mesh.faces.len())
            .filter(|(_, chunks)| group_rows(chunks.clone(), &rows).is_some())
            .count();
        // Only the groups still near the first vertex: 16 of 64.
        assert_eq!(groups.groups(mesh.faces.len()).count(), 64);
        assert_eq!(bounded, 16);
    }
}
