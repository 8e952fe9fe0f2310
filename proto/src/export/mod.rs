//! Writing particle state to files for ParaView (VTK) and spreadsheets (CSV), with
//! every channel the particles carry.

mod csv;
mod vtk;

pub use csv::write_csv;
pub use vtk::write_vtk;

use crate::particles::Particles;

/// File formats of exports.
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

/// The file of frame `k` of set `set` in a series of exported frames: the SPH
/// particles' `frame_00007.vtk`, another set's named after it (`solid_00007.vtk`,
/// any character but a letter, digit, `-` or `_` written `_`), so each set is a
/// series of its own in ParaView.
pub fn file_name(set: &str, k: usize, format: Format) -> String {
    let series: String = match set {
        "particles" => "frame".into(),
        _ => set.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' }).collect(),
    };
    format!("{series}_{k:05}.{}", format.extension())
}

/// Writes `particles` in `format` to `path`; `time` (s) goes in the VTK title.
pub fn write(path: &std::path::Path, format: Format, particles: &Particles, time: f64) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    match format {
        Format::Vtk => write_vtk(&mut out, particles, time)?,
        Format::Csv => write_csv(&mut out, particles)?,
    }
    std::io::Write::flush(&mut out)
}

/// Column names of a channel's components: the name itself for one component, else
/// `name_x`, `name_y`, `name_z`, `name_w`.
fn component_names(name: &str, components: u8) -> Vec<String> {
    match components {
        1 => vec![name.to_string()],
        c => ["x", "y", "z", "w"].iter().take(usize::from(c)).map(|axis| format!("{name}_{axis}")).collect(),
    }
}
