//! The handout's test model: the Cornell box with a short red and a tall blue block.
//!
//! The room and blocks are given in the units of the classic Cornell box data (side
//! L = 555) and then scaled into the cube [-1, 1]^3 with x and y negated, so that y
//! points down as in the handout's section 1.

use crate::pipeline::{Face, Mesh, Triangle};
use glam::Vec3;

pub const RED: Vec3 = Vec3::new(0.75, 0.15, 0.15);
pub const YELLOW: Vec3 = Vec3::new(0.75, 0.75, 0.15);
pub const GREEN: Vec3 = Vec3::new(0.15, 0.75, 0.15);
pub const CYAN: Vec3 = Vec3::new(0.15, 0.75, 0.75);
pub const BLUE: Vec3 = Vec3::new(0.15, 0.15, 0.75);
pub const PURPLE: Vec3 = Vec3::new(0.75, 0.15, 0.75);
pub const WHITE: Vec3 = Vec3::new(0.75, 0.75, 0.75);

/// Side of the box in the source data.
const L: f32 = 555.0;

/// The ten triangles of a block whose eight corners are A..H (bottom A-D, top E-H).
fn block(c: [Vec3; 8], color: Vec3, out: &mut Vec<Triangle>) {
    let [a, b, cc, d, e, f, g, h] = c;
    for (v0, v1, v2) in [
        (e, b, a),
        (e, f, b),
        (f, d, b),
        (f, h, d),
        (h, cc, d),
        (h, g, cc),
        (g, e, cc),
        (e, a, cc),
        (g, f, e),
        (g, h, f),
    ] {
        out.push(Triangle::new(v0, v1, v2, color));
    }
}

fn corners(bottom: [[f32; 3]; 4], height: f32) -> [Vec3; 8] {
    let b = bottom.map(Vec3::from_array);
    let up = Vec3::new(0.0, height, 0.0);
    [
        b[0],
        b[1],
        b[2],
        b[3],
        b[0] + up,
        b[1] + up,
        b[2] + up,
        b[3] + up,
    ]
}

/// The handout's test model: 30 triangles, in the course skeleton's order
/// (floor, left wall, right wall, ceiling, back wall, short block, tall block).
pub fn cornell_box() -> Mesh {
    Mesh::from_triangles(&cornell_triangles())
}

fn cornell_triangles() -> Vec<Triangle> {
    let mut t = Vec::with_capacity(30);
    let room = corners(
        [[L, 0.0, 0.0], [0.0, 0.0, 0.0], [L, 0.0, L], [0.0, 0.0, L]],
        L,
    );
    let [a, b, c, d, e, f, g, h] = room;
    for (v0, v1, v2, color) in [
        (c, b, a, GREEN), // floor
        (c, d, b, GREEN),
        (a, e, c, PURPLE), // left wall
        (c, e, g, PURPLE),
        (f, b, d, YELLOW), // right wall
        (h, f, d, YELLOW),
        (e, f, g, CYAN), // ceiling
        (f, h, g, CYAN),
        (g, d, c, WHITE), // back wall
        (g, h, d, WHITE),
    ] {
        t.push(Triangle::new(v0, v1, v2, color));
    }
    let short = [
        [290.0, 0.0, 114.0],
        [130.0, 0.0, 65.0],
        [240.0, 0.0, 272.0],
        [82.0, 0.0, 225.0],
    ];
    block(corners(short, 165.0), RED, &mut t);
    let tall = [
        [423.0, 0.0, 247.0],
        [265.0, 0.0, 296.0],
        [472.0, 0.0, 406.0],
        [314.0, 0.0, 456.0],
    ];
    block(corners(tall, 330.0), BLUE, &mut t);

    // Into [-1, 1]^3 as the course's LoadTestModel does: scale by 2/L (computed
    // once, in f32), shift by -1, then flip x and y so y points down.
    let scale = 2.0 / L;
    let to_lab = |v: Vec3| {
        let v = v * scale - Vec3::ONE;
        Vec3::new(-v.x, -v.y, v.z)
    };
    t.into_iter()
        .map(|tri| Triangle::new(to_lab(tri.v0), to_lab(tri.v1), to_lab(tri.v2), tri.color))
        .collect()
}

