//! The cache keeps what is worth keeping: array payloads are zstd-compressed (lossless: the
//! tables are byte-identical), large synthetic surfaces are not stored but regenerated when a
//! dependant needs their heights, and a regenerated node that does not reproduce its cached
//! metrics replaces its entry instead of feeding a dependant.

use std::path::{Path, PathBuf};

use asperity::engine::cache::{Cache, Manifest};
use asperity::engine::execute::{execute, ExecuteOptions, NoProgress, RunReport};
use asperity::engine::output::{OutputMetadata, ResultSet};
use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;

/// A synthetic surface just above 1024² points (so its heights are regenerated, not stored) and
/// a contact with fields at `pressure`.
fn study(pressure: &str) -> String {
    format!(
        r#"
study: policy
nodes:
  s:
    surface:
      synthetic: {{grid: [1025, 1024], size: [1 mm, 1 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 50 um, seed: 3}}
  c:
    contact:
      lower: s
      lower_material: s235jr
      nominal_pressures: [{pressure}]
      fields: true
"#
    )
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-policy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(dir: &Path, text: &str, cache: &Path, out: &str) -> (Plan, RunReport) {
    let path = dir.join("study.yaml");
    std::fs::write(&path, text).unwrap();
    let study = Study::<TribologyNode>::load(&path).unwrap();
    let plan = Plan::build(&study).unwrap();
    let options = ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget: 1 << 32,
        tool_version: String::from("test"),
    };
    let report = execute(&plan, &Cache::open(cache).unwrap(), &options, &NoProgress).unwrap();
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let meta = OutputMetadata {
        study: study.name().to_string(),
        study_file_hash: study.file_hash.clone(),
        tool_version: String::from("test"),
        overrides: Vec::new(),
    };
    let mut set = ResultSet::stage(&dir.join(out)).unwrap();
    set.write_tables(&plan, &report, &study.outputs, &meta)
        .unwrap();
    set.publish().unwrap();
    (plan, report)
}

/// The payload files and sizes the manifest of instance `i`'s entry lists.
fn payloads(cache: &Path, kind: &str, plan: &Plan, i: usize) -> Vec<(String, u64)> {
    let dir = Cache::open(cache)
        .unwrap()
        .entry_dir(kind, &plan.nodes[i].key);
    let manifest: Manifest =
        serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap();
    manifest
        .payloads
        .iter()
        .map(|p| (p.file.clone(), p.bytes))
        .collect()
}

fn assert_same_tables(a: &Path, b: &Path) {
    for name in ["surfaces.parquet", "contacts.parquet", "scenarios.parquet"] {
        assert!(
            std::fs::read(a.join(name)).unwrap() == std::fs::read(b.join(name)).unwrap(),
            "{name} differs"
        );
    }
}

#[test]
fn large_synthetic_heights_are_regenerated_and_arrays_compressed() {
    let dir = scratch("regenerate");
    let cache = dir.join("cache");
    let (plan, first) = run(&dir, &study("20 MPa"), &cache, "out-20");
    assert_eq!(first.computed, 2);
    let surface = payloads(&cache, "surface", &plan, 0);
    assert!(
        surface.iter().all(|(f, _)| !f.contains(".npy")),
        "heights stored: {surface:?}"
    );
    // The contact's arrays are compressed: the mostly-zero pressure map far below its 8.4 MB.
    let contact = payloads(&cache, "contact", &plan, 1);
    let raw = 1025 * 1024 * 8;
    let pressure = contact
        .iter()
        .find(|(f, _)| f == "pressure.npy.zst")
        .unwrap_or_else(|| panic!("{contact:?}"));
    assert!(
        pressure.1 < raw / 10,
        "pressure payload {} bytes",
        pressure.1
    );
    assert!(contact.iter().all(|(_, b)| *b < raw), "{contact:?}");

    // A new load on the same cache: the surface comes from the cache, its heights regenerated,
    // and the tables equal a fresh run's byte for byte.
    let (_, second) = run(&dir, &study("10 MPa"), &cache, "out-10");
    assert_eq!(
        (second.cached, second.computed, second.discarded),
        (1, 1, 0)
    );
    run(&dir, &study("10 MPa"), &dir.join("fresh"), "out-fresh");
    assert_same_tables(&dir.join("out-10"), &dir.join("out-fresh"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A cached entry whose metrics the regenerated node does not reproduce (here: edited, with a
/// valid checksum, as a non-deterministic kind would leave it) is replaced, not trusted.
#[test]
fn a_regenerated_node_must_reproduce_its_cached_metrics() {
    let dir = scratch("mismatch");
    let cache_dir = dir.join("cache");
    let (plan, _) = run(&dir, &study("20 MPa"), &cache_dir, "out-a");
    let cache = Cache::open(&cache_dir).unwrap();
    // Made an entry without a summary (read through its manifest), its metric sq renamed and
    // the manifest's checksum recomputed.
    let entry = cache.entry_dir("surface", &plan.nodes[0].key);
    std::fs::remove_file(entry.join("summary.bin")).unwrap();
    let path = entry.join("manifest.json");
    let mut manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    manifest["payloads"]
        .as_array_mut()
        .unwrap()
        .retain(|p| p["file"] != "summary.bin");
    let sq = manifest["metrics"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|m| m["name"] == "sq")
        .expect("the surface has the metric sq");
    sq["name"] = serde_json::Value::from("sQ");
    let bytes = serde_json::to_vec_pretty(&manifest).unwrap();
    std::fs::write(&path, &bytes).unwrap();
    std::fs::write(
        entry.join("manifest.blake3"),
        blake3::hash(&bytes).to_hex().as_bytes(),
    )
    .unwrap();

    let (_, report) = run(&dir, &study("10 MPa"), &cache_dir, "out-b");
    assert_eq!((report.discarded, report.computed), (1, 2));
    run(&dir, &study("10 MPa"), &dir.join("fresh"), "out-fresh");
    assert_same_tables(&dir.join("out-b"), &dir.join("out-fresh"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two bodies of one material deform equally: the contact's two deformation maps are one file
/// in the entry, and both read back.
#[test]
fn identical_arrays_of_an_entry_are_stored_once() {
    let dir = scratch("dedup");
    let cache_dir = dir.join("cache");
    let surface = |seed: u32| {
        format!(
            "    surface:\n      synthetic: {{grid: [64, 64], size: [0.1 mm, 0.1 mm], sq: 1 um, \
             hurst: 0.8, correlation_length: 20 um, seed: {seed}}}\n"
        )
    };
    let text = format!(
        "study: dedup\nnodes:\n  a:\n{}  b:\n{}  c:\n    contact:\n      lower: a\n      \
         upper: b\n      lower_material: s235jr\n      upper_material: s235jr\n      \
         nominal_pressures: [20 MPa]\n      fields: true\n",
        surface(1),
        surface(2)
    );
    let (plan, _) = run(&dir, &text, &cache_dir, "out");
    let cache = Cache::open(&cache_dir).unwrap();
    let key = &plan.nodes[2].key;
    let entry = cache.load("contact", key, true).unwrap().unwrap();
    let lower = &entry.artifact.arrays["deformation_lower"];
    assert_eq!(Some(lower), entry.artifact.arrays.get("deformation_upper"));
    let files = payloads(&cache_dir, "contact", &plan, 2);
    let upper = files
        .iter()
        .find(|(f, _)| f == "deformation_lower.npy.zst")
        .map(|(_, b)| *b);
    assert!(upper.is_some(), "{files:?}");
    let dir_entry = cache.entry_dir("contact", key);
    assert!(!dir_entry.join("deformation_upper.npy.zst").exists());
    assert!(dir_entry.join("deformation_lower.npy.zst").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
