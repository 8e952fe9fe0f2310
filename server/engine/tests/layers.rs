//! The engine's layers point one way: the core knows no scheme and no module;
//! a scheme knows the core, never a module or another scheme; a module knows the
//! core and the scheme interfaces (`crate::scheme`), never another module or a
//! scheme. The one exception is `registry.rs`, the list that registers them. The
//! GPU backend (floe-gpu) has the same folders and follows the same rule, its
//! lists being `modules/mod.rs` and `schemes/mod.rs`.
//!
//! Checked on the source: every path in code (comments left out) is resolved from
//! the file it is in (`crate::`, `super::`, `self::`, `floe_engine::`; floe-gpu's
//! folders mirror the engine's) and refused when it reaches a scheme's or module's
//! folder the file may not use. A test of the checker itself shows it catches each
//! kind of wrong import.

use std::path::{Path, PathBuf};

/// What part of the engine a source file (or a path) belongs to.
#[derive(Debug, Clone, PartialEq)]
enum Layer {
    Core,
    Scheme(String),
    Module(String),
    /// `registry.rs`, which names them all.
    Registry,
}

fn layer_of(module_path: &[String]) -> Layer {
    // A name under `modules::` or `schemes::` with no folder of its own is an item
    // of the list there (floe-gpu's `modules::PASSES`).
    let folder = |kind: &str, name: &str| {
        let engine = Path::new(env!("CARGO_MANIFEST_DIR"));
        [engine.join("src"), engine.join("../gpu/src")].iter().any(|src| src.join(kind).join(name).is_dir())
    };
    match module_path {
        [first, name, ..] if first == "schemes" && folder(first, name) => Layer::Scheme(name.clone()),
        [first, name, ..] if first == "modules" && folder(first, name) => Layer::Module(name.clone()),
        [first, ..] if first == "schemes" || first == "modules" => Layer::Registry,
        [first, ..] if first == "registry" => Layer::Registry,
        _ => Layer::Core,
    }
}

/// The module path of a file relative to `src/` (`modules/heat/cases.rs` is
/// `modules::heat::cases`; a `mod.rs` is its folder's module).
fn module_path(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let file = parts.pop().unwrap_or_default();
    let stem = file.trim_end_matches(".rs");
    if stem != "mod" && stem != "lib" {
        parts.push(stem.to_owned());
    }
    parts
}

/// The code of `text` with comments and the contents of string and character
/// literals blanked out (offsets kept).
fn code(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = b.to_vec();
    let mut i = 0;
    let blank = |out: &mut Vec<u8>, from: usize, to: usize| {
        for c in &mut out[from..to.min(b.len())] {
            if *c != b'\n' {
                *c = b' ';
            }
        }
    };
    while i < b.len() {
        match b[i] {
            b'/' if b.get(i + 1) == Some(&b'/') => {
                let end = text[i..].find('\n').map_or(b.len(), |k| i + k);
                blank(&mut out, i, end);
                i = end;
            }
            b'r' if (b.get(i + 1) == Some(&b'"') || b.get(i + 1) == Some(&b'#'))
                && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_')) =>
            {
                let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
                if b.get(i + 1 + hashes) != Some(&b'"') {
                    i += 1;
                    continue;
                }
                let close = format!("\"{}", "#".repeat(hashes));
                let body = i + 2 + hashes;
                let end = text[body..].find(&close).map_or(b.len(), |k| body + k + close.len());
                blank(&mut out, body, end);
                i = end;
            }
            b'"' => {
                let mut k = i + 1;
                while k < b.len() && b[k] != b'"' {
                    k += if b[k] == b'\\' { 2 } else { 1 };
                }
                blank(&mut out, i + 1, k);
                i = k + 1;
            }
            b'\'' => {
                // A character literal ('x', '\n', '"'), not a lifetime.
                let len = if b.get(i + 1) == Some(&b'\\') { 4 } else { 3 };
                if b.get(i + len - 1) == Some(&b'\'') {
                    blank(&mut out, i + 1, i + len - 1);
                    i += len;
                } else {
                    i += 1;
                }
            }
            _ => i += 1,
        }
    }
    String::from_utf8(out).expect("blanking keeps UTF-8")
}

