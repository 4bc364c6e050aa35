//! `gpu-grid`: our uniform grid (`grid`, same parameters) uploaded as it is: its cells'
//! compressed rows of primitive ids, its boundary planes, and the triangles in scene order.

use super::gpu_index::{GpuLayout, bytes_of, triangle_bytes};
use crate::geometry::Triangle;
use crate::index::{Grid, Index, IndexInfo};

/// `gpu-grid` ([`GpuLayout`] over [`Grid`]).
pub struct GridCells;

impl GpuLayout for GridCells {
    type Base = Grid;
    const SHADER: &'static str = include_str!("shaders/grid.wgsl");
    /// The triangle copy (36 B), the reference copy and their staging copies.
    const UPLOAD_BYTES_PER_PRIM: usize = 160;

    /// The header (resolution, bounds, cells per unit), the cell offsets and references, the
    /// planes of x, y and z, and the triangles in scene order.
    fn layout(grid: &Grid, tris: &[Triangle]) -> (IndexInfo, Vec<(&'static str, Vec<u8>)>) {
        let (layout, cells) = (grid.layout(), grid.cells());
        let mut header: Vec<u32> = layout.res.to_vec();
        header.push(0);
        header.extend(
            [layout.bounds.min, layout.bounds.max, layout.inv_cell]
                .iter()
                .flat_map(|v| v.to_array().map(f32::to_bits)),
        );
        let planes: Vec<f32> = layout
            .planes
            .iter()
            .flat_map(|p| p.iter().copied())
            .collect();
        let buffers = vec![
            ("triangles", triangle_bytes(tris, 0..tris.len() as u32)),
            ("header", bytes_of(&header)),
            ("cell offsets", bytes_of(&cells.offsets)),
            ("cell references", bytes_of(&cells.prims)),
            ("planes", bytes_of(&planes)),
        ];
        (grid.info(), buffers)
    }
}
