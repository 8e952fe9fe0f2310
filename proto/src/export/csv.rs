//! CSV: a header row naming the columns (`id,x,y,z`, then each channel's components:
//! `velocity_x,velocity_y,velocity_z,density,...`), then one particle per row.

use super::component_names;
use crate::frame::Values;
use crate::particles::Particles;
use std::io::{Result, Write};

/// Writes `p` as CSV.
pub fn write_csv(out: &mut impl Write, p: &Particles) -> Result<()> {
    let mut header = String::from("id,x,y,z");
    for (name, values) in &p.channels {
        for column in component_names(name, values.components()) {
            header += ",";
            header += &column;
        }
    }
    writeln!(out, "{header}")?;
    for (i, x) in p.positions.iter().enumerate() {
        write!(out, "{},{},{},{}", p.id(i), x[0], x[1], x[2])?;
        for (_, values) in &p.channels {
            match values {
                Values::Exact(v) => write!(out, ",{}", v[i])?,
                Values::Float { .. } => {
                    for c in values.get(i) {
                        write!(out, ",{c}")?;
                    }
                }
            }
        }
        writeln!(out)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_names_the_columns() {
        let p = Particles {
            set: "particles".into(),
            positions: vec![[1.0, 2.0, 3.0]],
            channels: vec![
                ("velocity".into(), Values::vectors(vec![[0.5, 0.0, -0.5]])),
                ("density".into(), Values::scalars(vec![1000.0])),
                ("material".into(), Values::Exact(vec![2])),
            ],
            grid: None,
            ids: None,
        };
        let mut buf = Vec::new();
        write_csv(&mut buf, &p).unwrap();
        assert_eq!(
            String::from_utf8(buf).unwrap(),
            "id,x,y,z,velocity_x,velocity_y,velocity_z,density,material\n0,1,2,3,0.5,0,-0.5,1000,2\n"
        );
    }
}
