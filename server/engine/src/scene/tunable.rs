//! Which scene fields may change while a scene runs, and applying such changes.
//!
//! Each tunable is a path into the scene document (`[*]` stands for any index of a
//! list), declared once with its unit and bounds. Everything else (resolution,
//! geometry, kernel, equation of state, ...) shapes the particles and buffers
//! themselves and needs a new scene. Applying overrides is generic: the new
//! document with every tunable path taken back from the current one must equal the
//! current one, or a field that cannot change was changed.

use super::Scene;
use super::load::{SceneError, apply_overrides, from_value};
use serde_json::Value;

/// A setting that may change while a scene exists (serialised as the REST API
/// lists it in a scene's view).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Tunable {
    /// Path in the scene document, as in overrides; `[*]` matches any index.
    pub path: &'static str,
    /// SI unit of the value (empty for a table or a dimensionless number).
    pub unit: &'static str,
    /// Lower bound of a numeric value, as validation checks it.
    pub min: Option<f64>,
    /// Upper bound of a numeric value.
    pub max: Option<f64>,
    /// What it does.
    pub about: &'static str,
    /// The module that owns it (`core` for the scene's own fields).
    pub module: &'static str,
}

/// The core's tunable fields (modules declare their own: `crate::module::ModuleDef::tunables`).
pub const CORE: &[Tunable] = &[
    Tunable {
        path: "gravity",
        unit: "m/s^2",
        min: None,
        max: None,
        about: "Gravitational acceleration vector.",
        module: "core",
    },
    Tunable {
        path: "solver.time_step",
        unit: "",
        min: None,
        max: None,
        about: "Time step control: adaptive (cfl, min, max in s) or fixed (dt in s).",
        module: "core",
    },
    Tunable {
        path: "solver.damping",
        unit: "1/s",
        min: Some(0.0),
        max: None,
        about: "Velocity damping rate while t < damping_until.",
        module: "core",
    },
    Tunable {
        path: "solver.damping_until",
        unit: "s",
        min: Some(0.0),
        max: None,
        about: "Simulated time at which damping stops.",
        module: "core",
    },
    Tunable {
        path: "guard",
        unit: "",
        min: None,
        max: None,
        about: "Stability guard bounds (max_compression, max_speed in m/s).",
        module: "core",
    },
];

/// Marks `t`'s field in the scene's JSON Schema with `"x-floe-tunable"`: its unit,
/// bounds, owning module and what it does, so editors and clients see which
/// fields may change while a scene runs.
pub fn mark(schema: &mut Value, t: &Tunable) {
    let mut pointer = String::new();
    for seg in segments(t.path) {
        // Follow a reference to its definition before descending.
        if let Some(r) = schema.pointer(&pointer).and_then(|n| n.get("$ref")).and_then(Value::as_str) {
            pointer = r.trim_start_matches('#').to_string();
        }
        pointer += if seg == "*" { "/items".to_string() } else { format!("/properties/{seg}") }.as_str();
    }
    if let Some(Value::Object(node)) = schema.pointer_mut(&pointer) {
        let bound = |b: Option<f64>| b.map_or(Value::Null, Value::from);
        node.insert(
            "x-floe-tunable".into(),
            serde_json::json!({ "unit": t.unit, "min": bound(t.min), "max": bound(t.max), "module": t.module, "about": t.about }),
        );
    }
}

/// Copies the value at `path` (segments; `*` for any index) from `from` into `into`,
/// where both documents have it.
fn copy_path(into: &mut Value, from: &Value, path: &[&str]) {
    let Some((head, rest)) = path.split_first() else {
        *into = from.clone();
        return;
    };
    match (*head, into, from) {
        ("*", Value::Array(a), Value::Array(b)) => {
            for (x, y) in a.iter_mut().zip(b) {
                copy_path(x, y, rest);
            }
        }
        (key, Value::Object(a), Value::Object(b)) => match (a.get_mut(key), b.get(key)) {
            (Some(x), Some(y)) => copy_path(x, y, rest),
            // The path ends at an optional field set or cleared (`snowfall.release.at`).
            (Some(_), None) if rest.is_empty() => {
                a.remove(key);
            }
            (None, Some(y)) if rest.is_empty() => {
                a.insert(key.to_string(), y.clone());
            }
            _ => {}
        },
        _ => {}
    }
}

