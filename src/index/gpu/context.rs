//! The one GPU device the suite uses ([`gpu`]): the first adapter wgpu finds (Vulkan, Metal or
//! DX12; on a machine without a GPU, a software Vulkan driver such as Mesa's lavapipe), opened
//! once per process with every limit the adapter offers and timestamp queries where it has them.

use std::sync::{Arc, Mutex, OnceLock};

/// An opened GPU device with its queue.
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// `name (driver driver_info, backend)`, for `meta.json` and notes.
    pub adapter: String,
    /// Whether compute passes can be timed with timestamp queries ([`wgpu::Features::TIMESTAMP_QUERY`]).
    pub timestamps: bool,
    /// Errors the device reported outside an error scope (device lost, out of memory), newest
    /// last; the traces read them after each batch instead of letting wgpu panic.
    pub errors: Arc<Mutex<Vec<String>>>,
}

/// The process's GPU, opened on first use, or why there is none (every GPU index is then
/// skipped with that line).
pub fn gpu() -> Result<&'static Gpu, String> {
    static GPU: OnceLock<Result<Gpu, String>> = OnceLock::new();
    GPU.get_or_init(|| pollster::block_on(open()))
        .as_ref()
        .map_err(Clone::clone)
}

async fn open() -> Result<Gpu, String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = instance
        .request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            ..Default::default()
        })
        .await
        .map_err(|e| {
            format!(
                "no GPU adapter found ({e}); on a machine without a GPU install a software \
                 Vulkan driver (Debian: apt-get install mesa-vulkan-drivers)"
            )
        })?;
    let info = adapter.get_info();
    let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
    let required_features = if timestamps {
        wgpu::Features::TIMESTAMP_QUERY
    } else {
        wgpu::Features::empty()
    };
    let (device, queue) = adapter
        .request_device(&wgpu::DeviceDescriptor {
            label: Some("accelbench"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        })
        .await
        .map_err(|e| format!("the GPU adapter {} refused a device: {e}", info.name))?;
    let errors = Arc::new(Mutex::new(Vec::new()));
    let sink = errors.clone();
    device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
        if let Ok(mut v) = sink.lock() {
            v.push(e.to_string());
        }
    }));
    Ok(Gpu {
        device,
        queue,
        adapter: format!(
            "{} ({} {}, {:?})",
            info.name, info.driver, info.driver_info, info.backend
        ),
        timestamps,
        errors,
    })
}

impl Gpu {
    /// The errors reported since the last call, if any, as one line.
    pub fn take_errors(&self) -> Option<String> {
        let mut v = self.errors.lock().ok()?;
        (!v.is_empty()).then(|| std::mem::take(&mut *v).join("; "))
    }
}
