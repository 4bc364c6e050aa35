//! Building one registered index: its typed parameters from a spec ([`parse_params`]) and the
//! geometry visitor that picks the concrete [`Geometry`] for the scene ([`build_dyn`]).

use super::spec::IndexSpec;
use crate::geometry::TriangleKernelKind;
use crate::index::{BatchIndex, BuildError, Index, TraceIndex, build_index_on};
use crate::scene::{FromScene, GeometryVisitor, SceneGeometry, with_geometry};

/// How the registry builds one of its indices.
pub(super) type BuildFn =
    fn(&IndexSpec, &SceneGeometry, TriangleKernelKind) -> Result<Box<dyn TraceIndex>, BuildError>;

/// How the registry estimates one of its indices' build peak ([`estimate_dyn`]).
pub(super) type EstimateFn = fn(&IndexSpec, usize) -> Result<Option<usize>, BuildError>;

/// [`Index::estimated_build_bytes`] of `I` with the parameters of `spec`, over `prims`
/// primitives.
pub(super) fn estimate_dyn<I: Index>(
    spec: &IndexSpec,
    prims: usize,
) -> Result<Option<usize>, BuildError> {
    Ok(I::estimated_build_bytes(prims, &parse_params::<I>(spec)?))
}

/// Parses the typed parameters of `I` from a spec (unknown keys rejected).
pub fn parse_params<I: Index>(spec: &IndexSpec) -> Result<I::Params, BuildError> {
    parse_typed::<I::Params>(spec)
}

/// Parses a spec's parameters as `P` (unknown keys rejected by `P`).
pub(super) fn parse_typed<P: serde::de::DeserializeOwned>(
    spec: &IndexSpec,
) -> Result<P, BuildError> {
    P::deserialize(toml::Value::Table(spec.params.clone())).map_err(|e| BuildError::Params {
        index: spec.name.clone(),
        message: e.to_string(),
    })
}

/// Builds index `I` from `spec` over the scene's primitives with the given kernel.
pub(super) fn build_dyn<I: BatchIndex>(
    spec: &IndexSpec,
    geom: &SceneGeometry,
    kernel: TriangleKernelKind,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    struct Visit<'a, I: BatchIndex> {
        name: &'a str,
        params: I::Params,
    }
    impl<I: BatchIndex> GeometryVisitor for Visit<'_, I> {
        type Output = Result<Box<dyn TraceIndex>, BuildError>;
        fn visit<G: FromScene>(self, geom: G) -> Self::Output {
            let bound = build_index_on::<I, G>(self.name, geom, self.params)?;
            Ok(Box::new(bound.movable()))
        }
    }
    let params = parse_params::<I>(spec)?;
    with_geometry(
        geom,
        kernel,
        Visit::<I> {
            name: &spec.name,
            params,
        },
    )
}

/// Builds GPU index `L` of `spec` (feature `gpu`): its base's parameters, then
/// [`crate::index::gpu::build`]. The kernel is the shaders' own.
#[cfg(feature = "gpu")]
pub(super) fn build_gpu<L: crate::index::gpu::GpuLayout>(
    spec: &IndexSpec,
    geom: &SceneGeometry,
    _kernel: TriangleKernelKind,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    let params = parse_params::<L::Base>(spec)?;
    crate::index::gpu::build::<L>(&spec.name, &params, geom)
}

/// [`crate::index::gpu::estimate`] of GPU index `L` with the parameters of `spec`.
#[cfg(feature = "gpu")]
pub(super) fn estimate_gpu<L: crate::index::gpu::GpuLayout>(
    spec: &IndexSpec,
    prims: usize,
) -> Result<Option<usize>, BuildError> {
    Ok(crate::index::gpu::estimate::<L>(
        &parse_params::<L::Base>(spec)?,
        prims,
    ))
}
