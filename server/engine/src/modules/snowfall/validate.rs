//! The `snowfall` section's checks: each names the setting it rejects and why.

use super::spec::{self, Object};
use super::{MAX_CELLS, MAX_OBJECTS, SECTION, cells};
use crate::math::Vec3;
use crate::scene::Scene;
use crate::scene::validate::Checker;

/// Checks a scene's `snowfall` section, where it has one.
pub(super) fn validate(scene: &Scene, c: &mut Checker) {
    let Some(s) = scene.section::<spec::Snowfall>(SECTION) else { return };
    for axis in 0..2 {
        let (lo, hi) = (s.area.min[axis], s.area.max[axis]);
        let path = format!("snowfall.area.max[{axis}]");
        if c.finite(&format!("snowfall.area.min[{axis}]"), lo) && c.finite(&path, hi) && hi <= lo {
            c.fail(&path, format!("must exceed area.min[{axis}] = {lo}, got {hi}"));
        }
    }
    c.finite("snowfall.floor", s.floor);
    if c.finite("snowfall.height", s.height) && s.height <= s.floor {
        c.fail("snowfall.height", format!("must lie above the floor ({} m), got {}", s.floor, s.height));
    }
    c.within("snowfall.intensity.flakes_per_m2_s", s.intensity.flakes_per_m2_s(), 1e-3, 1e6);
    let max = s.max_flakes_per_m2_s();
    if s.max_intensity.is_some() {
        c.within("snowfall.max_intensity.flakes_per_m2_s", max, 1e-3, 1e6);
    }
    if s.intensity.flakes_per_m2_s() > max {
        c.fail(
            "snowfall.intensity",
            format!(
                "{} flakes per m^2 per s is above max_intensity ({}): the ring of flakes is sized for that",
                s.intensity.flakes_per_m2_s(),
                max
            ),
        );
    }
    c.positive("snowfall.depth_per_hour", s.depth_per_hour);
    c.within("snowfall.terminal_speed", s.terminal_speed, 0.01, 100.0);
    c.vector("snowfall.wind", &s.wind);
    c.within("snowfall.gusts", s.gusts, 0.0, 1.0);
    c.positive("snowfall.gust_period", s.gust_period);
    c.non_negative("snowfall.flutter", s.flutter);
    if let Some(t) = s.turbulence {
        c.within("snowfall.turbulence.amplitude", t.amplitude, 0.0, 100.0);
        c.positive("snowfall.turbulence.scale", t.scale);
        c.positive("snowfall.turbulence.period", t.period);
    }
    if let Some(cell) = s.cell {
        c.positive("snowfall.cell", cell);
    }
    c.within("snowfall.coverage_cone", s.coverage_cone, 0.0, 80.0);
    if Vec3::from(scene.gravity).length() == 0.0 {
        c.fail("gravity", "snowfall needs gravity (it sets the flakes' drag)".into());
    }
    if s.objects.len() > MAX_OBJECTS {
        c.fail("snowfall.objects", format!("at most {MAX_OBJECTS} objects, got {}", s.objects.len()));
    }
    for (i, o) in s.objects.iter().enumerate() {
        let p = format!("snowfall.objects[{i}]");
        match o {
            Object::Box { min, max } => c.ordered_box(&p, *min, *max),
            Object::Mesh { mesh, min, max } => {
                c.ordered_box(&p, *min, *max);
                crate::mesh::validate(c, &format!("{p}.mesh"), mesh);
            }
            &Object::Cylinder { centre, radius, bottom, top } => {
                c.vector(&format!("{p}.centre"), &centre);
                c.positive(&format!("{p}.radius"), radius);
                if c.finite(&format!("{p}.bottom"), bottom) && c.finite(&format!("{p}.top"), top) && top <= bottom {
                    c.fail(&format!("{p}.top"), format!("must exceed bottom = {bottom}, got {top}"));
                }
            }
        }
    }
    if let Some(r) = &s.release {
        if let Some(at) = r.at {
            c.within("snowfall.release.at", at, 0.0, f32::MAX);
        }
        c.within("snowfall.release.min_slope", r.min_slope, 0.0, 90.0);
        if r.particles == 0 {
            c.fail("snowfall.release.particles", "must be at least 1".into());
        }
    }
    let (nx, nz) = cells(&s, scene.particle_spacing);
    if u64::from(nx) * u64::from(nz) > MAX_CELLS {
        c.fail(
            "snowfall.cell",
            format!("the snow grid would have {nx} x {nz} cells, more than {MAX_CELLS}; make the cells larger"),
        );
    }
}
