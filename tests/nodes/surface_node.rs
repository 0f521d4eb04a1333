//! The `surface` node on measured files and synthetic twins, end to end through the engine.
//! Uses `../shared/data/topography` (or `ASPERITY_TEST_DATA`); fails when `CI` is set and the data
//! is missing, skips with a note otherwise.

use crate::common;
use std::path::{Path, PathBuf};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::engine::value::Value;
use asperity::nodes::TribologyNode;
fn metric(fields: &[asperity::engine::value::Field], name: &str) -> Value {
    fields
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no metric {name}"))
        .value
        .clone()
}

fn float(v: Value) -> f64 {
    match v {
        Value::Float(x) => x,
        other => panic!("not a float: {other:?}"),
    }
}

/// Writes a 128² synthetic surface of 50 µm side as a Gwyddion-style text matrix.
fn write_text_surface(dir: &Path, sq: f64, seed: u64) -> PathBuf {
    use asperity::surface::synthetic::{generate_synthetic_surface, SyntheticSurfaceSpec};
    let map = generate_synthetic_surface(&SyntheticSurfaceSpec {
        nx: 128,
        ny: 128,
        lx: 50e-6,
        ly: 50e-6,
        sq,
        hurst: 0.8,
        correlation_length: 10e-6,
        short_wavelength_cutoff: None,
        anisotropy: None,
        seed,
    })
    .unwrap();
    let mut text = String::from(
        "# Channel: Height\n# Width: 50.000 µm\n# Height: 50.000 µm\n# Value units: m\n",
    );
    for row in map.heights().rows() {
        let line: Vec<String> = row.iter().map(|z| format!("{z:e}")).collect();
        text.push_str(&line.join("\t"));
        text.push('\n');
    }
    let path = dir.join(format!("measured-{seed}.txt"));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn measured_file_with_form_removal_and_a_twin_run_through_the_engine() {
    let Some(data) = common::data_dir() else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("asperity-surface-node-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let metropro = data.join("metropro-dat/metropro-1.dat");
    // "Measured" ground-like surfaces for the twin: synthetic ones written as Gwyddion-style text
    // matrices (real files here are not self-affine over the fitted band).
    let measured: Vec<PathBuf> = [(0.5e-6, 1u64), (1.0e-6, 2)]
        .iter()
        .map(|&(sq, seed)| write_text_surface(&dir, sq, seed))
        .collect();
    let text = format!(
        r#"
study: measured
nodes:
  levelled:
    surface:
      file: {{path: "{}", form_degree: 2}}
  twin:
    surface:
      twin:
        of: ["{}", "{}"]
        sq: 2 um
        grid: [128, 128]
        size: [50 um, 50 um]
        seed: 3
"#,
        metropro.display(),
        measured[0].display(),
        measured[1].display()
    );
    let study = Study::<TribologyNode>::from_source(&dir.join("s.yaml"), text).unwrap();
    let plan = Plan::build(&study).unwrap();
    let cache = Cache::open(&dir.join("cache")).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 30,
        tool_version: String::from("test"),
    };
    let report = execute(&plan, &cache, &options, &NoProgress).unwrap();
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let outcome = |name: &str| {
        let i = plan
            .nodes
            .iter()
            .position(|n| n.names.iter().any(|m| m == name))
            .unwrap();
        report.outcomes[i].clone().unwrap()
    };
    // SurfaceTopography asserts Sq after curvature (degree-2) detrend = 3.911386124282179e-09 m
    // (rtol 1e-6) for this MetroPro file.
    let levelled = outcome("levelled");
    let sq = float(metric(&levelled.metrics, "sq"));
    assert!((sq / 3.911386124282179e-09 - 1.0).abs() < 1e-6, "Sq {sq}");
    assert!(levelled.tables.contains_key("summits"));

    // The twin has exactly the requested Sq and reports what it predicted.
    let twin = outcome("twin");
    let sq = float(metric(&twin.metrics, "sq"));
    assert!((sq / 2e-6 - 1.0).abs() < 1e-12, "twin Sq {sq}");
    let h = float(metric(&twin.metrics, "twin_hurst"));
    assert!(h > 0.0 && h <= 1.0);
    match metric(&twin.metrics, "twin_warnings") {
        Value::Text(w) => assert!(
            w.contains("Extrapolated"),
            "2 um is outside the fitted range: {w}"
        ),
        other => panic!("{other:?}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}
