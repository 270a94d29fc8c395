//! The core's input: a mesh of vertices and triangular faces with materials.
//!
//! A vertex has a position and, when the scene has them, a normal and a (u, v)
//! coordinate; a face names three vertices, its normal (the handout's
//! `Triangle::normal`) and its material (the handout's `Triangle::color`, the
//! reflectance ρ of eq. 11).

use glam::{Vec2, Vec3};

/// What a surface is made of, as far as the handout goes: its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// The diffuse reflectance ρ of eq. 11, linear, per channel in [0, 1].
    pub color: Vec3,
}

impl Material {
    pub const fn new(color: Vec3) -> Material {
        Material { color }
    }
}

/// A triangle of the mesh: three indices into the vertex lists, in drawing order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Face {
    pub vertices: [u32; 3],
    /// The handout's normal of the face, `normalize((v2 - v0) × (v1 - v0))` unless
    /// the builder says otherwise.
    pub normal: Vec3,
    /// Index into [`Mesh::materials`].
    pub material: u32,
}

/// One corner of a face as the vertex shader sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    pub position: Vec3,
    /// The vertex normal where the mesh has them, else the face's normal.
    pub normal: Vec3,
    /// The (u, v) coordinate where the mesh has them, else zero.
    pub uv: Vec2,
}

/// Vertices and faces. `normals` and `uvs` are either empty or as long as
/// `positions`: one index addresses all three.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub uvs: Vec<Vec2>,
    pub faces: Vec<Face>,
    pub materials: Vec<Material>,
}

/// A face with its corners and material resolved: the handout's `Triangle`, which
/// the ray tracer and the measures walk.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub v0: Vec3,
    pub v1: Vec3,
    pub v2: Vec3,
    pub normal: Vec3,
    pub color: Vec3,
}

impl Triangle {
    /// A triangle whose normal is `normalize((v2 - v0) × (v1 - v0))` (handout section 6).
    pub fn new(v0: Vec3, v1: Vec3, v2: Vec3, color: Vec3) -> Self {
        Triangle {
            v0,
            v1,
            v2,
            normal: face_normal([v0, v1, v2]),
            color,
        }
    }

    pub fn vertices(&self) -> [Vec3; 3] {
        [self.v0, self.v1, self.v2]
    }
}

/// The handout's face normal, `normalize((v2 - v0) × (v1 - v0))`; zero for a
/// degenerate triangle.
pub fn face_normal([v0, v1, v2]: [Vec3; 3]) -> Vec3 {
    (v2 - v0).cross(v1 - v0).normalize_or_zero()
}

impl Mesh {
    /// A mesh of separate triangles (no shared vertices, no normals or (u, v)
    /// coordinates), one material per distinct colour.
    pub fn from_triangles(triangles: &[Triangle]) -> Self {
        let mut mesh = Mesh::default();
        for t in triangles {
            mesh.push_triangle(t.vertices(), t.normal, t.color);
        }
        mesh
    }

    /// Adds a triangle with its own three vertices, its face normal and a material
    /// of colour `color` (shared with earlier faces of the same colour).
    pub fn push_triangle(&mut self, corners: [Vec3; 3], normal: Vec3, color: Vec3) {
        let material = match self.materials.iter().position(|m| m.color == color) {
            Some(i) => i,
            None => {
                self.materials.push(Material { color });
                self.materials.len() - 1
            }
        } as u32;
        let first = self.positions.len() as u32;
        self.positions.extend(corners);
        self.faces.push(Face {
            vertices: [first, first + 1, first + 2],
            normal,
            material,
        });
    }

    /// The corner `k` (0, 1 or 2) of `face`.
    #[inline]
    pub fn vertex(&self, face: &Face, k: usize) -> Vertex {
        let i = face.vertices[k] as usize;
        Vertex {
            position: self.positions[i],
            normal: self.normals.get(i).copied().unwrap_or(face.normal),
            uv: self.uvs.get(i).copied().unwrap_or(Vec2::ZERO),
        }
    }

    #[inline]
    pub fn material(&self, face: &Face) -> &Material {
        &self.materials[face.material as usize]
    }

    /// Every face as a [`Triangle`], in order.
    pub fn triangles(&self) -> impl ExactSizeIterator<Item = Triangle> + '_ {
        self.faces.iter().map(|f| {
            let [v0, v1, v2] = f.vertices.map(|i| self.positions[i as usize]);
            Triangle {
                v0,
                v1,
                v2,
                normal: f.normal,
                color: self.material(f).color,
            }
        })
    }

    /// The same mesh with every position moved by `f` (face normals kept).
    pub fn map_positions(&self, f: impl Fn(Vec3) -> Vec3) -> Mesh {
        Mesh {
            positions: self.positions.iter().map(|&p| f(p)).collect(),
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangles_round_trip_through_a_mesh() {
        let red = Vec3::new(0.75, 0.15, 0.15);
        let t = [
            Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y, red),
            Triangle::new(Vec3::ZERO, Vec3::Y, Vec3::Z, Vec3::ONE),
            Triangle::new(Vec3::ZERO, Vec3::Z, Vec3::X, red),
        ];
        let mesh = Mesh::from_triangles(&t);
        assert_eq!(mesh.materials.len(), 2, "one material per colour");
        assert_eq!(mesh.triangles().collect::<Vec<_>>(), t);
        let v = mesh.vertex(&mesh.faces[1], 2);
        assert_eq!(
            (v.position, v.normal, v.uv),
            (Vec3::Z, t[1].normal, Vec2::ZERO)
        );
    }
}
