//! Writing particle state to files for ParaView (VTK) and spreadsheets (CSV).

mod csv;
mod vtk;

pub use csv::write_csv;
pub use vtk::write_vtk;

use crate::backend::Particles;

/// File formats of `floe run --export`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Legacy VTK polydata, binary (opens in ParaView).
    Vtk,
    /// Comma-separated values with a header row.
    Csv,
}

impl Format {
    /// File extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Vtk => "vtk",
            Format::Csv => "csv",
        }
    }
}

/// Writes `particles` in `format` to `path`.
pub fn write(path: &std::path::Path, format: Format, particles: &Particles, time: f64) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    match format {
        Format::Vtk => write_vtk(&mut out, particles, time)?,
        Format::Csv => write_csv(&mut out, particles)?,
    }
    std::io::Write::flush(&mut out)
}

/// Scalar channels present in `p`, as (name, values).
fn scalars(p: &Particles) -> Vec<(&'static str, &[f32])> {
    [("density", &p.densities), ("pressure", &p.pressures)]
        .into_iter()
        .filter_map(|(n, v)| v.as_deref().map(|v| (n, v)))
        .collect()
}
