//! Byte-reproducible results: the same study gives byte-identical Parquet tables on two fresh
//! caches, with 1 and with 2 worker threads, and again when every node is read from the cache;
//! rows follow the documented order (scenario, then the study file's node order); run times are
//! only in `timings.parquet`.

use std::path::{Path, PathBuf};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, RunReport};
use asperity::engine::output::{OutputMetadata, ResultSet};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;
use polars::prelude::{ParquetReader, SerReader};

/// Surface → contact → three friction nodes, two Sq × two seeds, with long tables and a summary.
/// The node names are deliberately not in alphabetical or dependency order in the file.
const STUDY: &str = r#"
study: reproducible
parameters:
  product:
    sq: [0.05 um, 0.08 um]
    seed: [2, 1]
nodes:
  zeta:
    friction:
      model: full_stick
      lower: surface
      lower_material: s235jr
      nominal_pressures: [10 MPa, 20 MPa]
  surface:
    surface:
      synthetic: {grid: [48, 48], size: [0.2 mm, 0.2 mm], sq: "${sq}", hurst: 0.8,
                  correlation_length: 20 um, seed: "${seed}"}
  alpha:
    friction:
      method: per_spot
      model: full_stick
      contact: contact
      lower_material: s235jr
      spots_table: true
  contact:
    contact:
      lower: surface
      lower_material: s235jr
      nominal_pressures: [10 MPa, 20 MPa]
      fields: true
  mid:
    friction:
      model: junction_shear
      contact: contact
      lower_material: s235jr
summaries:
  per_sq:
    by: [sq]
    metrics: [contact.area_fraction, zeta.mu_s, alpha.mu_s]
"#;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-repro-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the study on `threads` worker threads with the cache in `cache`, writes every table
/// (with the summaries and the timings) to `out`; returns the report.
fn run(study_path: &Path, cache: &Path, out: &Path, threads: usize) -> RunReport {
    let study = Study::<TribologyNode>::load(study_path).unwrap();
    let plan = Plan::build(&study).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 30,
        tool_version: String::from("test"),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let report = pool
        .install(|| execute(&plan, &Cache::open(cache).unwrap(), &options, &NoProgress))
        .unwrap();
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let meta = OutputMetadata {
        study: study.name().to_string(),
        study_file_hash: study.file_hash.clone(),
        tool_version: String::from("test"),
        overrides: Vec::new(),
    };
    let mut set = ResultSet::stage(out).unwrap();
    set.write_tables(&plan, &report, &study.outputs, &meta)
        .unwrap();
    set.write_summaries(&plan, &report, &study.file.summaries, &meta)
        .unwrap();
    set.write_timings(&plan, &report, &meta).unwrap();
    set.publish().unwrap();
    report
}

/// The files of an output folder, sorted by name.
fn files(out: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(out)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    v.sort();
    v
}

fn assert_same_bytes(a: &Path, b: &Path) {
    let (fa, fb) = (files(a), files(b));
    let names = |f: &[PathBuf]| -> Vec<String> {
        f.iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect()
    };
    assert_eq!(names(&fa), names(&fb));
    for (x, y) in fa.iter().zip(&fb) {
        if x.ends_with("timings.parquet") {
            continue;
        }
        assert!(
            std::fs::read(x).unwrap() == std::fs::read(y).unwrap(),
            "{} and {} differ",
            x.display(),
            y.display()
        );
    }
}

/// The `nodes` column (a list of names per row) of a table, each row's names joined by "+".
fn node_names(path: &Path) -> Vec<String> {
    let df = ParquetReader::new(std::fs::File::open(path).unwrap())
        .finish()
        .unwrap();
    let lists = df.column("nodes").unwrap().list().unwrap().clone();
    (0..lists.len())
        .map(|row| {
            let names = lists.get_as_series(row).unwrap();
            let names: Vec<&str> = names.str().unwrap().iter().flatten().collect();
            names.join("+")
        })
        .collect()
}

#[test]
fn tables_are_byte_identical_fresh_cached_and_on_any_thread_count() {
    let dir = scratch("bytes");
    let study = dir.join("study.yaml");
    std::fs::write(&study, STUDY).unwrap();
    let one = run(&study, &dir.join("cache-1"), &dir.join("out-1"), 1);
    let two = run(&study, &dir.join("cache-2"), &dir.join("out-2"), 2);
    let cached = run(&study, &dir.join("cache-1"), &dir.join("out-cached"), 2);
    assert_eq!((one.computed, one.cached), (two.computed, 0));
    assert_eq!((cached.computed, cached.cached), (0, one.computed));
    assert_same_bytes(&dir.join("out-1"), &dir.join("out-2"));
    assert_same_bytes(&dir.join("out-1"), &dir.join("out-cached"));
    let out = dir.join("out-1");
    assert!(files(&out).len() >= 8, "{:?}", files(&out));

    // Run times are only in the timings table; it says which results came from the cache.
    for f in files(&out) {
        let df = ParquetReader::new(std::fs::File::open(&f).unwrap())
            .finish()
            .unwrap();
        let has_time = df.column("compute_seconds").is_ok();
        assert_eq!(has_time, f.ends_with("timings.parquet"), "{}", f.display());
    }
    let timings =
        ParquetReader::new(std::fs::File::open(dir.join("out-cached/timings.parquet")).unwrap())
            .finish()
            .unwrap();
    assert!(timings
        .column("from_cache")
        .unwrap()
        .bool()
        .unwrap()
        .iter()
        .all(|v| v == Some(true)));

    // Friction rows: scenario by scenario, the study file's node order within one (zeta, alpha,
    // mid), although the plan instantiates them upstream first.
    let names = node_names(&out.join("friction.parquet"));
    let expected: Vec<String> = (0..4)
        .flat_map(|_| ["zeta", "alpha", "mid"])
        .map(String::from)
        .collect();
    assert_eq!(names, expected);
    let _ = std::fs::remove_dir_all(&dir);
}
