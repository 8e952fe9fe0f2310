use super::source::{MAX_PNG_BYTES, decode_base64, rasterise, read_assets};
use super::spec::{Heights, Slope, Terrain};
use super::*;
use base64::Engine as _;

fn slope(angle: f32, ripple: f32) -> Terrain {
    Terrain {
        min: [0.0, 0.0],
        max: [4.0, 1.0],
        heights: Heights::Slope(Slope { top: 1.0, valley: 0.0, angle, foot: 0.1, ripple, wavelength: 1.0 }),
        friction: 0.3,
        layers: 2,
    }
}

/// A grayscale PNG of `width` x rows, 8 or 16 bits.
pub(crate) fn encode_png(width: u32, values: &[u16], sixteen: bool) -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut e = png::Encoder::new(&mut bytes, width, values.len() as u32 / width);
    e.set_color(png::ColorType::Grayscale);
    e.set_depth(if sixteen { png::BitDepth::Sixteen } else { png::BitDepth::Eight });
    let mut w = e.write_header().unwrap();
    let data: Vec<u8> = if sixteen {
        values.iter().flat_map(|v| v.to_be_bytes()).collect()
    } else {
        values.iter().map(|&v| v as u8).collect()
    };
    w.write_image_data(&data).unwrap();
    w.finish().unwrap();
    bytes
}

fn png_terrain(bytes: &[u8], range: [f32; 2]) -> Terrain {
    Terrain {
        min: [1.0, 2.0],
        max: [3.0, 3.0],
        heights: Heights::Png {
            asset: None,
            png_base64: Some(base64::engine::general_purpose::STANDARD.encode(bytes)),
            height_range: range,
        },
        friction: 0.0,
        layers: 1,
    }
}

#[test]
fn the_slope_falls_at_its_angle_into_a_flat_valley() {
    let g = rasterise(&slope(30.0, 0.0), 0.05).unwrap();
    assert_eq!((g.nx, g.nz), (81, 21));
    let tan = 30f32.to_radians().tan();
    // On the slope (top at x = 0, foot at x = 1 / tan 30 = 1.73 m).
    for x in [0.0, 0.5, 1.2] {
        let (h, n) = g.eval(x, 0.37);
        assert!((h - (1.0 - tan * x)).abs() < 1e-5, "h({x}) = {h}");
        let want = Vec3::new(30f32.to_radians().sin(), 30f32.to_radians().cos(), 0.0);
        assert!((n - want).length() < 1e-4, "n({x}) = {n}");
    }
    // The valley is flat and level.
    for x in [2.0, 3.0, 4.0] {
        let (h, n) = g.eval(x, 0.8);
        assert!(h.abs() < 1e-6 && (n - Vec3::Y).length() < 1e-6, "{x}: {h} {n}");
    }
    // The foot is rounded: between the two, below the straight slope's line.
    let (h, _) = g.eval(1.0 / tan, 0.5);
    assert!(h > 0.0 && h < 0.1 / 4.0 + 1e-3, "foot {h}");
}

#[test]
fn the_slope_varies_gently_along_z() {
    let g = rasterise(&slope(30.0, 0.05), 0.05).unwrap();
    // At the top the ripple is at full amplitude: sin(2 pi z) with wavelength 1 m.
    assert!((g.eval(0.0, 0.25).0 - 1.05).abs() < 1e-4);
    assert!((g.eval(0.0, 0.75).0 - 0.95).abs() < 1e-4);
    // The normal leans along -z where heights grow with z.
    assert!(g.eval(0.0, 0.05).1.z < -0.01);
    // None in the valley.
    assert!(g.eval(3.0, 0.25).0.abs() < 1e-6);
}

#[test]
fn a_png_maps_black_to_white_onto_the_height_range_bilinearly() {
    for sixteen in [false, true] {
        let top = if sixteen { 65535 } else { 255 };
        // 3 x 2 pixels: row 0 (z = 2) rises along x, row 1 (z = 3) is white.
        let bytes = encode_png(3, &[0, top / 2, top, top, top, top], sixteen);
        let g = rasterise(&png_terrain(&bytes, [-1.0, 1.0]), 0.1).unwrap();
        assert_eq!((g.nx, g.nz, g.cell), (3, 2, [1.0, 1.0]));
        let half = -1.0 + 2.0 * (top / 2) as f32 / top as f32;
        assert!((g.eval(1.0, 2.0).0 + 1.0).abs() < 1e-6);
        assert!((g.eval(2.0, 2.0).0 - half).abs() < 1e-6);
        assert!((g.eval(3.0, 3.0).0 - 1.0).abs() < 1e-6);
        // Bilinear: the centre of the first cell averages its four corners.
        let want = (-1.0 + half + 1.0 + 1.0) / 4.0;
        let (h, n) = g.eval(1.5, 2.5);
        assert!((h - want).abs() < 1e-6, "{h} vs {want}");
        // Slope of the patch there: dh/dx = ((half+1) + 0) / 2, dh/dz = (2 + (1-half)) / 2.
        let (dx, dz) = ((half + 1.0) / 2.0, (2.0 + 1.0 - half) / 2.0);
        assert!((n - Vec3::new(-dx, 1.0, -dz).normalize()).length() < 1e-5, "{n}");
    }
}

