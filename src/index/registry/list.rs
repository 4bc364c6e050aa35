//! The list of every index the suite knows ([`REGISTRY`], in report order) and whose tests each
//! uses ([`Kind`]), the lookups by name, and building an index from its spec ([`build_index`]).

use super::build::{BuildFn, EstimateFn, build_dyn, estimate_dyn, parse_typed};
use super::spec::{IndexSpec, parse_params_list};
use crate::geometry::TriangleKernelKind;
use crate::index::peers::{ObvhsBvh2, ObvhsCwBvh};
use crate::index::tlas::TlasParams;
use crate::index::{
    BatchIndex, BruteForce, Bsp, BuildError, Bvh, Bvh4, Bvh8, Grid, Grid2, KdTree, NeighborOctree,
    TopDownOctree, TraceIndex,
};
use crate::scene::SceneGeometry;
use std::str::FromStr;

/// Whose triangle and box tests an index uses, which decides what a mismatch means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Ours: bound by the hit contract (brute force's hits, bit for bit); a mismatch is a bug.
    Ours,
    /// A peer (obvhs, ...) with its own triangle or box tests: its mismatches are reported, and
    /// callers decide whether they fail a run.
    Peer,
    /// A GPU shader over one of our structures (`index::gpu`): its own `f32` triangle test, so
    /// it is checked like a peer (classified, never failed).
    Gpu,
    /// Ours over an instanced scene (`tlas`): bound by the hit contract of instancing (brute
    /// force over the instances, rays moved into object space; [`crate::index::tlas`]), which
    /// rounds differently from the flattened world-space triangles every other index traces,
    /// so a run classifies it against them as it does peers. Built only when asked for
    /// (not in [`index_names`]).
    Instanced,
}

struct Entry {
    name: &'static str,
    build: BuildFn,
    estimate: EstimateFn,
    kind: Kind,
}

const fn entry<I: BatchIndex>(name: &'static str, kind: Kind) -> Entry {
    Entry {
        name,
        build: build_dyn::<I>,
        estimate: estimate_dyn::<I>,
        kind,
    }
}

/// The entry of GPU index `L` (feature `gpu`): its parameters are its base's.
#[cfg(feature = "gpu")]
const fn gpu_entry<L: crate::index::gpu::GpuLayout>(name: &'static str) -> Entry {
    Entry {
        name,
        build: super::build::build_gpu::<L>,
        estimate: super::build::estimate_gpu::<L>,
        kind: Kind::Gpu,
    }
}

/// Every index the suite knows, in report order. Adding an index is one line here; it is then
/// in `run`, `verify`, `stress`, `render`, the agreement and property tests and the benches.
#[rustfmt::skip]
const REGISTRY: &[Entry] = &[
    entry::<BruteForce>("brute", Kind::Ours),
    entry::<Bvh>("bvh", Kind::Ours),
    entry::<Bvh4>("bvh4", Kind::Ours),
    entry::<Bvh8>("bvh8", Kind::Ours),
    entry::<Grid>("grid", Kind::Ours),
    entry::<Grid2>("grid2", Kind::Ours),
    entry::<NeighborOctree>("octree", Kind::Ours),
    entry::<TopDownOctree>("octree-topdown", Kind::Ours),
    entry::<KdTree>("kdtree", Kind::Ours),
    entry::<Bsp>("bsp", Kind::Ours),
    entry::<ObvhsBvh2>("obvhs-bvh2", Kind::Peer),
    entry::<ObvhsCwBvh>("obvhs-cwbvh", Kind::Peer),
    #[cfg(feature = "embree")]
    entry::<crate::index::peers::embree::Embree>("embree", Kind::Peer),
    #[cfg(feature = "embree")]
    entry::<crate::index::peers::embree::EmbreeFast>("embree-fast", Kind::Peer),
    #[cfg(feature = "embree")]
    entry::<crate::index::peers::embree::EmbreeP16>("embree-p16", Kind::Peer),
    #[cfg(feature = "tinybvh")]
    entry::<crate::index::peers::tinybvh::TinyBvh8>("tinybvh-bvh8", Kind::Peer),
    #[cfg(feature = "gpu")]
    gpu_entry::<crate::index::gpu::CwBvh>("gpu-cwbvh"),
    #[cfg(feature = "gpu")]
    gpu_entry::<crate::index::gpu::Bvh2>("gpu-bvh2"),
    #[cfg(feature = "gpu")]
    gpu_entry::<crate::index::gpu::GridCells>("gpu-grid"),
    Entry {
        name: "tlas",
        build: build_tlas,
        estimate: estimate_tlas,
        kind: Kind::Instanced,
    },
];

