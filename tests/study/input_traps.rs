//! Inputs that must not silently go wrong: the corpus of semantic traps of measured files, each
//! answered with a clear error naming the file and the fix, or an explicit, documented result.
//! The trap files are written by the test (NumPy `.npy` and text matrices), so the corpus needs no
//! binary fixtures: unknown spacing (npy, bare CSV), a spacing that disagrees with the file's, a
//! 1 m pixel on µm roughness, a NaN-only map, a flat map, one valid point, infinite values.

use std::path::{Path, PathBuf};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, NodeOutcome, NodeStatus};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::engine::value::Value;
use asperity::nodes::TribologyNode;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-traps-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A deterministic rough 32² map (m): a few sines of ~0.1 µm amplitude.
fn rough(n: usize) -> Vec<f64> {
    (0..n * n)
        .map(|p| {
            let (x, y) = ((p % n) as f64, (p / n) as f64);
            1e-7 * ((0.7 * x).sin() + (1.3 * y + 0.4).cos() + (0.3 * x + 0.9 * y).sin())
        })
        .collect()
}

/// Writes a little-endian f8 C-order `.npy` of an n × n map.
fn write_npy(path: &Path, n: usize, values: &[f64]) {
    let mut dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, {n}), }}");
    while (10 + dict.len() + 1) % 64 != 0 {
        dict.push(' ');
    }
    dict.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((dict.len() as u16).to_le_bytes());
    bytes.extend(dict.as_bytes());
    for v in values {
        bytes.extend(v.to_le_bytes());
    }
    std::fs::write(path, bytes).unwrap();
}

/// Runs a study of one `surface: {file: {<file>}}` node `s` (and a contact on it); returns the
/// surface's outcome.
fn surface_outcome(dir: &Path, file_fields: &str) -> NodeOutcome {
    let text = format!("study: trap\nnodes:\n  s:\n    surface:\n      file: {{{file_fields}}}\n");
    let path = dir.join("trap.yaml");
    std::fs::write(&path, text).unwrap();
    let study = Study::<TribologyNode>::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let plan = Plan::build(&study).unwrap_or_else(|e| panic!("{e}"));
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 30,
        tool_version: String::from("test"),
    };
    let cache = Cache::open(&dir.join("cache")).unwrap();
    let report = execute(&plan, &cache, &options, &NoProgress).unwrap();
    report.outcomes[0].clone().expect("the surface was needed")
}

fn plan_error(dir: &Path, file_fields: &str) -> String {
    let text = format!("study: trap\nnodes:\n  s:\n    surface:\n      file: {{{file_fields}}}\n");
    let path = dir.join("trap.yaml");
    std::fs::write(&path, text).unwrap();
    match Study::<TribologyNode>::load(&path) {
        Ok(study) => Plan::build(&study)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default(),
        Err(e) => e.to_string(),
    }
}

fn failure(o: &NodeOutcome) -> &str {
    match &o.status {
        NodeStatus::Failed(m) => m,
        other => panic!("expected a failure, got {other:?}"),
    }
}

fn metric<'a>(o: &'a NodeOutcome, name: &str) -> &'a Value {
    &o.metrics
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no metric {name}"))
        .value
}

fn float(o: &NodeOutcome, name: &str) -> f64 {
    match metric(o, name) {
        Value::Float(x) => *x,
        other => panic!("{name}: {other:?}"),
    }
}

fn text(o: &NodeOutcome, name: &str) -> String {
    match metric(o, name) {
        Value::Text(s) => s.clone(),
        other => panic!("{name}: {other:?}"),
    }
}

