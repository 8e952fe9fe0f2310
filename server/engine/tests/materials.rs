//! Several fluids in one scene: each a material with its own rest density and
//! mass (Solenthaler & Pajarola 2008), stable at a density ratio of 10 and more;
//! and a one-material scene stores no per-particle material index.

use floe_engine::Simulation;
use floe_engine::scene::load::{Format, from_str};

/// A light fluid resting on a heavy one in an open tank, density ratio `ratio`.
fn layers(ratio: f32) -> Simulation {
    let text = format!(
        r#"
        name = "layers"
        particle_spacing = 0.02
        [[fluids]]
        name = "heavy"
        rest_density = 1000
        blocks = [{{ min = [0, 0, 0], max = [0.3, 0.2, 0.1] }}]
        [[fluids]]
        name = "light"
        rest_density = {}
        blocks = [{{ min = [0, 0.2, 0], max = [0.3, 0.4, 0.1] }}]
        [[boundaries]]
        kind = "box"
        min = [0, 0, 0]
        max = [0.3, 0.5, 0.1]
        open = ["+y"]
        [solver]
        damping = 5
        damping_until = 0.3
        "#,
        1000.0 / ratio
    );
    Simulation::new_cpu(from_str(&text, Format::Toml, &[]).unwrap()).unwrap()
}

/// Ratio 1 is the same tank with one rest density: the weakly compressible column's
/// own sloshing after the damping ends, which the two-material scenes are held to.
#[test]
fn a_light_fluid_rests_on_a_heavy_one_at_density_ratios_of_10_and_100() {
    let mut reference = 0.0;
    for (ratio, allowed) in [(1.0, 1.0), (10.0, 1.5), (100.0, 5.0)] {
        let mut sim = layers(ratio);
        assert_eq!(sim.model().materials.len(), 2);
        sim.run_until(0.6, |_, _| {}).unwrap_or_else(|h| panic!("ratio {ratio}: {h}"));
        let p = sim.read(&["velocity", "material", "density"]);
        let v = p.channel("velocity").and_then(|v| v.as_vectors()).unwrap();
        let speed = v.iter().map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()).fold(0.0, f32::max);
        let scale = (9.81f32 * 0.4).sqrt();
        let mean_speed =
            v.iter().map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()).sum::<f32>() / v.len() as f32;
        eprintln!(
            "ratio {ratio}: {} steps, largest speed {speed:.4} m/s ({:.2e} sqrt(g H)), mean {mean_speed:.4}",
            sim.steps(),
            speed / scale
        );
        if ratio == 1.0 {
            reference = mean_speed;
        }
        assert!(
            mean_speed <= allowed * reference,
            "ratio {ratio}: mean speed {mean_speed} m/s after settling, {allowed} x the one-density tank's {reference}"
        );
        // Each material keeps its own density: the light layer is not counted as heavy.
        let (m, rho) = (p.channel("material").and_then(|m| m.as_exact()).unwrap(), p.channel("density").unwrap());
        let rho = rho.as_scalars().unwrap();
        let mean = |k: u8| {
            let (sum, n) =
                m.iter().zip(rho).filter(|(mk, _)| **mk == k).fold((0.0, 0), |(s, n), (_, r)| (s + r, n + 1));
            sum / n as f32
        };
        assert!((mean(0) / 1000.0 - 1.0).abs() < 0.05, "ratio {ratio}: heavy mean density {}", mean(0));
        assert!((mean(1) * ratio / 1000.0 - 1.0).abs() < 0.1, "ratio {ratio}: light mean density {}", mean(1));
        // The heavy fluid stays below the light one.
        let heavy_top = p.positions.iter().zip(m).filter(|(_, k)| **k == 0).map(|(x, _)| x[1]).fold(0.0, f32::max);
        let light_bottom =
            p.positions.iter().zip(m).filter(|(_, k)| **k == 1).map(|(x, _)| x[1]).fold(f32::INFINITY, f32::min);
        assert!(
            heavy_top < light_bottom + 0.04,
            "ratio {ratio}: heavy up to {heavy_top}, light down to {light_bottom}"
        );
    }
}

#[test]
fn one_material_stores_no_index_and_offers_no_material_channel() {
    let one = Simulation::new_cpu(floe_engine::modules::fluid::presets::dam_break()).unwrap();
    assert!(one.backend().allocations().iter().all(|a| a.name != "material"));
    assert!(one.channels().iter().all(|c| c.name != "material"));
    let two = layers(10.0);
    let material = two.backend().allocations().into_iter().find(|a| a.name == "material").unwrap();
    assert_eq!(material.bytes, 4 * two.particle_count() as u64);
    assert!(two.channels().iter().any(|c| c.name == "material" && c.exact));
}
