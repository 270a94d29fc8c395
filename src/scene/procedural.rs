//! Scenes made by a formula: a UV sphere with smooth normals, and a floor grid.
//! Both have texture coordinates and any number of triangles, for measuring the
//! stages on meshes other than the box.

use super::cornell::{GREEN, WHITE};
use crate::pipeline::mesh::{face_normal, Face, Material, Mesh};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A sphere of radius 1 about the origin with about `n` triangles (at least 48):
/// `stacks` bands from top to bottom, `slices` around, `2 slices (stacks - 1)`
/// triangles, the two caps made of triangles so that none is degenerate.
///
/// Normals are the unit outward directions; `u` goes once around, `v` from 0 at the
/// bottom (y = 1) to 1 at the top (y = -1: y points down). The seam (u = 0) is at
/// the back (+z), and u grows toward +x on the side facing the default camera, so
/// a texture is not mirrored. Faces are wound so that the handout's normal points
/// outward.
pub fn sphere(n: usize) -> Mesh {
    // Twice as many slices as stacks keeps the quads near the equator square.
    let stacks = ((n as f64 / 4.0).sqrt().round() as usize).max(4);
    let slices = ((n as f64 / (2 * (stacks - 1)) as f64).round() as usize).max(8);
    let cols = slices + 1; // the seam's column is doubled, for u = 0 and u = 1
    let at = |key: usize| {
        let (i, j) = (key / cols, key % cols);
        let pole = i == 0 || i == stacks;
        // A pole has one vertex per slice, at the slice's middle u, so that each
        // cap triangle's texture is not sheared toward one side.
        let u = (j as f32 + if pole { 0.5 } else { 0.0 }) / slices as f32;
        let v = 1.0 - i as f32 / stacks as f32;
        let (theta, phi) = (PI * i as f32 / stacks as f32, 2.0 * PI * u);
        let normal = match i {
            0 => Vec3::NEG_Y,
            _ if i == stacks => Vec3::Y,
            _ => Vec3::new(
                -theta.sin() * phi.sin(),
                -theta.cos(),
                theta.sin() * phi.cos(),
            )
            .normalize(),
        };
        (normal, normal, Vec2::new(u, v))
    };
    let key = |i: usize, j: usize| i * cols + j;
    // Corners (i, j) top left, (i, j + 1) top right, (i + 1, j) bottom left seen
    // from outside: top left, top right, bottom left is clockwise on the screen
    // (y down), which makes (v2 - v0) x (v1 - v0) point outward.
    let faces = (0..stacks).flat_map(|i| {
        let mut band = Vec::with_capacity(2 * slices);
        for j in 0..slices {
            let (a, b, c, d) = (key(i, j), key(i, j + 1), key(i + 1, j), key(i + 1, j + 1));
            if i == 0 {
                band.push([a, d, c]); // the top cap: the pole vertex a stands for b too
            } else if i + 1 == stacks {
                band.push([a, b, c]); // the bottom cap: the pole vertex c stands for d
            } else {
                band.extend([[a, b, c], [b, d, c]]);
            }
        }
        band
    });
    build(WHITE, (stacks + 1) * cols, faces, at)
}

/// A floor: the square -1..1 in x and z at y = 1, the box's floor height, made of
/// k x k squares (2 k² about `n`, at least 2 triangles), facing up (-y), green as
/// the box's floor. `u` follows x and `v` follows z, each from 0 to 1.
pub fn grid(n: usize) -> Mesh {
    let k = ((n as f64 / 2.0).sqrt().round() as usize).max(1);
    let cols = k + 1;
    let at = |key: usize| {
        let uv = Vec2::new((key % cols) as f32, (key / cols) as f32) / k as f32;
        let p = Vec3::new(2.0 * uv.x - 1.0, 1.0, 2.0 * uv.y - 1.0);
        (p, Vec3::NEG_Y, uv)
    };
    let faces = (0..k).flat_map(|j| {
        (0..k).flat_map(move |i| {
            let a = j * cols + i;
            let (b, c, d) = (a + 1, a + cols, a + cols + 1);
            // (a, c, b): (b - a) x (c - a) = +x times +z = -y, up.
            [[a, c, b], [b, c, d]]
        })
    });
    build(GREEN, cols * cols, faces, at)
}

/// An indexed mesh of one material from faces given by vertex keys; `at(key)` is
/// the vertex's position, normal and texture coordinate.
///
/// A vertex is created when a face first uses it, visiting the corners in the order
/// (v0, v2, v1): that is the order a file written by `obj_text` lists them in, and
/// tobj numbers the vertices it loads in order of first use, so these meshes come
/// back from a written OBJ file with the same numbering.
fn build(
    color: Vec3,
    keys: usize,
    faces: impl Iterator<Item = [usize; 3]>,
    at: impl Fn(usize) -> (Vec3, Vec3, Vec2),
) -> Mesh {
    let mut mesh = Mesh {
        materials: vec![Material::new(color)],
        ..Mesh::default()
    };
    let mut id = vec![u32::MAX; keys];
    for keys in faces {
        for k in [keys[0], keys[2], keys[1]] {
            if id[k] == u32::MAX {
                let (p, n, uv) = at(k);
                id[k] = mesh.positions.len() as u32;
                mesh.positions.push(p);
                mesh.normals.push(n);
                mesh.uvs.push(uv);
            }
        }
        let vertices = keys.map(|k| id[k]);
        mesh.faces.push(Face {
            vertices,
            normal: face_normal(vertices.map(|i| mesh.positions[i as usize])),
            material: 0,
        });
    }
    mesh
}
