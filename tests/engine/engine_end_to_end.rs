//! End-to-end engine tests on real `surface` nodes: a 2 × 3 grid study, reruns, partial
//! recomputation, corrupted cache entries and interrupted runs.

use std::path::{Path, PathBuf};
use std::process::Command;

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, RunReport};
use asperity::engine::output::{OutputMetadata, ResultSet};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;
use polars::prelude::{ParquetReader, SerReader};

/// Two surfaces: `lower` uses `sq` (2 values), `upper` uses `seed` (3 values) → 6 scenarios,
/// 2 + 3 unique instances.
fn study_text(sq: &str, seeds: &str) -> String {
    format!(
        r#"
study: grid
parameters:
  product:
    sq: [{sq}]
    seed: {seeds}
nodes:
  lower:
    surface:
      synthetic: {{grid: [32, 32], size: [100 um, 100 um], sq: "${{sq}}", hurst: 0.8,
                  correlation_length: 20 um, seed: 7}}
  upper:
    surface:
      synthetic: {{grid: [32, 32], size: [100 um, 100 um], sq: 1 um, hurst: 0.7,
                  correlation_length: 20 um, seed: "${{seed}}"}}
"#
    )
}

struct Run {
    plan: Plan,
    report: RunReport,
    files: Vec<PathBuf>,
}

fn run(dir: &Path, text: &str, cache: &Path, out: &str) -> Run {
    let path = dir.join("study.yaml");
    std::fs::write(&path, text).unwrap();
    let study = Study::<TribologyNode>::load(&path).unwrap();
    let plan = Plan::build(&study).unwrap();
    let cache = Cache::open(cache).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 30,
        tool_version: String::from("test"),
    };
    let report = execute(&plan, &cache, &options, &NoProgress).unwrap();
    let meta = OutputMetadata {
        study: study.name().to_string(),
        study_file_hash: study.file_hash.clone(),
        tool_version: String::from("test"),
        overrides: Vec::new(),
    };
    let mut set = ResultSet::stage(&dir.join(out)).unwrap();
    set.write_tables(&plan, &report, &study.outputs, &meta)
        .unwrap();
    let files = set.publish().unwrap();
    Run {
        plan,
        report,
        files,
    }
}

/// Two Parquet tables hold the same cells.
fn same_cells(a: &Path, b: &Path) -> bool {
    let read = |p: &Path| {
        ParquetReader::new(std::fs::File::open(p).unwrap())
            .finish()
            .unwrap()
    };
    read(a).equals_missing(&read(b))
}

