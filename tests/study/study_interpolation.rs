//! `${name}` inside strings and the `glob` file axis: a study over a folder of measured pairs is
//! a few lines; substituted values get the same checks as whole values; keys hold file hashes.

use std::path::{Path, PathBuf};

use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::engine::value::Value;
use asperity::nodes::TribologyNode;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-interp-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("scans")).unwrap();
    dir
}

/// A tiny Gwyddion text export (calibrated: 8 µm over 8 columns) with heights varied by `seed`.
fn write_scan(path: &Path, seed: u32) {
    let mut body = String::from("# Width: 8 µm\n# Height: 8 µm\n# Value units: m\n");
    for iy in 0..8 {
        let row: Vec<String> = (0..8)
            .map(|ix| format!("{:e}", 1e-7 * (f64::from(ix * seed + iy)).sin()))
            .collect();
        body.push_str(&(row.join("\t") + "\n"));
    }
    std::fs::write(path, body).unwrap();
}

fn plan(dir: &Path, text: &str) -> Result<Plan, String> {
    let path = dir.join("study.yaml");
    std::fs::write(&path, text).unwrap();
    let study = Study::<TribologyNode>::load(&path).map_err(|e| e.to_string())?;
    Plan::build(&study).map_err(|e| e.to_string())
}

fn texts(plan: &Plan, parameter: &str) -> Vec<String> {
    let c = plan
        .scenarios
        .names
        .iter()
        .position(|n| n == parameter)
        .unwrap();
    plan.scenarios
        .rows
        .iter()
        .map(|r| r[c].to_string())
        .collect()
}

fn param(plan: &Plan, node: usize, name: &str) -> Value {
    plan.nodes[node]
        .task
        .params()
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no param {name}"))
        .value
        .clone()
}

const PAIRS: &str = r#"
study: pairs
parameters:
  product:
    pair: {glob: "scans/*-upper.txt", values: stems}
nodes:
  upper:
    surface:
      file: {path: "scans/${pair}-upper.txt"}
  lower:
    surface:
      file: {path: "scans/${ pair }-lower.txt"}
"#;

