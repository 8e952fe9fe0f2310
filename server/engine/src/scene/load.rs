//! Reading scenes: TOML or JSON text, presets, and `key=value` overrides.
//!
//! Every source is first turned into a JSON value, overrides are applied to that
//! value, and only then is it deserialised into [`Scene`] (with the path of any
//! bad field) and validated. One pipeline, so a field is named the same way
//! whether it came from a file, a preset or `--set`.

use super::{Scene, presets, validate};
use serde_json::Value;
use std::path::Path;

/// Why a scene could not be loaded. Each message names what was wrong.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("cannot read scene file {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The text is not valid TOML or JSON.
    #[error("{format} syntax error: {message}")]
    Syntax {
        /// "TOML" or "JSON".
        format: &'static str,
        /// The parser's message, with line and column.
        message: String,
    },
    /// A field has the wrong type or name, or is missing.
    #[error("{path}: {message}")]
    Field {
        /// Path of the field, e.g. `fluids[0].rest_density`.
        path: String,
        /// What was wrong.
        message: String,
    },
    /// One or more fields failed validation (one line each).
    #[error("{}", .0.join("\n"))]
    Invalid(Vec<String>),
    /// No preset has this name.
    #[error("unknown preset '{name}'; presets are: {}", presets::names().join(", "))]
    UnknownPreset {
        /// The name asked for.
        name: String,
    },
    /// An override is not `key=value` or names a path that cannot exist.
    #[error("override '{text}': {message}")]
    Override {
        /// The override as given.
        text: String,
        /// What was wrong.
        message: String,
    },
}

/// Format of a scene document.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// TOML.
    Toml,
    /// JSON.
    Json,
}

/// Parses scene text into a JSON value (no schema check yet).
pub fn parse_document(text: &str, format: Format) -> Result<Value, SceneError> {
    match format {
        Format::Json => {
            serde_json::from_str(text).map_err(|e| SceneError::Syntax { format: "JSON", message: e.to_string() })
        }
        Format::Toml => {
            let table: toml::Table = toml::from_str(text)
                .map_err(|e| SceneError::Syntax { format: "TOML", message: e.to_string().trim().to_owned() })?;
            for (key, value) in &table {
                refuse_non_finite(value, key.clone())?;
            }
            Ok(serde_json::to_value(table).expect("TOML values are representable in JSON"))
        }
    }
}

/// TOML has `nan` and `inf`, JSON has neither: converted, they would become `null`,
/// which an optional field takes as unset. Refused here, naming the field.
fn refuse_non_finite(value: &toml::Value, path: String) -> Result<(), SceneError> {
    match value {
        toml::Value::Float(f) if !f.is_finite() => {
            Err(SceneError::Field { path, message: format!("must be a finite number, got {f}") })
        }
        toml::Value::Array(items) => {
            items.iter().enumerate().try_for_each(|(i, v)| refuse_non_finite(v, format!("{path}[{i}]")))
        }
        toml::Value::Table(t) => t.iter().try_for_each(|(k, v)| refuse_non_finite(v, format!("{path}.{k}"))),
        _ => Ok(()),
    }
}

/// Turns a document value into a validated scene.
pub fn from_value(value: Value) -> Result<Scene, SceneError> {
    let scene = Scene::from_json(value)?;
    validate::validate(&scene).map_err(SceneError::Invalid)?;
    Ok(scene)
}

/// Parses and validates scene text.
pub fn from_str(text: &str, format: Format, overrides: &[String]) -> Result<Scene, SceneError> {
    let mut value = parse_document(text, format)?;
    apply_overrides(&mut value, overrides)?;
    from_value(value)
}

/// Loads a scene file (`.toml` or `.json`), applies overrides and validates.
pub fn from_file(path: &Path, overrides: &[String]) -> Result<Scene, SceneError> {
    let text =
        std::fs::read_to_string(path).map_err(|source| SceneError::Io { path: path.display().to_string(), source })?;
    let format = match path.extension().and_then(|e| e.to_str()) {
        Some("json") => Format::Json,
        _ => Format::Toml,
    };
    from_str(&text, format, overrides)
}

/// A preset by name with overrides applied, validated.
pub fn from_preset(name: &str, overrides: &[String]) -> Result<Scene, SceneError> {
    let scene = presets::get(name).ok_or_else(|| SceneError::UnknownPreset { name: name.into() })?;
    let mut value = serde_json::to_value(&scene).expect("scenes serialise");
    apply_overrides(&mut value, overrides)?;
    from_value(value)
}

/// Reads the terrain and mesh assets `scene` names from the assets directory `dir`
/// into the scene (see `terrain::source::read_assets`, `mesh::read_assets`): a name that is not a plain file name,
/// any asset when there is no directory, and a missing or unusable file are refused
/// naming the field.
pub fn with_assets(mut scene: Scene, dir: Option<&Path>) -> Result<Scene, SceneError> {
    crate::terrain::source::read_assets(&mut scene, dir).map_err(SceneError::Invalid)?;
    crate::mesh::read_assets(&mut scene, dir).map_err(SceneError::Invalid)?;
    Ok(scene)
}

