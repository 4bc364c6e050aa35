//! Run-time selection of indices by name (`bvh`, `grid:lambda=4`, ...) and the object-safe
//! [`TraceIndex`] that the harness, the CLI and reports use. The virtual call happens once per
//! batch of rays; inside, traversal is monomorphized for the index, the geometry and the stats.

use super::batch::trace_chunk;
use super::query::{AnyHit, Closest, Query};
use super::{
    BruteForce, Bsp, BuildError, Bvh, Counters, Index, IndexInfo, KdTree, NeighborOctree, NoStats,
    ObvhsBvh2, ObvhsCwBvh, TopDownOctree, TraceMode,
};
use crate::geometry::{Hit, Ray, TriangleKernelKind};
use crate::scene::{Geometry, GeometryVisitor, SceneGeometry, with_geometry};
use rayon::prelude::*;
use serde::Deserialize;
use std::fmt;
use std::str::FromStr;
use std::time::Instant;

/// Rays per parallel work item: large enough to amortize scheduling, small enough to balance.
const CHUNK: usize = 64;

type BuildFn =
    fn(&IndexSpec, &SceneGeometry, TriangleKernelKind) -> Result<Box<dyn TraceIndex>, BuildError>;

/// Whose triangle and box tests an index uses, which decides what a mismatch means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Ours: bound by the hit contract (brute force's hits, bit for bit); a mismatch is a bug.
    Ours,
    /// A peer (obvhs, ...) with its own triangle or box tests: its mismatches are reported, and
    /// callers decide whether they fail a run.
    Peer,
}

struct Entry {
    name: &'static str,
    build: BuildFn,
    kind: Kind,
}

const fn entry<I: Index>(name: &'static str, kind: Kind) -> Entry {
    Entry {
        name,
        build: build_dyn::<I>,
        kind,
    }
}

/// Every index the suite knows, in report order. Adding an index is one line here; it is then
/// in `run`, `verify`, `stress`, `render`, the agreement and property tests and the benches.
#[rustfmt::skip]
const REGISTRY: &[Entry] = &[
    entry::<BruteForce>("brute", Kind::Ours),
    entry::<Bvh>("bvh", Kind::Ours),
    entry::<super::Bvh4>("bvh4", Kind::Ours),
    entry::<super::Bvh8>("bvh8", Kind::Ours),
    entry::<super::Grid>("grid", Kind::Ours),
    entry::<super::Grid2>("grid2", Kind::Ours),
    entry::<NeighborOctree>("octree", Kind::Ours),
    entry::<TopDownOctree>("octree-topdown", Kind::Ours),
    entry::<KdTree>("kdtree", Kind::Ours),
    entry::<Bsp>("bsp", Kind::Ours),
    entry::<ObvhsBvh2>("obvhs-bvh2", Kind::Peer),
    entry::<ObvhsCwBvh>("obvhs-cwbvh", Kind::Peer),
    #[cfg(feature = "embree")]
    entry::<super::embree_peer::Embree>("embree", Kind::Peer),
    #[cfg(feature = "embree")]
    entry::<super::embree_peer::EmbreeFast>("embree-fast", Kind::Peer),
    #[cfg(feature = "embree")]
    entry::<super::embree_peer::EmbreeP16>("embree-p16", Kind::Peer),
    #[cfg(feature = "tinybvh")]
    entry::<super::tinybvh_peer::TinyBvh8>("tinybvh-bvh8", Kind::Peer),
];

/// Names of all registered indices, in report order.
pub fn index_names() -> Vec<&'static str> {
    REGISTRY.iter().map(|e| e.name).collect()
}

/// Whether `name` is a registered peer ([`Kind::Peer`]): its mismatches are reported, not
/// failed. The one place that answers this.
pub fn is_peer(name: &str) -> bool {
    REGISTRY
        .iter()
        .any(|e| e.name == name && e.kind == Kind::Peer)
}

/// Names of the registered peers, in report order.
pub fn peer_names() -> Vec<&'static str> {
    REGISTRY
        .iter()
        .filter(|e| e.kind == Kind::Peer)
        .map(|e| e.name)
        .collect()
}

/// An index name with optional parameters: `NAME` or `NAME:key=value,key=value`, values in TOML
/// syntax (`bvh:leaf_size=4,preset="sweep"`, `grid:res=[64,64,32]`).
#[derive(Debug, Clone, PartialEq)]
pub struct IndexSpec {
    pub name: String,
    pub params: toml::Table,
}

impl IndexSpec {
    /// The spec of `name` with default parameters.
    pub fn named(name: &str) -> IndexSpec {
        IndexSpec {
            name: name.to_owned(),
            params: toml::Table::new(),
        }
    }
}

