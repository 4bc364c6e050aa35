//! `accelbench info`: what a scene holds.

use crate::scene::load_scene;
use anyhow::Context;

#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// A mesh (.obj, .ply, .gltf, .glb) or .toml path, or a built-in scene name (`soup`, `soup:n=100000,seed=3`).
    #[arg(long)]
    scene: String,
}

pub fn run(a: InfoArgs) -> anyhow::Result<()> {
    let start = std::time::Instant::now();
    let scene = load_scene(&a.scene).with_context(|| format!("loading scene '{}'", a.scene))?;
    let seconds = start.elapsed().as_secs_f64();
    let b = scene.bounds();
    println!("scene:       {}", scene.name);
    println!("{}", load_line(&a.scene, seconds, scene.triangles.len()));
    println!("primitives:  {}", scene.len());
    println!("triangles:   {}", scene.triangles.len());
    println!("spheres:     {}", scene.spheres.len());
    println!("shapes:      {}", scene.shapes.len());
    println!(
        "degenerate:  {} zero-area triangles",
        scene.degenerate_triangles()
    );
    println!("bounds min:  {:?}", b.min.to_array());
    println!("bounds max:  {:?}", b.max.to_array());
    println!("lights:      {}", scene.lights.len());
    for l in &scene.lights {
        println!(
            "  position {:?} intensity {:?}",
            l.position.to_array(),
            l.intensity.to_array()
        );
    }
    match &scene.camera {
        Some(c) => println!(
            "camera:      eye {:?} look_at {:?} up {:?} fov {} deg",
            c.eye.to_array(),
            c.look_at.to_array(),
            c.up.to_array(),
            c.fov_deg
        ),
        None => println!("camera:      none (the protocol camera is used)"),
    }
    Ok(())
}

/// The `load:` line: the seconds `load_scene` took and, for a file, its size and the rates
/// (1 MB = 10^6 bytes; a `.gltf` counts its JSON only, not the `.bin` files it names).
fn load_line(arg: &str, seconds: f64, triangles: usize) -> String {
    let mtris = triangles as f64 / 1e6 / seconds.max(1e-9);
    match std::fs::metadata(arg) {
        Ok(m) if m.is_file() => {
            let mb = m.len() as f64 / 1e6;
            format!(
                "load:        {seconds:.3} s ({mb:.1} MB at {:.0} MB/s, {mtris:.1} Mtriangles/s)",
                mb / seconds.max(1e-9)
            )
        }
        _ => format!("load:        {seconds:.3} s (generated, {mtris:.1} Mtriangles/s)"),
    }
}
