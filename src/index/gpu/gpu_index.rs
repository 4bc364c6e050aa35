//! A structure on the GPU behind [`TraceIndex`] ([`GpuIndex`]), and building one ([`build`]):
//! the device, the scene's triangles, the budget, our structure's build and its upload, for
//! each structure's [`GpuLayout`].

use super::context::{Gpu, gpu};
use super::program::Program;
use crate::geometry::{Hit, Ray, Triangle, TriangleKernelKind};
use crate::heap_meter::peak_during;
use crate::index::{BuildError, Counters, Index, IndexInfo, TraceIndex, TraceMode};
use crate::scene::{FromScene, GeometryVisitor, SceneGeometry, with_geometry};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// A structure uploaded to the GPU. Batch calls trace the whole batch in dispatches on the
/// device (the calling thread waits); single-ray calls trace a batch of one.
pub struct GpuIndex {
    name: String,
    params: String,
    info: IndexInfo,
    program: Program,
    gpu: &'static Gpu,
    /// The kernel time of the last batch, where the adapter has timestamps.
    kernel: Mutex<Option<Duration>>,
    /// Whether a failed trace was reported (once per index).
    failed: Mutex<bool>,
}

/// One of our structures as a GPU index: the structure it is built from (`Base`, with its
/// parameters), the shader that walks it and the buffers it uploads.
pub trait GpuLayout {
    /// The structure of ours the index uploads (its parameters are the index's).
    type Base: Index;
    /// The walk, after the shared part (`shaders/common.wgsl`).
    const SHADER: &'static str;
    /// Heap bytes per triangle beyond `Base`'s build estimate: the buffers it makes and their
    /// staging copies.
    const UPLOAD_BYTES_PER_PRIM: usize;
    /// The buffers (name, bytes; bound from binding 3 on, the triangles first) and the
    /// figures of index `base` built over `tris`.
    fn layout(base: &Self::Base, tris: &[Triangle]) -> (IndexInfo, Vec<(&'static str, Vec<u8>)>);
}

/// The estimate of GPU index `L`'s build with its base's `params`: the base's and the upload's.
pub(crate) fn estimate<L: GpuLayout>(
    params: &<L::Base as Index>::Params,
    prims: usize,
) -> Option<usize> {
    L::Base::estimated_build_bytes(prims, params).map(|b| b + prims * L::UPLOAD_BYTES_PER_PRIM)
}

/// Builds GPU index `L`, named `name`, with its base's `params`: the base over the scene's
/// triangles, then the upload. Skipped ([`BuildError::Unsupported`]) without an adapter or on a
/// scene with other primitives (the shaders test triangles only); a build over the memory
/// budget is refused first.
pub(crate) fn build<L: GpuLayout>(
    name: &str,
    params: &<L::Base as Index>::Params,
    geom: &SceneGeometry,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    let name = &name.to_owned();
    let gpu = gpu().map_err(|reason| BuildError::Unsupported {
        index: name.clone(),
        reason,
    })?;
    if !geom.spheres.is_empty() || !geom.shapes.is_empty() {
        return Err(BuildError::Unsupported {
            index: name.clone(),
            reason: "the GPU shaders test triangles only, and this scene has spheres or other \
                     shapes"
                .into(),
        });
    }
    let tris: &[Triangle] = &geom.triangles;
    if tris.len() >= u32::MAX as usize {
        return Err(BuildError::Failed {
            index: name.clone(),
            message: format!("{} triangles exceed the shaders' 32-bit ids", tris.len()),
        });
    }
    if let Some(need) = estimate::<L>(params, tris.len()) {
        crate::index::build_budget::ensure_fits(name, tris.len(), need)?;
    }
    struct Build<'p, I: Index>(&'p I::Params);
    impl<I: Index> GeometryVisitor for Build<'_, I> {
        type Output = Result<I, BuildError>;
        fn visit<G: FromScene>(self, g: G) -> Self::Output {
            I::build(&g, self.0)
        }
    }
    let start = Instant::now();
    let (built, peak) = peak_during(|| -> Result<_, BuildError> {
        let base = with_geometry(
            geom,
            TriangleKernelKind::Watertight,
            Build::<L::Base>(params),
        )?;
        Ok(L::layout(&base, tris))
    });
    let (mut info, buffers) = built?;
    info.build_time = start.elapsed();
    info.peak_build_bytes = Some(peak);
    let params = toml::to_string(params)
        .unwrap_or_default()
        .trim()
        .replace('\n', ",");
    let upload = Instant::now();
    let source = format!("{}\n{}", super::COMMON, L::SHADER);
    let buffers: Vec<(&str, &[u8])> = buffers.iter().map(|(n, b)| (*n, b.as_slice())).collect();
    let program =
        Program::new(gpu, name, &source, &buffers).map_err(|message| BuildError::Failed {
            index: name.clone(),
            message,
        })?;
    let upload = upload.elapsed();
    info.build_time += upload;
    info.memory_bytes = program.bytes;
    info.uncounted = true;
    info.upload_time = Some(upload);
    Ok(Box::new(GpuIndex {
        name: name.clone(),
        params,
        info,
        program,
        gpu,
        kernel: Mutex::new(None),
        failed: Mutex::new(false),
    }))
}

