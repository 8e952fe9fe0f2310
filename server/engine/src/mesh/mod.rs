//! Bodies from triangle meshes: OBJ and STL (ASCII or binary), read by the crates
//! of the field (`tobj`, `stl_io`), checked to be closed and outward-facing, and
//! filled with particles on the lattice the blocks use or by Poisson-disk sampling.
//!
//! A scene names a mesh as an asset of the server's `--assets` directory (a plain
//! file name, read into the scene at creation so the scene never depends on the
//! file again), inline as base64, or as one of the meshes built into the server
//! ([`BUILTIN`]: the Stanford bunny) ([`MeshSource`]); the mesh is scaled uniformly
//! and centred to fit the box it fills. What is refused, each naming the file:
//! a file over [`MAX_MESH_BYTES`] or [`MAX_TRIANGLES`], one neither format parses,
//! a coordinate that is not finite, a mesh without volume, an open mesh (an edge
//! not shared by exactly two triangles running along it in opposite directions)
//! and an inverted one (its triangles facing inwards: negative volume).
//!
//! - [`parse`]: the formats into a welded [`TriMesh`].
//! - [`fill`]: the particles inside, by crossings of lattice rows with the mesh.
//! - [`poisson`]: or Poisson-disk sampled inside (Bridson 2007), `fill = "poisson"`.

pub mod fill;
pub mod parse;
pub mod poisson;

use crate::math::{Aabb, Real, Vec3};
use crate::scene::validate::Checker;
use base64::Engine as _;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::path::Path;

/// Largest mesh file (bytes, 16 MiB).
pub const MAX_MESH_BYTES: usize = 16 << 20;
/// Most triangles a mesh may have.
pub const MAX_TRIANGLES: usize = 1 << 20;

/// The meshes built into the server, by name, with where they come from.
pub const BUILTIN: &[(&str, &str)] = &[("bunny", include_str!("../../data/bunny.obj"))];

/// A mesh a scene names: exactly one of `asset`, `data_base64` and `builtin`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshSource {
    /// A file in the server's assets directory (`--assets DIR`): a plain name
    /// ending in `.obj` or `.stl`, read into `data_base64` when the scene is created.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub asset: Option<String>,
    /// The file's bytes, base64 (OBJ or STL, told apart by their content).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub data_base64: Option<String>,
    /// A mesh built into the server, by name: `bunny` (the Stanford bunny, 1839
    /// vertices, 3674 triangles; Stanford 3D Scanning Repository, public domain as
    /// the npm package `bunny` ships it). Scenes stay small: the mesh is not copied in.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub builtin: Option<String>,
    /// The name errors give the file (the asset's name, kept when it is read in).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// How the mesh is filled: `lattice` (default, the block's lattice points inside)
    /// or `poisson` (Poisson-disk sampled, Bridson 2007: about as many particles, in no
    /// rows; see [`poisson`]).
    #[serde(default, skip_serializing_if = "MeshFill::is_lattice")]
    pub fill: MeshFill,
}

/// How a mesh is filled with particles.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MeshFill {
    /// The lattice points inside, as a block's.
    #[default]
    Lattice,
    /// Poisson-disk samples inside, no two closer than
    /// [`poisson::RADIUS_PER_SPACING`] spacings.
    Poisson,
}

impl MeshFill {
    /// Whether it is the default (scene files may leave it out).
    pub fn is_lattice(&self) -> bool {
        *self == MeshFill::Lattice
    }
}

impl MeshSource {
    /// The name errors call the mesh by.
    pub fn name(&self) -> &str {
        self.file.as_deref().or(self.asset.as_deref()).or(self.builtin.as_deref()).unwrap_or("inline mesh")
    }

    /// The mesh, decoded and checked; errors name the file.
    pub fn load(&self) -> Result<TriMesh, String> {
        let name = self.name();
        if let Some(b) = &self.builtin {
            return TriMesh::from_bytes(builtin(b)?.as_bytes()).map_err(|e| format!("{name}: {e}"));
        }
        let Some(text) = &self.data_base64 else {
            return Err(match &self.asset {
                Some(a) => format!("asset {a:?} was not read: scenes naming an asset load with an assets directory"),
                None => "give exactly one of asset, data_base64 and builtin".into(),
            });
        };
        if text.len() / 4 * 3 > MAX_MESH_BYTES + 3 {
            return Err(format!("{name}: more than the limit of {MAX_MESH_BYTES} bytes (16 MiB)"));
        }
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(text)
            .map_err(|e| format!("{name}: data_base64 is not base64: {e}"))?;
        TriMesh::from_bytes(&bytes).map_err(|e| format!("{name}: {e}"))
    }
}

