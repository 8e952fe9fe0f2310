//! Built-in scenes: every module's presets, by name (`floe presets`).

use super::Scene;
pub use crate::modules::fluid::presets::{DAM_BREAK_A, dam_break, hydrostatic};

/// Names of the built-in presets, in registry order.
pub fn names() -> Vec<&'static str> {
    crate::modules::presets().iter().map(|p| p.name).collect()
}

/// The preset called `name`.
pub fn get(name: &str) -> Option<Scene> {
    crate::modules::presets().iter().find(|p| p.name == name).map(|p| (p.scene)())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid() {
        for name in names() {
            let scene = get(name).unwrap();
            crate::scene::validate::validate(&scene).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        }
        assert!(get("nope").is_none());
    }
}
