//! The `surface` node on measured files and synthetic twins, end to end through the engine.
//! Uses `../shared/data/topography` (or `ASPERITY_TEST_DATA`); fails when `CI` is set and the data
//! is missing, skips with a note otherwise.

use crate::common;
use std::path::{Path, PathBuf};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, NodeOutcome};
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

/// Runs study `text` in `dir`: whether every node succeeded, and each named node's outcome.
fn run(dir: &Path, text: String) -> (bool, impl Fn(&str) -> NodeOutcome) {
    let study = Study::<TribologyNode>::from_source(&dir.join("s.yaml"), text).unwrap();
    let plan = Plan::build(&study).unwrap();
    let cache = Cache::open(&dir.join("cache")).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 30,
        tool_version: String::from("test"),
    };
    let report = execute(&plan, &cache, &options, &NoProgress).unwrap();
    let all_ok = report.all_ok();
    let outcome = move |name: &str| {
        let i = plan
            .nodes
            .iter()
            .position(|n| n.names.iter().any(|m| m == name))
            .unwrap();
        report.outcomes[i].clone().unwrap()
    };
    (all_ok, outcome)
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
    let (all_ok, outcome) = run(&dir, text);
    assert!(all_ok);
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
    // 2 µm is outside the fitted range: flagged as a typed column and said in a sentence.
    assert_eq!(
        metric(&twin.metrics, "twin_extrapolated"),
        Value::Bool(true)
    );
    match metric(&twin.metrics, "twin_warnings") {
        Value::Texts(w) => assert!(
            w.len() == 1 && w[0].starts_with("Sq = 2.00 µm lies outside the measured range"),
            "{w:?}"
        ),
        other => panic!("{other:?}"),
    }
    assert_eq!(metric(&twin.metrics, "twin_measured_files"), Value::Int(2));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The real files of the twins issue: every failure names the file and the study field that fixes
/// it, and a twin of one real file at its own Sq works once its band is chosen.
#[test]
fn twins_of_real_files_fail_with_the_fix_or_work() {
    let Some(data) = common::data_dir() else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("asperity-real-twins-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let file = |name: &str| data.join(name).display().to_string();
    let text = format!(
        r#"
study: real-twins
nodes:
  no_filter:
    surface:
      twin: {{of: ["{plu}"], sq: 1 um, grid: [64, 64], size: [0.5 mm, 0.5 mm], seed: 1}}
  default_band:
    surface:
      twin:
        of: ["{plu}"]
        preprocess: {{form_degree: 2, l_filter: 200 um}}
        sq: 1 um
        grid: [64, 64]
        size: [0.5 mm, 0.5 mm]
        seed: 1
  spiky:
    surface:
      twin:
        of: ["{sur}"]
        preprocess: {{form_degree: 2, l_filter: 300 um}}
        sq: measured
        grid: [256, 256]
        size: [1 mm, 1 mm]
        seed: 1
  too_coarse:
    surface:
      twin:
        of: ["{sur}"]
        preprocess: {{form_degree: 2, l_filter: 300 um}}
        sq: measured
        grid: [16, 16]
        size: [1 mm, 1 mm]
        seed: 1
"#,
        plu = file("plu/plu-1.plu"),
        sur = file("sur/sur-2.sur"),
    );
    let (_, outcome) = run(&dir, text);
    let failure = |name: &str| outcome(name).status.message().to_string();
    let no_filter = failure("no_filter");
    assert!(
        no_filter.contains("plu-1.plu") && no_filter.contains("preprocess: {l_filter: 191 µm}"),
        "{no_filter}"
    );
    let band = failure("default_band");
    assert!(
        band.contains("plu-1.plu") && band.contains("hurst_band"),
        "{band}"
    );
    let coarse = failure("too_coarse");
    assert!(
        coarse.contains("use `size: [") && coarse.contains("grid: ["),
        "{coarse}"
    );
    let spiky = outcome("spiky");
    assert!(
        spiky.status.message().is_empty(),
        "{}",
        spiky.status.message()
    );
    assert_eq!(
        metric(&spiky.metrics, "twin_extrapolated"),
        Value::Bool(false)
    );
    assert_eq!(
        metric(&spiky.metrics, "twin_correlation_x_methods"),
        Value::Texts(vec![String::from("acf_crossing: 1")])
    );
    // A twin at the measured Sq has that Sq.
    let sq = float(metric(&spiky.metrics, "sq"));
    let measured = float(metric(&spiky.metrics, "twin_measured_sq_min"));
    assert!((sq / measured - 1.0).abs() < 1e-12, "{sq} vs {measured}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `channel:` picks a channel of a multi-channel file (ASCII case ignored; the default is the
/// height channel), and a name the file does not hold fails naming the channels it does.
#[test]
fn measured_file_channel_is_chosen_by_name() {
    let Some(data) = common::data_dir() else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("asperity-channel-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let file = data.join("di/di-5.di");
    let text = format!(
        r#"
study: channels
nodes:
  default:
    surface:
      file: {{path: "{f}"}}
  named:
    surface:
      file: {{path: "{f}", channel: zsensor}}
  unknown:
    surface:
      file: {{path: "{f}", channel: Phase}}
"#,
        f = file.display()
    );
    let (all_ok, outcome) = run(&dir, text);
    assert!(!all_ok);
    let sq = |name: &str| float(metric(&outcome(name).metrics, "sq"));
    assert_eq!(sq("named"), sq("default"));
    let message = outcome("unknown").status.message().to_string();
    assert!(
        message.contains("no channel `Phase`")
            && message.contains("`ZSensor`, `PeakForceError`")
            && message.contains("di-5.di"),
        "{message}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
