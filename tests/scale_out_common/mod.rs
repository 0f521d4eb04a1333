//! Shared by the scale-out tests (shards, cache commands, crash and concurrency): a small study
//! of fast nodes, running the `asperity` binary, comparing tables, verifying a cache.

#![allow(dead_code)] // each test binary uses a different part

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use asperity::engine::cache::Cache;
use asperity::engine::cache_admin::{list_entries, verify_entry};
use polars::prelude::{DataFrame, ParquetReader, SerReader};

/// `lowers` synthetic 64² lower surfaces (seeds 1..=lowers) against one upper surface, each pair
/// in contact at two loads: `2 × lowers + 1` instances, `lowers` units of work.
pub fn study_text(name: &str, lowers: usize) -> String {
    format!(
        r#"
study: {name}
parameters:
  product:
    seed: {{range: [1, {lowers}]}}
nodes:
  lower:
    surface:
      synthetic: {{grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 40 um, seed: "${{seed}}"}}
  upper:
    surface:
      synthetic: {{grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: 0.5 um, hurst: 0.7,
                  correlation_length: 40 um, seed: 1000}}
  pair:
    contact:
      lower: lower
      upper: upper
      lower_material: {{youngs_modulus: 210 GPa, poisson_ratio: 0.3}}
      upper_material: {{youngs_modulus: 210 GPa, poisson_ratio: 0.3}}
      flow_pressure: 4 GPa
      nominal_pressures: [5 MPa, 20 MPa]
"#
    )
}

/// A fresh, empty folder for one test.
pub fn tempdir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes the study into `dir` and returns its path.
pub fn write_study(dir: &Path, name: &str, lowers: usize) -> PathBuf {
    let path = dir.join(format!("{name}.yaml"));
    std::fs::write(&path, study_text(name, lowers)).unwrap();
    path
}

/// The `asperity` binary with `args`.
pub fn asperity(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_asperity"));
    c.args(args);
    c
}

/// Runs `asperity run STUDY --cache CACHE --out OUT -q [extra]` to completion.
pub fn run(study: &Path, cache: &Path, out: &Path, extra: &[&str]) -> Output {
    asperity(&["run", "-q"])
        .arg(study)
        .arg("--cache")
        .arg(cache)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .unwrap()
}

/// Asserts success and returns stdout.
pub fn ok(output: &Output) -> String {
    let stdout = String::from_utf8_lossy(&output.stdout).to_string();
    assert!(
        output.status.success(),
        "exit {:?}\nstdout: {stdout}\nstderr: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

fn read_table(path: &Path) -> DataFrame {
    ParquetReader::new(std::fs::File::open(path).unwrap())
        .finish()
        .unwrap()
}

/// The result tables of an output folder (every Parquet file but `timings.parquet`), sorted by
/// name.
pub fn tables(out: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(out)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "parquet"))
        .filter(|p| !p.ends_with("timings.parquet"))
        .collect();
    v.sort();
    v
}

/// Asserts that two output folders hold the same tables with the same cells (compute times
/// excepted).
pub fn assert_same_tables(a: &Path, b: &Path) {
    let (ta, tb) = (tables(a), tables(b));
    let names = |t: &[PathBuf]| -> Vec<_> {
        t.iter()
            .map(|p| p.file_name().unwrap().to_owned())
            .collect()
    };
    assert_eq!(names(&ta), names(&tb));
    assert!(!ta.is_empty(), "no tables in {}", a.display());
    for (x, y) in ta.iter().zip(&tb) {
        assert!(
            read_table(x).equals_missing(&read_table(y)),
            "{} and {} differ",
            x.display(),
            y.display()
        );
        assert!(
            std::fs::read(x).unwrap() == std::fs::read(y).unwrap(),
            "{} and {} hold the same cells but differ in bytes",
            x.display(),
            y.display()
        );
    }
}

/// Verifies every entry of the cache; returns how many there are.
pub fn assert_cache_verifies(cache_dir: &Path) -> usize {
    let cache = Cache::open(cache_dir).unwrap();
    let entries = list_entries(&cache).unwrap();
    for e in &entries {
        if let Err(reason) = verify_entry(&cache, e) {
            panic!("entry {} {} does not verify: {reason}", e.kind, e.key);
        }
    }
    entries.len()
}

/// Names in the cache's `tmp/` folder.
pub fn tmp_contents(cache_dir: &Path) -> Vec<String> {
    std::fs::read_dir(cache_dir.join("tmp"))
        .map(|r| {
            r.flatten()
                .map(|e| e.file_name().to_string_lossy().to_string())
                .collect()
        })
        .unwrap_or_default()
}

/// The text cells of column `name` of a Parquet table.
pub fn text_column(path: &Path, name: &str) -> Vec<String> {
    read_table(path)
        .column(name)
        .unwrap()
        .str()
        .unwrap()
        .iter()
        .map(|v| v.unwrap_or_default().to_string())
        .collect()
}

/// Asserts that a results folder holds one run's complete, joinable set: `scenarios`,
/// `timings` and the kind tables `kinds`, where the keys the scenarios name (every `*_key`
/// column) are exactly the keys of the kind tables and of the timings.
pub fn assert_joinable(out: &Path, kinds: &[&str]) {
    use std::collections::BTreeSet;
    let scenarios = out.join("scenarios.parquet");
    let named: BTreeSet<String> = read_table(&scenarios)
        .get_column_names()
        .iter()
        .filter(|c| c.ends_with("_key"))
        .flat_map(|c| text_column(&scenarios, c))
        .collect();
    let listed: BTreeSet<String> = kinds
        .iter()
        .flat_map(|k| text_column(&out.join(format!("{k}.parquet")), "key"))
        .collect();
    assert!(!named.is_empty(), "no keys in {}", scenarios.display());
    assert_eq!(
        named,
        listed,
        "scenarios and kind tables of {}",
        out.display()
    );
    let timed: BTreeSet<String> = text_column(&out.join("timings.parquet"), "key")
        .into_iter()
        .collect();
    assert_eq!(named, timed, "scenarios and timings of {}", out.display());
}

/// Names in `dir` that a results folder's staging or replacement left (`.<name>.staging.…`,
/// `.<name>.old.…`), or a temporary file.
pub fn staging_leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|r| {
            r.flatten()
                .map(|e| e.file_name().to_string_lossy().to_string())
                .filter(|n| n.contains(".staging.") || n.contains(".old.") || n.ends_with(".tmp"))
                .collect()
        })
        .unwrap_or_default()
}

/// The integer cells of column `name` of a Parquet table.
pub fn int_column(path: &Path, name: &str) -> Vec<i64> {
    read_table(path)
        .column(name)
        .unwrap()
        .i64()
        .unwrap()
        .iter()
        .map(|v| v.unwrap_or_default())
        .collect()
}