/// The inline modules of `code` (`mod tests { ... }`): where each starts and ends, and its name.
fn inline_modules(code: &str) -> Vec<(usize, usize, String)> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(k) = code[from..].find("mod ") {
        let at = from + k;
        from = at + 4;
        let before_ok = at == 0 || !code.as_bytes()[at - 1].is_ascii_alphanumeric();
        let rest = &code[at + 4..];
        let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
        let after = rest[name.len()..].trim_start();
        if !before_ok || name.is_empty() || !after.starts_with('{') {
            continue;
        }
        let open = at + 4 + name.len() + (rest[name.len()..].len() - after.len());
        let mut depth = 0;
        let mut end = code.len();
        for (k, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + k;
                        break;
                    }
                }
                _ => {}
            }
        }
        out.push((open, end, name));
    }
    out
}

/// Every path in `code` that starts at `crate`, `super`, `self` or `floe_engine`,
/// resolved to segments from the crate root, with the path as written (for
/// messages). A `{...}` list is expanded: `crate::{a::b, c}` is two paths.
fn paths(code: &str, file: &[String]) -> Vec<(Vec<String>, String)> {
    let ident = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let bytes = code.as_bytes();
    let inline = inline_modules(code);
    // The module a position is in: the file's, and the inline ones around it.
    let module_at = |at: usize| -> Vec<String> {
        let mut m = file.to_vec();
        m.extend(inline.iter().filter(|(s, e, _)| *s < at && at < *e).map(|(_, _, n)| n.clone()));
        m
    };
    let mut written = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts_path = ident(bytes[i]) && (i == 0 || !(ident(bytes[i - 1]) || bytes[i - 1] == b':'));
        if !starts_path {
            i += 1;
            continue;
        }
        let end = path_end(code, i);
        let here = module_at(i);
        written.extend(expand(&code[i..end]).into_iter().map(|w| (w, here.clone())));
        i = end.max(i + 1);
    }
    written
        .into_iter()
        .filter_map(|(w, here)| {
            let segments: Vec<&str> = w.split("::").collect();
            let mut resolved: Vec<String> = match segments[0] {
                "crate" | "floe_engine" => Vec::new(),
                "self" | "super" => here,
                _ => return None,
            };
            let mut rest = &segments[..];
            if segments[0] != "super" {
                rest = &rest[1..];
            }
            while rest.first() == Some(&"super") {
                resolved.pop();
                rest = &rest[1..];
            }
            resolved.extend(rest.iter().map(|s| s.to_string()));
            Some((resolved, w))
        })
        .collect()
}

/// Where the path starting at `i` ends: identifiers joined by `::`, and a `::{...}`
/// list with its nested lists.
fn path_end(code: &str, mut i: usize) -> usize {
    let bytes = code.as_bytes();
    let ident = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    loop {
        while i < bytes.len() && ident(bytes[i]) {
            i += 1;
        }
        if code[i..].starts_with("::{") {
            let mut depth = 0;
            for (k, c) in code[i + 2..].char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            return i + 2 + k + 1;
                        }
                    }
                    _ => {}
                }
            }
            return bytes.len();
        }
        if code[i..].starts_with("::") && bytes.get(i + 2).is_some_and(|&b| ident(b)) {
            i += 2;
        } else {
            return i;
        }
    }
}

/// The paths a written path stands for: `a::{b::c, d}` is `a::b::c` and `a::d`.
fn expand(path: &str) -> Vec<String> {
    let Some(open) = path.find("::{") else { return vec![path.trim().to_owned()] };
    let (prefix, inner) = (&path[..open], &path[open + 3..path.len() - 1]);
    let mut items = Vec::new();
    let (mut depth, mut from) = (0, 0);
    for (k, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&inner[from..k]);
                from = k + 1;
            }
            _ => {}
        }
    }
    items.push(&inner[from..]);
    items
        .into_iter()
        .map(|item| item.split(" as ").next().unwrap_or(item).trim())
        .filter(|item| !item.is_empty())
        .flat_map(|item| expand(&if item == "self" { prefix.to_owned() } else { format!("{prefix}::{item}") }))
        .collect()
}

