//! Engine overheads on a study of the real shape, a surface → contact → friction chain per
//! scenario on tiny grids, so the time is the engine's and not the numerics':
//!
//! * `plan_100k_scenarios_3_nodes`: `Study::from_source` + `Plan::build` (keying included) of
//!   10⁵ scenarios × 3 nodes. Goal: < 0.5 s.
//! * `cached_rerun_10k_scenarios_3_nodes`: parse, plan, execute with every node a cache hit and
//!   write the Parquet tables and `timings.parquet` (what `asperity run` does after the plan;
//!   the study has no summaries), 10⁴ scenarios × 3 nodes. Goal: < 0.5 s. The cache is filled once
//!   before the measurement, outside the timed closure, in memory (`/dev/shm` where there is
//!   one): there the fsyncs of the fill cost nothing, and a rerun reads the same hot files as from
//!   a disk's page cache.
//!
//! Run: `cargo bench --bench engine`; measured figures are in `docs/engine-overhead.md`.

use std::cell::OnceCell;
use std::path::{Path, PathBuf};

use criterion::{criterion_group, criterion_main, Criterion};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress};
use asperity::engine::output::{OutputMetadata, ResultSet};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;

/// A `seeds × hursts` product of scenarios, each an 8×8 synthetic surface, its contact with a
/// rigid flat (fields kept) and the junction-shear friction of that contact (without adhesion,
/// which would leave some of these tiny contacts without a compressive net force).
fn chain_study(seeds: usize, hursts: usize) -> String {
    format!(
        r#"
study: bench
parameters:
  product:
    seed: {{range: [1, {seeds}]}}
    hurst: {{linspace: [0.5, 0.9, {hursts}]}}
nodes:
  surface:
    surface:
      synthetic: {{grid: [8, 8], size: [10 um, 10 um], sq: 0.05 um, hurst: "${{hurst}}",
                  correlation_length: 5 um, seed: "${{seed}}"}}
  contact:
    contact:
      lower: surface
      lower_material: s235jr
      nominal_pressures: [20 MPa]
      fields: true
  friction:
    friction:
      model: junction_shear
      contact: contact
      lower_material: s235jr
      adhesion_energy: 0 N/m
"#
    )
}

fn parse(text: &str) -> Study<TribologyNode> {
    Study::from_source(Path::new("bench.yaml"), text.to_string()).unwrap()
}

fn planning(c: &mut Criterion) {
    let text = chain_study(1000, 100);
    let mut group = c.benchmark_group("engine");
    group.sample_size(10);
    group.bench_function("plan_100k_scenarios_3_nodes", |bench| {
        bench.iter(|| {
            let plan = Plan::build(&parse(&text)).unwrap();
            assert_eq!(plan.nodes.len(), 300_000);
            plan
        })
    });
    group.finish();
}

/// What the cached rerun reads: a temporary cache filled with the study's results.
struct Fixture {
    dir: PathBuf,
    cache: Cache,
    options: ExecuteOptions,
    meta: OutputMetadata,
}

impl Fixture {
    /// Computes every node of `text` into a new cache.
    fn fill(text: &str) -> Self {
        let memory = Path::new("/dev/shm");
        let base = if memory.is_dir() {
            memory.to_path_buf()
        } else {
            std::env::temp_dir()
        };
        let dir = base.join(format!("asperity-bench-{}", std::process::id()));
        let cache = Cache::open(&dir.join("cache")).unwrap();
        let study = parse(text);
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
        let plan = Plan::build(&study).unwrap();
        let report = execute(&plan, &cache, &options, &NoProgress).unwrap();
        assert!(report.all_ok(), "filling the cache failed");
        Self {
            dir,
            cache,
            options,
            meta,
        }
    }
}

impl Drop for Fixture {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn cached_rerun(c: &mut Criterion) {
    let text = chain_study(100, 100);
    // Filled on first use: only when this benchmark is selected, and never inside the timing.
    let fixture: OnceCell<Fixture> = OnceCell::new();
    let mut group = c.benchmark_group("engine");
    group.sample_size(10);
    group.bench_function("cached_rerun_10k_scenarios_3_nodes", |bench| {
        let f = fixture.get_or_init(|| Fixture::fill(&text));
        bench.iter(|| {
            let study = parse(&text);
            let plan = Plan::build(&study).unwrap();
            let report = execute(&plan, &f.cache, &f.options, &NoProgress).unwrap();
            assert_eq!(report.cached, 30_000);
            let out = f.dir.join("out");
            let mut set = ResultSet::stage(&out).unwrap();
            set.write_tables(&plan, &report, &study.outputs, &f.meta)
                .unwrap();
            set.write_timings(&plan, &report, &f.meta).unwrap();
            set.publish().unwrap()
        })
    });
    group.finish();
}

criterion_group!(benches, planning, cached_rerun);
criterion_main!(benches);
