//! GPU time per kernel from timestamp queries (`floe bench --backend gpu
//! --profile`): each compute pass writes a timestamp at its start and end; after
//! every submission the timestamps are resolved, read back and added to the
//! kernel's total. Only when profiling: the readback costs a wait per submission.

use wgpu::{Buffer, CommandEncoder, ComputePassTimestampWrites, Device, QuerySet};

/// Passes one submission may time.
const CAPACITY: u32 = 64;

/// Timestamps of the passes recorded since the last resolve, and the totals.
#[derive(Debug)]
pub struct Timer {
    set: QuerySet,
    resolve: Buffer,
    /// Labels of the passes recorded, in query order (pass k: queries 2k, 2k+1).
    recorded: Vec<&'static str>,
    /// Per kernel: seconds and dispatches.
    totals: Vec<(&'static str, f64, u64)>,
    /// Nanoseconds per timestamp tick.
    period_ns: f64,
}

impl Timer {
    /// A timer on `device`, whose queue counts `period_ns` per tick.
    pub fn new(device: &Device, period_ns: f32) -> Self {
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("kernel timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2 * CAPACITY,
        });
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("kernel timestamps resolved"),
            size: 16 * CAPACITY as u64,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Self { set, resolve, recorded: Vec::new(), totals: Vec::new(), period_ns: period_ns as f64 }
    }

    /// Timestamp writes for the next pass, labelled `label`; `None` when full.
    pub fn next(&mut self, label: &'static str) -> Option<ComputePassTimestampWrites<'_>> {
        let k = self.recorded.len() as u32;
        if k == CAPACITY {
            return None;
        }
        self.recorded.push(label);
        Some(ComputePassTimestampWrites {
            query_set: &self.set,
            beginning_of_pass_write_index: Some(2 * k),
            end_of_pass_write_index: Some(2 * k + 1),
        })
    }

    /// Records the resolve of this submission's timestamps; returns the buffer
    /// and byte length to read back after the submission, if any were written.
    pub fn resolve(&self, encoder: &mut CommandEncoder) -> Option<(&Buffer, u64)> {
        let k = self.recorded.len() as u32;
        if k == 0 {
            return None;
        }
        encoder.resolve_query_set(&self.set, 0..2 * k, &self.resolve, 0);
        Some((&self.resolve, 16 * k as u64))
    }

    /// Adds the resolved timestamps (pairs of u64 ticks, as u32 words) to the totals.
    pub fn add(&mut self, words: &[u32]) {
        let ticks: Vec<u64> = words.chunks_exact(2).map(|w| w[0] as u64 | (w[1] as u64) << 32).collect();
        for (label, pair) in self.recorded.drain(..).zip(ticks.chunks_exact(2)) {
            let seconds = pair[1].saturating_sub(pair[0]) as f64 * self.period_ns * 1e-9;
            match self.totals.iter_mut().find(|t| t.0 == label) {
                Some(t) => (t.1, t.2) = (t.1 + seconds, t.2 + 1),
                None => self.totals.push((label, seconds, 1)),
            }
        }
    }

    /// Per kernel: label, total GPU seconds, dispatches.
    pub fn totals(&self) -> &[(&'static str, f64, u64)] {
        &self.totals
    }
}
