//! The shape of the source that ARCHITECTURE.md and the brief ask for, checked on the text: no
//! two files of a folder import each other (a pair that does is one concept split in two, or
//! two concepts tangled), and no source file grows past 600 lines.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use super::architecture::rust_files;

/// The source folders of the three crates and of the Python bindings.
const CRATES: [&str; 4] = [
    "crates/numerics/src",
    "crates/engine/src",
    "src",
    "python/src",
];

/// Longest source file, in lines (tests included: a file is read whole).
const MAX_FILE_LINES: usize = 600;

/// The code of a file without its test module and comment lines.
fn code_lines(text: &str) -> impl Iterator<Item = &str> {
    let code = text.split("#[cfg(test)]").next().unwrap_or_default();
    code.lines().filter(|l| !l.trim_start().starts_with("//"))
}

/// First identifier of `text`.
fn ident(text: &str) -> &str {
    let text = text.trim_start();
    let end = text
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(text.len());
    &text[..end]
}

/// Module names the code reaches through `super::`: `x` in `use super::x::Y`, `x` and `y` in
/// `use super::{x::{A, B}, y}` (lists may span lines).
fn names_after_super(code: &str) -> Vec<&str> {
    let mut names = Vec::new();
    for part in code.split("super::").skip(1) {
        let Some(list) = part.strip_prefix('{') else {
            names.push(ident(part));
            continue;
        };
        // The items of the top level of the list: an identifier after `{` or a `,` at depth 1.
        let mut depth = 1;
        let mut item_start = true;
        for (i, c) in list.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 1 => break,
                '}' => depth -= 1,
                ',' if depth == 1 => item_start = true,
                c if item_start && !c.is_whitespace() => {
                    names.push(ident(&list[i..]));
                    item_start = false;
                }
                _ => {}
            }
        }
    }
    names
}

/// For every folder, the sibling files (not `mod.rs`) each file names through `super::`.
fn sibling_imports(root: &Path) -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let mut edges: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
    for file in rust_files(root) {
        let stem = file.file_stem().unwrap().to_string_lossy().to_string();
        if matches!(stem.as_str(), "mod" | "lib" | "main") {
            continue;
        }
        let dir = file.parent().unwrap();
        let text = std::fs::read_to_string(&file).unwrap();
        let code: Vec<&str> = code_lines(&text).collect();
        for name in names_after_super(&code.join("\n")) {
            let sibling = dir.join(format!("{name}.rs"));
            if name != stem && sibling.is_file() {
                edges.entry(file.clone()).or_default().insert(sibling);
            }
        }
    }
    edges
}

#[test]
fn no_two_files_of_a_folder_import_each_other() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut circles = Vec::new();
    let mut files_with_imports = 0;
    for krate in CRATES {
        let edges = sibling_imports(&repo.join(krate));
        files_with_imports += edges.len();
        for (a, targets) in &edges {
            for b in targets {
                if a < b && edges.get(b).is_some_and(|t| t.contains(a)) {
                    circles.push(format!("{} <-> {}", a.display(), b.display()));
                }
            }
        }
    }
    // The scan must see the imports it is meant to judge (e.g. `contact/solver.rs` names
    // `super::multilevel`).
    assert!(
        files_with_imports > 50,
        "only {files_with_imports} files import a sibling"
    );
    assert!(
        circles.is_empty(),
        "files that import each other (move what both need into a file of its own):\n{}",
        circles.join("\n")
    );
}

#[test]
fn no_source_file_is_longer_than_600_lines() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut long = Vec::new();
    for krate in CRATES {
        for file in rust_files(&repo.join(krate)) {
            let lines = std::fs::read_to_string(&file).unwrap().lines().count();
            if lines > MAX_FILE_LINES {
                long.push(format!("{}: {lines} lines", file.display()));
            }
        }
    }
    assert!(
        long.is_empty(),
        "source files over {MAX_FILE_LINES} lines (split them by concept):\n{}",
        long.join("\n")
    );
}
