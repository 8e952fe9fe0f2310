//! Regions of interest and level of detail: what part of a scene a frame stream
//! carries. A viewer of a scene larger than a browser can draw (or a link can carry)
//! asks for a region (a box, a camera's cone, or both) and a particle budget per
//! frame; the server culls and thins before it encodes, so bytes and encode time fall
//! with the region.
//!
//! Inside the region, without a camera, the budget keeps a uniform random subset;
//! with a camera, every particle near it and fewer farther out: particle `i` at
//! distance `d_i` from the camera has the key `d_i sqrt(u_i)`, with `u_i` uniform in
//! [0, 1) from a hash of its stable id, and the `budget` smallest keys are sent. That
//! keeps particle `i` when `u_i < (D / d_i)^2` for the distance `D` the budget sets,
//! so the share of particles kept falls as `1 / d^2` beyond `D`: a particle's
//! neighbours on the screen shrink as `1 / d`, so the points per unit of screen
//! area stay about even at every depth. The same particles are kept from frame to
//! frame (their `u` is fixed; a key changes only as the particle or the camera
//! moves), so nothing flickers, and the subset is spatially even (the hash has no
//! relation to position).

use super::ServiceError;
use floe_proto::Particles;
use serde::{Deserialize, Serialize};

/// Most particles a budget may ask for.
pub const MAX_BUDGET: u64 = 100_000_000;
/// Particles whose keys set a budget's threshold ([`View::select`]).
const SAMPLE: usize = 4096;
/// A camera's field of view when a request gives none (degrees).
pub const DEFAULT_FOV_DEG: f64 = 90.0;

/// A view as a request states it (the WebSocket's JSON, gRPC's `FrameView`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViewRequest {
    /// Only particles inside this box (m).
    #[serde(default, rename = "box", skip_serializing_if = "Option::is_none")]
    pub bounds: Option<BoxRequest>,
    /// Only particles the camera sees, thinned by distance from it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraRequest>,
    /// Most particles per frame (none: every particle in the region).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub budget: Option<u64>,
}

/// An axis-aligned box (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxRequest {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

/// A camera: where it is, where it looks, the cone it sees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraRequest {
    /// Its position (m).
    pub position: [f64; 3],
    /// The direction it looks in (any length but 0).
    pub direction: [f64; 3],
    /// The full opening angle of the cone it sees about `direction` (degrees, above
    /// 0 and at most 360; default 90). A viewer passes its diagonal field of view, so
    /// that the cone holds the whole screen.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov_deg: Option<f64>,
    /// The farthest it sees (m; default: no limit).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub far: Option<f64>,
}

/// A checked view.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    bounds: Option<([f32; 3], [f32; 3])>,
    camera: Option<Camera>,
    budget: Option<usize>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct Camera {
    position: [f32; 3],
    /// Unit length.
    direction: [f32; 3],
    /// Cosine of half the opening angle.
    cos_half: f32,
    /// The farthest it sees, squared (m^2).
    far2: f32,
}

fn bad<T>(m: String) -> Result<T, ServiceError> {
    Err(ServiceError::InvalidArgument(m))
}

fn finite3(name: &str, v: [f64; 3]) -> Result<[f32; 3], ServiceError> {
    match v.iter().position(|x| !x.is_finite() || x.abs() > f64::from(f32::MAX)) {
        Some(k) => bad(format!("{name}[{k}]: must be a finite number, got {}", v[k])),
        None => Ok(v.map(|x| x as f32)),
    }
}

impl ViewRequest {
    /// Whether it asks for anything (a region or a budget).
    pub fn is_empty(&self) -> bool {
        *self == ViewRequest::default()
    }

