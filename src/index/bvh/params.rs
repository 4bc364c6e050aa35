//! Build parameters of the BVH: a named preset (fastest build to best quality) and optional
//! overrides, checked into a [`BuildConfig`] before building.

use crate::index::BuildError;
use crate::index::build_budget::per_primitive;
pub use crate::index::kit::box_tree::layout::Layout;

/// Peak build heap per reference spatial splits may add, in bytes, for the estimate (`bvh` with
/// the default budget of 4 peaked at 351 B per primitive on the soup and 536 on slivers, where
/// the plain tree holds about 200).
pub const SPLIT_REF_BYTES: usize = 110;
use serde::{Deserialize, Serialize};
use std::fmt::Display;
use std::ops::RangeInclusive;

/// Smallest and largest number of SAH bins accepted.
pub const BINS: RangeInclusive<u32> = 2..=64;
/// Largest leaf size accepted (primitives per leaf).
pub const MAX_LEAF_SIZE: u32 = 64;
/// Accepted references per primitive with spatial splits (`split_budget`).
pub const SPLIT_BUDGET: RangeInclusive<f32> = 1.0..=64.0;
/// Largest traversal/intersection cost ratio accepted.
pub const MAX_COST_RATIO: f32 = 1000.0;

/// How a node's primitives are split.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SplitMethod {
    /// Binned SAH: centroids binned into `bins` buckets per axis, `bins - 1` candidate planes
    /// (nodes of `n < bins` primitives use `n` bins).
    Binned,
    /// Full sweep SAH: every split between centroid-sorted primitives on every axis.
    Sweep,
}

/// Presets from fastest build to best tree quality.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// Binned SAH, 8 bins, leaves up to 8 primitives.
    Fastest,
    /// Binned SAH, 12 bins, leaves up to 4 primitives.
    Fast,
    /// Binned SAH, 16 bins, leaves up to 4 primitives (the suite's default).
    #[default]
    Medium,
    /// Binned SAH, 32 bins, leaves up to 4 primitives.
    High,
    /// Full sweep SAH, leaves up to 4 primitives (slowest build, best SAH).
    Sweep,
}

impl Preset {
    /// Every preset, fastest build first.
    pub const ALL: [Preset; 5] = [
        Preset::Fastest,
        Preset::Fast,
        Preset::Medium,
        Preset::High,
        Preset::Sweep,
    ];

    /// Name as written in parameters (`bvh:preset="sweep"`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::Fastest => "fastest",
            Preset::Fast => "fast",
            Preset::Medium => "medium",
            Preset::High => "high",
            Preset::Sweep => "sweep",
        }
    }

    fn config(self) -> BuildConfig {
        let binned = |bins, leaf_size| BuildConfig {
            split: SplitMethod::Binned,
            bins,
            leaf_size,
            cost_ratio: 1.0,
            spatial_splits: false,
            split_budget: 4.0,
            sah_block: 1,
        };
        match self {
            Preset::Fastest => binned(8, 8),
            Preset::Fast => binned(12, 4),
            Preset::Medium => binned(16, 4),
            Preset::High => binned(32, 4),
            Preset::Sweep => BuildConfig {
                split: SplitMethod::Sweep,
                ..binned(32, 4)
            },
        }
    }
}

/// Parameters of `bvh` (`bvh:preset="sweep",leaf_size=2`): a preset, and overrides of its
/// fields. Unknown keys are rejected.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BvhParams {
    pub preset: Preset,
    /// Split method (overrides the preset's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub split: Option<SplitMethod>,
    /// SAH bins per axis for the binned split, in [`BINS`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bins: Option<u32>,
    /// Most primitives in a leaf, `1..=`[`MAX_LEAF_SIZE`]. Nodes with more are always split
    /// (unless the depth limit is reached); nodes with at most this many become leaves when the
    /// SAH says a split does not pay.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub leaf_size: Option<u32>,
    /// Cost of one node traversal relative to one primitive test, in `(0, `[`MAX_COST_RATIO`]`]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cost_ratio: Option<f32>,
    /// Spatial splits (SBVH, Stich et al. 2009): nodes whose object split leaves overlapping
    /// children may instead cut their primitives at a plane, so a primitive can be referenced
    /// by several leaves (see `spatial`). Off by default.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub spatial_splits: bool,
    /// With spatial splits, most references per primitive in the tree (memory bound), in
    /// [`SPLIT_BUDGET`]; default 4 (the `slivers` scene needs 4 for `bvh8` to beat the grid).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub split_budget: Option<f32>,
    /// Where the inner nodes sit in memory, applied after the build ([`Layout`]): `dfs` (the
    /// builder's depth-first order, default), `veb` (van Emde Boas by height) or `treelet`
    /// (page-sized treelets by surface area). The tree, its hits and its counters are the same.
    #[serde(skip_serializing_if = "Layout::is_default")]
    pub layout: Layout,
}