/// What a file of layer `from` may not reach in layer `to`, if it may not.
fn forbidden(from: &Layer, to: &Layer) -> Option<&'static str> {
    match (from, to) {
        (Layer::Registry, _) | (_, Layer::Core) => None,
        (Layer::Core, Layer::Scheme(_) | Layer::Module(_)) => Some("the core knows no scheme and no module"),
        (Layer::Core, Layer::Registry) => None,
        (Layer::Scheme(_), Layer::Module(_)) => Some("a scheme knows no module"),
        (Layer::Scheme(a), Layer::Scheme(b)) if a != b => Some("a scheme knows no other scheme"),
        (Layer::Module(_), Layer::Scheme(_)) => Some("a module knows the scheme interfaces, not a scheme"),
        (Layer::Module(a), Layer::Module(b)) if a != b => Some("a module knows no other module"),
        (Layer::Scheme(_) | Layer::Module(_), Layer::Registry) => Some("only the core reads the registry"),
        _ => None,
    }
}

/// The wrong imports of the file at `relative` (to `src/`) holding `text`.
fn violations(relative: &Path, text: &str) -> Vec<String> {
    let here = module_path(relative);
    let from = layer_of(&here);
    let mut out = Vec::new();
    for (target, written) in paths(&code(text), &here) {
        let to = layer_of(&target);
        if let Some(why) = forbidden(&from, &to) {
            out.push(format!("{}: `{written}` ({why})", relative.display()));
        }
    }
    out
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("a source folder") {
        let path = entry.expect("an entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The wrong imports of every source file under `src`.
fn crate_violations(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    assert!(files.len() > 20, "the sources of {}: {}", src.display(), files.len());
    let mut wrong = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).expect("a source file");
        wrong.extend(violations(f.strip_prefix(src).expect("under src"), &text));
    }
    wrong
}

#[test]
fn every_import_points_down_or_within_its_folder() {
    let wrong = crate_violations(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    assert!(wrong.is_empty(), "imports against the layers:\n{}", wrong.join("\n"));
}

#[test]
fn the_gpu_halves_follow_the_same_layers() {
    let wrong = crate_violations(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../gpu/src"));
    assert!(wrong.is_empty(), "imports against the layers in floe-gpu:\n{}", wrong.join("\n"));
}

#[test]
fn the_check_catches_each_kind_of_wrong_import() {
    let wrong = |file: &str, text: &str| violations(Path::new(file), text);
    assert_eq!(wrong("clock.rs", "use crate::schemes::wcsph::Eos;").len(), 1, "core -> scheme");
    assert_eq!(wrong("cpu/core.rs", "let x = crate::modules::heat::TEMPERATURE;").len(), 1, "core -> module");
    assert_eq!(wrong("modules/heat/mod.rs", "use crate::modules::fluid::varying;").len(), 1, "module -> module");
    assert_eq!(wrong("modules/heat/cases.rs", "use super::super::snow::spec::Snow;").len(), 1, "sideways by super");
    assert_eq!(wrong("modules/fluid/mod.rs", "use crate::schemes::wcsph::PTERM;").len(), 1, "module -> scheme");
    assert_eq!(
        wrong("modules/snow/mod.rs", "use crate::{math::Real, modules::{fluid::X, snow::Y}};").len(),
        1,
        "in a list"
    );
    assert_eq!(wrong("schemes/dfsph/mod.rs", "use crate::modules::fluid::FluidConsts;").len(), 1, "scheme -> module");
    assert_eq!(wrong("schemes/dfsph/cpu.rs", "use crate::schemes::wcsph::eos::Eos;").len(), 1, "scheme -> scheme");
    assert_eq!(wrong("modules/snow/mod.rs", "use floe_engine::modules::heat::X;").len(), 1, "from floe-gpu");
    assert_eq!(wrong("pass.rs", "let p = crate::modules::heat::BUOYANCY;").len(), 1, "core -> a module's pass");
    // Allowed: the core's own paths, a module's own folder, the scheme interface, the
    // registry naming them, comments and strings.
    assert!(wrong("modules/heat/cases.rs", "use super::presets::CAVITY_L; use crate::scheme::Stages;").is_empty());
    assert!(wrong("modules/heat/mod.rs", "use crate::modules::heat::spec::Heat;").is_empty());
    assert!(wrong("registry.rs", "pub static M: &[&ModuleDef] = &[&crate::modules::fluid::MODULE];").is_empty());
    assert!(wrong("pass.rs", "let all = crate::modules::PASSES;").is_empty(), "a list");
    assert!(wrong("clock.rs", "// see crate::modules::heat for an example\nlet s = \"crate::schemes::x\";").is_empty());
}
