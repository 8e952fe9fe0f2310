use super::*;
use std::fmt::Write as _;

/// A torus (major radius 1, minor 0.4), `u` x `v` quads split in two, facing out.
pub(crate) fn torus(u: usize, v: usize) -> TriMesh {
    let mut vertices = Vec::new();
    for i in 0..u {
        for j in 0..v {
            let (a, b) = (std::f32::consts::TAU * i as f32 / u as f32, std::f32::consts::TAU * j as f32 / v as f32);
            let r = 1.0 + 0.4 * b.cos();
            vertices.push(Vec3::new(r * a.cos(), 0.4 * b.sin(), r * a.sin()));
        }
    }
    let at = |i: usize, j: usize| ((i % u) * v + j % v) as u32;
    let mut triangles = Vec::new();
    for i in 0..u {
        for j in 0..v {
            let (p, q, r, s) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            triangles.push([p, r, q]);
            triangles.push([p, s, r]);
        }
    }
    TriMesh { vertices, triangles }
}

pub(crate) fn obj_text(m: &TriMesh) -> String {
    let mut s = String::from("# a test mesh\no body\n");
    for v in &m.vertices {
        writeln!(s, "v {} {} {}", v.x, v.y, v.z).unwrap();
    }
    for t in &m.triangles {
        writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1).unwrap();
    }
    s
}

fn binary_stl(m: &TriMesh) -> Vec<u8> {
    let mut out = vec![0u8; 80];
    out.extend((m.triangles.len() as u32).to_le_bytes());
    for t in &m.triangles {
        out.extend([0f32; 3].iter().flat_map(|c| c.to_le_bytes()));
        for &i in t {
            out.extend(m.vertices[i as usize].to_array().iter().flat_map(|c| c.to_le_bytes()));
        }
        out.extend([0u8; 2]);
    }
    out
}

fn ascii_stl(m: &TriMesh) -> String {
    let mut s = String::from("solid body\n");
    for t in &m.triangles {
        s.push_str("facet normal 0 0 0\nouter loop\n");
        for &i in t {
            let v = m.vertices[i as usize];
            writeln!(s, "vertex {} {} {}", v.x, v.y, v.z).unwrap();
        }
        s.push_str("endloop\nendfacet\n");
    }
    s + "endsolid body\n"
}

fn source(name: &str, bytes: &[u8]) -> MeshSource {
    MeshSource {
        asset: None,
        data_base64: Some(base64::engine::general_purpose::STANDARD.encode(bytes)),
        builtin: None,
        file: Some(name.into()),
        fill: MeshFill::Lattice,
    }
}

#[test]
fn obj_and_both_stl_forms_give_the_same_closed_mesh() {
    let t = torus(48, 24);
    let want = t.volume();
    for (name, bytes) in
        [("t.obj", obj_text(&t).into_bytes()), ("t.stl", binary_stl(&t)), ("t_ascii.stl", ascii_stl(&t).into_bytes())]
    {
        let m = source(name, &bytes).load().unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((m.vertices.len(), m.triangles.len()), (48 * 24, 2 * 48 * 24), "{name}");
        assert!((m.volume() - want).abs() < 1e-6 * want, "{name}: {} against {want}", m.volume());
    }
}

/// Particle counts within 2 % of volume / spacing^3 at three resolutions, for a
/// mesh with a hole through it (a row crosses it four times).
#[test]
fn a_closed_mesh_fills_with_its_volume_over_the_spacing_cubed() {
    let t = torus(96, 48);
    let volume = t.volume();
    let exact = 2.0 * std::f64::consts::PI.powi(2) * 1.0 * 0.4f64.powi(2);
    assert!((volume - exact).abs() < 0.01 * exact, "the polyhedron's volume {volume} against the torus' {exact}");
    let b = t.bounds();
    let lattice = Aabb::new(b.min - Vec3::splat(0.1), b.max + Vec3::splat(0.1));
    for spacing in [0.05f32, 0.04, 0.03] {
        let points = t.fill(lattice, spacing);
        let want = volume / (spacing as f64).powi(3);
        let off = (points.len() as f64 - want).abs() / want;
        assert!(
            off < 0.02,
            "spacing {spacing}: {} particles, volume / spacing^3 = {want:.0} ({:.2} %)",
            points.len(),
            off * 100.0
        );
        // The hole stays empty and every point is in the tube.
        for p in &points {
            let ring = (p.x * p.x + p.z * p.z).sqrt() - 1.0;
            assert!(ring * ring + p.y * p.y < (0.4 + spacing) * (0.4 + spacing), "{p} outside the tube");
        }
    }
}

