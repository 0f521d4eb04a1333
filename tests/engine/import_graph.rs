//! The import graph of the source, file by file, and its circles. A circle (files that reach
//! each other through imports, at any length and across folders) is one concept split over
//! several files or two concepts tangled; the house keeps none.
//!
//! **The graph.** A node is a source file (a module). Each file is read as tokens (comments,
//! strings and its `#[cfg(test)]` items removed) and every path it names becomes an edge to the
//! file that defines what the path reaches: `use` trees (`crate::`, `super::`, `self::` and child
//! modules, braces, renames, `pub use`), and paths in the code (`crate::a::f()`,
//! `super::b::C`, `child::LAW`). A path ends at the deepest module it names; when the next name
//! is a re-export of that module (`pub use sub::Item`), the edge goes on to the file that
//! defines it. Paths into other crates are not edges: the crate graph itself is acyclic
//! (`.ci/check-layers`).
//!
//! **What is not an edge**: a module using the items its ancestors define themselves (`use
//! super::FrictionTask` from `friction/per_spot.rs`). A parent module declares its children and
//! lends them its types; that containment is how Rust modules are built, not a circle. Anything
//! an ancestor only re-exports is followed to where it is defined, so a child reaching a sibling
//! through its parent still counts.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use super::architecture::rust_files;
use super::source_scan::code_tokens;

/// The crates whose files form the graph (folders below the repository root).
pub(crate) const SOURCE_ROOTS: [&str; 4] = [
    "crates/numerics/src",
    "crates/engine/src",
    "src",
    "python/src",
];

/// A module path below its crate root (`["friction", "laws"]`).
type ModulePath = Vec<String>;

/// One file of a crate: its module path and its tokens.
struct SourceFile {
    file: PathBuf,
    module: ModulePath,
    tokens: Vec<String>,
}

/// The import graph of one crate: edges between files with the names that make each edge.
pub(crate) struct ImportGraph {
    pub edges: BTreeMap<PathBuf, BTreeMap<PathBuf, BTreeSet<String>>>,
}

/// The module path of `file` below the crate root `root` (`lib.rs`/`main.rs` → `[]`,
/// `a/mod.rs` → `[a]`, `a/b.rs` → `[a, b]`).
fn module_path(root: &Path, file: &Path) -> ModulePath {
    let rel = file.strip_prefix(root).unwrap();
    let mut parts: ModulePath = rel
        .iter()
        .map(|p| p.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// The paths of a `use` tree starting at `tokens[i]` (after `use`), and the index after its
/// `;`. `use a::{b, c::d as e, f::*};` gives `a::b`, `a::c::d`, `a::f`.
fn use_tree_paths(tokens: &[String], mut i: usize) -> (Vec<ModulePath>, usize) {
    let mut paths = Vec::new();
    let mut prefix_stack: Vec<ModulePath> = vec![Vec::new()];
    let mut current: ModulePath = Vec::new();
    while i < tokens.len() {
        let t = tokens[i].as_str();
        match t {
            ";" => break,
            "{" => {
                let mut base = prefix_stack.last().unwrap().clone();
                base.append(&mut current);
                prefix_stack.push(base);
            }
            "}" => {
                flush(&mut paths, &prefix_stack, &mut current);
                prefix_stack.pop();
            }
            "," => flush(&mut paths, &prefix_stack, &mut current),
            "as" => i += 1,
            "::" | "*" => {}
            _ if t.chars().all(|c| c.is_alphanumeric() || c == '_') => current.push(t.to_string()),
            _ => {}
        }
        i += 1;
    }
    flush(&mut paths, &prefix_stack, &mut current);
    (paths, i + 1)
}

/// Ends the current path of a use tree (`self` names the prefix itself).
fn flush(paths: &mut Vec<ModulePath>, prefix_stack: &[ModulePath], current: &mut ModulePath) {
    if current.is_empty() {
        return;
    }
    let mut path = prefix_stack.last().unwrap().clone();
    for segment in current.drain(..) {
        if segment != "self" || path.is_empty() {
            path.push(segment);
        }
    }
    paths.push(path);
}

/// The paths a file names: its `use` trees (with whether they are `pub`) and the paths in its
/// code that start at `crate`, `super`, `self` or one of `children`.
fn named_paths(tokens: &[String], children: &BTreeSet<String>) -> Vec<(ModulePath, bool)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let after_path_sep = i > 0 && tokens[i - 1] == "::";
        if tokens[i] == "use" && !after_path_sep {
            let public = preceded_by_pub(tokens, i);
            let (paths, next) = use_tree_paths(tokens, i + 1);
            out.extend(paths.into_iter().map(|p| (p, public)));
            i = next;
            continue;
        }
        let starts_path = matches!(tokens[i].as_str(), "crate" | "super" | "self")
            || children.contains(&tokens[i]);
        if starts_path && !after_path_sep && tokens.get(i + 1).is_some_and(|t| t == "::") {
            let mut path = vec![tokens[i].clone()];
            let mut j = i + 1;
            while tokens.get(j).is_some_and(|t| t == "::")
                && tokens
                    .get(j + 1)
                    .is_some_and(|t| t.chars().all(|c| c.is_alphanumeric() || c == '_'))
            {
                path.push(tokens[j + 1].clone());
                j += 2;
            }
            out.push((path, false));
            i = j;
            continue;
        }
        i += 1;
    }
    out
}

