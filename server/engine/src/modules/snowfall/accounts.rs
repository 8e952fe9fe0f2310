//! The flakes' accounts: every flake emitted is airborne, landed (on the ground or
//! on objects), left or released, in integers, and the measures that report them.

use super::{FLAKE_V, GROUND_COUNT, SnowfallConsts, TALLY, TOP_COUNT, flakes};
use crate::attrs::Column;
use crate::simulation::Measure;

/// The flakes' accounting: emitted, airborne, landed (on the ground and on
/// objects), left and released, which always add up; with a release, the snow's
/// mass released and still on the ground.
pub fn measures(sim: &crate::Simulation) -> Vec<Measure> {
    let a = Accounts::of(sim.backend());
    let mut out = vec![
        Measure::new("snowfall.emitted", a.emitted as f64, ""),
        Measure::new("snowfall.airborne", a.airborne as f64, ""),
        Measure::new("snowfall.landed", (a.on_ground + a.on_objects) as f64, ""),
        Measure::new("snowfall.left", a.left as f64, ""),
    ];
    if let Some(r) = &sim.model().consts::<SnowfallConsts>().release {
        out.push(Measure::new("snowfall.released", a.released as f64, ""));
        out.push(Measure::new("snowfall.released_mass", a.released as f64 * r.flake_mass(), "kg"));
        out.push(Measure::new("snowfall.ground_mass", a.on_ground as f64 * r.flake_mass(), "kg"));
    }
    out
}

/// Where the flakes are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Accounts {
    /// Emitted since the start.
    pub emitted: u64,
    /// In the air now.
    pub airborne: u64,
    /// Landed on the ground.
    pub on_ground: u64,
    /// Landed on objects.
    pub on_objects: u64,
    /// Left the area (or lived too long).
    pub left: u64,
    /// Released from the ground as particles ([`super::release`]).
    pub released: u64,
}

impl Accounts {
    /// Every flake emitted is in exactly one of these: airborne, landed (on the
    /// ground or on objects), left or released.
    pub fn accounted(&self) -> u64 {
        self.airborne + self.on_ground + self.on_objects + self.left + self.released
    }

    /// A backend's accounts, from its state.
    pub fn of(b: &dyn crate::backend::Backend) -> Self {
        let mut cols = b.download(&[TALLY.name, FLAKE_V.name, GROUND_COUNT.name, TOP_COUNT.name]).into_iter();
        let mut next = || cols.next().expect("four columns");
        let (Column::U32(tally), Column::Vec4(v), Column::U32(ground), Column::U32(top)) =
            (next(), next(), next(), next())
        else {
            panic!("the snowfall's columns")
        };
        let sum = |n: &[u32]| n.iter().map(|&n| u64::from(n)).sum();
        let released = match b.model().consts::<SnowfallConsts>().release {
            Some(_) => match &b.download(&[super::release::RELEASED.name])[..] {
                [Column::U32(n)] => u64::from(n[0]),
                _ => panic!("the released flakes"),
            },
            None => 0,
        };
        Self {
            emitted: u64::from(tally[flakes::tally::EMITTED]),
            airborne: v.iter().filter(|v| v[3] == flakes::AIRBORNE).count() as u64,
            on_ground: sum(&ground),
            on_objects: sum(&top),
            left: u64::from(tally[flakes::tally::LEFT]),
            released,
        }
    }
}