/// Loads `source`: a preset name if one has that name, otherwise a file path.
pub fn resolve(source: &str, overrides: &[String]) -> Result<Scene, SceneError> {
    if presets::names().contains(&source) {
        from_preset(source, overrides)
    } else if Path::new(source).exists() {
        from_file(Path::new(source), overrides)
    } else {
        Err(SceneError::UnknownPreset { name: source.into() })
    }
}

/// Applies `key.path[i].leaf=value` overrides. The value is read as JSON when it
/// parses as JSON (numbers, arrays, booleans, quoted strings), else as a bare string.
pub fn apply_overrides(doc: &mut Value, overrides: &[String]) -> Result<(), SceneError> {
    for text in overrides {
        let err = |message: String| SceneError::Override { text: text.clone(), message };
        let (key, raw) = text.split_once('=').ok_or_else(|| err("expected key=value".into()))?;
        let value = serde_json::from_str(raw.trim()).unwrap_or_else(|_| Value::String(raw.trim().into()));
        let segments = parse_path(key.trim()).map_err(err)?;
        set_path(doc, &segments, value).map_err(err)?;
    }
    Ok(())
}

/// Sets the field at `path` (`fluids[0].xsph`) of a scene document to `value`.
pub fn set(doc: &mut Value, path: &str, value: Value) -> Result<(), String> {
    set_path(doc, &parse_path(path)?, value)
}

#[derive(Debug, PartialEq)]
enum Segment {
    Key(String),
    Index(usize),
}

/// Reads `name.name[i][j].name`: names of letters, digits and `_`, indices of digits,
/// no empty part (a stray `.` or a `+1` index is an error, not a different path).
fn parse_path(key: &str) -> Result<Vec<Segment>, String> {
    let mut out = Vec::new();
    for part in key.split('.') {
        let (name, mut rest) = part.split_at(part.find('[').unwrap_or(part.len()));
        if name.is_empty() {
            return Err(format!("empty name in '{key}' (each part between dots needs a name)"));
        }
        if let Some(c) = name.chars().find(|c| !(c.is_ascii_alphanumeric() || *c == '_')) {
            return Err(format!("unexpected {c:?} in '{key}' (names are letters, digits and _)"));
        }
        out.push(Segment::Key(name.into()));
        while let Some(inner) = rest.strip_prefix('[') {
            let close = inner.find(']').ok_or_else(|| format!("unclosed '[' in '{key}'"))?;
            let digits = &inner[..close];
            let index = Some(digits)
                .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
                .and_then(|d| d.parse().ok())
                .ok_or_else(|| format!("bad index '{digits}' in '{key}'"))?;
            out.push(Segment::Index(index));
            rest = &inner[close + 1..];
        }
        if !rest.is_empty() {
            return Err(format!("unexpected '{rest}' in '{key}'"));
        }
    }
    Ok(out)
}