#[test]
fn a_file_without_lateral_calibration_needs_pixel_size_or_size() {
    let dir = scratch("spacing");
    write_npy(&dir.join("s.npy"), 32, &rough(32));
    let csv: String = rough(32)
        .chunks(32)
        .map(|row| {
            let cells: Vec<String> = row.iter().map(|z| format!("{z:e}")).collect();
            cells.join(",") + "\n"
        })
        .collect();
    std::fs::write(dir.join("s.csv"), csv).unwrap();
    for file in ["s.npy", "s.csv"] {
        let o = surface_outcome(&dir, &format!("path: {file}"));
        let m = failure(&o);
        for part in [
            file,
            "spacing: not in the file",
            "pixel_size",
            "size: [Lx, Ly]",
        ] {
            assert!(m.contains(part), "{file}: '{part}' not in: {m}");
        }
        let o = surface_outcome(&dir, &format!("path: {file}, pixel_size: 0.5 um"));
        assert_eq!(o.status, NodeStatus::Computed, "{:?}", o.status);
        assert_eq!(float(&o, "dx"), 0.5e-6);
        assert_eq!(float(&o, "dy"), 0.5e-6);
        assert_eq!(text(&o, "height_unit_source"), "assumed");
        assert_eq!(text(&o, "lateral_scale_warning"), "");
        let o = surface_outcome(&dir, &format!("path: {file}, size: [32 um, 16 um]"));
        assert_eq!((float(&o, "dx"), float(&o, "dy")), (1e-6, 0.5e-6));
    }
    let both = plan_error(&dir, "path: s.npy, pixel_size: 1 um, size: 32 um");
    assert!(both.contains("not both"), "{both}");
    let lone = plan_error(&dir, "path: s.npy, override_file_spacing: true");
    assert!(lone.contains("neither is given"), "{lone}");
    let bad = plan_error(&dir, "path: s.npy, pixel_size: [1 um, 2 um, 3 um]");
    assert!(bad.contains("list of two"), "{bad}");
    let negative = plan_error(&dir, "path: s.npy, pixel_size: -1 um");
    assert!(negative.contains("must be > 0 m"), "{negative}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A file without a height unit (npy, a bare CSV matrix) is read as metres only with a flag
/// naming `height_unit`; `height_unit` scales its values (a unit name or the length of one stored
/// value) and the row says where the unit came from; a unit that is no length is a plan error.
#[test]
fn a_file_without_height_unit_is_flagged_unless_the_study_gives_it() {
    let dir = scratch("height-unit");
    let microns: Vec<f64> = rough(32).iter().map(|z| z * 1e6).collect();
    write_npy(&dir.join("s.npy"), 32, &microns);
    let assumed = surface_outcome(&dir, "path: s.npy, pixel_size: 0.5 um");
    assert_eq!(assumed.label(), "flagged");
    let flag = assumed.flags.join("; ");
    for part in [
        "s.npy",
        "stores no height unit",
        "read as metres",
        "height_unit: um",
    ] {
        assert!(flag.contains(part), "'{part}' not in: {flag}");
    }
    assert_eq!(text(&assumed, "height_unit_source"), "assumed");
    let sq_assumed = float(&assumed, "sq");
    for unit in ["um", "1 um", "1000 nm"] {
        let o = surface_outcome(
            &dir,
            &format!("path: s.npy, pixel_size: 0.5 um, height_unit: {unit}"),
        );
        assert_eq!(o.label(), "ok", "{unit}: {:?} {:?}", o.status, o.flags);
        assert_eq!(text(&o, "height_unit_source"), "study");
        let sq = float(&o, "sq");
        assert!(
            (sq / sq_assumed - 1e-6).abs() < 1e-15,
            "{unit}: Sq {sq:e} vs {sq_assumed:e} m"
        );
    }
    let bad = plan_error(&dir, "path: s.npy, pixel_size: 0.5 um, height_unit: 1 MPa");
    assert!(bad.contains("height_unit"), "{bad}");
    let negative = plan_error(&dir, "path: s.npy, pixel_size: 0.5 um, height_unit: -1 um");
    assert!(negative.contains("> 0 m"), "{negative}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A calibrated file (a Gwyddion text export: 50 µm over 32 columns) checks a given pixel size:
/// equal to 1e-6 passes, different fails naming `override_file_spacing`, which then applies it.
#[test]
fn a_given_spacing_must_agree_with_the_file_unless_overridden() {
    let dir = scratch("agree");
    let mut body = String::from("# Width: 32.000 µm\n# Height: 32.000 µm\n# Value units: m\n");
    for row in rough(32).chunks(32) {
        let cells: Vec<String> = row.iter().map(|z| format!("{z:e}")).collect();
        body.push_str(&(cells.join("\t") + "\n"));
    }
    std::fs::write(dir.join("g.txt"), body).unwrap();
    let o = surface_outcome(&dir, "path: g.txt");
    assert_eq!(float(&o, "dx"), 1e-6);
    assert_eq!(text(&o, "height_unit_source"), "file");
    let refused = surface_outcome(&dir, "path: g.txt, height_unit: nm");
    let refused = failure(&refused);
    assert!(
        refused.contains("states its own height unit") && refused.contains("g.txt"),
        "{refused}"
    );
    let o = surface_outcome(&dir, "path: g.txt, pixel_size: 1.0000001 um");
    assert_eq!(
        o.status,
        NodeStatus::Computed,
        "within 1e-6: {:?}",
        o.status
    );
    assert_eq!(float(&o, "dx"), 1e-6, "the file's value is kept");
    let o = surface_outcome(&dir, "path: g.txt, pixel_size: 1.1 um");
    let m = failure(&o);
    assert!(
        m.contains("override_file_spacing: true") && m.contains("g.txt"),
        "{m}"
    );
    let o = surface_outcome(
        &dir,
        "path: g.txt, pixel_size: 1.1 um, override_file_spacing: true",
    );
    assert!((float(&o, "dx") - 1.1e-6).abs() < 1e-18);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A 1 m pixel on 0.1 µm heights (the classic npy mistake once a pixel size is required) is
/// computed but flagged in `lateral_scale_warning`; so is a pixel far too small.
#[test]
fn an_absurd_pixel_size_is_flagged() {
    let dir = scratch("absurd");
    write_npy(&dir.join("s.npy"), 32, &rough(32));
    let o = surface_outcome(&dir, "path: s.npy, pixel_size: 1 m");
    assert_eq!(o.status, NodeStatus::Computed);
    let w = text(&o, "lateral_scale_warning");
    assert!(w.contains("pixel size too large"), "{w}");
    let o = surface_outcome(&dir, "path: s.npy, pixel_size: 1 pm");
    assert!(text(&o, "lateral_scale_warning").contains("too small"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// NaN-only, flat and one-valid-point maps fail with a message; ±inf are missing points.
#[test]
fn degenerate_maps_fail_clearly() {
    let dir = scratch("degenerate");
    let n = 32;
    write_npy(&dir.join("nan.npy"), n, &vec![f64::NAN; n * n]);
    write_npy(&dir.join("flat.npy"), n, &vec![2e-6; n * n]);
    let mut one = vec![f64::NAN; n * n];
    one[100] = 1e-6;
    write_npy(&dir.join("one.npy"), n, &one);
    let mut inf = rough(n);
    inf[5] = f64::INFINITY;
    inf[6] = f64::NEG_INFINITY;
    write_npy(&dir.join("inf.npy"), n, &inf);
    let cases = [
        (
            "path: nan.npy, pixel_size: 1 um",
            "no valid (measured) point",
        ),
        (
            "path: nan.npy, pixel_size: 1 um, fill_missing: true",
            "no valid point to fill from",
        ),
        ("path: flat.npy, pixel_size: 1 um", "perfectly flat"),
        ("path: one.npy, pixel_size: 1 um", "perfectly flat"),
        (
            "path: one.npy, pixel_size: 1 um, fill_missing: true",
            "only 1 of 1024 points are valid",
        ),
    ];
    for (fields, expected) in cases {
        let o = surface_outcome(&dir, fields);
        let m = failure(&o);
        assert!(m.contains(expected), "{fields}: {m}");
    }
    let o = surface_outcome(&dir, "path: inf.npy, pixel_size: 1 um");
    assert_eq!(o.status, NodeStatus::Computed);
    assert_eq!(metric(&o, "missing_points"), &Value::Int(2));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `asperity inspect` says the spacing is not in the file, how to give it, and prints no size or
/// slope statistics that would depend on it.
#[test]
fn inspect_says_the_spacing_is_not_in_the_file() {
    let dir = scratch("inspect");
    write_npy(&dir.join("s.npy"), 32, &rough(32));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .arg("inspect")
        .arg(dir.join("s.npy"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    assert!(stdout.contains("spacing:   not in the file"), "{stdout}");
    assert!(stdout.contains("pixel_size"), "{stdout}");
    assert!(!stdout.contains("size:      "), "{stdout}");
    assert!(!stdout.contains("Sdq ="), "{stdout}");
    let _ = std::fs::remove_dir_all(&dir);
}