impl fmt::Display for IndexSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name)?;
        for (i, (k, v)) in self.params.iter().enumerate() {
            write!(f, "{}{k}={v}", if i == 0 { ':' } else { ',' })?;
        }
        Ok(())
    }
}

impl FromStr for IndexSpec {
    type Err = BuildError;

    fn from_str(s: &str) -> Result<IndexSpec, BuildError> {
        let (name, rest) = s.split_once(':').unwrap_or((s, ""));
        let name = name.trim();
        if !REGISTRY.iter().any(|e| e.name == name) {
            return Err(unknown(name));
        }
        let bad = |message: String| BuildError::Params {
            index: name.to_owned(),
            message,
        };
        // Split on commas outside brackets and quotes, then parse as TOML `key = value` lines.
        let mut doc = String::new();
        let (mut depth, mut quoted, mut start) = (0i32, false, 0usize);
        let bytes = rest.as_bytes();
        for i in 0..=bytes.len() {
            let c = bytes.get(i).copied();
            match c {
                Some(b'"') => quoted = !quoted,
                Some(b'[') if !quoted => depth += 1,
                Some(b']') if !quoted => depth -= 1,
                Some(b',') | None if depth == 0 && !quoted => {
                    let item = rest[start..i].trim();
                    start = i + 1;
                    if item.is_empty() {
                        continue;
                    }
                    let (k, v) = item
                        .split_once('=')
                        .ok_or_else(|| bad(format!("'{item}' is not key=value")))?;
                    doc.push_str(&format!("{} = {}\n", k.trim(), v.trim()));
                }
                _ => {}
            }
        }
        let params: toml::Table = doc.parse().map_err(|e| bad(format!("{e}")))?;
        Ok(IndexSpec {
            name: name.to_owned(),
            params,
        })
    }
}

fn unknown(name: &str) -> BuildError {
    BuildError::UnknownIndex(name.to_owned(), index_names().join(", "))
}

/// Builds the index `spec` over a scene's primitives with the given triangle kernel.
pub fn build_index(
    spec: &IndexSpec,
    geom: &SceneGeometry,
    kernel: TriangleKernelKind,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    let entry = REGISTRY
        .iter()
        .find(|e| e.name == spec.name)
        .ok_or_else(|| unknown(&spec.name))?;
    if geom.is_empty() {
        return Err(BuildError::EmptyScene);
    }
    (entry.build)(spec, geom, kernel)
}

/// Parses the typed parameters of `I` from a spec (unknown keys rejected).
pub fn parse_params<I: Index>(spec: &IndexSpec) -> Result<I::Params, BuildError> {
    I::Params::deserialize(toml::Value::Table(spec.params.clone())).map_err(|e| {
        BuildError::Params {
            index: spec.name.clone(),
            message: e.to_string(),
        }
    })
}

