//! The study parser never panics: mutated study files and arbitrary bytes give a study or a
//! `StudyError`, and a study that parses plans to a `Plan` or a `StudyError`. The deterministic
//! companion of the `study` cargo-fuzz target (fuzz/README.md), run by `cargo test`.

use std::path::Path;

use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;
use proptest::prelude::*;

/// A study using every construct the mutations can break: product, zip, ranges, units,
/// `${param}` references, two surface sources, a contact and outputs.
const SEED_STUDY: &str = r#"
study: fuzz-seed
parameters:
  product:
    sq: [0.38 um, 1.19 um]
    seed: {range: [1, 3]}
  zip:
    - hurst: {linspace: [0.6, 0.9, 2]}
      load: [5 MPa, 20 MPa]
nodes:
  lower:
    surface:
      synthetic: {grid: [32, 32], size: [0.1 mm, 0.1 mm], sq: "${sq}", hurst: "${hurst}",
                  correlation_length: 20 um, anisotropy: {ratio: 2, angle: 30 deg}, seed: "${seed}"}
  upper:
    surface:
      synthetic: {grid: [32, 32], size: [0.1 mm, 0.1 mm], sq: 0.5 um, hurst: 0.7,
                  correlation_length: 20 um, seed: 9}
  pair:
    contact:
      lower: lower
      upper: upper
      lower_material: {youngs_modulus: 210 GPa, poisson_ratio: 0.3}
      upper_material: {youngs_modulus: 70 GPa, poisson_ratio: 0.33}
      flow_pressure: 4 GPa
      nominal_pressures: ["${load}"]
outputs: [scenarios, surfaces, contacts]
"#;

/// Tokens that steer mutations towards YAML and study structure.
const TOKENS: &[&str] = &[
    ":",
    "- ",
    "[",
    "]",
    "{",
    "}",
    ",",
    "\"",
    "'",
    "${",
    "}",
    "\n  ",
    "\n",
    "#",
    "&a",
    "*a",
    "!!",
    "~",
    "null",
    "-1",
    "0",
    "1e308",
    "NaN",
    "inf",
    "um",
    "GPa",
    "deg",
    "range",
    "linspace",
    "lower",
    "upper",
    "surface",
    "contact",
    "nodes",
    "parameters",
    "outputs",
    "\t",
    "%",
];

fn check(text: &str) {
    let Ok(study) = Study::<TribologyNode>::from_source(Path::new("fuzz.yaml"), text.to_string())
    else {
        return;
    };
    // Planning a study whose mutated axes expand to millions of scenarios is legitimate but slow
    // (MAX_SCENARIOS caps it); plan only spaces of a realistic test size.
    if study
        .file
        .parameters
        .expand(std::path::Path::new("."))
        .is_ok_and(|s| s.rows.len() <= 10_000)
    {
        let _ = Plan::build(&study);
    }
}

#[derive(Debug, Clone)]
enum Mutation {
    Delete(usize, usize),
    Insert(usize, usize),
    Replace(usize, u8),
    Duplicate(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1usize..20).prop_map(|(a, n)| Mutation::Delete(a, n)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, t)| Mutation::Insert(a, t)),
        (any::<usize>(), 0x20u8..0x7f).prop_map(|(a, b)| Mutation::Replace(a, b)),
        (any::<usize>(), 1usize..40).prop_map(|(a, n)| Mutation::Duplicate(a, n)),
    ]
}

fn apply(text: &mut Vec<u8>, m: &Mutation) {
    let len = text.len().max(1);
    match *m {
        Mutation::Delete(at, n) => {
            let at = at % len;
            let end = (at + n).min(text.len());
            text.drain(at.min(end)..end);
        }
        Mutation::Insert(at, t) => {
            let at = at % (text.len() + 1);
            let token = TOKENS[t % TOKENS.len()].as_bytes();
            text.splice(at..at, token.iter().copied());
        }
        Mutation::Replace(at, b) => {
            if let Some(c) = text.get_mut(at % len) {
                *c = b;
            }
        }
        Mutation::Duplicate(at, n) => {
            let at = at % len;
            let end = (at + n).min(text.len());
            let piece: Vec<u8> = text.get(at.min(end)..end).unwrap_or_default().to_vec();
            text.splice(at..at, piece);
        }
    }
}

#[test]
fn the_seed_study_parses_and_plans() {
    let study =
        Study::<TribologyNode>::from_source(Path::new("seed.yaml"), SEED_STUDY.into()).unwrap();
    assert_eq!(Plan::build(&study).unwrap().scenarios.rows.len(), 12);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn mutated_studies_never_panic(mutations in proptest::collection::vec(mutation(), 1..6)) {
        let mut bytes = SEED_STUDY.as_bytes().to_vec();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        check(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,300}") {
        check(&text);
    }
}