    /// The view, or an error naming the first bad field (under `view.`).
    pub fn check(&self) -> Result<View, ServiceError> {
        let bounds = match self.bounds {
            None => None,
            Some(b) => {
                let (min, max) = (finite3("view.box.min", b.min)?, finite3("view.box.max", b.max)?);
                if let Some(k) = (0..3).find(|&k| min[k] > max[k]) {
                    return bad(format!("view.box: min[{k}] = {} is above max[{k}] = {}", min[k], max[k]));
                }
                Some((min, max))
            }
        };
        let camera = match self.camera {
            None => None,
            Some(c) => {
                let position = finite3("view.camera.position", c.position)?;
                let d = finite3("view.camera.direction", c.direction)?;
                let length = d.iter().map(|x| f64::from(*x).powi(2)).sum::<f64>().sqrt();
                if !(length > 0.0 && length.is_finite()) {
                    return bad("view.camera.direction: must not be zero".into());
                }
                let fov = c.fov_deg.unwrap_or(DEFAULT_FOV_DEG);
                if !(fov.is_finite() && fov > 0.0 && fov <= 360.0) {
                    return bad(format!("view.camera.fov_deg: must be above 0 and at most 360, got {fov}"));
                }
                let far = c.far.unwrap_or(f64::INFINITY);
                if far.is_nan() || far <= 0.0 {
                    return bad(format!("view.camera.far: must be above 0, got {far}"));
                }
                Some(Camera {
                    position,
                    direction: d.map(|x| (f64::from(x) / length) as f32),
                    cos_half: (0.5 * fov).to_radians().cos() as f32,
                    far2: (far * far).min(f64::from(f32::MAX)) as f32,
                })
            }
        };
        let budget = match self.budget {
            None => None,
            Some(b) if (1..=MAX_BUDGET).contains(&b) => Some(b as usize),
            Some(b) => return bad(format!("view.budget: must be 1 to {MAX_BUDGET} particles, got {b}")),
        };
        Ok(View { bounds, camera, budget })
    }
}

impl View {
    /// Whether `x` is inside the box (everywhere without one).
    #[inline(always)]
    fn in_box(&self, x: [f32; 3]) -> bool {
        self.bounds.is_none_or(|(lo, hi)| {
            x[0] >= lo[0] && x[0] <= hi[0] && x[1] >= lo[1] && x[1] <= hi[1] && x[2] >= lo[2] && x[2] <= hi[2]
        })
    }

    /// Whether `x` is inside the region, and its squared distance from the camera (0
    /// without one). The cone's test `a >= cos(half) d` (with `a` the distance along
    /// the camera's direction) is made on squares, so no root is taken.
    #[inline(always)]
    fn inside(&self, x: [f32; 3]) -> Option<f32> {
        if !self.in_box(x) {
            return None;
        }
        let Some(c) = &self.camera else { return Some(0.0) };
        let d = [x[0] - c.position[0], x[1] - c.position[1], x[2] - c.position[2]];
        let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let a = d[0] * c.direction[0] + d[1] * c.direction[1] + d[2] * c.direction[2];
        let (a2, cone2) = (a * a, c.cos_half * c.cos_half * d2);
        let in_cone = if c.cos_half >= 0.0 { a >= 0.0 && a2 >= cone2 } else { a >= 0.0 || a2 <= cone2 };
        (in_cone && d2 <= c.far2).then_some(d2)
    }

    /// Particle `i`'s key if it is inside the region and the key at most `t`: `u`
    /// without a camera, `d^2 u` with one (the square of `d sqrt(u)`, which orders
    /// alike). Smaller: kept first. Without a camera the key needs no position, so the
    /// box is read only for particles under `t`.
    #[inline(always)]
    fn key(&self, p: &Particles, i: usize, t: f32) -> Option<f32> {
        if self.camera.is_none() {
            let u = rank(p.id(i));
            return (u <= t && self.in_box(p.positions[i])).then_some(u);
        }
        let k = self.inside(p.positions[i])? * rank(p.id(i));
        (k <= t).then_some(k)
    }

