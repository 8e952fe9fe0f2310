//! CSV: a header row naming the columns (`id,x,y,z,vx,vy,vz,density,pressure`,
//! as far as the channels are present), then one particle per row.

use super::scalars;
use crate::backend::Particles;
use std::io::{Result, Write};

/// Writes `p` as CSV.
pub fn write_csv(out: &mut impl Write, p: &Particles) -> Result<()> {
    let scalars = scalars(p);
    let mut header = String::from("id,x,y,z");
    if p.velocities.is_some() {
        header += ",vx,vy,vz";
    }
    for (name, _) in &scalars {
        header += ",";
        header += name;
    }
    writeln!(out, "{header}")?;
    for (i, x) in p.positions.iter().enumerate() {
        write!(out, "{i},{},{},{}", x[0], x[1], x[2])?;
        if let Some(v) = &p.velocities {
            write!(out, ",{},{},{}", v[i][0], v[i][1], v[i][2])?;
        }
        for (_, values) in &scalars {
            write!(out, ",{}", values[i])?;
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
            positions: vec![[1.0, 2.0, 3.0]],
            velocities: Some(vec![[0.5, 0.0, -0.5]]),
            densities: Some(vec![1000.0]),
            pressures: Some(vec![20.5]),
        };
        let mut buf = Vec::new();
        write_csv(&mut buf, &p).unwrap();
        assert_eq!(
            String::from_utf8(buf).unwrap(),
            "id,x,y,z,vx,vy,vz,density,pressure\n0,1,2,3,0.5,0,-0.5,1000,20.5\n"
        );
    }
}