#[test]
fn a_mesh_fits_its_box_scaled_uniformly() {
    let t = torus(24, 12);
    let target = Aabb::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 4.0));
    let f = t.fitted(target).bounds();
    assert!((f.size().x - 1.0).abs() < 1e-5, "the narrowest side fills: {f:?}");
    assert!((f.size().y - 0.4 / 1.4 * 1.0).abs() < 1e-5, "aspect kept: {f:?}");
    assert!(f.min.cmpge(target.min - 1e-5).all() && f.max.cmple(target.max + 1e-5).all(), "{f:?}");
}

#[test]
fn bad_meshes_are_refused_naming_the_file_and_the_fault() {
    let t = torus(12, 6);
    let err = |name: &str, bytes: &[u8]| source(name, bytes).load().unwrap_err();
    let mut open = t.clone();
    open.triangles.pop();
    let e = err("open.obj", obj_text(&open).as_bytes());
    assert!(e.starts_with("open.obj: not a closed surface: 3 edges"), "{e}");
    let mut inverted = t.clone();
    inverted.triangles.iter_mut().for_each(|t| t.swap(1, 2));
    let e = err("inside_out.stl", &binary_stl(&inverted));
    assert!(e.starts_with("inside_out.stl: inverted: its triangles face inwards"), "{e}");
    let e = err("garbage.obj", b"v 1 2\nf 1 2 x\n\x00\x01");
    assert!(e.starts_with("garbage.obj: "), "{e}");
    let e = err("empty.obj", b"# nothing\n");
    assert_eq!(e, "empty.obj: no triangles");
    let mut nan = t.clone();
    nan.vertices[0].x = f32::NAN;
    let e = err("nan.stl", &binary_stl(&nan));
    assert!(e.starts_with("nan.stl: a vertex is not finite"), "{e}");
    let huge = vec![b' '; MAX_MESH_BYTES + 1];
    let e = err("huge.stl", &huge);
    assert_eq!(e, "huge.stl: 16777217 bytes, more than the limit of 16777216 (16 MiB)");
    let e = MeshSource {
        asset: Some("a.obj".into()),
        data_base64: None,
        builtin: None,
        file: None,
        fill: MeshFill::Lattice,
    }
    .load()
    .unwrap_err();
    assert!(e.contains("scenes naming an asset load with an assets directory"), "{e}");
}

/// A scene whose fluid block is `mesh` (a field as the scene file spells it).
fn scene_with(mesh: serde_json::Value) -> Result<crate::scene::Scene, crate::scene::load::SceneError> {
    let block = serde_json::json!({"min": [0, 0, 0], "max": [1.4, 0.4, 1.4], "mesh": mesh});
    let overrides = vec![
        "particle_spacing=0.04".to_string(),
        format!("fluids[0].blocks={}", serde_json::json!([block])),
        "boundaries=[]".into(),
        r#"domain={"min":[-1,-1,-1],"max":[3,2,3]}"#.into(),
    ];
    crate::scene::load::from_preset("hydrostatic", &overrides)
}

