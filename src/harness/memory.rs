//! Memory checks before a run allocates: an estimate of the bytes the suite holds at once for
//! its ray sets ([`suite_need`]) and for a ray file ([`rays_need`]), the memory the machine has
//! (`MemAvailable` of `/proc/meminfo`), and the budget a run is held to ([`Budget`]), so a size
//! that cannot fit is refused with one message before anything is allocated.
//!
//! The estimates are upper bounds of what the suite keeps alive together, in bytes; they leave
//! out the scene and the indices (already built or without an estimate before their build).

use super::suite::SuiteConfig;
use super::workload::RaySet;
use crate::geometry::{Hit, Ray};
use crate::index::trace::reorder;
use crate::index::{Counters, TraceMode};
use crate::scene::Scene;
use std::mem::size_of;

pub use crate::heap_meter::human;

/// What a command is about to allocate: `bytes` for `what`, lowered by the option `lower`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Need {
    pub bytes: u64,
    /// E.g. "the primary rays of scene soup (16,777,216 rays)".
    pub what: String,
    /// The option that lowers it, with its value, e.g. "--primary-size (4096)".
    pub lower: String,
}

/// The memory a command may use, in bytes, and where the number comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Budget {
    pub bytes: u64,
    /// E.g. "--memory-budget" or "80% of the 3.1 GiB available (MemAvailable, /proc/meminfo)".
    pub source: String,
}

/// The share of the available memory a run may use by default, in percent.
pub const DEFAULT_SHARE_PERCENT: u64 = 80;

impl Budget {
    /// `given` (from `--memory-budget`), else [`DEFAULT_SHARE_PERCENT`] of the available
    /// memory; `None` when neither is known (no `/proc/meminfo`): then nothing is checked.
    pub fn of(given: Option<u64>) -> Option<Budget> {
        if let Some(bytes) = given {
            return Some(Budget {
                bytes,
                source: "--memory-budget".into(),
            });
        }
        let available = available_bytes()?;
        Some(Budget {
            bytes: available / 100 * DEFAULT_SHARE_PERCENT,
            source: format!(
                "{DEFAULT_SHARE_PERCENT}% of the {} available (MemAvailable in /proc/meminfo)",
                human(available)
            ),
        })
    }

    /// Holds every later index build of the process to this budget
    /// ([`crate::index::build_budget`]).
    pub fn hold_builds(&self) {
        crate::index::build_budget::set_build_budget(self.bytes, &self.source);
    }

    /// Fails with one message (what, how much, the budget, what to lower) when `need` is over.
    pub fn check(&self, need: &Need) -> anyhow::Result<()> {
        anyhow::ensure!(
            need.bytes <= self.bytes,
            "not enough memory: {} need about {}, over the memory budget of {} ({}); lower {}, \
             or raise --memory-budget",
            need.what,
            human(need.bytes),
            human(self.bytes),
            self.source,
            need.lower
        );
        Ok(())
    }
}

/// `MemAvailable` of `/proc/meminfo` in bytes (Linux); `None` elsewhere.
pub fn available_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    meminfo_available(&text)
}

/// The `MemAvailable:   123456 kB` line of a `/proc/meminfo` text, in bytes.
fn meminfo_available(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

/// Parses a `--memory-budget`: a number of bytes with an optional 1024-based unit, `K`, `M`,
/// `G` or `T` (also `KiB`, `MB`, ...; any case): `512M`, `1.5G`, `2000000`.
pub fn parse_bytes(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let v: f64 = number.parse().map_err(|_| {
        format!("'{s}' is not an amount of memory: give e.g. 512M, 1.5G or 2000000")
    })?;
    let shift = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 0,
        "k" | "kb" | "kib" => 10,
        "m" | "mb" | "mib" => 20,
        "g" | "gb" | "gib" => 30,
        "t" | "tb" | "tib" => 40,
        other => {
            return Err(format!(
                "unknown unit '{other}' in '{s}': give bytes, or a number with K, M, G or T (512M, 1.5G)"
            ));
        }
    };
    let bytes = v * (1u64 << shift) as f64;
    if !(1.0..=u64::MAX as f64 / 2.0).contains(&bytes) {
        return Err(format!("'{s}' is out of range: give at least 1 byte"));
    }
    Ok(bytes as u64)
}

/// Rays of `set` on `scene` at most (a secondary set has one ray per primary ray, shadow rays
/// one per primary ray and light).
fn set_rays(set: RaySet, scene: &Scene, cfg: &SuiteConfig) -> u64 {
    let primary = u64::from(cfg.sizes.primary_side).pow(2);
    match set {
        RaySet::Incoherent => cfg.sizes.incoherent as u64,
        RaySet::Shadow => primary * scene.lights_or_default().len() as u64,
        _ => primary,
    }
}