fn tempdir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-e2e-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn grid_study_runs_reruns_identically_and_recomputes_only_what_changed() {
    let dir = tempdir("grid");
    let cache = dir.join("cache");
    let text = study_text("0.5 um, 1.0 um", "{range: [1, 3]}");
    let first = run(&dir, &text, &cache, "out1");
    assert_eq!(first.plan.scenarios.rows.len(), 6);
    assert_eq!(first.plan.nodes.len(), 5, "identical instances are shared");
    assert_eq!((first.report.computed, first.report.cached), (5, 0));

    let surfaces =
        ParquetReader::new(std::fs::File::open(dir.join("out1/surfaces.parquet")).unwrap())
            .finish()
            .unwrap();
    assert_eq!(surfaces.height(), 5);
    let sq = surfaces.column("sq_m").unwrap().f64().unwrap().clone();
    let target = surfaces
        .column("sq_target_m")
        .unwrap()
        .f64()
        .unwrap()
        .clone();
    for (a, b) in sq.iter().zip(target.iter()) {
        let (a, b) = (a.unwrap(), b.unwrap());
        // Synthetic surfaces are normalised to the target Sq: exact up to round-off.
        assert!((a - b).abs() <= 1e-12 * b, "{a} vs {b}");
    }
    let scenarios =
        ParquetReader::new(std::fs::File::open(dir.join("out1/scenarios.parquet")).unwrap())
            .finish()
            .unwrap();
    assert_eq!(scenarios.height(), 6);
    for col in [
        "scenario",
        "sq_m",
        "seed",
        "lower_key",
        "upper_key",
        "status",
    ] {
        assert!(scenarios.column(col).is_ok(), "missing column {col}");
    }

    let second = run(&dir, &text, &cache, "out2");
    assert_eq!((second.report.computed, second.report.cached), (0, 5));
    for (a, b) in first.files.iter().zip(&second.files) {
        assert!(
            std::fs::read(a).unwrap() == std::fs::read(b).unwrap(),
            "rerun changed {}",
            a.display()
        );
    }

    // Change one value of `seed`: only the `upper` instance with the new seed is computed.
    let changed = run(
        &dir,
        &study_text("0.5 um, 1.0 um", "[1, 2, 9]"),
        &cache,
        "out3",
    );
    assert_eq!((changed.report.computed, changed.report.cached), (1, 4));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn outputs_limit_what_is_computed() {
    let dir = tempdir("outputs");
    let text = format!("{}outputs: [scenarios]\n", study_text("0.5 um", "[1]"));
    let r = run(&dir, &text, &dir.join("cache"), "out");
    assert_eq!(r.report.computed, 0, "scenarios alone need no node");
    assert_eq!(r.files.len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Flips one byte in the middle of a file.
fn flip_a_byte(path: &Path) {
    let mut bytes = std::fs::read(path).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 0x40;
    std::fs::write(path, bytes).unwrap();
}

#[test]
fn corrupted_payload_is_detected_discarded_and_recomputed() {
    let dir = tempdir("corrupt");
    let cache_dir = dir.join("cache");
    let text = study_text("0.5 um", "[1]");
    let first = run(&dir, &text, &cache_dir, "out1");
    assert_eq!(first.report.computed, 2);
    // A damaged heights payload: a read of the arrays finds it; a read of the metrics and
    // tables does not read the arrays.
    let cache = Cache::open(&cache_dir).unwrap();
    let node = &first.plan.nodes[0];
    let entry = cache.entry_dir("surface", &node.key);
    flip_a_byte(&entry.join("heights.npy.zst"));
    assert!(cache.load("surface", &node.key, true).is_err());
    assert!(cache.load("surface", &node.key, false).unwrap().is_some());
    // A damaged summary is found by every read, so the rerun replaces the entry.
    flip_a_byte(&entry.join("summary.bin"));
    assert!(cache.load("surface", &node.key, false).is_err());

    let second = run(&dir, &text, &cache_dir, "out2");
    assert_eq!(second.report.discarded, 1);
    assert_eq!((second.report.computed, second.report.cached), (1, 1));
    for (a, b) in first.files.iter().zip(&second.files) {
        assert!(same_cells(a, b), "{} differs", a.display());
    }
    assert!(cache.load("surface", &node.key, true).unwrap().is_some());

    // An entry written before summaries is read through its manifest, and a truncated manifest
    // is corrupt.
    let manifest = as_first_format(&cache, "surface", &node.key);
    assert!(cache.verify("surface", &node.key).unwrap());
    let loaded = cache.load("surface", &node.key, true).unwrap().unwrap();
    assert!(loaded.artifact.arrays.contains_key("heights"));
    assert!(!loaded.artifact.tables.is_empty());
    let m = std::fs::read(&manifest).unwrap();
    std::fs::write(&manifest, &m[..m.len() / 2]).unwrap();
    assert!(cache.load("surface", &node.key, false).is_err());
    // An entry that lost its manifest is damaged, not missing.
    std::fs::remove_file(&manifest).unwrap();
    assert!(cache.load("surface", &node.key, false).is_err());
    let third = run(&dir, &text, &cache_dir, "out3");
    assert_eq!(third.report.discarded, 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Rewrites the entry of `kind` and `key` as one written before summaries (entry format 1): no
/// `summary.bin` and no table files, its metrics and flags in the manifest, its tables in
/// `tables.json`, and the manifest's checksum recomputed. Returns the manifest's path.
pub(crate) fn as_first_format(
    cache: &Cache,
    kind: &str,
    key: &asperity::engine::hash::NodeKey,
) -> PathBuf {
    let loaded = cache.load(kind, key, false).unwrap().unwrap().artifact;
    let entry = cache.entry_dir(kind, key);
    let path = entry.join("manifest.json");
    let mut manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    let object = manifest.as_object_mut().unwrap();
    object.remove("format");
    object.insert(
        String::from("metrics"),
        serde_json::to_value(&loaded.metrics).unwrap(),
    );
    if !loaded.flags.is_empty() {
        object.insert(
            String::from("flags"),
            serde_json::to_value(&loaded.flags).unwrap(),
        );
    }
    let payloads = object["payloads"].as_array_mut().unwrap();
    for p in payloads.iter() {
        let file = p["file"].as_str().unwrap();
        if file == "summary.bin" || file.ends_with(".parquet") {
            std::fs::remove_file(entry.join(file)).unwrap();
        }
    }
    payloads.retain(|p| {
        let file = p["file"].as_str().unwrap();
        file != "summary.bin" && !file.ends_with(".parquet")
    });
    if !loaded.tables.is_empty() {
        let tables = serde_json::to_vec(&loaded.tables).unwrap();
        std::fs::write(entry.join("tables.json"), &tables).unwrap();
        payloads.push(serde_json::json!({
            "file": "tables.json",
            "bytes": tables.len(),
            "blake3": blake3::hash(&tables).to_hex().to_string(),
        }));
    }
    let bytes = serde_json::to_vec_pretty(&manifest).unwrap();
    std::fs::write(&path, &bytes).unwrap();
    let checksum = blake3::hash(&bytes).to_hex().to_string();
    std::fs::write(entry.join("manifest.blake3"), checksum).unwrap();
    path
}

/// An entry of format 2 keeps its metrics only in its summary: without it, it is corrupt, not
/// read as an entry without metrics.
#[test]
fn an_entry_without_its_summary_is_corrupt_unless_it_is_of_the_first_format() {
    let dir = tempdir("format");
    let cache_dir = dir.join("cache");
    let first = run(&dir, &study_text("0.5 um", "[1]"), &cache_dir, "out1");
    let cache = Cache::open(&cache_dir).unwrap();
    let node = &first.plan.nodes[0];
    let entry = cache.entry_dir("surface", &node.key);
    std::fs::remove_file(entry.join("summary.bin")).unwrap();
    assert!(cache.load("surface", &node.key, false).is_err());
    assert!(cache.verify("surface", &node.key).is_err());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A surface whose contact is cached is read without its heights; when the contact's entry turns
/// out corrupt, the heights are read for its recomputation, and damaged ones are recomputed too.
#[test]
fn damaged_arrays_read_for_a_recomputed_dependant_are_recomputed() {
    let dir = tempdir("corrupt-upstream");
    let cache_dir = dir.join("cache");
    let text = r#"
study: chain
nodes:
  s:
    surface:
      synthetic: {grid: [32, 32], size: [100 um, 100 um], sq: 0.1 um, hurst: 0.8,
                  correlation_length: 20 um, seed: 7}
  c:
    contact: {lower: s, lower_material: s235jr, nominal_pressures: [20 MPa]}
"#;
    let first = run(&dir, text, &cache_dir, "out1");
    assert_eq!(first.report.computed, 2);
    let cache = Cache::open(&cache_dir).unwrap();
    let [surface, contact] = [0, 1].map(|i| &first.plan.nodes[i]);
    flip_a_byte(
        &cache
            .entry_dir("surface", &surface.key)
            .join("heights.npy.zst"),
    );
    flip_a_byte(&cache.entry_dir("contact", &contact.key).join("summary.bin"));

    let second = run(&dir, text, &cache_dir, "out2");
    assert!(second.report.all_ok(), "{:?}", second.report.outcomes);
    assert_eq!(second.report.discarded, 2);
    for (a, b) in first.files.iter().zip(&second.files) {
        assert!(same_cells(a, b), "{} differs", a.display());
    }
    for node in [surface, contact] {
        let kind = node.task.kind();
        assert!(cache.load(kind, &node.key, true).unwrap().is_some());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn killed_run_leaves_no_entry_that_reads_back_as_valid() {
    let dir = tempdir("killed");
    let cache_dir = dir.join("cache");
    // Enough work that a kill lands mid-run: 12 surfaces of 256².
    let text = r#"
study: killed
parameters:
  product:
    seed: {range: [1, 12]}
nodes:
  s:
    surface:
      synthetic: {grid: [256, 256], size: [1 mm, 1 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 50 um, seed: "${seed}"}
"#;
    let study = dir.join("killed.yaml");
    std::fs::write(&study, text).unwrap();
    let bin = env!("CARGO_BIN_EXE_asperity");
    for delay_ms in [5u64, 20, 60] {
        let mut child = Command::new(bin)
            .args(["run", "-q", "--jobs", "2", "--cache"])
            .arg(&cache_dir)
            .arg("--out")
            .arg(dir.join("out-killed"))
            .arg(&study)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(delay_ms));
        let _ = child.kill();
        let _ = child.wait();
        // Whatever is in the cache now either verifies or is reported corrupt; a rerun from it
        // must give the same tables as a clean run.
        let cache = Cache::open(&cache_dir).unwrap();
        let s = Study::<TribologyNode>::load(&study).unwrap();
        let plan = Plan::build(&s).unwrap();
        for node in &plan.nodes {
            if let Ok(Some(entry)) = cache.load("surface", &node.key, true) {
                assert_eq!(entry.artifact.arrays["heights"].len(), 256 * 256);
            }
        }
    }
    let resumed = run(&dir, text, &cache_dir, "out-resumed");
    assert!(resumed.report.all_ok());
    let clean = run(&dir, text, &dir.join("clean-cache"), "out-clean");
    for (a, b) in resumed.files.iter().zip(&clean.files) {
        assert!(same_cells(a, b), "{} differs", a.display());
    }
    // No temporary folders of dead writers survive a run.
    let tmp: Vec<_> = std::fs::read_dir(cache_dir.join("tmp")).unwrap().collect();
    assert!(tmp.is_empty(), "stale temporary folders left: {tmp:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_failing_node_fails_only_itself_and_is_a_row_with_its_message() {
    let dir = tempdir("failing");
    // A file whose content is not a topography: planning hashes it, computing it fails.
    std::fs::write(
        dir.join("broken.x3p"),
        b"PK\x03\x04 this is not a zip archive",
    )
    .unwrap();
    let text = r#"
study: failing
nodes:
  good:
    surface:
      synthetic: {grid: [16, 16], size: [50 um, 50 um], sq: 1 um, hurst: 0.8,
                  correlation_length: 10 um, seed: 1}
  bad:
    surface:
      file: {path: broken.x3p}
"#;
    let r = run(&dir, text, &dir.join("cache"), "out");
    assert_eq!((r.report.computed, r.report.failed), (1, 1));
    assert!(!r.report.all_ok());
    let surfaces =
        ParquetReader::new(std::fs::File::open(dir.join("out/surfaces.parquet")).unwrap())
            .finish()
            .unwrap();
    let status: Vec<_> = surfaces
        .column("status")
        .unwrap()
        .str()
        .unwrap()
        .iter()
        .map(|s| s.unwrap().to_string())
        .collect();
    let message: Vec<_> = surfaces
        .column("message")
        .unwrap()
        .str()
        .unwrap()
        .iter()
        .map(|s| s.unwrap().to_string())
        .collect();
    let bad = status.iter().position(|s| s == "failed").unwrap();
    assert!(message[bad].contains("broken.x3p"), "{}", message[bad]);
    assert!(status.contains(&String::from("ok")));
    // The failure is not cached: the next run tries again.
    let again = run(&dir, text, &dir.join("cache"), "out2");
    assert_eq!((again.report.cached, again.report.failed), (1, 1));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A node whose memory estimate and the process's base exceed the budget fails before it
/// allocates, naming the sizes and `--memory-mib`; with a budget that holds it, it computes.
#[test]
fn a_node_larger_than_the_memory_budget_fails_before_it_allocates() {
    let dir = tempdir("memory_budget");
    let path = dir.join("study.yaml");
    std::fs::write(&path, study_text("1 um", "[1]")).unwrap();
    let study = Study::<TribologyNode>::load(&path).unwrap();
    let plan = Plan::build(&study).unwrap();
    let cache = Cache::open(&dir.join("cache")).unwrap();
    let run_with = |memory_budget: u64| {
        let options = ExecuteOptions {
            tables: study.outputs.clone(),
            memory_budget,
            tool_version: String::from("test"),
        };
        execute(&plan, &cache, &options, &NoProgress).unwrap()
    };
    let report = run_with(1 << 10);
    assert_eq!(report.failed, plan.nodes.len());
    for outcome in report.outcomes.iter().flatten() {
        let message = outcome.status.message();
        assert!(
            message.contains("exceeds the run's budget of 1 MiB")
                && message.contains("--memory-mib"),
            "{message}"
        );
    }
    assert!(run_with(1 << 30).all_ok());
}

/// `surfaces_by_scenario`: one row per scenario and surface node, the scenario's parameters as
/// `param_*` beside the measured columns, and each row's values those of its instance's row in
/// `surfaces`.
#[test]
fn the_tidy_view_carries_the_scenario_parameters() {
    use polars::prelude::DataType;
    let dir = tempdir("tidy");
    let text = study_text("0.5 um, 1.0 um", "{range: [1, 3]}");
    run(&dir, &text, &dir.join("cache"), "out");
    let read = |name: &str| {
        ParquetReader::new(std::fs::File::open(dir.join("out").join(name)).unwrap())
            .finish()
            .unwrap()
    };
    let tidy = read("surfaces_by_scenario.parquet");
    let surfaces = read("surfaces.parquet");
    assert_eq!(tidy.height(), 12, "6 scenarios × 2 surface nodes");
    let names: Vec<String> = tidy
        .get_column_names()
        .iter()
        .map(|n| n.to_string())
        .collect();
    assert_eq!(
        &names[..5],
        ["scenario", "param_sq_m", "param_seed", "node", "key"]
    );
    let column = |df: &polars::prelude::DataFrame, name: &str, row: usize| {
        df.column(name)
            .unwrap()
            .cast(&DataType::String)
            .unwrap()
            .str()
            .unwrap()
            .get(row)
            .map(str::to_string)
    };
    for row in 0..tidy.height() {
        let scenario = row / 2;
        assert_eq!(column(&tidy, "scenario", row), Some(scenario.to_string()));
        assert_eq!(
            column(&tidy, "node", row).as_deref(),
            Some(["lower", "upper"][row % 2])
        );
        // Scenarios run sq slowest, seed fastest.
        let sq = [0.5e-6, 1.0e-6][scenario / 3];
        let param_sq = tidy.column("param_sq_m").unwrap().f64().unwrap().get(row);
        assert_eq!(param_sq, Some(sq));
        let key = column(&tidy, "key", row).unwrap();
        let instance = (0..surfaces.height())
            .find(|&r| column(&surfaces, "key", r).as_deref() == Some(key.as_str()))
            .expect("every tidy row is an instance of the kind table");
        for name in surfaces.get_column_names().iter().map(|n| n.as_str()) {
            // The instance's bookkeeping stays in the kind table.
            if !matches!(name, "nodes" | "kind_version") && !name.ends_with("_key") {
                assert_eq!(
                    column(&tidy, name, row),
                    column(&surfaces, name, instance),
                    "{name} of row {row}"
                );
            }
        }
        let measured = tidy
            .column("sq_m")
            .unwrap()
            .f64()
            .unwrap()
            .get(row)
            .unwrap();
        if row % 2 == 0 {
            assert!(
                (measured - sq).abs() <= 1e-12 * sq,
                "lower's Sq is the parameter"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
