//! Exclusive prefix sum over the per-cell counts (see scan.wgsl).

use crate::layout::ScanParams;
use crate::program::Access::{ReadWrite as W, Uniform as U};
use crate::program::Recorder;
use crate::program::{Access, Kernel, Layout, module};
use wgpu::util::DeviceExt;
use wgpu::{Buffer, Device};

/// Source of scan.wgsl (stand-alone: it needs no scene constants).
pub const SOURCE: &str = include_str!("scan.wgsl");

/// Values one workgroup scans.
const BLOCK: u32 = 512;
/// Largest array one level can scan (one dispatch dimension of blocks).
pub const MAX_LEN: u64 = 65_535 * BLOCK as u64;

const BINDINGS: &[Access] = &[U, W, W];

/// The scan kernels.
#[derive(Debug)]
pub struct Scan {
    blocks: Kernel,
    add: Kernel,
}

/// The levels of one array's scan: each level's values, block totals and bindings.
#[derive(Debug)]
pub struct ScanPlan {
    levels: Vec<(u32, wgpu::BindGroup)>,
    /// Block totals of every level (bound by `levels`).
    sums: Vec<Buffer>,
}

impl ScanPlan {
    /// Bytes of the block totals.
    pub fn bytes(&self) -> u64 {
        self.sums.iter().map(|b| b.size()).sum()
    }
}

impl Scan {
    pub fn new(device: &Device) -> Self {
        let m = module(device, "scan.wgsl", SOURCE);
        let layout = Layout::new(device, "scan", BINDINGS);
        Self {
            blocks: Kernel::new(device, &m, "scan blocks", "scan_blocks", &layout, 256),
            add: Kernel::new(device, &m, "scan add block sums", "add_block_sums", &layout, 256),
        }
    }

    /// Plans the scan of the first `len` u32 of `data` (`len <= MAX_LEN`).
    pub fn plan(&self, device: &Device, data: &Buffer, len: u32) -> ScanPlan {
        assert!(len as u64 <= MAX_LEN, "scan of {len} values exceeds {MAX_LEN}");
        let mut levels = Vec::new();
        let mut sums = Vec::new();
        let mut len = len;
        loop {
            let blocks = len.div_ceil(BLOCK);
            let totals = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("scan block totals"),
                size: 4 * blocks as u64,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            });
            let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("scan params"),
                contents: bytemuck::bytes_of(&ScanParams { len, _pad: [0; 3] }),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let source = sums.last().unwrap_or(data);
            levels.push((len, self.blocks.bind(device, &[&uniform, source, &totals])));
            sums.push(totals);
            if blocks == 1 {
                break;
            }
            len = blocks;
        }
        ScanPlan { levels, sums }
    }

    /// Records the scan: blocks of every level up, then block offsets back down.
    pub fn record(&self, rec: &mut Recorder, plan: &ScanPlan) {
        for (len, bind) in &plan.levels {
            self.blocks.dispatch(rec, bind, len.div_ceil(2));
        }
        for (len, bind) in plan.levels.iter().rev().skip(1) {
            self.add.dispatch(rec, bind, *len);
        }
    }
}