/// Whether the `use` at `i` is a re-export (`pub use`, `pub(crate) use`, `pub(super) use`).
fn preceded_by_pub(tokens: &[String], i: usize) -> bool {
    if i >= 1 && tokens[i - 1] == "pub" {
        return true;
    }
    i >= 4 && tokens[i - 1] == ")" && tokens[i - 3] == "(" && tokens[i - 4] == "pub"
}

/// `path` made absolute from `module` (`crate`, `super`, `self`, a child module); `None` for a
/// path into another crate.
fn absolute(
    module: &ModulePath,
    path: &ModulePath,
    modules: &BTreeMap<ModulePath, usize>,
) -> Option<ModulePath> {
    let mut base = module.clone();
    let mut rest = path.as_slice();
    match rest.first()?.as_str() {
        "crate" => {
            base.clear();
            rest = &rest[1..];
        }
        "self" => rest = &rest[1..],
        "super" => {
            while rest.first().is_some_and(|s| s == "super") {
                base.pop()?;
                rest = &rest[1..];
            }
        }
        first => {
            let mut child = module.clone();
            child.push(first.to_string());
            if !modules.contains_key(&child) {
                return None;
            }
        }
    }
    base.extend(rest.iter().cloned());
    Some(base)
}

impl ImportGraph {
    /// The graph of the crate whose source folder is `root`.
    pub(crate) fn of_crate(root: &Path) -> Self {
        let files = rust_files(root)
            .into_iter()
            .map(|file| {
                let text = std::fs::read_to_string(&file).unwrap();
                (module_path(root, &file), file, text)
            })
            .collect::<Vec<_>>();
        Self::of_sources(
            files
                .into_iter()
                .map(|(module, file, text)| (file, module, text)),
        )
    }

    /// The graph of files given as (file, module path, text).
    pub(crate) fn of_sources(sources: impl Iterator<Item = (PathBuf, ModulePath, String)>) -> Self {
        let files: Vec<SourceFile> = sources
            .map(|(file, module, text)| SourceFile {
                file,
                module,
                tokens: code_tokens(&text).into_iter().map(|t| t.text).collect(),
            })
            .collect();
        let modules: BTreeMap<ModulePath, usize> = files
            .iter()
            .enumerate()
            .map(|(i, f)| (f.module.clone(), i))
            .collect();
        let reexports = reexports(&files, &modules);
        let mut edges: BTreeMap<PathBuf, BTreeMap<PathBuf, BTreeSet<String>>> = BTreeMap::new();
        for source in &files {
            let children = children_of(&source.module, &modules);
            for (path, _) in named_paths(&source.tokens, &children) {
                let Some(abs) = absolute(&source.module, &path, &modules) else {
                    continue;
                };
                let Some((target, item)) = resolve(&abs, &modules, &reexports) else {
                    continue;
                };
                let target_module = &files[target].module;
                if target_module == &source.module || source.module.starts_with(target_module) {
                    continue;
                }
                edges
                    .entry(source.file.clone())
                    .or_default()
                    .entry(files[target].file.clone())
                    .or_default()
                    .insert(item);
            }
        }
        Self { edges }
    }