/// `tlas`'s parameters and the spec of its `inner` index, which must be one of ours.
fn tlas_params(spec: &IndexSpec) -> Result<(TlasParams, IndexSpec), BuildError> {
    let params: TlasParams = parse_typed(spec)?;
    let bad = |message: String| BuildError::Params {
        index: spec.name.clone(),
        message,
    };
    let inner: IndexSpec = (params.inner.parse()).map_err(|e| bad(format!("inner: {e}")))?;
    if kind_of(&inner.name) != Some(Kind::Ours) {
        let ours: Vec<&str> = (REGISTRY.iter().filter(|e| e.kind == Kind::Ours))
            .map(|e| e.name)
            .collect();
        return Err(bad(format!(
            "inner = \"{}\" is not one of our indices: give one of {}",
            inner.name,
            ours.join(", ")
        )));
    }
    params.check_top(&spec.name)?;
    Ok((params, inner))
}

/// Builds `tlas` ([`crate::index::tlas`]), each mesh's structure by `inner` through
/// [`build_index`] with the run's kernel.
fn build_tlas(
    spec: &IndexSpec,
    geom: &SceneGeometry,
    kernel: TriangleKernelKind,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    let (params, inner) = tlas_params(spec)?;
    let build_mesh = |mesh: &SceneGeometry| build_index(&inner, mesh, kernel);
    crate::index::tlas::build(&spec.name, &params, geom, &build_mesh)
}

/// `tlas` has no estimate of its own ([`crate::index::tlas::build`] says why); its parameters
/// are still checked.
fn estimate_tlas(spec: &IndexSpec, _prims: usize) -> Result<Option<usize>, BuildError> {
    tlas_params(spec).map(|_| None)
}

/// Names of the indices a run builds when none are named, in report order: every registered
/// one but `tlas` ([`Kind::Instanced`]), which traces only scenes with instances and is built
/// when asked for.
pub fn index_names() -> Vec<&'static str> {
    (REGISTRY.iter())
        .filter(|e| e.kind != Kind::Instanced)
        .map(|e| e.name)
        .collect()
}

/// Whether `name` is a registered peer, GPU or instanced index ([`Kind::Peer`], [`Kind::Gpu`],
/// [`Kind::Instanced`]): its mismatches with brute force on the flattened scene are classified
/// and reported, not failed. The one place that answers this.
pub fn is_peer(name: &str) -> bool {
    REGISTRY
        .iter()
        .any(|e| e.name == name && e.kind != Kind::Ours)
}

/// The kind of registered index `name`, `None` for an unknown name.
pub fn kind_of(name: &str) -> Option<Kind> {
    REGISTRY.iter().find(|e| e.name == name).map(|e| e.kind)
}

/// Names of the registered peers and GPU indices, in report order.
pub fn peer_names() -> Vec<&'static str> {
    REGISTRY
        .iter()
        .filter(|e| matches!(e.kind, Kind::Peer | Kind::Gpu))
        .map(|e| e.name)
        .collect()
}

impl FromStr for IndexSpec {
    type Err = BuildError;