/// A fluid block shaped by a mesh, inline and as an asset of the assets directory:
/// the particles fill the fitted mesh's volume, and the scene steps.
#[test]
fn a_fluid_block_may_be_a_mesh_inline_or_an_asset() {
    let t = torus(48, 24);
    let text = obj_text(&t);
    let inline = scene_with(serde_json::json!({
        "data_base64": base64::engine::general_purpose::STANDARD.encode(&text)
    }))
    .unwrap();
    let mut sim = crate::Simulation::new_cpu(inline.clone()).unwrap();
    // The torus (2.8 x 0.8 x 2.8) fits the block at half its size.
    let want = t.volume() * 0.125 / 0.04f64.powi(3);
    let n = sim.particle_count() as f64;
    assert!((n - want).abs() < 0.03 * want, "{n} particles, volume / spacing^3 = {want:.0}");
    sim.step().unwrap();
    // Poisson-disk filled: about as many particles, and the scene steps.
    let poisson = scene_with(serde_json::json!({
        "data_base64": base64::engine::general_purpose::STANDARD.encode(&text),
        "fill": "poisson"
    }))
    .unwrap();
    let mut sim = crate::Simulation::new_cpu(poisson).unwrap();
    let p = sim.particle_count() as f64;
    assert!((p - want).abs() < 0.05 * want, "poisson: {p} particles, volume / spacing^3 = {want:.0}");
    assert_ne!(p, n, "not the lattice's points");
    sim.step().unwrap();

    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("ring.obj"), &text).unwrap();
    std::fs::write(dir.path().join("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let named = scene_with(serde_json::json!({"asset": "ring.obj"})).unwrap();
    let read = crate::scene::load::with_assets(named, Some(dir.path())).unwrap();
    let sim = crate::Simulation::new_cpu(read.clone()).unwrap();
    assert_eq!(sim.particle_count() as f64, n, "the asset fills as the inline mesh does");
    let document = serde_json::to_value(&read).unwrap();
    let mesh: MeshSource = serde_json::from_value(document["fluids"][0]["blocks"][0]["mesh"].clone()).unwrap();
    assert_eq!((mesh.asset.as_deref(), mesh.file.as_deref()), (None, Some("ring.obj")), "read into the scene");

    let refused = |asset: &str| {
        let scene = scene_with(serde_json::json!({ "asset": asset }));
        let err = scene.and_then(|s| crate::scene::load::with_assets(s, Some(dir.path()))).unwrap_err();
        err.to_string()
    };
    let e = refused("open.obj");
    assert!(e.contains("fluids[0].blocks[0].mesh.asset: open.obj: not a closed surface"), "{e}");
    let e = refused("../ring.obj");
    assert!(e.contains("fluids[0].blocks[0].mesh.asset: must be a plain file name"), "{e}");
    let e = refused("missing.stl");
    assert!(e.contains("no asset named \"missing.stl\""), "{e}");
    let e = refused("ring.png");
    assert!(e.contains("must name an .obj or .stl file"), "{e}");
    let e = scene_with(serde_json::json!({"data_base64": "bm90IGEgbWVzaA=="})).unwrap_err().to_string();
    assert!(e.contains("fluids[0].blocks[0].mesh: inline mesh: "), "{e}");
    let e = scene_with(serde_json::json!({"builtin": "teapot"})).unwrap_err().to_string();
    assert!(
        e.contains("fluids[0].blocks[0].mesh.builtin: no built-in mesh named \"teapot\" (there are: [\"bunny\"])"),
        "{e}"
    );
    let e = scene_with(serde_json::json!({"builtin": "bunny", "asset": "a.obj"})).unwrap_err().to_string();
    assert!(e.contains("fluids[0].blocks[0].mesh: give exactly one of asset, data_base64 and builtin"), "{e}");
}

/// The built-in bunny is a closed, outward-facing mesh, its volume 0.27 of its
/// bounding box (the Stanford bunny's), y up.
#[test]
fn the_builtin_bunny_is_closed_and_outward() {
    let m = MeshSource { builtin: Some("bunny".into()), ..source("x", b"") };
    let m = MeshSource { data_base64: None, file: None, ..m }.load().unwrap();
    assert_eq!((m.vertices.len(), m.triangles.len()), (1839, 3674));
    let size = m.bounds().max - m.bounds().min;
    let share = m.volume() / f64::from(size.x * size.y * size.z);
    assert!((share - 0.269).abs() < 1e-3, "{share}");
    assert!(size.y > 0.95 * size.x && size.z < size.y, "{size:?}");
}

/// Poisson-disk filling: every point inside the tube, none two closer than the
/// radius, the same points for the same seed, and about volume / spacing^3 of them.
#[test]
fn poisson_disk_filling_keeps_its_radius_and_the_lattice_count() {
    let t = torus(96, 48);
    let volume = t.volume();
    for spacing in [0.05f32, 0.04, 0.03] {
        let r = spacing * super::poisson::RADIUS_PER_SPACING;
        let points = super::poisson::inside(&t, r, 7);
        let want = volume / (spacing as f64).powi(3);
        let off = (points.len() as f64 - want) / want;
        eprintln!("spacing {spacing}: {} points, {want:.0} wanted ({:+.2} %)", points.len(), 100.0 * off);
        assert!(off.abs() < 0.02, "spacing {spacing}: {} points, volume / spacing^3 = {want:.0}", points.len());
        for p in &points {
            let ring = (p.x * p.x + p.z * p.z).sqrt() - 1.0;
            // Within the polyhedron's distance from the analytic torus (its inner facets
            // lie up to 0.6 (1 - cos(pi / 96)) = 3.2e-4 m nearer the axis).
            assert!(ring * ring + p.y * p.y < 0.401 * 0.401, "{p} outside the tube");
        }
        let mut sorted = points.clone();
        sorted.sort_by(|a, b| a.x.total_cmp(&b.x));
        for (i, p) in sorted.iter().enumerate() {
            for q in sorted[i + 1..].iter().take_while(|q| q.x - p.x < r) {
                assert!((*q - *p).length() >= r * 0.9999, "{p} and {q} closer than {r}");
            }
        }
        assert_eq!(super::poisson::inside(&t, r, 7), points, "the same seed gives the same points");
    }
}
