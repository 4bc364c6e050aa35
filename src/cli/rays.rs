//! `accelbench rays`: write a protocol ray set of a scene.

use crate::rays::{RaySetKind, incoherent_rays, primary_rays, write_rays};
use crate::scene::load_scene;
use anyhow::Context;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct RaysArgs {
    /// An .obj or .toml path, or a built-in scene name (`soup`, `soup:n=100000,seed=3`).
    #[arg(long)]
    scene: String,
    /// Which standard set (see ../shared/PROTOCOL.md).
    #[arg(long, value_enum)]
    set: RaySetKind,
    /// Output .rays file.
    #[arg(long)]
    out: PathBuf,
    /// Image width and height for the primary set.
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(1..=16384))]
    size: u32,
    /// Number of incoherent rays.
    #[arg(long, default_value_t = 1 << 20, value_parser = clap::value_parser!(u64).range(1..=(1u64 << 28)))]
    count: u64,
    /// Seed of the incoherent set's SplitMix64.
    #[arg(long, default_value_t = 42)]
    seed: u64,
}

pub fn run(a: RaysArgs) -> anyhow::Result<()> {
    let scene = load_scene(&a.scene).with_context(|| format!("loading scene '{}'", a.scene))?;
    let b = scene.ray_set_bounds();
    let rays = match a.set {
        RaySetKind::Primary => primary_rays(&b, a.size, a.size)?,
        RaySetKind::Incoherent => incoherent_rays(&b, a.count as usize, a.seed),
    };
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
