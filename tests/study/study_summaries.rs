//! `summaries:` — grouped mean, sample standard deviation and count of node metrics, checked
//! against the same statistics computed here from the node table.

use std::path::{Path, PathBuf};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, RunReport};
use asperity::engine::output::{OutputMetadata, ResultSet};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;
use polars::prelude::{DataFrame, ParquetReader, SerReader};

const STUDY: &str = r#"
study: summaries
parameters:
  product:
    sq: [0.5 um, 2 um]
    seed: [1, 2, 3]
nodes:
  s:
    surface:
      synthetic: {grid: [32, 32], size: [100 um, 100 um], sq: "${sq}", hurst: 0.8,
                  correlation_length: 20 um, seed: "${seed}"}
outputs: [scenarios]
summaries:
  per_sq:
    by: [sq]
    metrics: [s.summit_count, s.sdq]
  overall:
    metrics: [s.summit_count]
"#;

fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("asperity-summaries-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn read(path: &Path) -> DataFrame {
    ParquetReader::new(std::fs::File::open(path).unwrap())
        .finish()
        .unwrap()
}

fn floats(df: &DataFrame, column: &str) -> Vec<f64> {
    let c = df
        .column(column)
        .unwrap()
        .cast(&polars::prelude::DataType::Float64);
    c.unwrap()
        .f64()
        .unwrap()
        .iter()
        .map(|v| v.unwrap())
        .collect()
}

struct Run {
    study: Study<TribologyNode>,
    plan: Plan,
    report: RunReport,
    meta: OutputMetadata,
}

/// Loads `text` as `dir/study.yaml` and computes what its tables and summaries need.
fn run(dir: &Path, text: &str) -> Run {
    let path = dir.join("study.yaml");
    std::fs::write(&path, text).unwrap();
    let study = Study::<TribologyNode>::load(&path).unwrap();
    let plan = Plan::build(&study).unwrap();
    let cache = Cache::open(&dir.join("cache")).unwrap();
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
    Run {
        study,
        plan,
        report,
        meta,
    }
}

#[test]
fn grouped_statistics_match_the_node_table() {
    let dir = scratch("grouped");
    let Run {
        study,
        plan,
        report,
        meta,
    } = run(&dir, STUDY);
    // The summaries need the surface table even though `outputs` lists only scenarios.
    assert_eq!(study.outputs, ["scenarios", "surfaces"]);
    let out = dir.join("out");
    let mut set = ResultSet::stage(&out).unwrap();
    set.write_tables(&plan, &report, &study.outputs, &meta)
        .unwrap();
    set.write_summaries(&plan, &report, &study.file.summaries, &meta)
        .unwrap();
    let files = set.publish().unwrap();
    let summaries = files.iter().filter(|f| {
        f.file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with("summary_"))
    });
    assert_eq!(summaries.count(), 2);

    let surfaces = read(&out.join("surfaces.parquet"));
    let per_sq = read(&out.join("summary_per_sq.parquet"));
    assert_eq!(
        per_sq
            .get_column_names()
            .iter()
            .map(|n| n.as_str())
            .collect::<Vec<_>>(),
        [
            "sq_m",
            "scenarios",
            "s_summit_count_n",
            "s_summit_count_mean",
            "s_summit_count_std",
            "s_sdq_n",
            "s_sdq_mean",
            "s_sdq_std"
        ]
    );
    assert_eq!(floats(&per_sq, "sq_m"), [0.5e-6, 2e-6]);
    assert_eq!(floats(&per_sq, "scenarios"), [3.0, 3.0]);
    // Group g holds surfaces 3g .. 3g+2 (seed varies fastest; every instance is distinct).
    let counts = floats(&surfaces, "summit_count");
    let gradients = floats(&surfaces, "sdq");
    for (g, x) in [&counts, &gradients].into_iter().enumerate() {
        let name = ["s_summit_count", "s_sdq"][g];
        for group in 0..2 {
            let values = &x[3 * group..3 * group + 3];
            let mean = values.iter().sum::<f64>() / 3.0;
            let std = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 2.0).sqrt();
            // Same sums in the same order: equal to round-off of one reordering at most.
            let got_mean = floats(&per_sq, &format!("{name}_mean"))[group];
            let got_std = floats(&per_sq, &format!("{name}_std"))[group];
            assert!((got_mean - mean).abs() <= 1e-12 * mean.abs(), "{name} mean");
            assert!(
                (got_std - std).abs() <= 1e-12 * std.abs().max(1e-300),
                "{name} std"
            );
            assert!(std > 0.0, "replicates differ");
        }
    }
    let overall = read(&out.join("summary_overall.parquet"));
    assert_eq!(floats(&overall, "scenarios"), [6.0]);
    assert_eq!(floats(&overall, "s_summit_count_n"), [6.0]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_metric_the_node_does_not_have_is_an_error_with_a_suggestion() {
    let dir = scratch("unknown");
    let Run {
        study,
        plan,
        report,
        meta,
    } = run(&dir, &STUDY.replace("s.sdq", "s.sdqq"));
    let mut set = ResultSet::stage(&dir.join("out")).unwrap();
    let e = set
        .write_summaries(&plan, &report, &study.file.summaries, &meta)
        .unwrap_err()
        .to_string();
    drop(set);
    // The failed set left nothing: no results folder, no staging folder.
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n.contains("out"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    assert!(e.contains("summary 'per_sq'"), "{e}");
    assert!(e.contains("no numeric metric 'sdqq'"), "{e}");
    assert!(e.contains("did you mean 'sdq'"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
