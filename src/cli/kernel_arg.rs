//! The `--kernel` option of the subcommands that trace: a triangle kernel by name.

use crate::geometry::TriangleKernelKind;

/// Parses a `--kernel` value: a triangle kernel name.
pub(crate) fn parse_kernel(s: &str) -> Result<TriangleKernelKind, String> {
    TriangleKernelKind::parse(s).ok_or_else(|| {
        let names: Vec<_> = TriangleKernelKind::ALL.iter().map(|k| k.name()).collect();
        format!("unknown kernel '{s}': choose one of {}", names.join(", "))
    })
}