    /// The particles of `p` this view keeps, by index (ascending). A grid is sent
    /// whole (views are refused for grid sets).
    ///
    /// Under a budget, the keys of a sample of the particles give a threshold that
    /// about 1.25 budgets pass, one pass keeps the particles under it, and the budget
    /// smallest of those are the budget smallest of all (where fewer than a budget
    /// pass, every particle inside is ranked instead): exact, without ranking
    /// millions of keys.
    pub fn select(&self, p: &Particles) -> Vec<u32> {
        let n = p.positions.len();
        let Some(budget) = self.budget else {
            let mut out = Vec::new();
            for (i, &x) in p.positions.iter().enumerate() {
                if self.inside(x).is_some() {
                    out.push(i as u32);
                }
            }
            return out;
        };
        let stride = (n / SAMPLE).max(1);
        let mut sample: Vec<f32> = (0..n).step_by(stride).filter_map(|i| self.key(p, i, f32::INFINITY)).collect();
        let inside = sample.len() * stride;
        let threshold = if inside <= budget || sample.is_empty() {
            f32::INFINITY
        } else {
            sample.sort_unstable_by(f32::total_cmp);
            let q = (1.25 * budget as f64 / inside as f64 + 2.0 / sample.len() as f64).min(1.0);
            sample[((q * sample.len() as f64) as usize).min(sample.len() - 1)]
        };
        let under = |t: f32| -> Vec<(f32, u32)> {
            let mut out = Vec::new();
            for i in 0..n {
                if let Some(k) = self.key(p, i, t) {
                    out.push((k, i as u32));
                }
            }
            out
        };
        let mut keyed = under(threshold);
        if keyed.len() < budget && threshold < f32::INFINITY {
            keyed = under(f32::INFINITY);
        }
        if keyed.len() > budget {
            keyed.select_nth_unstable_by(budget, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            keyed.truncate(budget);
        }
        let mut out: Vec<u32> = keyed.into_iter().map(|(_, i)| i).collect();
        out.sort_unstable();
        out
    }

    /// The particles of `p` this view keeps, with their ids.
    pub fn apply(&self, p: &Particles) -> Particles {
        p.pick(&self.select(p))
    }
}

/// A number in [0, 1) fixed by a particle's id and spread evenly over ids (the
/// finaliser of MurmurHash3, top 24 bits).
fn rank(id: u32) -> f32 {
    let mut h = id;
    h ^= h >> 16;
    h = h.wrapping_mul(0x85eb_ca6b);
    h ^= h >> 13;
    h = h.wrapping_mul(0xc2b2_ae35);
    h ^= h >> 16;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n^3` particles on a unit lattice from the origin, ids 0 .. n^3.
    fn lattice(n: usize) -> Particles {
        let mut positions = Vec::new();
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    positions.push([x as f32, y as f32, z as f32]);
                }
            }
        }
        let count = positions.len();
        let speed = floe_proto::Values::scalars((0..count).map(|i| i as f32).collect());
        Particles { set: "particles".into(), positions, channels: vec![("speed".into(), speed)], grid: None, ids: None }
    }

    fn view(json: &str) -> View {
        serde_json::from_str::<ViewRequest>(json).unwrap().check().unwrap()
    }

    #[test]
    fn a_box_keeps_exactly_the_particles_inside_with_their_ids_and_channels() {
        let p = lattice(10);
        let v = view(r#"{"box": {"min": [2, 0, 0], "max": [4.5, 9, 0]}}"#);
        let got = v.apply(&p);
        assert_eq!(got.positions.len(), 3 * 10);
        assert!(got.positions.iter().all(|x| (2.0..=4.5).contains(&x[0]) && x[2] == 0.0));
        let ids = got.ids.as_ref().unwrap();
        assert!(ids.windows(2).all(|w| w[0] < w[1]), "ids ascend");
        for (k, &id) in ids.iter().enumerate() {
            assert_eq!(got.positions[k], p.positions[id as usize]);
            assert_eq!(got.channel("speed").unwrap().get(k), vec![id as f32]);
        }
    }

    #[test]
    fn a_budget_keeps_that_many_the_same_ones_each_frame_evenly_spread() {
        let p = lattice(20);
        let v = view(r#"{"budget": 800}"#);
        let a = v.select(&p);
        assert_eq!(a.len(), 800);
        // The same particles when they move (a key without a camera is the id's alone).
        let mut moved = p.clone();
        moved.positions.iter_mut().for_each(|x| x[1] += 0.3);
        assert_eq!(v.select(&moved), a);
        // Spread: each half of the lattice along x holds about half of them.
        let left = a.iter().filter(|&&i| p.positions[i as usize][0] < 10.0).count();
        assert!((340..=460).contains(&left), "{left} of 800 in the left half");
    }

    #[test]
    fn a_camera_keeps_everything_near_it_and_thins_with_distance() {
        let p = lattice(30);
        // On the lattice's x = 0 face, looking along +x, a cone of 120 degrees.
        let v = view(
            r#"{"camera": {"position": [-0.5, 14.5, 14.5], "direction": [1, 0, 0], "fov_deg": 120}, "budget": 3000}"#,
        );
        let kept = v.select(&p);
        assert_eq!(kept.len(), 3000);
        let d = |i: u32| {
            let x = p.positions[i as usize];
            ((x[0] + 0.5).powi(2) + (x[1] - 14.5).powi(2) + (x[2] - 14.5).powi(2)).sqrt()
        };
        // Nothing outside the cone.
        assert!(kept.iter().all(|&i| p.positions[i as usize][0] + 0.5 >= 0.5 * d(i)));
        // Every particle within 3 m of the camera and in the cone is kept.
        let near: Vec<u32> = (0..p.positions.len() as u32)
            .filter(|&i| d(i) < 3.0 && p.positions[i as usize][0] + 0.5 >= 0.5 * d(i))
            .collect();
        assert!(!near.is_empty() && near.iter().all(|i| kept.contains(i)));
        // The share kept falls with distance: the nearest third of the cone's
        // particles keeps a larger share than the farthest third.
        let mut cone: Vec<u32> =
            (0..p.positions.len() as u32).filter(|&i| p.positions[i as usize][0] + 0.5 >= 0.5 * d(i)).collect();
        cone.sort_by(|&a, &b| d(a).total_cmp(&d(b)));
        let third = cone.len() / 3;
        let share = |s: &[u32]| s.iter().filter(|i| kept.contains(i)).count() as f64 / s.len() as f64;
        let (near, far) = (share(&cone[..third]), share(&cone[2 * third..]));
        assert!(near > 3.0 * far, "near share {near}, far share {far}");
        // A camera that moves a little keeps almost all of the same particles.
        let moved = view(
            r#"{"camera": {"position": [-0.6, 14.5, 14.5], "direction": [1, 0, 0], "fov_deg": 120}, "budget": 3000}"#,
        );
        let again = moved.select(&p);
        let same = again.iter().filter(|i| kept.binary_search(i).is_ok()).count();
        assert!(same > 2800, "{same} of 3000 the same after a 0.1 m move");
    }

    #[test]
    fn far_limits_the_camera() {
        let p = lattice(10);
        let v = view(r#"{"camera": {"position": [0, 0, 0], "direction": [1, 1, 1], "fov_deg": 360, "far": 2}}"#);
        let kept = v.apply(&p);
        assert!(kept.positions.iter().all(|x| x.iter().map(|c| c * c).sum::<f32>() <= 4.0));
        assert_eq!(kept.positions.len(), 11, "the lattice points within 2 m of a corner");
    }

    #[test]
    fn bad_views_are_refused_naming_the_field() {
        let refused = |json: &str| {
            let e = serde_json::from_str::<ViewRequest>(json).unwrap().check().unwrap_err();
            assert!(matches!(e, ServiceError::InvalidArgument(_)), "{e:?}");
            e.to_string()
        };
        assert!(
            refused(r#"{"box": {"min": [1, 0, 0], "max": [0, 1, 1]}}"#)
                .contains("view.box: min[0] = 1 is above max[0] = 0")
        );
        assert!(
            refused(r#"{"camera": {"position": [0, 0, 0], "direction": [0, 0, 0]}}"#).contains("view.camera.direction")
        );
        assert!(
            refused(r#"{"camera": {"position": [0, 0, 0], "direction": [1, 0, 0], "fov_deg": 0}}"#).contains("fov_deg")
        );
        assert!(
            refused(r#"{"camera": {"position": [0, 0, 0], "direction": [1, 0, 0], "far": -1}}"#)
                .contains("view.camera.far")
        );
        assert!(refused(r#"{"budget": 0}"#).contains("view.budget: must be 1 to"));
        assert!(refused(r#"{"box": {"min": [1e39, 0, 0], "max": [2e39, 1, 1]}}"#).contains("view.box.min[0]"));
        assert!(serde_json::from_str::<ViewRequest>(r#"{"boxx": {}}"#).is_err(), "unknown fields refused");
    }
}
