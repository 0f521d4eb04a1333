//! The architecture invariants of ARCHITECTURE.md that the crate graph cannot state, checked on
//! the source text so a violation fails the tests instead of waiting for a review. (Which crate
//! may depend on which is checked by `.ci/check-layers` on `cargo tree`.)

use std::path::{Path, PathBuf};

/// Every `.rs` file below `dir`, sorted.
pub(crate) fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out.sort();
    out
}

/// Lines of `module` (a path below the repository root: a folder, or a file without `.rs`)
/// that contain a forbidden text.
fn violations(module: &str, forbidden: &[&str]) -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join(module);
    // A module is a folder or a file `<module>.rs`; a missing one is an error, so a renamed
    // module cannot silently escape the check.
    let files = if root.is_dir() {
        rust_files(&root)
    } else {
        let file = root.with_extension("rs");
        assert!(file.is_file(), "module {module} not found");
        vec![file]
    };
    let mut found = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for (n, line) in text.lines().enumerate() {
            for f in forbidden {
                if line.contains(f) {
                    found.push(format!("{}:{}: {}", file.display(), n + 1, line.trim()));
                }
            }
        }
    }
    found
}

#[test]
fn the_libraries_never_print() {
    let forbidden = ["println!", "eprintln!", "print!(", "dbg!("];
    for module in [
        "crates/numerics/src",
        "crates/engine/src",
        "src/nodes",
        "src/report",
    ] {
        let v = violations(module, &forbidden);
        assert!(
            v.is_empty(),
            "{module} is a library: it returns values and typed errors, only the CLI prints:\n{}",
            v.join("\n")
        );
    }
}

#[test]
fn the_report_reads_tables_and_the_cache_but_never_prints_or_computes() {
    let forbidden = [
        "crate::surface",
        "crate::contact",
        "crate::friction",
        "crate::nodes",
    ];
    let v = violations("src/report", &forbidden);
    assert!(
        v.is_empty(),
        "report must only read results and the cache, and never print:\n{}",
        v.join("\n")
    );
}

/// The engine's modules form layers, no cycle: syntax → task → resolve → node → study → plan →
/// shard / execute → summary → output (code lines naming `crate::<module>` are the edges;
/// comments and tests do not count). A cycle is printed as the modules it joins.
#[test]
fn engine_modules_import_without_cycles() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/engine/src");
    let mut edges: std::collections::BTreeMap<String, std::collections::BTreeSet<String>> =
        std::collections::BTreeMap::new();
    for file in rust_files(&root) {
        let rel = file.strip_prefix(&root).unwrap();
        let module = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy()
            .trim_end_matches(".rs")
            .to_string();
        let text = std::fs::read_to_string(&file).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap_or_default();
        for line in code.lines().filter(|l| !l.trim_start().starts_with("//")) {
            for part in line.split("crate::").skip(1) {
                let target: String = part
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                if !target.is_empty() && target != module && module != "lib" {
                    edges.entry(module.clone()).or_default().insert(target);
                }
            }
        }
    }
    assert!(edges.len() >= 10, "engine modules found: {edges:?}");
    // Depth-first search for a back edge.
    fn visit(
        m: &str,
        edges: &std::collections::BTreeMap<String, std::collections::BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut std::collections::BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = path.iter().position(|p| p == m) {
            return Some(path[i..].to_vec());
        }
        if !done.insert(m.to_string()) {
            return None;
        }
        path.push(m.to_string());
        for next in edges.get(m).into_iter().flatten() {
            if let Some(cycle) = visit(next, edges, path, done) {
                return Some(cycle);
            }
        }
        path.pop();
        None
    }
    let mut done = std::collections::BTreeSet::new();
    for m in edges.keys() {
        let cycle = visit(m, &edges, &mut Vec::new(), &mut done);
        assert!(cycle.is_none(), "engine import cycle: {cycle:?}");
    }
}
