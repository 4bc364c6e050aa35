//! One GPU structure ready to trace ([`Program`]): its compute pipeline and its buffers on the
//! device, and the batch trace (upload the rays, dispatch, read the hits back), with the
//! kernel's own time from timestamp queries where the adapter has them.
//!
//! Bindings every shader shares (`shaders/common.wgsl`): 0 the rays (8 `f32` each, the
//! protocol's order: origin, direction, `t_min`, `t_max`), 1 the hits (2 `u32` each: the bits of
//! `t`, `+inf` for a miss, and the primitive id), 2 the batch's parameters (ray count, any-hit, the bits of `+inf`, a zero),
//! then the structure's own buffers from binding 3 on.

use super::context::Gpu;
use crate::geometry::Ray;
use std::sync::Mutex;
use std::time::Duration;
use wgpu::util::DeviceExt;

/// Threads per workgroup of every trace shader (`@workgroup_size(64)`).
const WORKGROUP: u32 = 64;
/// Rays of one dispatch: at most 65,535 workgroups in x.
const MAX_DISPATCH_RAYS: usize = 65_535 * WORKGROUP as usize;
/// Bytes of one ray and one hit on the device.
const RAY_BYTES: usize = 32;
const HIT_BYTES: usize = 8;

/// A structure on the device, with its pipeline.
pub struct Program {
    pipeline: wgpu::ComputePipeline,
    structure: Vec<wgpu::Buffer>,
    /// Device bytes of the structure's buffers.
    pub bytes: usize,
    scratch: Mutex<Option<Scratch>>,
}

/// The per-batch buffers, kept between batches of the same size or smaller.
struct Scratch {
    rays: usize,
    ray_buf: wgpu::Buffer,
    hit_buf: wgpu::Buffer,
    read_buf: wgpu::Buffer,
    params: wgpu::Buffer,
    bind: wgpu::BindGroup,
    timer: Option<(wgpu::QuerySet, wgpu::Buffer, wgpu::Buffer)>,
}

/// Hits of a batch as the device wrote them, and the kernel time of all its dispatches.
pub struct Traced {
    /// `[t bits, prim]` per ray.
    pub hits: Vec<[u32; 2]>,
    pub kernel: Option<Duration>,
}