/// Checks a mesh a scene names under `path`: a decoded one fully; one still named
/// as an asset by its name only (it is read and checked when the scene is created,
/// [`read_assets`]).
pub fn validate(c: &mut Checker, path: &str, mesh: &MeshSource) {
    let given = [mesh.asset.is_some(), mesh.data_base64.is_some(), mesh.builtin.is_some()];
    if given.iter().filter(|g| **g).count() != 1 {
        return c.fail(path, "give exactly one of asset, data_base64 and builtin".into());
    }
    match (&mesh.asset, &mesh.builtin) {
        (_, Some(name)) => {
            if let Err(e) = builtin(name) {
                c.fail(&format!("{path}.builtin"), e);
            }
        }
        (Some(name), None) => {
            if let Err(e) = asset_name(name) {
                c.fail(&format!("{path}.asset"), e);
            }
        }
        (None, None) => {
            if let Err(e) = mesh.load() {
                c.fail(path, e);
            }
        }
    }
}

/// The OBJ text of the built-in mesh `name`.
fn builtin(name: &str) -> Result<&'static str, String> {
    BUILTIN.iter().find(|(n, _)| *n == name).map(|(_, text)| *text).ok_or_else(|| {
        let names: Vec<&str> = BUILTIN.iter().map(|(n, _)| *n).collect();
        format!("no built-in mesh named {name:?} (there are: {names:?})")
    })
}

/// A plain file name ending in `.obj` or `.stl`.
fn asset_name(name: &str) -> Result<(), String> {
    if !crate::terrain::spec::plain_name(name) {
        return Err(format!(
            "must be a plain file name in the server's assets directory (no '/', '\\', '..' or absolute path), got {name:?}"
        ));
    }
    let lower = name.to_ascii_lowercase();
    if !(lower.ends_with(".obj") || lower.ends_with(".stl")) {
        return Err(format!("must name an .obj or .stl file, got {name:?}"));
    }
    Ok(())
}

/// Reads every mesh asset the scene's sections name (an object under a `mesh` key
/// with an `asset`) from the assets directory `dir` into the scene (`data_base64`,
/// keeping the name in `file`), checking each; errors name the field and the file.
pub fn read_assets(scene: &mut crate::scene::Scene, dir: Option<&Path>) -> Result<(), Vec<String>> {
    let mut errors = Vec::new();
    for (key, value) in scene.sections.iter_mut() {
        read_in(value, key.to_owned(), dir, &mut errors);
    }
    if errors.is_empty() { Ok(()) } else { Err(errors) }
}

fn read_in(value: &mut Value, path: String, dir: Option<&Path>, errors: &mut Vec<String>) {
    match value {
        Value::Array(items) => {
            for (i, v) in items.iter_mut().enumerate() {
                read_in(v, format!("{path}[{i}]"), dir, errors);
            }
        }
        Value::Object(fields) => {
            for (k, v) in fields.iter_mut() {
                let here = format!("{path}.{k}");
                match v {
                    Value::Object(mesh) if k == "mesh" => {
                        if let Err(e) = read_one(mesh, dir) {
                            errors.push(format!("{here}.asset: {e}"));
                        }
                    }
                    _ => read_in(v, here, dir, errors),
                }
            }
        }
        _ => {}
    }
}

fn read_one(mesh: &mut serde_json::Map<String, Value>, dir: Option<&Path>) -> Result<(), String> {
    let Some(Value::String(name)) = mesh.get("asset").cloned() else { return Ok(()) };
    asset_name(&name)?;
    let dir = dir.ok_or_else(|| format!("{name:?}: no assets directory was given (--assets DIR)"))?;
    let path = dir.join(&name);
    let meta = std::fs::metadata(&path).map_err(|_| format!("no asset named {name:?} in the assets directory"))?;
    if !meta.is_file() {
        return Err(format!("asset {name:?} is not a file"));
    }
    if meta.len() > MAX_MESH_BYTES as u64 {
        return Err(format!("{name}: {} bytes, more than the limit of {MAX_MESH_BYTES} (16 MiB)", meta.len()));
    }
    let bytes = std::fs::read(&path).map_err(|e| format!("cannot read asset {name:?}: {e}"))?;
    TriMesh::from_bytes(&bytes).map_err(|e| format!("{name}: {e}"))?;
    mesh.remove("asset");
    mesh.insert("data_base64".into(), Value::String(base64::engine::general_purpose::STANDARD.encode(bytes)));
    mesh.insert("file".into(), Value::String(name));
    Ok(())
}