fn set_path(doc: &mut Value, path: &[Segment], value: Value) -> Result<(), String> {
    let mut node = doc;
    let mut walked = String::new();
    for segment in path {
        node = match segment {
            Segment::Key(k) => {
                walked += &if walked.is_empty() { k.clone() } else { format!(".{k}") };
                if node.is_null() {
                    *node = Value::Object(Default::default());
                }
                let map = node.as_object_mut().ok_or_else(|| format!("{walked}: parent is not a table"))?;
                map.entry(k.clone()).or_insert(Value::Null)
            }
            Segment::Index(i) => {
                let list = node.as_array_mut().ok_or_else(|| format!("{walked}: is not a list"))?;
                let len = list.len();
                walked += &format!("[{i}]");
                list.get_mut(*i).ok_or_else(|| format!("{walked}: index out of range (the list has {len} items)"))?
            }
        };
    }
    *node = value;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_schemes_setting_picks_it() {
        for m in crate::scheme::all() {
            let setting = format!("solver.method=\"{}\"", m.id);
            let scene = from_preset("hydrostatic", &[setting, "solver.delta_sph=null".into()]).unwrap();
            assert_eq!(scene.solver.method, m.id);
        }
        let e = from_preset("hydrostatic", &["solver.method=\"isph\"".into()]).unwrap_err().to_string();
        assert_eq!(e, "solver.method: unknown scheme \"isph\"; schemes are wcsph, dfsph");
    }

    #[test]
    fn sections_are_read_by_their_owners_and_unknown_keys_named() {
        let scene = from_preset("convection", &[]).unwrap();
        let json = serde_json::to_value(&scene).unwrap();
        // A section's defaults are filled in by its module: a scene read back equals itself.
        assert_eq!(from_value(json.clone()).unwrap(), scene);
        assert!(json["solver"]["dfsph"]["max_iterations"].is_number(), "a scheme's settings with their defaults");
        let e = from_preset("convection", &["lava={\"t\":1}".into()]).unwrap_err().to_string();
        assert!(e.starts_with("lava: unknown field; the fields here are name, modules,"), "{e}");
        assert!(e.ends_with("and the sections fluids, heat, snow, snowfall, solid"), "{e}");
        let e = from_preset("convection", &["solver.isph={}".into()]).unwrap_err().to_string();
        assert!(e.starts_with("solver.isph: unknown field;") && e.contains("the sections delta_sph"), "{e}");
        let e = from_preset("convection", &["heat.fluids[0].conductivity=\"x\"".into()]).unwrap_err().to_string();
        assert!(e.starts_with("heat.fluids[0].conductivity: invalid type"), "{e}");
    }

    #[test]
    fn paths_parse() {
        assert_eq!(
            parse_path("fluids[0].viscosity.nu").unwrap(),
            vec![
                Segment::Key("fluids".into()),
                Segment::Index(0),
                Segment::Key("viscosity".into()),
                Segment::Key("nu".into())
            ]
        );
        assert!(parse_path("a[x]").is_err());
        assert!(parse_path("a[1").is_err());
        for bad in ["a..b", "a.", ".a", "a.[0]", "[0]", "a[+1]", "a[]", "a[0]b", "a b", "a]", "a[1]]", "a-b", ""] {
            assert!(parse_path(bad).is_err(), "{bad:?} was accepted");
        }
        assert_eq!(parse_path("a[0][12]").unwrap().len(), 3);
    }

    #[test]
    fn non_finite_numbers_are_refused_naming_the_field() {
        let scene = r#"
            particle_spacing = 0.05
            [[fluids]]
            xsph = nan
            blocks = [{ min = [0, 0, 0], max = [0.5, 0.5, inf] }]
        "#;
        let e = from_str(scene, Format::Toml, &[]).unwrap_err().to_string();
        assert_eq!(e, "fluids[0].blocks[0].max[2]: must be a finite number, got inf");
        let e = from_str(&scene.replace("inf", "1"), Format::Toml, &[]).unwrap_err().to_string();
        assert_eq!(e, "fluids[0].xsph: must be a finite number, got NaN");
        let e = from_str("particle_spacing = -inf", Format::Toml, &[]).unwrap_err().to_string();
        assert_eq!(e, "particle_spacing: must be a finite number, got -inf");
        let e = from_preset("dam_break", &["particle_spacing=NaN".into()]).unwrap_err().to_string();
        assert!(e.starts_with("particle_spacing: invalid type: string \"NaN\""), "{e}");
    }

    #[test]
    fn overrides_set_numbers_strings_and_lists() {
        let scene = from_preset(
            "dam_break",
            &["particle_spacing=0.05".into(), "solver.kernel=cubic_spline".into(), "gravity=[0,-1,0]".into()],
        )
        .unwrap();
        assert_eq!(scene.particle_spacing, 0.05);
        assert_eq!(scene.solver.kernel, crate::kernel::KernelKind::CubicSpline);
        assert_eq!(scene.gravity, [0.0, -1.0, 0.0]);
    }

    #[test]
    fn bad_values_name_the_field() {
        let e = from_preset("dam_break", &["fluids[0].rest_density=-3".into()]).unwrap_err();
        assert_eq!(e.to_string(), "fluids[0].rest_density: must be > 0, got -3");
        let e = from_preset("dam_break", &["fluids[0].rest_density=\"heavy\"".into()]).unwrap_err();
        assert!(e.to_string().starts_with("fluids[0].rest_density: invalid type"), "{e}");
        let e = from_preset("dam_break", &["solver.colour=red".into()]).unwrap_err();
        assert!(e.to_string().starts_with("solver.colour: unknown field; the fields here are method,"), "{e}");
        let e = from_preset("dam_break", &["fluids[4].xsph=0.1".into()]).unwrap_err();
        assert!(e.to_string().contains("fluids[4]: index out of range"), "{e}");
        assert!(matches!(from_preset("nope", &[]), Err(SceneError::UnknownPreset { .. })));
    }

    #[test]
    fn toml_and_json_documents_load() {
        let toml = r#"
            particle_spacing = 0.05
            [[fluids]]
            blocks = [{ min = [0, 0, 0], max = [0.5, 0.5, 0.5] }]
            [[boundaries]]
            kind = "box"
            min = [0, 0, 0]
            max = [1, 1, 1]
        "#;
        let a = from_str(toml, Format::Toml, &[]).unwrap();
        let json = serde_json::to_string(&a).unwrap();
        let b = from_str(&json, Format::Json, &[]).unwrap();
        assert_eq!(a, b);
        let e = from_str("particle_spacing = ", Format::Toml, &[]).unwrap_err();
        assert!(e.to_string().starts_with("TOML syntax error"), "{e}");
        let e = from_str(&toml.replace("min = [0, 0, 0], max", "min = [0, 0], max"), Format::Toml, &[]).unwrap_err();
        assert!(e.to_string().starts_with("fluids[0].blocks[0].min: invalid length 2"), "{e}");
    }
}