/// Splits every triangle into k x k smaller ones on a grid of its barycentric
/// coordinates, keeping its normal and material: the same surfaces with k² times
/// the triangles, for measuring how cost and per-vertex error change with mesh
/// density. Neighbouring small triangles share their grid corners, as the
/// triangles of a modelled mesh share vertices: (k + 1)(k + 2)/2 vertices for
/// each triangle split, not 3k².
pub fn subdivide(mesh: &Mesh, k: u32) -> Mesh {
    let k = k.max(1);
    let corners_per_face = ((k + 1) * (k + 2) / 2) as usize;
    let mut out = Mesh {
        materials: mesh.materials.clone(),
        ..Mesh::default()
    };
    out.positions.reserve(mesh.faces.len() * corners_per_face);
    out.faces.reserve(mesh.faces.len() * (k * k) as usize);
    for face in &mesh.faces {
        let [v0, v1, v2] = face.vertices.map(|i| mesh.positions[i as usize]);
        // Corner (i, j) of the grid: v0 + (i/k)(v1 - v0) + (j/k)(v2 - v0), i + j <= k,
        // stored row by row (j), each row k + 1 - j corners long.
        let first = out.positions.len() as u32;
        for j in 0..=k {
            for i in 0..=k - j {
                let (a, b) = (i as f32 / k as f32, j as f32 / k as f32);
                out.positions.push(v0 + (v1 - v0) * a + (v2 - v0) * b);
            }
        }
        let at = |i: u32, j: u32| first + j * (2 * k + 3 - j) / 2 + i;
        let mut push = |vertices| {
            out.faces.push(Face {
                vertices,
                normal: face.normal,
                material: face.material,
            })
        };
        for j in 0..k {
            for i in 0..k - j {
                push([at(i, j), at(i + 1, j), at(i, j + 1)]);
                if i + j + 1 < k {
                    push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thirty_triangles_inside_the_unit_cube() {
        let tris: Vec<Triangle> = cornell_box().triangles().collect();
        assert_eq!(tris.len(), 30);
        for t in &tris {
            for v in t.vertices() {
                assert!(v.abs().max_element() <= 1.0 + 1e-6, "{v}");
            }
            assert!((t.normal.length() - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn subdivision_keeps_area_normals_and_winding() {
        let mesh = cornell_box();
        let tris: Vec<Triangle> = mesh.triangles().collect();
        let area = |t: &Triangle| (t.v1 - t.v0).cross(t.v2 - t.v0).length() / 2.0;
        for k in [1, 2, 4] {
            let sub: Vec<Triangle> = subdivide(&mesh, k).triangles().collect();
            assert_eq!(sub.len(), 30 * (k * k) as usize);
            let (a, b): (f32, f32) = (tris.iter().map(area).sum(), sub.iter().map(area).sum());
            assert!((a - b).abs() < 1e-4 * a, "k = {k}: {a} vs {b}");
            for s in &sub {
                // Same winding: the recomputed normal agrees with the kept one.
                let n = (s.v2 - s.v0).cross(s.v1 - s.v0).normalize();
                assert!(n.abs_diff_eq(s.normal, 1e-4), "{n} vs {}", s.normal);
            }
        }
    }

    #[test]
    fn subdivision_shares_corners_and_gives_each_small_triangle_exactly() {
        let mesh = cornell_box();
        for k in [1, 3, 7] {
            let sub = subdivide(&mesh, k);
            assert_eq!(sub.positions.len(), 30 * ((k + 1) * (k + 2) / 2) as usize);
            // Each small triangle, computed on its own from its grid corners.
            let mut expected = Vec::new();
            for t in mesh.triangles() {
                let at = |i: u32, j: u32| {
                    let (a, b) = (i as f32 / k as f32, j as f32 / k as f32);
                    t.v0 + (t.v1 - t.v0) * a + (t.v2 - t.v0) * b
                };
                for j in 0..k {
                    for i in 0..k - j {
                        expected.push(([at(i, j), at(i + 1, j), at(i, j + 1)], t.color));
                        if i + j + 1 < k {
                            expected
                                .push(([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)], t.color));
                        }
                    }
                }
            }
            let got: Vec<_> = sub
                .triangles()
                .map(|t| ([t.v0, t.v1, t.v2], t.color))
                .collect();
            assert_eq!(got, expected, "k = {k}");
        }
    }

    #[test]
    fn normals_point_into_the_room() {
        let tris: Vec<Triangle> = cornell_box().triangles().collect();
        // Floor (y = +1 after the flip) faces up, toward -y; back wall (z = 1) faces -z.
        assert!(tris[0].normal.abs_diff_eq(Vec3::new(0.0, -1.0, 0.0), 1e-6));
        assert!(tris[8].normal.abs_diff_eq(Vec3::new(0.0, 0.0, -1.0), 1e-6));
        // Left wall (x = -1 after the flip) faces +x.
        assert!(tris[2].normal.abs_diff_eq(Vec3::new(1.0, 0.0, 0.0), 1e-6));
    }
}
