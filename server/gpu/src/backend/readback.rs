//! Readbacks: copying buffer ranges from the GPU to the CPU, the only places the
//! backend waits for the device.

use super::GpuBackend;
use crate::layout::QuantGrid;
use crate::program::Recorder;
use floe_engine::attrs::PARTICLES;
use floe_engine::backend::{Backend, Particles};
use floe_engine::channels::SetSpec;
use floe_engine::quantize::PositionGrid;
use wgpu::Buffer;

impl GpuBackend {
    /// A set's channels with the particles' positions quantised on `grid` by the
    /// GPU (6 bytes a particle read back instead of 16), where the backend has the
    /// quantiser; other sets, and the parts of the SPH particles, are read whole.
    pub(super) fn read_quantized(&self, set: &SetSpec, channels: &[&str], grid: &PositionGrid) -> Particles {
        let Some(quantize) = self.core.quantize.as_ref().filter(|_| set.space == PARTICLES && set.kind.is_none())
        else {
            return self.read_set(set, channels);
        };
        let b = &self.buffers;
        self.gpu.queue.write_buffer(b.get("quant_grid"), 0, bytemuck::bytes_of(&QuantGrid::from(grid)));
        let encoder =
            self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("quantize") });
        let mut e = Recorder { encoder, timer: None };
        self.gpu.programs.quantize.dispatch(&mut e, quantize, self.n.div_ceil(2));
        self.gpu.queue.submit([e.encoder.finish()]);
        let got = self.download_words(&[(b.get("codes"), 0, 12 * (self.n as u64).div_ceil(2))]);
        let codes: &[u16] = bytemuck::cast_slice(&got[0]);
        let positions =
            codes.chunks_exact(3).take(self.n as usize).map(|c| std::array::from_fn(|k| grid.value(c[k], k))).collect();
        floe_engine::backend::read(self, set, channels, Some(positions))
    }

    /// Copies byte ranges (multiples of 4 bytes) of buffers back to the CPU, one
    /// submission and one wait, as 4-byte words. Panics if the device is lost (a
    /// scene's worker turns that into a halt).
    pub(super) fn download_words(&self, ranges: &[(&Buffer, u64, u64)]) -> Vec<Vec<u32>> {
        self.try_download(ranges).unwrap_or_else(|e| panic!("{e}"))
    }

    /// [`GpuBackend::download_words`], or why the GPU could not deliver.
    pub(super) fn try_download(&self, ranges: &[(&Buffer, u64, u64)]) -> Result<Vec<Vec<u32>>, String> {
        let device = &self.gpu.device;
        let mut e = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("floe readback") });
        let staging: Vec<Buffer> = ranges
            .iter()
            .map(|&(src, offset, size)| {
                let s = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("readback"),
                    size: size.max(4),
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                if size > 0 {
                    e.copy_buffer_to_buffer(src, offset, &s, 0, size);
                }
                s
            })
            .collect();
        self.gpu.queue.submit([e.finish()]);
        let mapped: Vec<(&Buffer, u64)> = staging.iter().zip(ranges).map(|(s, r)| (s, r.2)).collect();
        self.read_mapped(&mapped)
    }

    /// Maps readback buffers written by work already submitted, waits for them,
    /// and copies out their first `len` bytes as words.
    pub(super) fn read_mapped(&self, staging: &[(&Buffer, u64)]) -> Result<Vec<Vec<u32>>, String> {
        let device = &self.gpu.device;
        let (tx, rx) = std::sync::mpsc::channel();
        for (s, _) in staging {
            let tx = tx.clone();
            s.map_async(wgpu::MapMode::Read, .., move |r| {
                let _ = tx.send(r);
            });
        }
        device
            .poll(wgpu::PollType::Wait { submission_index: None, timeout: None })
            .map_err(|e| format!("GPU device failed: {e}"))?;
        for _ in staging {
            rx.recv()
                .map_err(|e| format!("GPU readback lost: {e}"))?
                .map_err(|e| format!("GPU readback failed: {e}"))?;
        }
        staging
            .iter()
            .map(|&(s, len)| {
                let view = s.get_mapped_range(..).map_err(|e| format!("GPU readback failed: {e}"))?;
                let words = bytemuck::cast_slice(&view[..len as usize]).to_vec();
                drop(view);
                s.unmap();
                Ok(words)
            })
            .collect()
    }
}