/// Checked build settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BuildConfig {
    pub split: SplitMethod,
    pub bins: u32,
    pub leaf_size: u32,
    pub cost_ratio: f32,
    pub spatial_splits: bool,
    pub split_budget: f32,
    /// Primitives one leaf test covers: the SAH counts each side's (and each leaf's)
    /// primitives rounded up to a multiple of it, as Embree's builders count blocks of four
    /// triangles, so splits favour leaves that fill whole blocks. 1 (plain counts) except for
    /// the wide BVH's triangle-block leaves ([`crate::index::kit::box_tree::leaves::BLOCK_LANES`]); not
    /// a user parameter.
    pub sah_block: u32,
}

impl BvhParams {
    /// The preset's parameters.
    pub fn preset(preset: Preset) -> BvhParams {
        BvhParams {
            preset,
            ..BvhParams::default()
        }
    }

    /// The estimate of a box tree's build peak ([`crate::index::Index::estimated_build_bytes`])
    /// over `prims` primitives: `plain` bytes per primitive (the tree without spatial splits)
    /// and, with spatial splits, [`SPLIT_REF_BYTES`] for each reference the budget allows per
    /// primitive. `None` for parameters the build refuses.
    pub fn estimated_build_bytes(&self, prims: usize, plain: usize) -> Option<usize> {
        let c = self.config().ok()?;
        let splits = if c.spatial_splits {
            (SPLIT_REF_BYTES as f32 * c.split_budget) as usize
        } else {
            0
        };
        per_primitive(prims, plain + splits)
    }

    /// The preset with the overrides applied, or an error saying which value is out of range.
    pub fn config(&self) -> Result<BuildConfig, BuildError> {
        let mut c = self.preset.config();
        if let Some(split) = self.split {
            c.split = split;
        }
        c.spatial_splits = self.spatial_splits;
        if let Some(b) = self.split_budget {
            c.split_budget = in_range(
                "split_budget",
                b,
                &SPLIT_BUDGET,
                " references per primitive",
            )?;
        }
        if let Some(bins) = self.bins {
            c.bins = in_range("bins", bins, &BINS, "")?;
        }
        if let Some(leaf) = self.leaf_size {
            c.leaf_size = in_range("leaf_size", leaf, &(1..=MAX_LEAF_SIZE), "")?;
        }
        if let Some(r) = self.cost_ratio {
            if !(r > 0.0 && r <= MAX_COST_RATIO) {
                let accepted = format!("a number > 0 and <= {MAX_COST_RATIO}");
                return Err(out_of_range("cost_ratio", r, accepted));
            }
            c.cost_ratio = r;
        }
        Ok(c)
    }
}

/// `value` of parameter `name` if `range` holds it, else the error saying to use `range`
/// (`"1 to 64"`, followed by `unit`).
fn in_range<T: PartialOrd + Display>(
    name: &str,
    value: T,
    range: &RangeInclusive<T>,
    unit: &str,
) -> Result<T, BuildError> {
    if !range.contains(&value) {
        let accepted = format!("{} to {}{unit}", range.start(), range.end());
        return Err(out_of_range(name, value, accepted));
    }
    Ok(value)
}

/// The error for `value` of parameter `name`, saying what to use instead (`accepted`).
fn out_of_range(name: &str, value: impl Display, accepted: String) -> BuildError {
    BuildError::Params {
        index: "bvh".into(),
        message: format!("{name} = {value} is out of range: use {accepted}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_apply_and_absurd_values_are_errors() {
        let p = BvhParams {
            preset: Preset::Sweep,
            leaf_size: Some(2),
            ..BvhParams::default()
        };
        let c = p.config().unwrap();
        assert_eq!((c.split, c.leaf_size), (SplitMethod::Sweep, 2));
        for bad in [
            BvhParams {
                bins: Some(1),
                ..BvhParams::default()
            },
            BvhParams {
                bins: Some(10_000),
                ..BvhParams::default()
            },
            BvhParams {
                leaf_size: Some(0),
                ..BvhParams::default()
            },
            BvhParams {
                cost_ratio: Some(f32::NAN),
                ..BvhParams::default()
            },
            BvhParams {
                cost_ratio: Some(-1.0),
                ..BvhParams::default()
            },
            BvhParams {
                split_budget: Some(0.5),
                ..BvhParams::default()
            },
        ] {
            let e = bad.config().unwrap_err().to_string();
            assert!(e.contains("out of range"), "{e}");
        }
    }

    #[test]
    fn layouts_parse_by_name_and_the_default_is_left_out() {
        for l in Layout::ALL {
            let p: BvhParams = toml::from_str(&format!("layout = \"{}\"", l.name())).unwrap();
            assert_eq!(p.layout, l);
            let shown = toml::to_string(&p).unwrap();
            assert_eq!(shown.contains("layout"), l != Layout::Dfs, "{shown}");
        }
        let e = toml::from_str::<BvhParams>("layout = \"zorder\"").unwrap_err();
        let e = e.to_string();
        assert!(
            e.contains("zorder") && e.contains("`dfs`, `veb`, `treelet`"),
            "{e}"
        );
    }

    #[test]
    fn every_preset_is_valid() {
        for p in Preset::ALL {
            let c = BvhParams::preset(p).config().unwrap();
            assert!(BINS.contains(&c.bins) && c.leaf_size >= 1, "{}", p.name());
        }
    }
}
