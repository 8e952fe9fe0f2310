//! Every relative link in the project's Markdown (README, ARCHITECTURE, TESTING,
//! docs/, the clients' READMEs) names a file or directory the repository holds, so
//! the docs read whole in a clone; and none cites a file outside the repository.

use std::path::{Path, PathBuf};

/// The repository's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("tests/ is in the repository").to_path_buf()
}

/// Every `.md` file under `dir`, build outputs, dependencies and hidden folders left out.
fn markdown(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable directory") {
        let path = entry.expect("directory entry").path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if path.is_dir() {
            if !(name.starts_with('.') || name == "target" || name == "node_modules") {
                markdown(&path, out);
            }
        } else if name.ends_with(".md") {
            out.push(path);
        }
    }
}

/// The targets of the inline links `[text](target)` of `text`, outside fenced code.
fn links(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut found = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let mut rest = line;
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let end = after.find(')').unwrap_or(after.len());
            found.push(after[..end].trim().to_string());
            rest = &after[end..];
        }
    }
    found
}

#[test]
fn every_relative_link_in_the_docs_resolves_in_the_repository() {
    let root = root();
    let mut files = Vec::new();
    markdown(&root, &mut files);
    assert!(files.len() > 20, "found only {} Markdown files under {}", files.len(), root.display());
    let mut broken = Vec::new();
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).expect("readable Markdown");
        for link in links(&text) {
            let target = match link.strip_prefix('<') {
                Some(inner) => inner.split('>').next().unwrap_or(""),
                None => link.split_whitespace().next().unwrap_or(""),
            };
            let path = target.split('#').next().unwrap_or("");
            if path.is_empty() || target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let resolved = if let Some(from_root) = path.strip_prefix('/') {
                root.join(from_root)
            } else {
                file.parent().expect("a file's folder").join(path)
            };
            checked += 1;
            let inside = resolved.canonicalize().is_ok_and(|p| p.starts_with(&root));
            if !inside {
                broken.push(format!("{}: ({link})", file.strip_prefix(&root).unwrap_or(file).display()));
            }
        }
    }
    assert!(checked > 50, "only {checked} relative links found: is the link reader broken?");
    assert!(broken.is_empty(), "links to nothing in the repository:\n{}", broken.join("\n"));
}

#[test]
fn the_docs_cite_no_file_outside_the_repository() {
    let root = root();
    let mut files = Vec::new();
    markdown(&root, &mut files);
    let outside: Vec<String> = files
        .iter()
        .filter(|f| std::fs::read_to_string(f).expect("readable Markdown").contains("VALIDATION.md"))
        .map(|f| f.strip_prefix(&root).unwrap_or(f).display().to_string())
        .collect();
    assert!(
        outside.is_empty(),
        "cite VALIDATION.md, which a clone has not (docs/validation/cases.md has the cases): {outside:?}"
    );
}

#[test]
fn the_link_reader_finds_inline_links_outside_code() {
    let text =
        "See [a](docs/a.md) and [b](../b.md#part).\n```\n[c](not/a/link.md)\n```\n[d](https://x.org) [e](<f g.md>)";
    assert_eq!(links(text), ["docs/a.md", "../b.md#part", "https://x.org", "<f g.md>"]);
}
