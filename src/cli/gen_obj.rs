//! `accelbench gen`: write a generator's triangles as an OBJ file (by default into `meshes/`,
//! where the suite picks it up).

use crate::scene::generators::{DEFAULT_SEED, DEFAULT_SIZE, GENERATOR_NAMES, GeneratorSpec};
use crate::scene::obj_writer::write_obj;
use anyhow::Context;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct GenArgs {
    /// Generator name (icosphere, soup, terrain, stadium, slivers, room, flat; spheres, mixed
    /// and shapes contain spheres or shapes, which OBJ cannot hold).
    #[arg(long)]
    generator: String,
    /// Target primitive count.
    #[arg(long, default_value_t = DEFAULT_SIZE as i64, allow_negative_numbers = true)]
    n: i64,
    /// Seed of the random generators.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    seed: u64,
    /// Output .obj file (default: meshes/GENERATOR_nN_seedS.obj).
    #[arg(long)]
    out: Option<PathBuf>,
}

pub fn run(a: GenArgs) -> anyhow::Result<()> {
    let spec = GeneratorSpec::new(&a.generator, a.n, a.seed)?;
    let scene = spec.generate()?;
    anyhow::ensure!(
        scene.spheres.is_empty() && scene.shapes.is_empty(),
        "generator '{}' makes spheres or shapes, which an OBJ file cannot hold; choose a triangle generator ({})",
        spec.name,
        GENERATOR_NAMES
            .iter()
            .filter(|g| !matches!(**g, "spheres" | "mixed" | "shapes"))
            .copied()
            .collect::<Vec<_>>()
            .join(", ")
    );
    let out = a.out.unwrap_or_else(|| {
        PathBuf::from("meshes").join(format!("{}_n{}_seed{}.obj", spec.name, spec.n, spec.seed))
    });
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("creating the directory {}", dir.display()))?;
    }
    let comment = format!(
        "accelbench gen --generator {} --n {} --seed {}\n{} triangles",
        spec.name,
        spec.n,
        spec.seed,
        scene.triangles.len()
    );
    write_obj(&out, &scene.triangles, &comment)?;
    eprintln!(
        "wrote {} triangles of '{}' to {}",
        scene.triangles.len(),
        spec,
        out.display()
    );
    Ok(())
}