#[test]
fn a_glob_of_stems_pairs_files_by_name_and_keys_hold_content_hashes() {
    let dir = scratch("pairs");
    for (i, pair) in ["p10", "p01", "p02"].iter().enumerate() {
        write_scan(&dir.join(format!("scans/{pair}-upper.txt")), 3 + i as u32);
        write_scan(&dir.join(format!("scans/{pair}-lower.txt")), 3 + i as u32);
    }
    write_scan(&dir.join("scans/notes-lower.txt"), 9);
    let p = plan(&dir, PAIRS).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        texts(&p, "pair"),
        ["'p01'", "'p02'", "'p10'"],
        "sorted stems"
    );
    assert!(p.unused_parameters.is_empty(), "used inside strings");
    // Upper and lower of a pair have the same content: one instance, keyed by the file hash.
    assert_eq!(p.nodes.len(), 3);
    for s in 0..3 {
        assert_eq!(p.scenario_nodes[s][0], p.scenario_nodes[s][1]);
    }
    let hashes: Vec<Value> = (0..3).map(|i| param(&p, i, "file_blake3")).collect();
    assert!(hashes[0] != hashes[1] && hashes[1] != hashes[2]);
    // The paths themselves are in no key.
    assert!(p.nodes[0].task.params().iter().all(|f| f.name != "path"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_glob_of_paths_is_sorted_and_an_empty_match_is_an_error() {
    let dir = scratch("paths");
    write_scan(&dir.join("scans/b.txt"), 2);
    write_scan(&dir.join("scans/a.txt"), 3);
    std::fs::create_dir_all(dir.join("scans/c.txt")).unwrap();
    let text = |pattern: &str, values: &str| {
        format!(
            "study: g\nparameters:\n  product:\n    f: {{glob: \"{pattern}\"{values}}}\n\
             nodes:\n  s:\n    surface:\n      file: {{path: \"${{f}}\"}}\n"
        )
    };
    let p = plan(&dir, &text("scans/*.txt", "")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        texts(&p, "f"),
        ["'scans/a.txt'", "'scans/b.txt'"],
        "directories never match"
    );
    let e = plan(&dir, &text("scans/*.x3p", "")).unwrap_err();
    assert!(e.contains("no file matches 'scans/*.x3p'"), "{e}");
    assert!(e.contains("study.yaml:4:"), "{e}");
    let e = plan(&dir, &text("scans/*/*.txt", ", values: stems")).unwrap_err();
    assert!(e.contains("exactly one '*'"), "{e}");
    let e = plan(&dir, &text("scans/*.txt", ", values: names")).unwrap_err();
    assert!(e.contains("values: 'names'"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn substituted_strings_are_checked_like_whole_values() {
    let dir = scratch("checks");
    write_scan(&dir.join("01-upper.txt"), 3);
    let synthetic = |axis: &str, sq: &str| {
        format!(
            "study: s\nparameters:\n  product:\n    n: {axis}\nnodes:\n  s:\n    surface:\n      \
             synthetic: {{grid: [16, 16], size: [0.1 mm, 0.1 mm], sq: \"{sq}\", hurst: 0.8,\n                  \
             correlation_length: 20 um, seed: 1}}\n"
        )
    };
    let p = plan(&dir, &synthetic("[1, 2]", "${n} um")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(param(&p, 0, "sq_target"), Value::Float(1e-6));
    assert_eq!(param(&p, 1, "sq_target"), Value::Float(2e-6));
    // Adjacent references are two references, like a reference followed by a digit.
    let p = plan(&dir, &synthetic("[1, 2]", "${n}${n} um")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(param(&p, 0, "sq_target"), Value::Float(11e-6));
    assert_eq!(param(&p, 1, "sq_target"), Value::Float(22e-6));
    let p = plan(&dir, &synthetic("[1]", "${n}0 um")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(param(&p, 0, "sq_target"), Value::Float(10e-6));
    let cases = [
        (
            synthetic("[abc]", "${n} um"),
            vec!["expected a length", "'${n} um'"],
        ),
        (
            synthetic("[1]", "${m} um"),
            vec!["unknown parameter '${m}'", "did you mean 'n'"],
        ),
        (synthetic("[1]", "${n um"), vec!["without a closing '}'"]),
        (synthetic("[[1, 2]]", "${n} um"), vec!["is a list"]),
        (synthetic("[1]", "${n} MPa"), vec!["expected a length"]),
    ];
    for (text, expected) in cases {
        let e = plan(&dir, &text).unwrap_err();
        for part in expected {
            assert!(e.contains(part), "'{part}' not in: {e}");
        }
        assert!(e.contains("nodes.s.surface.synthetic.sq"), "{e}");
    }
    // Material names: a reference inside the name.
    let material = |grade: &str| {
        format!(
            "study: m\nparameters:\n  product:\n    grade: [{grade}]\nnodes:\n  s:\n    surface:\n      \
             synthetic: {{grid: [16, 16], size: [0.1 mm, 0.1 mm], sq: 1 um, hurst: 0.8,\n                  \
             correlation_length: 20 um, seed: 1}}\n  c:\n    contact:\n      lower: s\n      \
             lower_material: \"s${{grade}}jr\"\n      nominal_pressures: [20 MPa]\n"
        )
    };
    assert!(plan(&dir, &material("235")).is_ok());
    let e = plan(&dir, &material("236")).unwrap_err();
    assert!(e.contains("unknown material 's236jr'"), "{e}");
    // A text field whose value reads like a number and an unknown unit is still a path.
    let p = plan(
        &dir,
        "study: t\nnodes:\n  s:\n    surface:\n      file: {path: 01-upper.txt}\n",
    );
    assert!(p.is_ok(), "{p:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
