//! Finding a GPU: the adapter, its device and queue, and the compiled kernels,
//! shared by every scene on it.

use crate::pass::GpuPass;
use crate::passes::Programs;
use crate::program::Kernel;
use std::sync::{Arc, Mutex};

/// Why no GPU backend could be started.
#[derive(Debug, Clone, thiserror::Error)]
pub enum GpuError {
    /// No Vulkan adapter at all (no driver, or no device).
    #[error(
        "no Vulkan adapter found (install a Vulkan driver, e.g. Debian's mesa-vulkan-drivers for the software one)"
    )]
    NoAdapter,
    /// Only software adapters, and a hardware one was required.
    #[error("only a software Vulkan adapter was found ({0}); a hardware GPU is required here")]
    SoftwareOnly(String),
    /// The adapter refused a device.
    #[error("could not open a device on {adapter}: {reason}")]
    Device {
        /// The adapter's name.
        adapter: String,
        /// The driver's message.
        reason: String,
    },
}

/// Which adapters qualify.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Adapters {
    /// Hardware GPUs only (discrete, integrated or virtual).
    Hardware,
    /// Hardware first, else a software rasteriser such as Mesa's lavapipe.
    Any,
}

/// Plan passes compiled on a device, with their kernels.
type Compiled = Vec<(&'static GpuPass, Arc<Kernel>)>;

/// A device with Floe's kernels compiled on it. Cheap to clone.
#[derive(Debug, Clone)]
pub struct GpuContext {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) programs: Arc<Programs>,
    /// Plan passes compiled so far, shared by every scene on the device.
    passes: Arc<Mutex<Compiled>>,
    info: wgpu::AdapterInfo,
    profile: bool,
}

impl GpuContext {
    /// Opens the best qualifying Vulkan adapter: discrete before integrated
    /// before virtual before software. With `profile`, scenes on it time every
    /// kernel (when the adapter has timestamp queries; see [`crate::timer`]).
    pub fn new(which: Adapters, profile: bool) -> Result<Self, GpuError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
        let rank = |t: wgpu::DeviceType| match t {
            wgpu::DeviceType::DiscreteGpu => 0,
            wgpu::DeviceType::IntegratedGpu => 1,
            wgpu::DeviceType::VirtualGpu => 2,
            wgpu::DeviceType::Other => 3,
            wgpu::DeviceType::Cpu => 4,
        };
        let adapter = adapters.into_iter().min_by_key(|a| rank(a.get_info().device_type)).ok_or(GpuError::NoAdapter)?;
        let info = adapter.get_info();
        if which == Adapters::Hardware && info.device_type == wgpu::DeviceType::Cpu {
            return Err(GpuError::SoftwareOnly(info.name));
        }
        let profile = profile && adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        // The adapter's own limits: large scenes need its full buffer sizes.
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("floe"),
            required_features: if profile { wgpu::Features::TIMESTAMP_QUERY } else { wgpu::Features::empty() },
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device { adapter: info.name.clone(), reason: e.to_string() })?;
        let programs = Arc::new(Programs::new(&device));
        Ok(Self { device, queue, programs, passes: Arc::default(), info, profile })
    }

    /// The adapter's name and kind, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (software)`.
    pub fn describe(&self) -> String {
        let kind = match self.info.device_type {
            wgpu::DeviceType::DiscreteGpu => "discrete GPU",
            wgpu::DeviceType::IntegratedGpu => "integrated GPU",
            wgpu::DeviceType::VirtualGpu => "virtual GPU",
            wgpu::DeviceType::Cpu => "software",
            wgpu::DeviceType::Other => "other",
        };
        format!("{} ({kind}, driver {})", self.info.name, self.info.driver_info)
    }

    /// Whether scenes time their kernels.
    pub fn profiling(&self) -> bool {
        self.profile
    }

    /// Whether the adapter is a software rasteriser.
    pub fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }

    /// The compiled kernel of plan pass `pass`, compiled on its first use on this device.
    pub(crate) fn kernel(&self, pass: &'static GpuPass) -> Arc<Kernel> {
        let mut cache = self.passes.lock().expect("kernel cache");
        if let Some((_, k)) = cache.iter().find(|(p, _)| std::ptr::eq(*p, pass)) {
            return k.clone();
        }
        let access: Vec<crate::program::Access> = pass.bindings.iter().map(|(a, _)| *a).collect();
        let kernel = Arc::new(Kernel::single(&self.device, pass.name, pass.source, pass.entry, &access));
        cache.push((pass, kernel.clone()));
        kernel
    }

    /// Storage buffers a kernel may bind on this device.
    pub fn max_storage_buffers(&self) -> u32 {
        self.device.limits().max_storage_buffers_per_shader_stage
    }

    /// Largest storage buffer binding (bytes).
    pub(crate) fn max_binding(&self) -> u64 {
        self.device.limits().max_storage_buffer_binding_size
    }
}
