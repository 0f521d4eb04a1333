//! The third outcome, `flagged`: a computed instance whose values must be read with a sentence.
//! Its row keeps its numbers with `status = flagged` and the sentences as `message`; the scenario
//! is `flagged` when none of its nodes failed; the flags are cached with the entry (also when it
//! is read through its manifest) and a cached run writes the same bytes as the computing one.

use std::path::{Path, PathBuf};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, RunReport};
use asperity::engine::output::{OutputMetadata, ResultSet};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;

use super::engine_end_to_end::as_first_format;
use polars::prelude::{ParquetReader, SerReader};

/// Two contacts: on a 4 × 4 grid (flagged: it resolves no contact spot) and on a 16 × 16 one
/// (ordinary), each on its own surface.
const STUDY: &str = r#"
study: flagged
parameters:
  product:
    n: [4, 16]
nodes:
  s:
    surface:
      synthetic: {grid: ["${n}", "${n}"], size: [20 um, 20 um], sq: 0.1 um, hurst: 0.8,
                  correlation_length: 5 um, seed: 1}
  c:
    contact: {lower: s, lower_material: s235jr, nominal_pressures: [20 MPa]}
"#;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-flagged-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(dir: &Path, out: &str) -> (Plan, RunReport) {
    let study =
        Study::<TribologyNode>::from_source(&dir.join("flagged.yaml"), STUDY.to_string()).unwrap();
    let plan = Plan::build(&study).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 30,
        tool_version: String::from("test"),
    };
    let cache = Cache::open(&dir.join("cache")).unwrap();
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
    set.write_timings(&plan, &report, &meta).unwrap();
    set.publish().unwrap();
    (plan, report)
}

fn texts(path: &Path, column: &str) -> Vec<String> {
    let df = ParquetReader::new(std::fs::File::open(path).unwrap())
        .finish()
        .unwrap();
    df.column(column)
        .unwrap()
        .str()
        .unwrap()
        .iter()
        .map(|v| v.unwrap_or("null").to_string())
        .collect()
}

fn same_bytes(a: &Path, b: &Path, table: &str) -> bool {
    std::fs::read(a.join(table)).unwrap() == std::fs::read(b.join(table)).unwrap()
}

#[test]
fn a_flagged_row_keeps_its_numbers_says_why_and_reads_back_from_the_cache() {
    let dir = scratch("rows");
    let (plan, first) = run(&dir, "out1");
    assert_eq!((first.computed, first.flagged, first.failed), (4, 1, 0));
    assert!(first.all_ok(), "flagged rows are not failures");
    let contacts = dir.join("out1/contacts.parquet");
    assert_eq!(texts(&contacts, "status"), ["flagged", "ok"]);
    let message = texts(&contacts, "message");
    assert!(
        message[0].contains("resolves no contact spot"),
        "{}",
        message[0]
    );
    assert_eq!(message[1], "");
    assert_eq!(
        texts(&dir.join("out1/scenarios.parquet"), "status"),
        ["flagged", "ok"]
    );
    assert_eq!(
        texts(&dir.join("out1/timings.parquet"), "status"),
        ["ok", "flagged", "ok", "ok"]
    );

    // From the cache: the same flags, the same bytes.
    let (_, second) = run(&dir, "out2");
    assert_eq!((second.cached, second.flagged), (4, 1));
    for table in [
        "contacts.parquet",
        "contacts_load_curve.parquet",
        "scenarios.parquet",
        "surfaces.parquet",
    ] {
        assert!(
            same_bytes(&dir.join("out1"), &dir.join("out2"), table),
            "{table}"
        );
    }

    // Read through the manifest (an entry without `summary.bin`): the flags are there too; an
    // unflagged entry's manifest has no `flags` field, as entries written before flags existed.
    let cache = Cache::open(&dir.join("cache")).unwrap();
    for node in &plan.nodes {
        let kind = node.task.kind();
        let manifest = std::fs::read_to_string(as_first_format(&cache, kind, &node.key)).unwrap();
        let flagged = manifest.contains("\"flags\"");
        let loaded = cache.load(kind, &node.key, false).unwrap().unwrap();
        assert_eq!(flagged, !loaded.artifact.flags.is_empty());
    }
    let (_, third) = run(&dir, "out3");
    assert_eq!((third.cached, third.flagged), (4, 1));
    assert!(same_bytes(
        &dir.join("out1"),
        &dir.join("out3"),
        "contacts.parquet"
    ));
    let _ = std::fs::remove_dir_all(&dir);
}
