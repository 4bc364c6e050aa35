//! `gpu-bvh2`: our binary BVH (`bvh`, same parameters) uploaded as it is: its 64-byte nodes,
//! its leaf-order primitive ids, and the triangles copied in leaf order.

use super::gpu_index::{GpuLayout, bytes_of, triangle_bytes};
use crate::geometry::Triangle;
use crate::index::{Bvh, Index, IndexInfo};

/// `gpu-bvh2` ([`GpuLayout`] over [`Bvh`]).
pub struct Bvh2;

impl GpuLayout for Bvh2 {
    type Base = Bvh;
    const SHADER: &'static str = include_str!("shaders/bvh2.wgsl");
    /// The triangle copy (36 B), the node and id copies and their staging copies.
    const UPLOAD_BYTES_PER_PRIM: usize = 120;

    /// The header (root reference and box), the nodes as 16 words each (boxes, then the two
    /// children's index and count), the leaf-order ids and their triangles.
    fn layout(bvh: &Bvh, tris: &[Triangle]) -> (IndexInfo, Vec<(&'static str, Vec<u8>)>) {
        let (root_bounds, root, nodes, ids) = bvh.parts();
        let mut header = vec![root.index, root.count];
        header.extend(
            [root_bounds.min, root_bounds.max]
                .iter()
                .flat_map(|v| v.to_array().map(f32::to_bits)),
        );
        let node_words: Vec<u32> = nodes
            .iter()
            .flat_map(|n| {
                let lanes = [n.x, n.y, n.z].map(|v| v.to_array().map(f32::to_bits));
                let c = n.children;
                lanes
                    .into_iter()
                    .flatten()
                    .chain([c[0].index, c[0].count, c[1].index, c[1].count])
            })
            .collect();
        let buffers = vec![
            ("triangles", triangle_bytes(tris, ids.iter().copied())),
            ("header", bytes_of(&header)),
            ("nodes", bytes_of(&node_words)),
            ("ids", bytes_of(ids)),
        ];
        (bvh.info(), buffers)
    }
}
