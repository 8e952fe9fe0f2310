//! Sections of a scene document that the core does not own: each module's (`fluids`,
//! `heat`, `snow`) at the top level, each scheme's settings (`dfsph`, `delta_sph`)
//! under `solver`. The core keeps them as JSON values by key; the module or scheme
//! that owns a key declares it with a [`SectionDef`], which parses it (naming a bad
//! field by its path), gives its JSON Schema and its canonical form (defaults filled
//! in), and reads it back typed. An unknown key is an error naming the known ones.
//!
//! Two scenes are equal when their core fields and canonical sections are: a scene
//! read back from a snapshot equals the one that wrote it.

use super::load::SceneError;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::{Map, Value};
use std::collections::BTreeMap;

/// The sections of one level of a scene document, by key.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
#[serde(transparent)]
pub struct Sections(BTreeMap<String, Value>);

impl Sections {
    /// The section `key` as a `T`, if the scene has it. Sections are parsed when a
    /// scene is loaded, so one that is there reads back.
    pub fn get<T: DeserializeOwned>(&self, key: &str) -> Option<T> {
        let value = self.0.get(key)?;
        Some(serde_json::from_value(value.clone()).unwrap_or_else(|e| panic!("section {key} was parsed at load: {e}")))
    }

    /// Sets section `key` (a preset's, or a test's).
    pub fn set<T: Serialize>(&mut self, key: &str, value: &T) {
        self.0.insert(key.into(), serde_json::to_value(value).expect("sections serialise"));
    }

    /// Removes section `key`.
    pub fn remove(&mut self, key: &str) {
        self.0.remove(key);
    }

    /// Whether the scene has section `key`.
    pub fn has(&self, key: &str) -> bool {
        self.0.contains_key(key)
    }

    /// Every section's document, by key, to edit in place (the core reading assets
    /// a section names into it).
    pub(crate) fn iter_mut(&mut self) -> impl Iterator<Item = (&String, &mut Value)> {
        self.0.iter_mut()
    }

    /// The keys present.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.0.keys().map(String::as_str)
    }
}

/// A key some module or scheme owns.
#[derive(Debug, Clone, Copy)]
pub struct SectionDef {
    /// Its key in the document (`fluids`, `heat`, `delta_sph`).
    pub key: &'static str,
    /// Reads the value at `path` into its canonical form, or names the bad field.
    pub parse: fn(&Value, &str) -> Result<Value, SceneError>,
    /// The value a document without the key (or with `null` there) gets, if it
    /// gets one (a scheme's settings with defaults); `None`: the key stays absent.
    pub absent: fn() -> Option<Value>,
    /// Its JSON Schema.
    pub schema: fn(&mut schemars::SchemaGenerator) -> schemars::Schema,
}

impl SectionDef {
    /// A section of type `T`, absent unless given.
    pub const fn of<T: DeserializeOwned + Serialize + schemars::JsonSchema>(key: &'static str) -> Self {
        Self { key, parse: canonical::<T>, absent: || None, schema: |g| g.subschema_for::<T>() }
    }

    /// A section of type `T`, `T::default()` where the document has none.
    pub const fn defaulted<T: DeserializeOwned + Serialize + schemars::JsonSchema + Default>(
        key: &'static str,
    ) -> Self {
        Self {
            key,
            parse: canonical::<T>,
            absent: || Some(serde_json::to_value(T::default()).expect("sections serialise")),
            schema: |g| g.subschema_for::<T>(),
        }
    }
}

/// `value` read as a `T` and written back: defaults filled in, the field order of `T`.
fn canonical<T: DeserializeOwned + Serialize>(value: &Value, path: &str) -> Result<Value, SceneError> {
    let typed: T = serde_path_to_error::deserialize(value.clone()).map_err(|e| {
        let inner = e.path().to_string();
        let path = match inner.as_str() {
            "." => path.to_owned(),
            p if p.starts_with('[') => format!("{path}{p}"),
            p => format!("{path}.{p}"),
        };
        SceneError::Field { path, message: e.into_inner().to_string() }
    })?;
    Ok(serde_json::to_value(typed).expect("sections serialise"))
}

/// Splits `object` (the document level at `path`, `""` for the top) into the
/// entries `core` names and the sections `defs` own, each parsed; any other key is
/// refused, naming the fields and sections there are.
pub fn split(
    object: Map<String, Value>,
    path: &str,
    core: &[&str],
    defs: &[SectionDef],
) -> Result<(Map<String, Value>, Sections), SceneError> {
    let at = |key: &str| if path.is_empty() { key.to_owned() } else { format!("{path}.{key}") };
    let mut rest = Map::new();
    let mut sections = BTreeMap::new();
    for (key, value) in object {
        if let Some(def) = defs.iter().find(|d| d.key == key) {
            // `null` is the key left out (TOML has no null).
            if !value.is_null() {
                let parsed = (def.parse)(&value, &at(&key))?;
                sections.insert(key, parsed);
            }
        } else if core.contains(&key.as_str()) {
            rest.insert(key, value);
        } else {
            let owned: Vec<&str> = defs.iter().map(|d| d.key).collect();
            return Err(SceneError::Field {
                path: at(&key),
                message: format!(
                    "unknown field; the fields here are {}, and the sections {}",
                    core.join(", "),
                    if owned.is_empty() { "(none)".into() } else { owned.join(", ") }
                ),
            });
        }
    }
    for def in defs {
        if !sections.contains_key(def.key)
            && let Some(v) = (def.absent)()
        {
            sections.insert(def.key.into(), v);
        }
    }
    Ok((rest, Sections(sections)))
}

/// Adds each section's schema to `properties`, an object schema's properties.
pub fn add_schemas(properties: &mut Value, schemas: Vec<(&'static str, Value)>) {
    if let Value::Object(p) = properties {
        p.extend(schemas.into_iter().map(|(k, v)| (k.to_owned(), v)));
    }
}