fn build_dyn<I: Index>(
    spec: &IndexSpec,
    geom: &SceneGeometry,
    kernel: TriangleKernelKind,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    struct Visit<'a, I: Index> {
        name: &'a str,
        params: I::Params,
    }
    impl<I: Index> GeometryVisitor for Visit<'_, I> {
        type Output = Result<Box<dyn TraceIndex>, BuildError>;
        fn visit<G: Geometry>(self, geom: G) -> Self::Output {
            Ok(Box::new(build_index_on::<I, G>(
                self.name,
                geom,
                self.params,
            )?))
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

/// Builds index `I` over a concrete geometry (for tests and benches that want static types).
pub fn build_index_on<I: Index, G: Geometry>(
    name: &str,
    geom: G,
    params: I::Params,
) -> Result<BoundIndex<I, G>, BuildError> {
    if geom.is_empty() {
        return Err(BuildError::EmptyScene);
    }
    let start = Instant::now();
    let index = I::build(&geom, &params)?;
    let build_time = start.elapsed();
    let mut info = index.info();
    info.build_time = build_time;
    Ok(BoundIndex {
        params: toml::to_string(&params)
            .unwrap_or_default()
            .trim()
            .replace('\n', ","),
        name: name.to_owned(),
        index,
        geom,
        info,
    })
}

/// A built index with the geometry it was built on.
pub struct BoundIndex<I: Index, G: Geometry> {
    pub index: I,
    pub geom: G,
    name: String,
    params: String,
    info: IndexInfo,
}

/// The object-safe face of a built index. Batch methods run in parallel on the current rayon
/// pool (`ThreadPool::install` picks the thread count); single-ray methods are for callers that
/// do per-ray work around the query (rendering).
pub trait TraceIndex: Send + Sync {
    /// Registry name (`bvh`, `grid`, ...).
    fn name(&self) -> &str;
    /// The parameters it was built with, as `key=value` pairs.
    fn params(&self) -> &str;
    fn info(&self) -> &IndexInfo;
    /// Whether the index has a batch technique of its own ([`Index::STREAM`]).
    fn has_stream(&self) -> bool;
    /// Whether its one-query-at-a-time rows are its own ([`Index::SINGLE`]).
    fn has_single(&self) -> bool;
    /// Whether the suite traces it in `mode`: `stream` only with a batch technique of its own,
    /// the one-at-a-time modes only when they are its own.
    fn traces_in(&self, mode: TraceMode) -> bool {
        match mode {
            TraceMode::Stream => self.has_stream(),
            TraceMode::Single | TraceMode::LastHit => self.has_single(),
            TraceMode::Packets(_) => true,
        }
    }
    fn closest_hit(&self, ray: &Ray) -> Option<Hit>;
    fn closest_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> Option<Hit>;
    fn any_hit(&self, ray: &Ray) -> bool;
    fn any_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> bool;
    /// Closest hits of a batch (`out.len() == rays.len()`) traced in `mode`, with per-ray
    /// counters (reset first) when `counters` is given.
    fn closest_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    );
    /// Any-hit results of a batch traced in `mode`, as [`TraceIndex::closest_hits_in`].
    fn any_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    );
    /// Closest hits of a batch (`out.len() == rays.len()`), no counting.
    fn closest_hits(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        self.closest_hits_in(TraceMode::Single, rays, out, None);
    }
    /// Any-hit results of a batch, no counting.
    fn any_hits(&self, rays: &[Ray], out: &mut [bool]) {
        self.any_hits_in(TraceMode::Single, rays, out, None);
    }
    /// Closest hits with per-ray counters.
    fn closest_hits_counted(&self, rays: &[Ray], out: &mut [Option<Hit>], c: &mut [Counters]) {
        self.closest_hits_in(TraceMode::Single, rays, out, Some(c));
    }
    /// Any-hit results with per-ray counters.
    fn any_hits_counted(&self, rays: &[Ray], out: &mut [bool], c: &mut [Counters]) {
        self.any_hits_in(TraceMode::Single, rays, out, Some(c));
    }
}

impl<I: Index, G: Geometry> BoundIndex<I, G> {
    /// Answers query `Q` for a batch traced in `mode`, in parallel chunks of [`CHUNK`] rays,
    /// with per-ray counters (reset first) when `counters` is given.
    fn hits_in<Q: Query>(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [Q::Answer],
        counters: Option<&mut [Counters]>,
    ) {
        assert_eq!(rays.len(), out.len(), "one output per ray");
        let chunk = |(rays, out): (&[Ray], &mut [Q::Answer]), c: Option<&mut [Counters]>| {
            let (index, geom) = (&self.index, &self.geom);
            match c {
                Some(c) => {
                    c.fill(Counters::default());
                    trace_chunk::<Q, _, _, _>(index, geom, mode, rays, out, c)
                }
                None => {
                    let none = &mut [NoStats; CHUNK][..rays.len()];
                    trace_chunk::<Q, _, _, _>(index, geom, mode, rays, out, none)
                }
            }
        };
        let work = rays.par_chunks(CHUNK).zip(out.par_chunks_mut(CHUNK));
        match counters {
            Some(c) => {
                assert_eq!(rays.len(), c.len(), "one counter per ray");
                work.zip(c.par_chunks_mut(CHUNK))
                    .for_each(|(w, c)| chunk(w, Some(c)));
            }
            None => work.for_each(|w| chunk(w, None)),
        }
    }
}

impl<I: Index, G: Geometry> TraceIndex for BoundIndex<I, G> {
    fn name(&self) -> &str {
        &self.name
    }
    fn params(&self) -> &str {
        &self.params
    }
    fn info(&self) -> &IndexInfo {
        &self.info
    }
    fn has_stream(&self) -> bool {
        I::STREAM
    }
    fn has_single(&self) -> bool {
        I::SINGLE
    }
    fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        self.index.closest_hit(&self.geom, ray, &mut NoStats)
    }
    fn closest_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> Option<Hit> {
        self.index.closest_hit(&self.geom, ray, counters)
    }
    fn any_hit(&self, ray: &Ray) -> bool {
        self.index.any_hit(&self.geom, ray, &mut NoStats)
    }
    fn any_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> bool {
        self.index.any_hit(&self.geom, ray, counters)
    }
    fn closest_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    ) {
        self.hits_in::<Closest>(mode, rays, out, counters);
    }
    fn any_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    ) {
        self.hits_in::<AnyHit>(mode, rays, out, counters);
    }
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
}