impl Program {
    /// Compiles `shader` (WGSL, entry point `main`) and uploads `buffers` (name, bytes; bound
    /// from binding 3 on, in order), or says what the device refused: a buffer over the
    /// adapter's limit, a shader it cannot compile.
    pub fn new(
        gpu: &Gpu,
        name: &str,
        shader: &str,
        buffers: &[(&str, &[u8])],
    ) -> Result<Program, String> {
        let limits = gpu.device.limits();
        let max = limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size);
        for (what, data) in buffers {
            if data.len() as u64 > max {
                return Err(format!(
                    "{name}'s {what} need {} bytes; the GPU adapter binds at most {max} in one buffer: trace a smaller scene",
                    data.len()
                ));
            }
        }
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(name),
                source: wgpu::ShaderSource::Wgsl(shader.into()),
            });
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(name),
                layout: None,
                module: &module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            });
        let structure: Vec<wgpu::Buffer> = buffers
            .iter()
            .map(|(what, data)| {
                // A binding may not be empty: at least 16 bytes.
                let mut bytes = data.to_vec();
                bytes.resize(bytes.len().max(16).next_multiple_of(4), 0);
                gpu.device
                    .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(what),
                        contents: &bytes,
                        usage: wgpu::BufferUsages::STORAGE,
                    })
            })
            .collect();
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(format!("the GPU refused {name}: {e}"));
        }
        Ok(Program {
            pipeline,
            bytes: buffers.iter().map(|(_, d)| d.len()).sum(),
            structure,
            scratch: Mutex::new(None),
        })
    }

    /// Traces `rays` (closest hits, or any hit when `any`), in dispatches of at most
    /// [`MAX_DISPATCH_RAYS`] and of what one binding holds.
    pub fn trace(&self, gpu: &Gpu, rays: &[Ray], any: bool) -> Result<Traced, String> {
        let limits = gpu.device.limits();
        let per_binding = (limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size) as usize)
            / RAY_BYTES;
        let chunk = MAX_DISPATCH_RAYS.min(per_binding).min(rays.len().max(1));
        let mut guard = self
            .scratch
            .lock()
            .map_err(|_| "a GPU trace panicked".to_owned())?;
        if guard.as_ref().is_none_or(|s| s.rays < chunk) {
            *guard = Some(self.scratch(gpu, chunk));
        }
        let scratch = guard.as_ref().expect("just made");
        let mut hits = Vec::with_capacity(rays.len());
        let mut kernel = gpu.timestamps.then_some(Duration::ZERO);
        let mut packed: Vec<[f32; 8]> = Vec::with_capacity(chunk);
        for part in rays.chunks(chunk) {
            packed.clear();
            packed.extend(part.iter().map(|r| {
                [
                    r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, r.t_min, r.t_max,
                ]
            }));
            let n = part.len() as u32;
            gpu.queue
                .write_buffer(&scratch.ray_buf, 0, bytemuck::cast_slice(&packed));
            gpu.queue.write_buffer(
                &scratch.params,
                0,
                bytemuck::cast_slice(&[n, any as u32, f32::INFINITY.to_bits(), 0u32]),
            );
            let mut enc = gpu.device.create_command_encoder(&Default::default());
            {
                let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: None,
                    timestamp_writes: scratch.timer.as_ref().map(|(q, _, _)| {
                        wgpu::ComputePassTimestampWrites {
                            query_set: q,
                            beginning_of_pass_write_index: Some(0),
                            end_of_pass_write_index: Some(1),
                        }
                    }),
                });
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &scratch.bind, &[]);
                pass.dispatch_workgroups(n.div_ceil(WORKGROUP), 1, 1);
            }
            let hit_bytes = (part.len() * HIT_BYTES) as u64;
            enc.copy_buffer_to_buffer(&scratch.hit_buf, 0, &scratch.read_buf, 0, hit_bytes);
            if let Some((q, resolve, read)) = &scratch.timer {
                enc.resolve_query_set(q, 0..2, resolve, 0);
                enc.copy_buffer_to_buffer(resolve, 0, read, 0, 16);
            }
            gpu.queue.submit([enc.finish()]);
            let mut reads = vec![(&scratch.read_buf, hit_bytes)];
            if let Some((_, _, read)) = &scratch.timer {
                reads.push((read, 16));
            }
            for (buf, len) in &reads {
                buf.slice(..*len).map_async(wgpu::MapMode::Read, |_| {});
            }
            gpu.device
                .poll(wgpu::PollType::wait_indefinitely())
                .map_err(|e| format!("the GPU did not finish a trace: {e}"))?;
            if let Some(e) = gpu.take_errors() {
                return Err(format!("the GPU failed a trace: {e}"));
            }
            {
                let view = scratch
                    .read_buf
                    .get_mapped_range(..hit_bytes)
                    .map_err(|e| format!("reading the GPU's hits back: {e}"))?;
                hits.extend_from_slice(bytemuck::cast_slice::<u8, [u32; 2]>(&view));
            }
            scratch.read_buf.unmap();
            if let Some((_, _, read)) = &scratch.timer {
                {
                    let view = read
                        .get_mapped_range(..16)
                        .map_err(|e| format!("reading the GPU's timestamps back: {e}"))?;
                    let [t0, t1]: [u64; 2] = bytemuck::pod_read_unaligned(&view);
                    let ns = t1.saturating_sub(t0) as f64 * gpu.queue.get_timestamp_period() as f64;
                    kernel = kernel.map(|k| k + Duration::from_nanos(ns as u64));
                }
                read.unmap();
            }
        }
        Ok(Traced { hits, kernel })
    }

    /// Buffers for batches of up to `rays` rays.
    fn scratch(&self, gpu: &Gpu, rays: usize) -> Scratch {
        let dev = &gpu.device;
        let buffer = |label, size: usize, usage| {
            dev.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as U;
        let ray_buf = buffer("rays", rays * RAY_BYTES, U::STORAGE | U::COPY_DST);
        let hit_buf = buffer("hits", rays * HIT_BYTES, U::STORAGE | U::COPY_SRC);
        let read_buf = buffer(
            "hits read back",
            rays * HIT_BYTES,
            U::MAP_READ | U::COPY_DST,
        );
        let params = buffer("params", 16, U::UNIFORM | U::COPY_DST);
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: ray_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: hit_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: params.as_entire_binding(),
            },
        ];
        entries.extend(
            self.structure
                .iter()
                .enumerate()
                .map(|(i, b)| wgpu::BindGroupEntry {
                    binding: 3 + i as u32,
                    resource: b.as_entire_binding(),
                }),
        );
        let bind = dev.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let timer = gpu.timestamps.then(|| {
            let q = dev.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("kernel time"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            });
            let resolve = buffer("timestamps", 16, U::QUERY_RESOLVE | U::COPY_SRC);
            let read = buffer("timestamps read back", 16, U::MAP_READ | U::COPY_DST);
            (q, resolve, read)
        });
        Scratch {
            rays,
            ray_buf,
            hit_buf,
            read_buf,
            params,
            bind,
            timer,
        }
    }
}
