//! Engine overheads: planning + keying a 10⁵-scenario grid (goal < 1 s) and a fully cached rerun
//! of a 10⁴-scenario study (goal < 2 s). Run: `cargo bench --bench engine`.

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress};
use asperity::engine::output::{write_tables, OutputMetadata};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;

fn grid_study(a: usize, b: usize) -> String {
    format!(
        r#"
study: bench
parameters:
  product:
    seed: {{range: [1, {a}]}}
    hurst: {{linspace: [0.5, 0.9, {b}]}}
nodes:
  s:
    surface:
      synthetic: {{grid: [4, 4], size: [10 um, 10 um], sq: 1 um, hurst: "${{hurst}}",
                  correlation_length: 5 um, seed: "${{seed}}"}}
"#
    )
}

fn planning(c: &mut Criterion) {
    let text = grid_study(1000, 100);
    let mut group = c.benchmark_group("engine");
    group.sample_size(10);
    group.bench_function("plan_and_key_100k_scenarios", |bench| {
        bench.iter(|| {
            let study =
                Study::<TribologyNode>::from_source(Path::new("bench.yaml"), text.clone()).unwrap();
            let plan = Plan::build(&study).unwrap();
            assert_eq!(plan.nodes.len(), 100_000);
            plan
        })
    });

    let text = grid_study(100, 100);
    let dir = std::env::temp_dir().join(format!("asperity-bench-{}", std::process::id()));
    let cache = Cache::open(&dir.join("cache")).unwrap();
    let study = Study::<TribologyNode>::from_source(Path::new("bench.yaml"), text.clone()).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 30,
        tool_version: String::from("bench"),
    };
    let meta = OutputMetadata {
        study: String::from("bench"),
        study_file_hash: study.file_hash.clone(),
        tool_version: String::from("bench"),
        overrides: Vec::new(),
    };
    // Fill the cache once.
    let plan = Plan::build(&study).unwrap();
    execute(&plan, &cache, &options, &NoProgress).unwrap();
    group.bench_function("cached_rerun_10k_scenarios", |bench| {
        bench.iter(|| {
            let study =
                Study::<TribologyNode>::from_source(Path::new("bench.yaml"), text.clone()).unwrap();
            let plan = Plan::build(&study).unwrap();
            let report = execute(&plan, &cache, &options, &NoProgress).unwrap();
            assert_eq!(report.cached, 10_000);
            write_tables(&dir.join("out"), &plan, &report, &study.outputs, &meta).unwrap()
        })
    });
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, planning);
criterion_main!(benches);