    /// The circles: strongly connected sets of more than one file, each sorted.
    pub(crate) fn circles(&self) -> Vec<Vec<PathBuf>> {
        strongly_connected(&self.edges)
            .into_iter()
            .filter(|c| c.len() > 1)
            .collect()
    }

    /// Number of edges.
    pub(crate) fn edge_count(&self) -> usize {
        self.edges.values().map(BTreeMap::len).sum()
    }
}

/// The child modules of `module`.
fn children_of(module: &ModulePath, modules: &BTreeMap<ModulePath, usize>) -> BTreeSet<String> {
    modules
        .keys()
        .filter(|m| m.len() == module.len() + 1 && m.starts_with(module))
        .map(|m| m.last().unwrap().clone())
        .collect()
}

/// For every module, the items it re-exports (`pub use`) and the absolute path they come from.
fn reexports(
    files: &[SourceFile],
    modules: &BTreeMap<ModulePath, usize>,
) -> BTreeMap<(ModulePath, String), ModulePath> {
    let mut out = BTreeMap::new();
    for source in files {
        let children = children_of(&source.module, modules);
        for (path, public) in named_paths(&source.tokens, &children) {
            if !public {
                continue;
            }
            if let Some(abs) = absolute(&source.module, &path, modules) {
                let name = abs.last().unwrap().clone();
                out.insert((source.module.clone(), name), abs);
            }
        }
    }
    out
}

/// The file an absolute path ends in and the name it reaches there: the deepest module of the
/// path, followed through re-exports to where the item is defined.
fn resolve(
    abs: &ModulePath,
    modules: &BTreeMap<ModulePath, usize>,
    reexports: &BTreeMap<(ModulePath, String), ModulePath>,
) -> Option<(usize, String)> {
    let mut path = abs.clone();
    for _ in 0..8 {
        let depth = (0..=path.len())
            .rev()
            .find(|&n| modules.contains_key(&path[..n]))?;
        let module = path[..depth].to_vec();
        let Some(item) = path.get(depth).cloned() else {
            return Some((modules[&module], module.last().cloned().unwrap_or_default()));
        };
        match reexports.get(&(module.clone(), item.clone())) {
            Some(source) if source != &path[..=depth] => {
                let mut next = source.clone();
                next.extend(path[depth + 1..].iter().cloned());
                path = next;
            }
            _ => return Some((modules[&module], item)),
        }
    }
    None
}

/// Tarjan's strongly connected components of `edges`.
fn strongly_connected(
    edges: &BTreeMap<PathBuf, BTreeMap<PathBuf, BTreeSet<String>>>,
) -> Vec<Vec<PathBuf>> {
    let nodes: Vec<&PathBuf> = edges
        .keys()
        .chain(edges.values().flat_map(BTreeMap::keys))
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let index_of: BTreeMap<&PathBuf, usize> =
        nodes.iter().enumerate().map(|(i, n)| (*n, i)).collect();
    let successors: Vec<Vec<usize>> = nodes
        .iter()
        .map(|n| {
            edges
                .get(*n)
                .into_iter()
                .flat_map(BTreeMap::keys)
                .map(|t| index_of[t])
                .collect()
        })
        .collect();
    let mut tarjan = Tarjan {
        successors: &successors,
        index: vec![None; nodes.len()],
        low: vec![0; nodes.len()],
        on_stack: vec![false; nodes.len()],
        stack: Vec::new(),
        next: 0,
        components: Vec::new(),
    };
    for v in 0..nodes.len() {
        if tarjan.index[v].is_none() {
            tarjan.visit(v);
        }
    }
    tarjan
        .components
        .into_iter()
        .map(|c| {
            let mut files: Vec<PathBuf> = c.into_iter().map(|i| nodes[i].clone()).collect();
            files.sort();
            files
        })
        .collect()
}

struct Tarjan<'a> {
    successors: &'a [Vec<usize>],
    index: Vec<Option<usize>>,
    low: Vec<usize>,
    on_stack: Vec<bool>,
    stack: Vec<usize>,
    next: usize,
    components: Vec<Vec<usize>>,
}

