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

use super::engine_end_to_end::as_first_format;

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
    // Made an entry of the first format (read through its manifest), its metric sq renamed and
    // the manifest's checksum recomputed.
    let entry = cache.entry_dir("surface", &plan.nodes[0].key);
    let path = as_first_format(&cache, "surface", &plan.nodes[0].key);
    let mut manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
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

/// Two equal arrays of one entry are one file, and both read back.
#[test]
fn identical_arrays_of_an_entry_are_stored_once() {
    let dir = scratch("dedup");
    let cache = Cache::open(&dir.join("cache")).unwrap();
    let key = asperity::engine::hash::node_key("test", 1, &[], &[]);
    let map = ndarray::ArrayD::from_shape_fn(ndarray::IxDyn(&[8, 8]), |i| (i[0] * i[1]) as f64);
    let mut artifact = asperity::engine::artifact::Artifact::default();
    artifact.arrays.insert(String::from("a"), map.clone());
    artifact.arrays.insert(String::from("b"), map.clone());
    artifact
        .arrays
        .insert(String::from("left_out"), map.clone());
    let manifest = Manifest {
        format: 0,
        key: key.to_hex(),
        kind: String::from("test"),
        version: 1,
        params: Vec::new(),
        upstream: Vec::new(),
        payloads: Vec::new(),
        compute_seconds: 0.0,
        tool_version: String::from("test"),
        created_unix: 0,
    };
    assert!(cache
        .store(manifest, &artifact, &|name| name != "left_out")
        .unwrap());
    let entry = cache.load("test", &key, true).unwrap().unwrap();
    assert_eq!(entry.artifact.arrays.len(), 2);
    assert!(entry.artifact.arrays.values().all(|a| *a == map));
    let files = cache.entry_dir("test", &key);
    assert!(files.join("a.npy.zst").exists());
    assert!(!files.join("b.npy.zst").exists() && !files.join("left_out.npy.zst").exists());
    assert!(cache.verify("test", &key).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Surfaces, a contact with fields over three load steps and, in a second study on the same
/// cache, a per-summit friction node: the contact's entry holds its pressure maps only; the
/// friction node computed from the cached contact (whose other maps are derived from them)
/// writes the table a fresh run writes, byte for byte.
#[test]
fn a_cached_contact_derives_its_maps_for_a_new_consumer() {
    let dir = scratch("derive");
    let cache = dir.join("cache");
    let text = |friction: &str| {
        format!(
            r#"
study: derive
nodes:
  a:
    surface:
      synthetic: {{grid: [64, 64], size: [0.2 mm, 0.2 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 1}}
  b:
    surface:
      synthetic: {{grid: [64, 64], size: [0.2 mm, 0.2 mm], sq: 0.5 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 2}}
  c:
    contact:
      lower: a
      upper: b
      lower_material: s235jr
      upper_material: {{youngs_modulus: 110 GPa, poisson_ratio: 0.34, hardness: 1 GPa}}
      nominal_pressures: [5 MPa, 10 MPa, 20 MPa]
      fields: true
{friction}"#
        )
    };
    let friction = concat!(
        "  f:\n",
        "    friction:\n",
        "      method: per_summit\n",
        "      contact: c\n",
        "      lower_material: s235jr\n",
        "      upper_material: {youngs_modulus: 110 GPa, poisson_ratio: 0.34, hardness: 1 GPa}\n",
    );
    let (plan, first) = run(&dir, &text(""), &cache, "out-contact");
    assert_eq!(first.computed, 3);
    let mut files: Vec<String> = payloads(&cache, "contact", &plan, 2)
        .into_iter()
        .map(|(f, _)| f)
        .collect();
    files.sort();
    assert_eq!(
        files,
        [
            "pressure.npy.zst",
            "pressure_step_0.npy.zst",
            "pressure_step_1.npy.zst",
            "summary.bin"
        ]
    );
    let (_, second) = run(&dir, &text(friction), &cache, "out-cached");
    assert_eq!((second.cached, second.computed), (3, 1), "{second:?}");
    run(&dir, &text(friction), &dir.join("fresh"), "out-fresh");
    for name in ["friction.parquet", "contacts_load_curve.parquet"] {
        assert!(
            std::fs::read(dir.join("out-cached").join(name)).unwrap()
                == std::fs::read(dir.join("out-fresh").join(name)).unwrap(),
            "{name} differs"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
