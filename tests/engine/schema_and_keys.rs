//! The committed JSON Schema is current, and node keys are pinned so a change is deliberate.

use std::path::Path;

use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;

#[test]
fn committed_schema_is_current() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("schemas/study.schema.json");
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    let current = asperity::nodes::study_schema_json();
    assert!(
        committed == current,
        "schemas/study.schema.json is stale: regenerate it with \
         `cargo run -- schema > schemas/study.schema.json`"
    );
}

#[test]
fn quickstart_study_validates() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/quickstart.yaml");
    let study = Study::<TribologyNode>::load(&path).unwrap();
    let plan = Plan::build(&study).unwrap();
    assert_eq!(plan.scenarios.rows.len(), 9);
    assert!(plan.unused_parameters.is_empty());
}

/// Keys depend only on kind, kind version, resolved SI parameters and upstream keys. These
/// values are pinned: if this test fails, either a node kind's version was bumped (update the
/// pins) or something that must not enter a key now does (fix that).
#[test]
fn node_keys_are_pinned() {
    let text = |sq: &str, out: &str| {
        format!(
            r#"
study: pinned
nodes:
  a:
    surface:
      synthetic: {{grid: [64, 32], size: [1 mm, 0.5 mm], sq: {sq}, hurst: 0.8,
                  correlation_length: 20 um, seed: 1}}
{out}"#
        )
    };
    let key = |t: String| {
        let study = Study::<TribologyNode>::from_source(Path::new("pinned.yaml"), t).unwrap();
        Plan::build(&study).unwrap().nodes[0].key.to_hex()
    };
    let base = key(text("1.19 um", ""));
    // The same value written in other units, and the choice of outputs, do not change the key.
    assert_eq!(base, key(text("1190 nm", "")));
    assert_eq!(base, key(text("1.19e-6", "outputs: [surfaces]\n")));
    assert_ne!(base, key(text("1.2 um", "")));
    assert_eq!(
        base, "d7729bbb26f85c8bf24cfd85889a477435639c0ab4617f0945c5c3a0af9c570a",
        "pinned key of the reference surface changed"
    );
}