/// Triangles `order` (scene ids) as the shaders read them: 9 `f32` each, as bytes.
pub(super) fn triangle_bytes(tris: &[Triangle], order: impl Iterator<Item = u32>) -> Vec<u8> {
    let words: Vec<f32> = order
        .flat_map(|id| {
            let v = &tris[id as usize].v;
            [
                v[0].x, v[0].y, v[0].z, v[1].x, v[1].y, v[1].z, v[2].x, v[2].y, v[2].z,
            ]
        })
        .collect();
    bytemuck::cast_slice(&words).to_vec()
}

/// Plain words as bytes for a buffer.
pub(super) fn bytes_of<T: bytemuck::Pod>(words: &[T]) -> Vec<u8> {
    bytemuck::cast_slice(words).to_vec()
}

impl GpuIndex {
    /// Traces `rays` on the device; on a device error the rays are misses, and the error is
    /// printed once (the rows then count them wrong).
    fn run(&self, rays: &[Ray], any: bool, mut put: impl FnMut(usize, Option<Hit>)) {
        match self.program.trace(self.gpu, rays, any) {
            Ok(traced) => {
                for (i, [t, prim]) in traced.hits.into_iter().enumerate() {
                    put(
                        i,
                        (prim != u32::MAX).then(|| Hit {
                            t: f32::from_bits(t),
                            prim,
                        }),
                    );
                }
                if let Ok(mut k) = self.kernel.lock() {
                    *k = traced.kernel;
                }
            }
            Err(e) => {
                if let Ok(mut failed) = self.failed.lock()
                    && !std::mem::replace(&mut *failed, true)
                {
                    eprintln!("{}: {e}; its rays count as misses", self.name);
                }
                (0..rays.len()).for_each(|i| put(i, None));
            }
        }
    }
}

fn reset(counters: Option<&mut [Counters]>) {
    if let Some(c) = counters {
        c.fill(Counters::default());
    }
}

impl TraceIndex for GpuIndex {
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
        true
    }
    /// One query per dispatch is not what a GPU is for: the rows are `+stream` only.
    fn has_single(&self) -> bool {
        false
    }
    fn refused(&self, _rays: &[Ray]) -> Option<(usize, &'static str)> {
        None
    }
    fn can_refit(&self) -> bool {
        false
    }
    fn refit(&mut self, _frame: &SceneGeometry) -> Result<(), BuildError> {
        Err(BuildError::Unsupported {
            index: self.name.clone(),
            reason: "it has no refit; rebuild it".into(),
        })
    }
    fn kernel_time(&self) -> Option<Duration> {
        self.kernel.lock().ok().and_then(|k| *k)
    }
    fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        let mut out = None;
        self.run(std::slice::from_ref(ray), false, |_, h| out = h);
        out
    }
    fn closest_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> Option<Hit> {
        *counters = Counters::default();
        self.closest_hit(ray)
    }
    fn any_hit(&self, ray: &Ray) -> bool {
        let mut out = false;
        self.run(std::slice::from_ref(ray), true, |_, h| out = h.is_some());
        out
    }
    fn any_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> bool {
        *counters = Counters::default();
        self.any_hit(ray)
    }
    fn closest_hits_in(
        &self,
        _mode: TraceMode,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    ) {
        reset(counters);
        self.run(rays, false, |i, h| out[i] = h);
    }
    fn any_hits_in(
        &self,
        _mode: TraceMode,
        rays: &[Ray],
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    ) {
        reset(counters);
        self.run(rays, true, |i, h| out[i] = h.is_some());
    }
}