#[test]
fn unusable_pngs_are_refused_naming_why() {
    let rgb = {
        let mut bytes = Vec::new();
        let mut e = png::Encoder::new(&mut bytes, 2, 2);
        e.set_color(png::ColorType::Rgb);
        e.set_depth(png::BitDepth::Eight);
        e.write_header().unwrap().write_image_data(&[0; 12]).unwrap();
        bytes
    };
    let err = rasterise(&png_terrain(&rgb, [0.0, 1.0]), 0.1).unwrap_err();
    assert!(err.contains("grayscale"), "{err}");
    let err = rasterise(&png_terrain(b"not a png", [0.0, 1.0]), 0.1).unwrap_err();
    assert!(err.contains("not a PNG"), "{err}");
    let big = "A".repeat(MAX_PNG_BYTES / 3 * 4 + 8);
    assert!(decode_base64(&big).unwrap_err().contains("2 MiB"));
}

fn scene_with(heights: Heights) -> crate::scene::Scene {
    let mut scene = crate::scene::load::from_preset("hydrostatic", &[]).unwrap();
    scene.boundaries.push(crate::scene::Boundary::Terrain(Terrain { heights, ..slope(30.0, 0.0) }));
    scene
}

fn asset(name: &str) -> Heights {
    Heights::Png { asset: Some(name.into()), png_base64: None, height_range: [0.0, 1.0] }
}

#[test]
fn assets_are_plain_names_in_the_assets_directory() {
    let n = 1;
    for name in ["../secret.png", "/etc/passwd", "dir/a.png", "a\\b.png", ".."] {
        let errors = crate::scene::validate::validate(&scene_with(asset(name))).unwrap_err();
        assert!(
            errors.iter().any(|e| e.starts_with(&format!("boundaries[{n}].heights.asset: must be a plain file name"))),
            "{errors:?}"
        );
        let errors = read_assets(&mut scene_with(asset(name)), Some(std::path::Path::new("/"))).unwrap_err();
        assert!(errors[0].starts_with(&format!("boundaries[{n}].heights.asset: must be a plain")), "{errors:?}");
    }
    let dir = tempfile::tempdir().unwrap();
    let errors = read_assets(&mut scene_with(asset("a.png")), None).unwrap_err();
    assert!(errors[0].contains("no assets directory"), "{errors:?}");
    let errors = read_assets(&mut scene_with(asset("a.png")), Some(dir.path())).unwrap_err();
    assert!(errors[0].contains("no asset named \"a.png\""), "{errors:?}");
    // An asset never read cannot be built, with a client's error, not a panic.
    let err = crate::model::Model::build(&scene_with(asset("a.png"))).unwrap_err();
    assert!(err.to_string().contains("boundaries[1].heights: asset \"a.png\" was not read"), "{err}");
    // A real one is read into the scene, which then builds without the directory.
    std::fs::write(dir.path().join("a.png"), encode_png(2, &[0, 255, 255, 0], false)).unwrap();
    let mut scene = scene_with(asset("a.png"));
    read_assets(&mut scene, Some(dir.path())).unwrap();
    let crate::scene::Boundary::Terrain(t) = &scene.boundaries[1] else { panic!() };
    assert!(matches!(&t.heights, Heights::Png { asset: None, png_base64: Some(_), .. }));
    crate::scene::validate::validate(&scene).unwrap();
    assert!(crate::model::Model::build(&scene).is_ok());
}