    fn from_str(s: &str) -> Result<IndexSpec, BuildError> {
        let (name, rest) = s.split_once(':').unwrap_or((s, ""));
        let name = name.trim();
        if !REGISTRY.iter().any(|e| e.name == name) {
            return Err(unknown(name));
        }
        Ok(IndexSpec {
            name: name.to_owned(),
            params: parse_params_list(name, rest)?,
        })
    }
}

fn unknown(name: &str) -> BuildError {
    let all: Vec<&str> = REGISTRY.iter().map(|e| e.name).collect();
    BuildError::UnknownIndex(name.to_owned(), all.join(", "))
}

fn find_entry(name: &str) -> Result<&'static Entry, BuildError> {
    REGISTRY
        .iter()
        .find(|e| e.name == name)
        .ok_or_else(|| unknown(name))
}

/// The estimate of the build's peak heap of index `spec` over `prims` primitives
/// ([`crate::index::Index::estimated_build_bytes`]), `None` where it has none.
pub fn estimated_build_bytes(spec: &IndexSpec, prims: usize) -> Result<Option<usize>, BuildError> {
    (find_entry(&spec.name)?.estimate)(spec, prims)
}

/// Builds the index `spec` over a scene's primitives with the given triangle kernel.
pub fn build_index(
    spec: &IndexSpec,
    geom: &SceneGeometry,
    kernel: TriangleKernelKind,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    let entry = find_entry(&spec.name)?;
    if geom.is_empty() {
        return Err(BuildError::EmptyScene);
    }
    (entry.build)(spec, geom, kernel)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spec_parsing() {
        let s: IndexSpec = "brute".parse().unwrap();
        assert_eq!(s, IndexSpec::named("brute"));
        assert!(matches!(
            "nope".parse::<IndexSpec>(),
            Err(BuildError::UnknownIndex(..))
        ));
        let s: IndexSpec = "brute:a=1,b=[1,2,3],c=\"x,y\"".parse().unwrap();
        assert_eq!(s.params.len(), 3);
        assert_eq!(s.to_string(), "brute:a=1,b=[1, 2, 3],c=\"x,y\"");
        assert!(matches!(
            "brute:oops".parse::<IndexSpec>(),
            Err(BuildError::Params { .. })
        ));
        // Unknown keys are rejected by the typed parameters.
        let g = SceneGeometry {
            triangles: std::sync::Arc::from(crate::scene::generators::icosphere(0)),
            ..Default::default()
        };
        let err = build_index(&s, &g, TriangleKernelKind::Watertight)
            .err()
            .unwrap();
        assert!(err.to_string().contains("unknown field"), "{err}");
    }

    /// The box trees' `layout` reaches the build; an unknown value is a parameter error that
    /// names the index and the accepted values, as an unknown preset is.
    #[test]
    fn layout_specs_build_or_name_the_choices() {
        let g = SceneGeometry {
            triangles: std::sync::Arc::from(crate::scene::generators::icosphere(2)),
            ..Default::default()
        };
        for name in ["bvh", "bvh4", "bvh8"] {
            let spec: IndexSpec = format!("{name}:layout=\"veb\"").parse().unwrap();
            let index = build_index(&spec, &g, TriangleKernelKind::Watertight).unwrap();
            assert!(
                index.params().contains("layout = \"veb\""),
                "{}",
                index.params()
            );
            let plain = build_index(&IndexSpec::named(name), &g, TriangleKernelKind::Watertight);
            assert!(
                !plain.unwrap().params().contains("layout"),
                "the default is left out"
            );
            let bad: IndexSpec = format!("{name}:layout=\"zorder\"").parse().unwrap();
            let err = build_index(&bad, &g, TriangleKernelKind::Watertight)
                .err()
                .unwrap();
            assert!(matches!(err, BuildError::Params { .. }), "{err}");
            let text = err.to_string();
            assert!(
                text.contains(name) && text.contains("zorder") && text.contains("`veb`"),
                "{text}"
            );
        }
    }
}