impl Tarjan<'_> {
    fn visit(&mut self, v: usize) {
        self.index[v] = Some(self.next);
        self.low[v] = self.next;
        self.next += 1;
        self.stack.push(v);
        self.on_stack[v] = true;
        for &w in &self.successors[v] {
            match self.index[w] {
                None => {
                    self.visit(w);
                    self.low[v] = self.low[v].min(self.low[w]);
                }
                Some(iw) if self.on_stack[w] => self.low[v] = self.low[v].min(iw),
                Some(_) => {}
            }
        }
        if Some(self.low[v]) == self.index[v] {
            let mut component = Vec::new();
            while let Some(w) = self.stack.pop() {
                self.on_stack[w] = false;
                component.push(w);
                if w == v {
                    break;
                }
            }
            self.components.push(component);
        }
    }
}

/// A circle in words: its files and the names each takes from the others.
fn describe(graph: &ImportGraph, circle: &[PathBuf], root: &Path) -> String {
    let shown = |p: &PathBuf| p.strip_prefix(root).unwrap_or(p).display().to_string();
    let mut lines = Vec::new();
    for a in circle {
        for (b, names) in graph.edges.get(a).into_iter().flatten() {
            if circle.contains(b) {
                let names: Vec<&str> = names.iter().map(String::as_str).collect();
                lines.push(format!(
                    "  {} -> {}: {}",
                    shown(a),
                    shown(b),
                    names.join(", ")
                ));
            }
        }
    }
    lines.join("\n")
}

#[test]
fn the_import_graph_has_no_circles() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut report = Vec::new();
    let mut edges = 0;
    for root in SOURCE_ROOTS {
        let graph = ImportGraph::of_crate(&repo.join(root));
        edges += graph.edge_count();
        for circle in graph.circles() {
            report.push(format!(
                "circle of {} files:\n{}",
                circle.len(),
                describe(&graph, &circle, repo)
            ));
        }
    }
    // The scan must see the imports it judges (several hundred between files today).
    assert!(edges > 400, "only {edges} edges between files were found");
    assert!(
        report.is_empty(),
        "import circles (move what the files share into a file of its own, or let the data \
         flow one way):\n{}",
        report.join("\n")
    );
}

/// The scanner finds what it is meant to find, on a small tree: a three-file circle through a
/// re-export and a path in the code, and no edge for a child using its parent's own type.
#[test]
fn the_scanner_sees_circles_through_reexports_and_code_paths() {
    let source = |file: &str, module: &[&str], text: &str| {
        (
            PathBuf::from(file),
            module.iter().map(|s| s.to_string()).collect::<ModulePath>(),
            text.to_string(),
        )
    };
    let files = vec![
        source("lib.rs", &[], "mod a; mod b; pub use b::Thing;"),
        source(
            "a/mod.rs",
            &["a"],
            "mod leaf; pub struct Own; fn f() { leaf::g(); }",
        ),
        source(
            "a/leaf.rs",
            &["a", "leaf"],
            "use super::Own; // the parent's own type\n\
             pub fn g() { let _ = crate::Thing::new(\"crate::x::y\"); }",
        ),
        source(
            "b.rs",
            &["b"],
            "#[cfg(test)]\nmod tests { use crate::c::T; }\npub struct Thing; \
             fn h() { crate::a::Own; }",
        ),
    ];
    let graph = ImportGraph::of_sources(files.into_iter());
    let circles = graph.circles();
    assert_eq!(
        circles,
        vec![vec![
            PathBuf::from("a/leaf.rs"),
            PathBuf::from("a/mod.rs"),
            PathBuf::from("b.rs"),
        ]],
        "{}",
        describe(&graph, &circles.concat(), Path::new(""))
    );
    // `leaf.rs` → `b.rs` through the re-export in `lib.rs`; `lib.rs` is no node of the circle.
    assert!(graph.edges[&PathBuf::from("a/leaf.rs")].contains_key(&PathBuf::from("b.rs")));
    let lib: Vec<&PathBuf> = graph.edges[&PathBuf::from("lib.rs")].keys().collect();
    assert_eq!(lib, [&PathBuf::from("b.rs")]);
}
