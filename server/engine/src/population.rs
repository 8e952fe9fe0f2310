//! Births and deaths: particles created and removed while a scene runs (snow falling
//! from the sky, fluid leaving through an outlet).
//!
//! A module reserves room for the particles it will add (`ModelBuilder::reserve`:
//! the scene's capacity, what a backend allocates and the server's particle limit
//! counts), declares its emitters (`ModelBuilder::emitter`: new particles after
//! each step, a function of the model, the step and the time, so both backends and
//! a restored scene emit alike) and, to remove particles, marks them in the core's
//! `remove` attribute from its passes (`ModelBuilder::removal`). After every step
//! the core removes the marked particles (the others keep their order) and then
//! appends the emitted ones ([`after_step`]). Every pass, reduction, frame and
//! snapshot sees the live particles only; ids come from the scene's `next_id`
//! (state, saved with it) and are never reused, so a particle's id names it for the
//! scene's whole life. A scene with neither emitters nor removal has none of this.
//!
//! Particles are then addressed by id without a table from ids to slots (ids grow
//! without bound, memory must not): such a scene has no `slot_of`, and no index
//! map over its particles.

use crate::attrs::{AttrSpec, Elem, PARTICLES, Role};
use crate::backend::Backend;
use crate::math::{Real, Vec3};
use crate::plan::{PassSpec, Stage};

/// The space of the scene's counters (one element).
pub const COUNTERS: &str = "population";

/// The id the next particle born gets.
pub static NEXT_ID: AttrSpec = AttrSpec {
    name: "next_id",
    elem: Elem::U32,
    unit: "",
    role: Role::State,
    added_later: false,
    space: COUNTERS,
    module: "core",
    about: "The id of the next particle born (ids are never reused).",
};

/// Particles to remove after the step: 1 (a module's pass marks them), else 0 (an
/// f32, so a GPU counts them with its sum reduction before copying anything back).
pub static REMOVE: AttrSpec = AttrSpec {
    name: "remove",
    elem: Elem::F32,
    unit: "",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "core",
    about: "1 where the particle is removed after this step.",
};

/// The sort of a scene whose particles are born and die: by cell, without `slot_of`.
pub static SORT: PassSpec = PassSpec {
    name: "core.sort",
    module: "core",
    stage: Stage::Sort,
    reads: &["x", "id"],
    writes: &[],
    accumulates: &[],
    tolerance: 0.0,
};

/// Particles an emitter adds after a step.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Births {
    /// Positions (m).
    pub x: Vec<Vec3>,
    /// Velocities (m/s).
    pub v: Vec<Vec3>,
    /// Material indices (in a scene of one material, all 0).
    pub material: Vec<u32>,
}

impl Births {
    /// How many.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
}

/// A source of particles.
#[derive(Debug, Clone, Copy)]
pub struct Emitter {
    /// Name, in messages.
    pub name: &'static str,
    /// The particles born after step `step` (1 for the first), which ended at `time`
    /// (s) after a step of `dt` (s). An emitter may read its module's state and
    /// write it back (a snow cover turned into particles loses their snow); an error
    /// says why the births cannot be (the scene halts with it) and must leave the
    /// state as it was.
    pub emit: fn(b: &mut dyn Backend, step: u64, time: f64, dt: Real) -> Result<Births, String>,
}

/// A scene's births and deaths.
#[derive(Debug, Clone)]
pub struct Population {
    /// Particles the scene can hold at once.
    pub capacity: usize,
    /// Its emitters, in the order the modules declared them.
    pub emitters: Vec<Emitter>,
    /// Whether passes mark particles to remove.
    pub removal: bool,
    /// The id of the next particle born (mirrors the `next_id` attribute).
    pub next_id: u32,
}

/// After step `step` (ended at `time`, of `dt`): removes the particles marked, then
/// adds the emitters' births. The error says what does not fit (the scene halts).
pub fn after_step(b: &mut dyn Backend, step: u64, time: f64, dt: Real) -> Result<(), String> {
    let Some(p) = b.model().population.clone() else { return Ok(()) };
    if p.removal {
        b.compact();
    }
    let mut next = p.next_id;
    for e in &p.emitters {
        let births = (e.emit)(b, step, time, dt)?;
        if births.is_empty() {
            continue;
        }
        let n = b.particle_count();
        if n + births.len() > p.capacity {
            return Err(format!(
                "particle capacity {} reached: emitter {} could not add {} particles to {n} (reserve more room)",
                p.capacity,
                e.name,
                births.len()
            ));
        }
        let Some(after) = u32::try_from(births.len()).ok().and_then(|k| next.checked_add(k)) else {
            return Err(format!("emitter {}: particle ids exhausted (2^32 births)", e.name));
        };
        b.emit(&births, next);
        next = after;
    }
    if next != p.next_id {
        b.model_mut().population.as_mut().expect("read above").next_id = next;
        b.upload(NEXT_ID.name, crate::attrs::Column::U32(vec![next]));
    }
    Ok(())
}
