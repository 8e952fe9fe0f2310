//! A compute kernel: one entry point of a WGSL module with its explicit bind
//! group layout, and how to bind and dispatch it.
//!
//! Layouts are explicit (not derived from the shader) so one layout fits every
//! bind group of a kernel, and a binding a shader stops using is still checked.

use crate::timer::Timer;
use wgpu::{BindGroup, Buffer, CommandEncoder, ComputePipeline, Device};

/// Where passes are recorded: a command encoder, and the timer when profiling.
#[derive(Debug)]
pub struct Recorder {
    pub encoder: CommandEncoder,
    pub timer: Option<Timer>,
}

/// How a kernel sees one binding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// A uniform buffer.
    Uniform,
    /// A read-only storage buffer.
    Read,
    /// A read-write storage buffer.
    ReadWrite,
}

/// The bindings `a` then `b` (a kernel binding another's and more of its own).
pub const fn join<const A: usize, const B: usize, const C: usize>(
    a: [(Access, &'static str); A],
    b: [(Access, &'static str); B],
) -> [(Access, &'static str); C] {
    assert!(A + B == C && A > 0, "join: C must be A + B");
    let mut out = [a[0]; C];
    let mut k = 0;
    while k < C {
        out[k] = if k < A { a[k] } else { b[k - A] };
        k += 1;
    }
    out
}

/// Largest workgroup count per dispatch dimension (WebGPU's guaranteed limit).
const MAX_GROUPS: u32 = 65_535;

/// A bind group layout with its bindings (binding `k` is the `k`-th entry); kernels
/// sharing one accept each other's bind groups.
#[derive(Debug, Clone)]
pub struct Layout {
    layout: wgpu::BindGroupLayout,
    bindings: usize,
}

impl Layout {
    /// The layout of group 0 with `bindings`, numbered from 0.
    pub fn new(device: &Device, label: &'static str, bindings: &[Access]) -> Self {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
            .iter()
            .enumerate()
            .map(|(binding, &access)| wgpu::BindGroupLayoutEntry {
                binding: binding as u32,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: match access {
                        Access::Uniform => wgpu::BufferBindingType::Uniform,
                        Access::Read => wgpu::BufferBindingType::Storage { read_only: true },
                        Access::ReadWrite => wgpu::BufferBindingType::Storage { read_only: false },
                    },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            })
            .collect();
        let layout =
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries: &entries });
        Self { layout, bindings: bindings.len() }
    }
}

/// One entry point with its pipeline and bind group layout.
#[derive(Debug)]
pub struct Kernel {
    label: &'static str,
    pipeline: ComputePipeline,
    layout: Layout,
    workgroup: u32,
}

impl Kernel {
    /// Builds `entry` of `module` on `layout`, with `workgroup` threads per
    /// workgroup (as declared in the shader).
    pub fn new(
        device: &Device,
        module: &wgpu::ShaderModule,
        label: &'static str,
        entry: &'static str,
        layout: &Layout,
        workgroup: u32,
    ) -> Self {
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&layout.layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: Some(&pipeline_layout),
            module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        });
        Self { label, pipeline, layout: layout.clone(), workgroup }
    }

    /// The kernel of a WGSL source with one entry point, `entry`, on its own layout
    /// with `bindings` and workgroups of 128 threads (`WG` in common.wgsl).
    pub fn single(
        device: &Device,
        label: &'static str,
        source: &'static str,
        entry: &'static str,
        bindings: &[Access],
    ) -> Self {
        let m = module(device, label, source);
        Self::new(device, &m, label, entry, &Layout::new(device, label, bindings), 128)
    }

    /// The kernel's label.
    pub fn label(&self) -> &'static str {
        self.label
    }

    /// A bind group with `buffers` in the order of the kernel's bindings.
    pub fn bind(&self, device: &Device, buffers: &[&Buffer]) -> BindGroup {
        assert_eq!(buffers.len(), self.layout.bindings, "{}: wrong number of buffers", self.label);
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .enumerate()
            .map(|(binding, b)| wgpu::BindGroupEntry { binding: binding as u32, resource: b.as_entire_binding() })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(self.label),
            layout: &self.layout.layout,
            entries: &entries,
        })
    }

    /// Records a dispatch of at least `threads` threads (one pass, labelled).
    /// Counts above 65535 workgroups spill into a second dimension, which the
    /// shaders fold back (`thread_index` in common.wgsl).
    pub fn dispatch(&self, rec: &mut Recorder, bind: &BindGroup, threads: u32) {
        let groups = threads.div_ceil(self.workgroup).max(1);
        let (x, y) = if groups > MAX_GROUPS { (MAX_GROUPS, groups.div_ceil(MAX_GROUPS)) } else { (groups, 1) };
        let timestamp_writes = rec.timer.as_mut().and_then(|t| t.next(self.label));
        let mut pass =
            rec.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(self.label), timestamp_writes });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}

/// A shader module from WGSL source, labelled.
pub fn module(device: &Device, label: &'static str, source: &'static str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    })
}