/// A closed, outward-facing triangle mesh with shared vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct TriMesh {
    /// Vertex positions (the file's units).
    pub vertices: Vec<Vec3>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// Parses OBJ or STL bytes and checks the mesh (errors say what is wrong,
    /// without the file's name).
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        if bytes.len() > MAX_MESH_BYTES {
            return Err(format!("{} bytes, more than the limit of {MAX_MESH_BYTES} (16 MiB)", bytes.len()));
        }
        let mesh = parse::parse(bytes)?;
        mesh.check()?;
        Ok(mesh)
    }

    /// The box around the vertices.
    pub fn bounds(&self) -> Aabb {
        let first = Aabb::new(self.vertices[0], self.vertices[0]);
        self.vertices.iter().fold(first, |b, &v| b.union(Aabb::new(v, v)))
    }

    /// The enclosed volume (divergence theorem, summed in f64): positive when the
    /// triangles face outwards.
    pub fn volume(&self) -> f64 {
        let sum: f64 = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices[i as usize].as_dvec3());
                a.dot(b.cross(c))
            })
            .sum();
        sum / 6.0
    }

    /// Checks finiteness, size, closure (each directed edge once, its reverse once)
    /// and orientation (positive volume).
    fn check(&self) -> Result<(), String> {
        if self.triangles.is_empty() {
            return Err("no triangles".into());
        }
        if self.triangles.len() > MAX_TRIANGLES {
            return Err(format!("{} triangles, more than the limit of {MAX_TRIANGLES}", self.triangles.len()));
        }
        if let Some(v) = self.vertices.iter().find(|v| !v.is_finite()) {
            return Err(format!("a vertex is not finite: {v}"));
        }
        let mut edges: std::collections::HashMap<(u32, u32), u32> = std::collections::HashMap::new();
        for t in &self.triangles {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *edges.entry((a, b)).or_default() += 1;
            }
        }
        let open = edges.iter().filter(|&(&(a, b), &n)| n != 1 || edges.get(&(b, a)) != Some(&1)).count();
        if open > 0 {
            return Err(format!(
                "not a closed surface: {open} edges are not shared by exactly two triangles running along them in \
                 opposite directions (an open or inconsistently oriented mesh)"
            ));
        }
        let volume = self.volume();
        let scale = self.bounds().size().as_dvec3();
        if volume.abs() <= 1e-9 * scale.x * scale.y * scale.z {
            return Err("encloses no volume".into());
        }
        if volume < 0.0 {
            return Err(format!(
                "inverted: its triangles face inwards (volume {volume:.4e}); reverse their vertex order"
            ));
        }
        Ok(())
    }

    /// The mesh scaled uniformly and centred to fit inside `target`.
    pub fn fitted(&self, target: Aabb) -> TriMesh {
        let b = self.bounds();
        let size = b.size();
        let room = target.size();
        let scale = (room.x / size.x).min(room.y / size.y).min(room.z / size.z);
        let (from, to) = ((b.min + b.max) * 0.5, (target.min + target.max) * 0.5);
        TriMesh {
            vertices: self.vertices.iter().map(|&v| to + (v - from) * scale).collect(),
            triangles: self.triangles.clone(),
        }
    }

    /// Particle centres inside the mesh on the lattice of `spacing` that fills
    /// `lattice` (the lattice [`crate::sampling::fill_box`] puts in that box).
    pub fn fill(&self, lattice: Aabb, spacing: Real) -> Vec<Vec3> {
        fill::inside_lattice(self, lattice, spacing)
    }

    /// Particle centres inside the mesh as `how` places them for `spacing` (the
    /// Poisson-disk samples from a fixed seed: a scene always gets the same ones).
    pub fn fill_with(&self, how: MeshFill, lattice: Aabb, spacing: Real) -> Vec<Vec3> {
        match how {
            MeshFill::Lattice => self.fill(lattice, spacing),
            MeshFill::Poisson => poisson::inside(self, spacing * poisson::RADIUS_PER_SPACING, 2007),
        }
    }
}

#[cfg(test)]
mod tests;