/// The segments of a tunable path: `fluids[*].xsph` is `fluids`, `*`, `xsph`.
fn segments(path: &str) -> Vec<&str> {
    path.split('.').flat_map(|part| part.split('[').map(|s| s.trim_end_matches(']'))).collect()
}

/// Applies `key=value` overrides to a running scene, all or nothing: the new scene,
/// validated; or every refused key with its own reason (a field that cannot change
/// while the scene runs, a value that does not parse or is out of range), each on a
/// line of its own, and a last line saying that nothing was applied.
pub fn apply(current: &Scene, overrides: &[String]) -> Result<Scene, SceneError> {
    let now = serde_json::to_value(current).expect("scenes serialise");
    let tunables = crate::module::tunables(current);
    let mut refused = Vec::new();
    for text in overrides {
        let key = text.split('=').next().unwrap_or(text).trim();
        let mut value = now.clone();
        let alone = apply_overrides(&mut value, std::slice::from_ref(text)).and_then(|()| from_value(value));
        match alone {
            Err(e) => refused.push(e.to_string()),
            Ok(next) => {
                let mut kept = serde_json::to_value(&next).expect("scenes serialise");
                for t in &tunables {
                    copy_path(&mut kept, &now, &segments(t.path));
                }
                if kept != now {
                    refused.push(format!("{key}: cannot change while the scene exists"));
                }
            }
        }
    }
    let nothing = |mut lines: Vec<String>, tunable: bool| {
        let paths: Vec<&str> = tunables.iter().map(|t| t.path).collect();
        let list = if tunable { format!("; tunable fields are {}", paths.join(", ")) } else { String::new() };
        lines.push(format!("nothing was applied{list}"));
        SceneError::Invalid(lines)
    };
    if !refused.is_empty() {
        let fixed = refused.iter().any(|r| r.ends_with("cannot change while the scene exists"));
        return Err(nothing(refused, fixed));
    }
    // Each key alone is fine; together they must make a valid scene too.
    let mut value = now;
    apply_overrides(&mut value, overrides)?;
    from_value(value).map_err(|e| nothing(e.to_string().lines().map(str::to_owned).collect(), false))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::presets;

    #[test]
    fn tunable_fields_change_and_others_are_refused() {
        let scene = presets::get("dam_break").unwrap();
        let next = apply(&scene, &["gravity=[0,-1,0]".into(), "fluids[0].xsph=0.2".into()]).unwrap();
        assert_eq!(next.gravity, [0.0, -1.0, 0.0]);
        assert_eq!(next.section::<serde_json::Value>("fluids").unwrap()[0]["xsph"], 0.2f32 as f64);
        let e = apply(&scene, &["particle_spacing=0.01".into()]).unwrap_err().to_string();
        assert!(e.starts_with("particle_spacing: cannot change while the scene exists\nnothing was applied; "), "{e}");
        let e = apply(&scene, &["fluids[0].xsph=7".into()]).unwrap_err().to_string();
        assert_eq!(e, "fluids[0].xsph: must be between 0 and 1, got 7\nnothing was applied");
    }

    /// Several keys: only the refused ones are named, each with its own reason, and
    /// nothing is applied.
    #[test]
    fn a_refusal_names_only_the_refused_keys() {
        let scene = presets::get("dam_break").unwrap();
        let e = apply(&scene, &["fluids[0].xsph=0.1".into(), "particle_spacing=0.02".into()]).unwrap_err();
        let lines: Vec<String> = e.to_string().lines().map(str::to_owned).collect();
        assert_eq!(lines[0], "particle_spacing: cannot change while the scene exists");
        assert!(lines[1].starts_with("nothing was applied; tunable fields are gravity"), "{lines:?}");
        assert_eq!(lines.len(), 2, "{lines:?}");
        let e =
            apply(&scene, &["fluids[0].xsph=2".into(), "gravity=[0,-1,0]".into(), "solver.kernel=\"mueller\"".into()])
                .unwrap_err()
                .to_string();
        assert_eq!(
            e.lines().take(2).collect::<Vec<_>>(),
            ["fluids[0].xsph: must be between 0 and 1, got 2", "solver.kernel: cannot change while the scene exists"]
        );
        assert!(!e.contains("gravity:"), "{e}");
    }
}
