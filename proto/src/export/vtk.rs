//! Legacy VTK (version 3.0) binary polydata: one vertex per particle, point data
//! `id` and every channel (three components as VECTORS, others as SCALARS).
//! Binary legacy VTK is big-endian.

use crate::frame::Values;
use crate::particles::Particles;
use std::io::{Result, Write};

fn be_floats(out: &mut impl Write, values: impl Iterator<Item = f32>) -> Result<()> {
    for v in values {
        out.write_all(&v.to_be_bytes())?;
    }
    writeln!(out)
}

/// Writes `p` as a legacy binary VTK polydata file; `time` goes in the title.
pub fn write_vtk(out: &mut impl Write, p: &Particles, time: f64) -> Result<()> {
    let n = p.positions.len();
    writeln!(out, "# vtk DataFile Version 3.0")?;
    writeln!(out, "floe {} t={time:.6} s", p.set)?;
    writeln!(out, "BINARY\nDATASET POLYDATA\nPOINTS {n} float")?;
    be_floats(out, p.positions.iter().flatten().copied())?;
    writeln!(out, "VERTICES {n} {}", 2 * n)?;
    for i in 0..n as u32 {
        out.write_all(&1u32.to_be_bytes())?;
        out.write_all(&i.to_be_bytes())?;
    }
    writeln!(out)?;
    writeln!(out, "POINT_DATA {n}\nSCALARS id int 1\nLOOKUP_TABLE default")?;
    for i in 0..n {
        out.write_all(&p.id(i).to_be_bytes())?;
    }
    writeln!(out)?;
    for (name, values) in &p.channels {
        // VTK names may not contain spaces.
        let name = name.replace(' ', "_");
        match values {
            Values::Float { components: 3, data } => {
                writeln!(out, "VECTORS {name} float")?;
                be_floats(out, data.iter().copied())?;
            }
            Values::Float { components, data } => {
                writeln!(out, "SCALARS {name} float {components}\nLOOKUP_TABLE default")?;
                be_floats(out, data.iter().copied())?;
            }
            Values::Exact(v) => {
                writeln!(out, "SCALARS {name} unsigned_char 1\nLOOKUP_TABLE default")?;
                out.write_all(v)?;
                writeln!(out)?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_and_sizes_are_consistent() {
        let p = Particles {
            set: "particles".into(),
            positions: vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]],
            channels: vec![
                ("velocity".into(), Values::vectors(vec![[0.5; 3]; 2])),
                ("density".into(), Values::scalars(vec![1000.0, 1001.0])),
                ("material".into(), Values::Exact(vec![0, 1])),
            ],
            grid: None,
            ids: None,
        };
        let mut buf = Vec::new();
        write_vtk(&mut buf, &p, 0.25).unwrap();
        let text = String::from_utf8_lossy(&buf);
        assert!(text.starts_with("# vtk DataFile Version 3.0\nfloe particles t=0.250000 s\nBINARY\n"));
        assert!(text.contains("POINTS 2 float\n"));
        assert!(text.contains("VECTORS velocity float\n"));
        assert!(text.contains("SCALARS density float 1\n"));
        assert!(text.contains("SCALARS material unsigned_char 1\nLOOKUP_TABLE default\n\u{0}\u{1}\n"));
        assert!(!text.contains("pressure"));
        // The first point follows the POINTS line as 3 big-endian f32.
        let at = buf.windows(15).position(|w| w == b"POINTS 2 float\n").unwrap() + 15;
        assert_eq!(f32::from_be_bytes(buf[at + 4..at + 8].try_into().unwrap()), 2.0);
        // 24 bytes of points + newline, then VERTICES.
        assert!(buf[at + 25..].starts_with(b"VERTICES 2 4\n"));
    }
}
