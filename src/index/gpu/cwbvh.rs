//! `gpu-cwbvh`: our binary BVH (`bvh`, same parameters) collapsed into the compressed 8-wide
//! nodes of Ylitie et al. (`cwbvh_layout`), with the triangles copied in the wide tree's order.

use super::cwbvh_layout::{NODE_WORDS, collapse};
use super::gpu_index::{GpuLayout, bytes_of, triangle_bytes};
use crate::geometry::Triangle;
use crate::index::{Bvh, Index, IndexInfo};

/// `gpu-cwbvh` ([`GpuLayout`] over [`Bvh`], collapsed).
pub struct CwBvh;

impl GpuLayout for CwBvh {
    type Base = Bvh;
    const SHADER: &'static str = include_str!("shaders/cwbvh.wgsl");
    /// The wide nodes (about 30 B), the triangle copy (36 B) and their staging copies.
    const UPLOAD_BYTES_PER_PRIM: usize = 160;

    /// The wide nodes (20 words each), the ids in the wide tree's triangle order and their
    /// triangles. The figures are the wide tree's; the binary tree's SAH cost is kept as
    /// `binary_sah_cost`.
    fn layout(bvh: &Bvh, tris: &[Triangle]) -> (IndexInfo, Vec<(&'static str, Vec<u8>)>) {
        let (root_bounds, root, nodes, ids) = bvh.parts();
        let wide = collapse(root_bounds, root, nodes);
        let order: Vec<u32> = wide.order.iter().map(|&k| ids[k as usize]).collect();
        let binary = bvh.info();
        let sah = binary.extra.iter().find(|e| e.0 == "sah_cost");
        let info = IndexInfo {
            nodes: wide.nodes.len() / NODE_WORDS,
            depth: wide.depth,
            leaves: binary.leaves,
            prim_refs: order.len(),
            extra: vec![("binary_sah_cost".into(), sah.map_or(f64::NAN, |e| e.1))],
            ..IndexInfo::default()
        };
        let buffers = vec![
            ("triangles", triangle_bytes(tris, order.iter().copied())),
            ("nodes", bytes_of(&wide.nodes)),
            ("ids", bytes_of(&order)),
        ];
        (info, buffers)
    }
}
