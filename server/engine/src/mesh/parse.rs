//! OBJ and STL bytes into a [`TriMesh`] whose triangles share vertices: STL
//! repeats each vertex per facet and OBJ files often repeat positions between
//! groups, so vertices at the same position (bit for bit) are welded into one,
//! which the closure check needs.

use super::TriMesh;
use crate::math::Vec3;
use std::collections::HashMap;

/// Which format the bytes hold, told apart by content (an inline mesh has no name).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    AsciiStl,
    BinaryStl,
    Obj,
}

fn format(bytes: &[u8]) -> Format {
    let head = &bytes[..bytes.len().min(512)];
    let text = String::from_utf8_lossy(head);
    let binary_size = bytes.len() >= 84 && {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        84 + 50 * n == bytes.len()
    };
    if binary_size {
        Format::BinaryStl
    } else if text.trim_start().starts_with("solid") {
        Format::AsciiStl
    } else {
        Format::Obj
    }
}

/// Parses OBJ (every object's faces, triangulated) or STL (ASCII or binary).
pub fn parse(bytes: &[u8]) -> Result<TriMesh, String> {
    let soup: Vec<[Vec3; 3]> = match format(bytes) {
        Format::AsciiStl | Format::BinaryStl => stl(bytes)?,
        Format::Obj => obj(bytes)?,
    };
    if soup.len() > super::MAX_TRIANGLES {
        return Err(format!("{} triangles, more than the limit of {}", soup.len(), super::MAX_TRIANGLES));
    }
    Ok(weld(&soup))
}

fn stl(bytes: &[u8]) -> Result<Vec<[Vec3; 3]>, String> {
    let mesh = stl_io::read_stl(&mut std::io::Cursor::new(bytes)).map_err(|e| format!("not a valid STL file: {e}"))?;
    let vertex = |i: usize| Vec3::from(mesh.vertices[i].0);
    Ok(mesh.faces.iter().map(|f| f.vertices.map(vertex)).collect())
}

fn obj(bytes: &[u8]) -> Result<Vec<[Vec3; 3]>, String> {
    let options =
        tobj::LoadOptions { triangulate: true, ignore_points: true, ignore_lines: true, ..Default::default() };
    let no_materials = |_: &std::path::Path| Err(tobj::LoadError::OpenFileFailed);
    let (models, _) = tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, no_materials)
        .map_err(|e| format!("neither STL nor a valid OBJ file: {e}"))?;
    let mut soup = Vec::new();
    for m in &models {
        let p = &m.mesh.positions;
        let vertex = |i: u32| -> Result<Vec3, String> {
            let i = i as usize * 3;
            p.get(i..i + 3).map(|v| Vec3::new(v[0], v[1], v[2])).ok_or_else(|| format!("a face names vertex {}", i / 3))
        };
        for t in m.mesh.indices.chunks_exact(3) {
            soup.push([vertex(t[0])?, vertex(t[1])?, vertex(t[2])?]);
        }
    }
    Ok(soup)
}

/// One vertex per position.
fn weld(soup: &[[Vec3; 3]]) -> TriMesh {
    let mut index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut vertices = Vec::new();
    let mut id = |v: Vec3| {
        // -0.0 + 0.0 is 0.0: one vertex for both zeros.
        let v = v + Vec3::ZERO;
        *index.entry(v.to_array().map(f32::to_bits)).or_insert_with(|| {
            vertices.push(v);
            (vertices.len() - 1) as u32
        })
    };
    let triangles = soup.iter().map(|t| t.map(&mut id)).collect();
    TriMesh { vertices, triangles }
}