#[test]
fn terrain_fields_are_checked_with_their_paths() {
    let mut t = slope(30.0, 0.0);
    (t.friction, t.max, t.layers) = (-0.1, [-1.0, 1.0], 9);
    let mut scene = scene_with(Heights::default());
    scene.boundaries[1] = crate::scene::Boundary::Terrain(t);
    let errors = crate::scene::validate::validate(&scene).unwrap_err();
    for want in
        ["boundaries[1].friction: must be >= 0", "boundaries[1].max: must exceed min along x", "boundaries[1].layers"]
    {
        assert!(errors.iter().any(|e| e.starts_with(want)), "{want} not in {errors:?}");
    }
    // The document form: `kind = "terrain"` with the terrain's fields beside it.
    let doc = r#"
        particle_spacing = 0.1
        [[boundaries]]
        kind = "terrain"
        min = [0, 0]
        max = [2, 1]
        friction = nan
    "#;
    let err = crate::scene::load::from_str(doc, crate::scene::load::Format::Toml, &[]).unwrap_err();
    assert!(err.to_string().contains("boundaries[0].friction: must be a finite number"), "{err}");
}

#[test]
fn the_surface_is_sampled_about_a_spacing_apart_along_the_slope() {
    let g = rasterise(&slope(45.0, 0.0), 0.1).unwrap();
    let p = sample_surface(&g, 0.1, 2);
    // Rows of 10 along z; along x the slope (sqrt 2 m long) plus the valley.
    let first_row: Vec<Vec3> = p.iter().step_by(2).copied().filter(|q| (q.z - 0.05).abs() < 1e-6).collect();
    for w in first_row.windows(2) {
        let d = (w[1] - w[0]).length();
        assert!((0.07..0.12).contains(&d), "neighbours {d} apart at {:?}", w[0]);
    }
    // Every particle lies under the surface by about its layer's depth.
    for q in &p {
        let (h, n) = g.eval(q.x, q.z);
        assert!(q.y < h && (h - q.y) * n.y < 0.16, "{q} vs {h}");
    }
}

#[test]
fn contact_friction_slows_without_reversing_and_the_ground_holds() {
    let grid = Arc::new(rasterise(&slope(30.0, 0.0), 0.05).unwrap());
    let c = TerrainConstraint { grid: grid.clone(), friction: 0.5, contact: 0.05, first: 0 };
    let g_dt = Vec3::new(0.0, -9.81, 0.0) * 1e-3;
    let (s, co) = (30f32.to_radians().sin(), 30f32.to_radians().cos());
    let (n, down_slope) = (Vec3::new(s, co, 0.0), Vec3::new(co, -s, 0.0));
    // Under the surface, moving into it and down the slope: back on the surface, the
    // inward speed gone, the tangential speed reduced by mu (removed + g cos a dt).
    let (h, _) = grid.eval(0.5, 0.5);
    let (mut x, mut v) = (Vec3::new(0.5, h - 0.01, 0.5), down_slope * 2.0 - n * 1.0);
    c.apply(&mut x, &mut v, g_dt, &grid.heights);
    assert!((x.y - h).abs() < 1e-6);
    let want = 2.0 - 0.5 * (1.0 + 9.81e-3 * co);
    assert!(v.dot(n).abs() < 1e-5 && (v.dot(down_slope) - want).abs() < 1e-5, "{v}");
    // A slow particle in contact stops; it does not turn back up the slope.
    let (mut x, mut v) = (Vec3::new(0.5, h + 0.02, 0.5), down_slope * 1e-3);
    c.apply(&mut x, &mut v, g_dt, &grid.heights);
    assert!(v.length() < 1e-6 && v.dot(down_slope) > -1e-9, "{v}");
    // Out of contact (two spacings up) nothing changes.
    let (mut x, mut v) = (Vec3::new(0.5, h + 0.12, 0.5), down_slope);
    c.apply(&mut x, &mut v, g_dt, &grid.heights);
    assert_eq!(v, down_slope);
}

#[test]
fn blocks_lose_the_particles_a_terrain_buries() {
    let mut scene = scene_with(Heights::default());
    let before = crate::Simulation::new_cpu(crate::scene::load::from_preset("hydrostatic", &[]).unwrap())
        .unwrap()
        .particle_count();
    // The hydrostatic column stands in [0, 0.2] (x); a slope from 0.1 m high at x = 0.
    let crate::scene::Boundary::Terrain(t) = &mut scene.boundaries[1] else { panic!() };
    t.heights = Heights::Slope(Slope { top: 0.1, angle: 30.0, foot: 0.0, ripple: 0.0, ..Slope::default() });
    let grid = rasterise(t, scene.particle_spacing).unwrap();
    let sim = crate::Simulation::new_cpu(scene).unwrap();
    assert!(sim.particle_count() < before);
    let x = sim.read(&[]).positions;
    assert!(x.iter().all(|p| !grid.buried(Vec3::from(*p), 0.025)));
}
