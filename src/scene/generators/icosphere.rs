//! Subdivided icosahedron: a closed, welded, consistently wound unit sphere mesh with
//! `20 * 4^level` triangles.

use crate::geometry::Triangle;
use glam::Vec3A;
use std::collections::HashMap;

/// Vertices and faces (indices into the vertex list) of a unit icosphere after `level`
/// subdivisions. Shared edges reuse the same vertex values, so the mesh is watertight.
pub fn icosphere_mesh(level: u32) -> (Vec<Vec3A>, Vec<[u32; 3]>) {
    let p = (1.0 + 5.0f32.sqrt()) / 2.0;
    let mut verts: Vec<Vec3A> = [
        [-1.0, p, 0.0],
        [1.0, p, 0.0],
        [-1.0, -p, 0.0],
        [1.0, -p, 0.0],
        [0.0, -1.0, p],
        [0.0, 1.0, p],
        [0.0, -1.0, -p],
        [0.0, 1.0, -p],
        [p, 0.0, -1.0],
        [p, 0.0, 1.0],
        [-p, 0.0, -1.0],
        [-p, 0.0, 1.0],
    ]
    .iter()
    .map(|v| Vec3A::from(*v).normalize())
    .collect();
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut midpoint = |a: u32, b: u32, verts: &mut Vec<Vec3A>| -> u32 {
            let key = (a.min(b), a.max(b));
            *mid.entry(key).or_insert_with(|| {
                verts.push(((verts[a as usize] + verts[b as usize]) * 0.5).normalize());
                verts.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(faces.len() * 4);
        for [a, b, c] in faces {
            let ab = midpoint(a, b, &mut verts);
            let bc = midpoint(b, c, &mut verts);
            let ca = midpoint(c, a, &mut verts);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    (verts, faces)
}

/// The triangles of [`icosphere_mesh`].
pub fn icosphere(level: u32) -> Vec<Triangle> {
    let (v, f) = icosphere_mesh(level);
    f.iter()
        .map(|&[a, b, c]| Triangle::new(v[a as usize], v[b as usize], v[c as usize]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_closed() {
        let (v, f) = icosphere_mesh(2);
        assert_eq!(f.len(), 20 * 16);
        assert_eq!(v.len(), 10 * 16 + 2); // Euler: V = 10*4^n + 2
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for [a, b, c] in f {
            for (x, y) in [(a, b), (b, c), (c, a)] {
                *edges.entry((x.min(y), x.max(y))).or_default() += 1;
            }
        }
        assert!(edges.values().all(|&n| n == 2), "every edge has two faces");
    }
}
