//! Built-in scenes: every module's presets, by name (`floe presets`).

use super::Scene;

/// Names of the built-in presets, in registry order.
pub fn names() -> Vec<&'static str> {
    crate::module::presets().iter().map(|p| p.name).collect()
}

/// The preset called `name`, as a scene read from its document would be (every
/// section in the form its owner reads it, defaults filled in).
pub fn get(name: &str) -> Option<Scene> {
    let preset = crate::module::presets().into_iter().find(|p| p.name == name)?;
    let doc = serde_json::to_value((preset.scene)()).expect("scenes serialise");
    Some(Scene::from_json(doc).unwrap_or_else(|e| panic!("preset {name}: {e}")))
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
