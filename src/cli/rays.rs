//! `accelbench rays`: write a protocol or camera-model ray set of a scene.

use crate::harness::memory::{Budget, Need, rays_bytes};
use crate::rays::{RaySetKind, ray_set, write_rays};
use crate::scene::load_scene;
use anyhow::Context;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct RaysArgs {
    /// A mesh (.obj, .ply, .gltf, .glb) or .toml path, or a built-in scene name (`soup`, `soup:n=100000,seed=3`).
    #[arg(long)]
    scene: String,
    /// Which set: the protocol's `primary` and `incoherent` (see ../shared/PROTOCOL.md), or the
    /// camera-model sets `dof`, `motion`, `lens` (see docs/ray-sets.md).
    #[arg(long, value_enum)]
    set: RaySetKind,
    /// Output .rays file.
    #[arg(long)]
    out: PathBuf,
    /// Image width and height for the primary, dof, motion and lens sets.
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(1..=16384))]
    size: u32,
    /// Number of incoherent rays.
    #[arg(long, default_value_t = 1 << 20, value_parser = clap::value_parser!(u64).range(1..=(1u64 << 28)))]
    count: u64,
    /// Seed of the incoherent set's SplitMix64 [default: 42] or of the dof and motion sets'
    /// lens and time samples [default: 19].
    #[arg(long)]
    seed: Option<u64>,
    /// The memory the ray set may take (`512M`, `4G`; 1024-based): a set over it is refused
    /// before it is made [default: 80% of the available memory].
    #[arg(long, value_parser = crate::harness::memory::parse_bytes)]
    memory_budget: Option<u64>,
}

/// The set's rays, what they are and the option that sets their number.
fn planned(a: &RaysArgs) -> Need {
    let (rays, lower) = match a.set {
        RaySetKind::Incoherent => (a.count, format!("--count ({})", a.count)),
        _ => (u64::from(a.size).pow(2), format!("--size ({})", a.size)),
    };
    Need {
        bytes: rays_bytes(rays),
        what: format!("{rays} {} rays", a.set.name()),
        lower,
    }
}

pub fn run(a: RaysArgs) -> anyhow::Result<()> {
    if let Some(budget) = Budget::of(a.memory_budget) {
        budget.check(&planned(&a))?;
    }
    let scene = load_scene(&a.scene).with_context(|| format!("loading scene '{}'", a.scene))?;
    let b = scene.ray_set_bounds();
    let rays = ray_set(a.set, &b, a.size, a.count as usize, a.seed)?;
    write_rays(&a.out, &rays)?;
    eprintln!(
        "wrote {} {} rays of '{}' to {}",
        rays.len(),
        a.set.name(),
        scene.name,
        a.out.display()
    );
    Ok(())
}
