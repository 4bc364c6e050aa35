//! `accelbench gen`: write a generator's triangles as an OBJ or binary PLY file (by default
//! into `meshes/`, where the suite picks it up).

use crate::scene::generators::{DEFAULT_SEED, DEFAULT_SIZE, GENERATOR_NAMES, GeneratorSpec};
use crate::scene::obj_writer::write_obj;
use crate::scene::ply_writer::write_ply;
use anyhow::Context;
use std::path::{Path, PathBuf};

/// The file format `gen` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MeshFormat {
    /// Wavefront OBJ text, shortest round-tripping decimals.
    Obj,
    /// Binary little-endian PLY, the `f32` bits as they are (smaller and faster to load).
    Ply,
}

impl MeshFormat {
    fn extension(self) -> &'static str {
        match self {
            MeshFormat::Obj => "obj",
            MeshFormat::Ply => "ply",
        }
    }

    /// The format `--format` gives, else the one `--out`'s extension names (`.ply`), else OBJ.
    fn chosen(flag: Option<MeshFormat>, out: Option<&Path>) -> anyhow::Result<MeshFormat> {
        let by_name = out
            .and_then(|p| p.extension())
            .is_some_and(|e| e.eq_ignore_ascii_case("ply"))
            .then_some(MeshFormat::Ply);
        match (flag, by_name, out) {
            (Some(MeshFormat::Ply), None, Some(p)) => anyhow::bail!(
                "--format ply with --out {}: name the file .ply (or leave out --format)",
                p.display()
            ),
            (Some(MeshFormat::Obj), Some(_), Some(p)) => anyhow::bail!(
                "--format obj with --out {}: a .ply name is a PLY file; name it .obj",
                p.display()
            ),
            (Some(f), _, _) => Ok(f),
            (None, by_name, _) => Ok(by_name.unwrap_or(MeshFormat::Obj)),
        }
    }
}

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
    /// Output file (default: meshes/GENERATOR_nN_seedS.obj, or .ply with --format ply).
    #[arg(long)]
    out: Option<PathBuf>,
    /// File format: obj, or ply (binary little-endian); default: by --out's extension (.ply),
    /// else obj.
    #[arg(long, value_enum)]
    format: Option<MeshFormat>,
}

pub fn run(a: GenArgs) -> anyhow::Result<()> {
    let format = MeshFormat::chosen(a.format, a.out.as_deref())?;
    let spec = GeneratorSpec::new(&a.generator, a.n, a.seed)?;
    let scene = spec.generate()?;
    anyhow::ensure!(
        scene.spheres.is_empty() && scene.shapes.is_empty(),
        "generator '{}' makes spheres or shapes, which an OBJ or PLY file cannot hold; choose a triangle generator ({})",
        spec.name,
        GENERATOR_NAMES
            .iter()
            .filter(|g| !matches!(**g, "spheres" | "mixed" | "shapes"))
            .copied()
            .collect::<Vec<_>>()
            .join(", ")
    );
    let out = a.out.unwrap_or_else(|| {
        PathBuf::from("meshes").join(format!(
            "{}_n{}_seed{}.{}",
            spec.name,
            spec.n,
            spec.seed,
            format.extension()
        ))
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
    match format {
        MeshFormat::Obj => write_obj(&out, &scene.triangles, &comment)?,
        MeshFormat::Ply => write_ply(&out, &scene.triangles, &comment)?,
    }
    eprintln!(
        "wrote {} triangles of '{}' to {}",
        scene.triangles.len(),
        spec,
        out.display()
    );
    Ok(())
}
