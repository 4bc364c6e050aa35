//! What the triangle-only outside peers (Embree, tinybvh) share: their input, the scene's
//! triangles in id order, or the reason they skip a scene; their query, a library call per
//! query kind; and the figures of the library's build.

use crate::geometry::{Ray, Triangle};
use crate::index::{BuildError, HitQuery, Index, IndexInfo, NoStats};
use crate::scene::Geometry;

/// The answer to query `Q` of a peer that asks its library: its own [`Index::closest_hit`] or
/// [`Index::any_hit`] (which it overrides with the library's calls), without counters (the
/// libraries count nothing).
#[inline(always)]
pub(crate) fn library_query<Q: HitQuery, I: Index, G: Geometry>(
    index: &I,
    geom: &G,
    ray: &Ray,
) -> Q::Answer {
    Q::select(
        || index.closest_hit(geom, ray, &mut NoStats),
        || index.any_hit(geom, ray, &mut NoStats),
    )
}

/// The scene's triangles (primitive id = position), or [`BuildError::Unsupported`] when the
/// scene has other primitives (the peers test triangles only) and [`BuildError::Failed`] when
/// ids do not fit the peers' 32-bit primitive ids.
pub(crate) fn peer_triangles<'g, G: Geometry>(
    geom: &'g G,
    index: &str,
) -> Result<&'g [Triangle], BuildError> {
    let tris = geom
        .triangles_only()
        .ok_or_else(|| BuildError::Unsupported {
            index: index.to_owned(),
            reason: "the peer tests triangles only, and this scene has spheres or other shapes"
                .to_owned(),
        })?;
    if tris.is_empty() {
        return Err(BuildError::EmptyScene);
    }
    // Both peers take `u32` primitive ids and reserve `u32::MAX` (Embree: RTC_INVALID_GEOMETRY_ID).
    if tris.len() >= u32::MAX as usize / 3 {
        return Err(BuildError::Failed {
            index: index.to_owned(),
            message: format!(
                "{} triangles: the peer's 32-bit vertex indices hold at most {}",
                tris.len(),
                u32::MAX / 3 - 1
            ),
        });
    }
    Ok(tris)
}

/// What a triangle-only peer knows of its library's build, where our heap counter sees nothing
/// (the library allocates for itself).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LibraryFigures {
    /// Triangles handed to the library: one primitive reference each (no splits).
    pub triangles: usize,
    /// Bytes the library holds for the built structure, as it reports them.
    pub memory_bytes: usize,
    /// The most the build held: our copy of the input plus the library's allocations at their
    /// peak.
    pub peak_build_bytes: usize,
}

impl LibraryFigures {
    /// The peer's [`IndexInfo`] from these figures, `uncounted` (the library's walk reports
    /// nothing to our `Stats`); the peer adds what else it knows (nodes, `extra`).
    pub(crate) fn info(&self) -> IndexInfo {
        IndexInfo {
            memory_bytes: self.memory_bytes,
            peak_build_bytes: Some(self.peak_build_bytes),
            prim_refs: self.triangles,
            uncounted: true,
            ..IndexInfo::default()
        }
    }
}
