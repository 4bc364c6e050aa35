//! `accelbench info`: what a scene holds.

use crate::scene::load_scene;
use anyhow::Context;

#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// An .obj path or a built-in scene name.
    #[arg(long)]
    scene: String,
}

pub fn run(a: InfoArgs) -> anyhow::Result<()> {
    let scene = load_scene(&a.scene).with_context(|| format!("loading scene '{}'", a.scene))?;
    let b = scene.bounds();
    println!("scene:       {}", scene.name);
    println!("primitives:  {}", scene.len());
    println!("triangles:   {}", scene.triangles.len());
    println!("spheres:     {}", scene.spheres.len());
    println!(
        "degenerate:  {} zero-area triangles",
        scene.degenerate_triangles()
    );
    println!("bounds min:  {:?}", b.min.to_array());
    println!("bounds max:  {:?}", b.max.to_array());
    println!("lights:      {}", scene.lights.len());
    Ok(())
}