/// The option that sets the size of `set`, with its value.
fn size_option(set: RaySet, cfg: &SuiteConfig) -> String {
    match set {
        RaySet::Incoherent => format!("--incoherent ({})", cfg.sizes.incoherent),
        _ => format!("--primary-size ({})", cfg.sizes.primary_side),
    }
}

/// Bytes per ray of a set while the suite runs it: the rays, brute force's sample of them with
/// its ids and hits, the counting pass's per-ray counters, and per index and mode its answers,
/// plus the first index's copy, the reference mode's copy and the timed pass's output and its
/// copy, and with the `reorder` mode what it holds while it traces ([`reorder::BYTES_PER_RAY`]).
fn bytes_per_ray(cfg: &SuiteConfig) -> u64 {
    let (ray, hit) = (size_of::<Ray>() as u64, size_of::<Option<Hit>>() as u64);
    let entries = (cfg.indices.len() * cfg.modes.len().max(1)) as u64;
    let reorder = match cfg.modes.contains(&TraceMode::Reorder) {
        true => reorder::BYTES_PER_RAY as u64,
        false => 0,
    };
    2 * ray
        + size_of::<usize>() as u64
        + size_of::<Counters>() as u64
        + hit * (entries + 5)
        + reorder
}

/// The most the suite holds at once for ray sets over `scenes`: per scene the primary rays (and
/// their hits, when a secondary set starts from them) plus its largest set's [`bytes_per_ray`].
/// `None` when there is nothing to run.
pub fn suite_need(scenes: &[Scene], cfg: &SuiteConfig) -> Option<Need> {
    let (ray, hit) = (size_of::<Ray>() as u64, size_of::<Option<Hit>>() as u64);
    let per_ray = bytes_per_ray(cfg);
    let primary = u64::from(cfg.sizes.primary_side).pow(2);
    let secondary = cfg.sets.iter().any(|s| s.is_secondary());
    let held = primary * (ray + if secondary { hit } else { 0 });
    scenes
        .iter()
        .flat_map(|scene| cfg.sets.iter().map(move |&set| (scene, set)))
        .map(|(scene, set)| {
            let rays = set_rays(set, scene, cfg);
            Need {
                bytes: held.saturating_add(rays.saturating_mul(per_ray)),
                what: format!(
                    "the {} rays of scene {} ({} rays, with the primary rays and every index's answers)",
                    set.name(),
                    scene.name,
                    rays
                ),
                lower: size_option(set, cfg),
            }
        })
        .max_by_key(|n| n.bytes)
}

/// The bytes `rays` rays take in memory (`accelbench rays`, `accelbench trace`).
pub fn rays_bytes(rays: u64) -> u64 {
    rays.saturating_mul(size_of::<Ray>() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budgets_parse_with_units() {
        assert_eq!(parse_bytes("2000"), Ok(2000));
        assert_eq!(parse_bytes("1K"), Ok(1024));
        assert_eq!(parse_bytes("1.5g"), Ok(3 << 29));
        assert_eq!(parse_bytes("512 MiB"), Ok(512 << 20));
        for bad in ["", "x", "5Q", "0", "-1", "1e99T"] {
            assert!(parse_bytes(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn available_memory_is_read_from_meminfo() {
        let text = "MemTotal:  100 kB\nMemFree: 10 kB\nMemAvailable:    2048 kB\n";
        assert_eq!(meminfo_available(text), Some(2 << 20));
        assert_eq!(meminfo_available("MemTotal: 1 kB\n"), None);
        assert_eq!(human(3 << 29), "1.5 GiB");
        assert_eq!(human(10), "10 B");
    }

    #[test]
    fn a_need_over_the_budget_says_what_and_which_option() {
        let b = Budget {
            bytes: 1 << 20,
            source: "--memory-budget".into(),
        };
        let need = Need {
            bytes: 3 << 30,
            what: "the primary rays".into(),
            lower: "--primary-size (8192)".into(),
        };
        let e = b.check(&need).unwrap_err().to_string();
        assert!(e.contains("3.0 GiB") && e.contains("1.0 MiB"), "{e}");
        assert!(e.contains("lower --primary-size (8192)"), "{e}");
        assert!(
            b.check(&Need {
                bytes: 1 << 20,
                ..need
            })
            .is_ok()
        );
    }
}
