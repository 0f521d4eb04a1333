//! `--set NAME=VALUE` parameter overrides: parsing, axis replacement in `product` and `zip`,
//! errors for unknown or sampled parameters, and the keys they lead to.

use std::path::Path;

use asperity::engine::plan::Plan;
use asperity::engine::study::{ParameterOverride, Study};
use asperity::engine::value::ParamValue;
use asperity::nodes::TribologyNode;

const STUDY: &str = r#"
study: overrides
parameters:
  product:
    n: [128]
    sq: [0.38 um, 1.19 um]
  zip:
    - seed: [1, 2, 3]
      hurst: [0.7, 0.8, 0.9]
  latin_hypercube:
    samples: 2
    seed: 5
    ranges:
      ratio: [1, 4]
nodes:
  lower:
    surface:
      synthetic:
        grid: ["${n}", "${n}"]
        size: [100 um, 100 um]
        sq: ${sq}
        hurst: ${hurst}
        correlation_length: 20 um
        anisotropy: {ratio: "${ratio}", angle: 0 deg}
        seed: ${seed}
"#;

fn study() -> Study<TribologyNode> {
    Study::from_source(Path::new("overrides.yaml"), STUDY.to_string()).unwrap()
}

fn set(args: &[&str]) -> Vec<ParameterOverride> {
    args.iter().map(|a| a.parse().unwrap()).collect()
}

fn column(plan: &Plan, name: &str) -> Vec<ParamValue> {
    let i = plan.scenarios.names.iter().position(|n| n == name).unwrap();
    plan.scenarios.rows.iter().map(|r| r[i].clone()).collect()
}

#[test]
fn scalar_list_and_generator_values_replace_axes_in_place() {
    let mut s = study();
    s.apply_overrides(&set(&["n=32", "sq=[1 um]", "seed={range: [4, 6]}"]))
        .unwrap();
    let plan = Plan::build(&s).unwrap();
    // 1 (n) × 1 (sq) × 3 (zip) × 2 (hypercube) scenarios; the parameter order is unchanged.
    assert_eq!(plan.scenarios.rows.len(), 6);
    assert_eq!(
        plan.scenarios.names,
        ["n", "sq", "seed", "hurst", "ratio"].map(String::from)
    );
    assert!(column(&plan, "n").iter().all(|v| *v == ParamValue::Int(32)));
    assert_eq!(
        column(&plan, "seed")[..3],
        [ParamValue::Int(4), ParamValue::Int(4), ParamValue::Int(5)]
    );
    assert_eq!(
        s.overrides,
        [("n", "32"), ("sq", "[1 um]"), ("seed", "{range: [4, 6]}")]
            .map(|(a, b)| (a.to_string(), b.to_string()))
    );
}

#[test]
fn an_override_gives_the_keys_of_the_same_values_written_in_the_file() {
    let mut overridden = study();
    overridden.apply_overrides(&set(&["n=64"])).unwrap();
    let edited = Study::<TribologyNode>::from_source(
        Path::new("overrides.yaml"),
        STUDY.replace("n: [128]", "n: [64]"),
    )
    .unwrap();
    let a = Plan::build(&overridden).unwrap();
    let b = Plan::build(&edited).unwrap();
    let keys = |p: &Plan| p.nodes.iter().map(|n| n.key).collect::<Vec<_>>();
    assert_eq!(keys(&a), keys(&b));
}

#[test]
fn the_last_override_of_a_name_wins() {
    let mut s = study();
    s.apply_overrides(&set(&["n=32", "n=16"])).unwrap();
    let plan = Plan::build(&s).unwrap();
    assert!(column(&plan, "n").iter().all(|v| *v == ParamValue::Int(16)));
    assert_eq!(s.overrides, [(String::from("n"), String::from("16"))]);
}

#[test]
fn unknown_and_sampled_parameters_are_errors_that_say_what_to_do() {
    let mut s = study();
    let e = s
        .apply_overrides(&set(&["sd=1 um"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no parameter 'sd'"), "{e}");
    assert!(e.contains("did you mean 'sq'"), "{e}");
    assert!(e.contains("parameters: n, sq, seed, hurst"), "{e}");
    let e = s
        .apply_overrides(&set(&["ratio=2"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("latin_hypercube"), "{e}");
}

#[test]
fn a_zip_override_must_keep_the_group_length() {
    let mut s = study();
    s.apply_overrides(&set(&["hurst=[0.5, 0.6]"])).unwrap();
    let e = Plan::build(&s).unwrap_err().to_string();
    assert!(e.contains("equal lengths"), "{e}");
}

#[test]
fn malformed_arguments_are_rejected_with_examples() {
    for (arg, expect) in [
        ("n", "expected NAME=VALUE"),
        ("=3", "name before '=' is empty"),
        ("n=", "no value after 'n='"),
        ("n=[1, 2", "not valid YAML"),
    ] {
        let e = arg.parse::<ParameterOverride>().unwrap_err().to_string();
        assert!(e.contains(expect), "{arg}: {e}");
    }
}
