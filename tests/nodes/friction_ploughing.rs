//! `model: ploughing` through the engine on two-body contacts: the row's adhesion and
//! deformation parts add up to μ_s, the adhesion part is junction shear's μ_s, the deformation
//! part stands beside its topography baseline, swapping the bodies and reversing the direction
//! changes nothing, the lay makes the groove direction-dependent, the harder body ploughs, a
//! rigid flat ploughs nothing, and an angle needs its unit.

use crate::nodes_common;
use asperity::engine::execute::{NodeOutcome, RunReport};
use asperity::engine::plan::Plan;
use asperity::engine::value::Value;
use nodes_common::{column, float, plan_error, rough_and_smooth, run, text};

/// A ground pair with the lay along x, contact at 20 MPa with fields both ways round, junction
/// shear and the ploughing law along and across the lay, and along the lay on the swapped pair
/// (the direction reversed: the same sliding).
const GROUND: &str = r#"
study: ploughing
nodes:
  a:
    surface:
      synthetic: {grid: [96, 96], size: [53.4 um, 53.4 um], sq: 1.19 um, hurst: 0.8,
                  correlation_length: 20 um, anisotropy: {ratio: 3, angle: 0 deg},
                  short_wavelength_cutoff: 2.5 um, seed: 1}
  b:
    surface:
      synthetic: {grid: [96, 96], size: [53.4 um, 53.4 um], sq: 0.38 um, hurst: 0.85,
                  correlation_length: 15 um, anisotropy: {ratio: 3, angle: 0 deg},
                  short_wavelength_cutoff: 2.5 um, seed: 2}
  pair:
    contact:
      lower: a
      upper: b
      lower_material: s235jr
      upper_material: s235jr
      nominal_pressures: [20 MPa]
      fields: true
  swapped:
    contact:
      lower: b
      upper: a
      lower_material: s235jr
      upper_material: s235jr
      nominal_pressures: [20 MPa]
      fields: true
  shear:
    friction: {model: junction_shear, contact: pair, lower_material: s235jr,
               upper_material: s235jr}
  along:
    friction: {model: ploughing, contact: pair, spots_table: true, lower_material: s235jr,
               upper_material: s235jr}
  across:
    friction: {model: {ploughing: {sliding_direction: 90 deg}}, contact: pair,
               lower_material: s235jr, upper_material: s235jr}
  reversed:
    friction: {model: {ploughing: {sliding_direction: 180 deg}}, contact: swapped,
               lower_material: s235jr, upper_material: s235jr}
"#;

/// The outcome of the study node called `name`.
fn named<'a>(plan: &Plan, report: &'a RunReport, name: &str) -> &'a NodeOutcome {
    let at = plan
        .nodes
        .iter()
        .position(|n| n.names.iter().any(|m| m == name))
        .unwrap_or_else(|| panic!("no node {name}"));
    report.outcomes[at].as_ref().unwrap()
}

/// The key field `name` of the study node called `node`, as text.
fn key_text(plan: &Plan, node: &str, name: &str) -> String {
    let task = &plan
        .nodes
        .iter()
        .find(|n| n.names.iter().any(|m| m == node))
        .unwrap()
        .task;
    match task
        .params()
        .into_iter()
        .find(|f| f.name == name)
        .map(|f| f.value)
    {
        Some(Value::Text(t)) => t,
        other => panic!("{node}.{name}: {other:?}"),
    }
}

#[test]
fn ploughing_rows_split_mu_into_adhesion_and_deformation() {
    let (plan, report) = run(GROUND, "ploughing");
    let [shear, along, across, reversed] =
        ["shear", "along", "across", "reversed"].map(|n| named(&plan, &report, n));
    for row in [along, across, reversed] {
        assert_eq!(text(row, "model_basis"), "textbook_law");
        let (a, d) = (float(row, "mu_adhesion"), float(row, "mu_deformation"));
        assert!((a + d - float(row, "mu_s_computed")).abs() < 1e-12);
        // The adhesion part is junction shear's coefficient on the same spots.
        assert!((a - float(shear, "mu_s")).abs() < 1e-9 * a);
        assert!(float(row, "mu_deformation_slope_baseline") > 0.0);
    }
    // Equal steels: both bodies plough, each with half of the deformation part.
    assert_eq!(key_text(&plan, "along", "ploughing_body"), "both");
    // The same sliding seen from the other body: the same numbers.
    for name in ["mu_s", "mu_deformation", "mu_deformation_slope_baseline"] {
        let (x, y) = (float(along, name), float(reversed, name));
        assert!((x - y).abs() < 1e-6 * x, "{name}: {x} vs {y}");
    }
    // The groove ploughs: across the lay the caps are short and steep.
    let (d_along, d_across) = (
        float(along, "mu_deformation"),
        float(across, "mu_deformation"),
    );
    assert!(
        d_along > 0.0 && d_across > d_along,
        "{d_along} along, {d_across} across"
    );
    // The spots table: one deformation force per spot, summing to the row's part.
    let q = column(along, "spots", "deformation_force");
    let p = column(along, "spots", "normal_force");
    let net = float(along, "normal_load") - float(along, "adhesion_force");
    let share = q.iter().sum::<f64>() / net;
    assert!(
        (share - d_along).abs() < 1e-9 * d_along,
        "{share} vs {d_along}"
    );
    assert_eq!(column(along, "spots", "groove_ratio").len(), p.len());
}

/// A rough body against a smooth one of another material, both ways round, and against a rigid
/// flat: `{rough}` and `{smooth}` are materials.
/// The nodes beside the bodies of `nodes_common::rough_and_smooth`.
const HARDNESS: &str = r#"
  hard_rough:
    contact: {lower: rough, upper: smooth, lower_material: aisi52100,
              upper_material: al6061-t6, nominal_pressures: [20 MPa], fields: true}
  soft_rough:
    contact: {lower: rough, upper: smooth, lower_material: al6061-t6,
              upper_material: aisi52100, nominal_pressures: [20 MPa], fields: true}
  rigid_flat:
    contact: {lower: rough, lower_material: al6061-t6, nominal_pressures: [20 MPa],
              fields: true}
  hard_rough_ploughs:
    friction: {model: ploughing, contact: hard_rough, lower_material: aisi52100,
               upper_material: al6061-t6}
  soft_rough_ploughs:
    friction: {model: ploughing, contact: soft_rough, lower_material: al6061-t6,
               upper_material: aisi52100}
  flat_ploughs:
    friction: {model: ploughing, contact: rigid_flat, lower_material: al6061-t6}
"#;

#[test]
fn the_harder_body_ploughs() {
    let (plan, report) = run(&rough_and_smooth("hardness", HARDNESS), "hardness");
    let [hard, soft, flat] = ["hard_rough_ploughs", "soft_rough_ploughs", "flat_ploughs"]
        .map(|n| named(&plan, &report, n));
    assert_eq!(
        key_text(&plan, "hard_rough_ploughs", "ploughing_body"),
        "lower"
    );
    assert_eq!(
        key_text(&plan, "soft_rough_ploughs", "ploughing_body"),
        "upper"
    );
    assert_eq!(key_text(&plan, "flat_ploughs", "ploughing_body"), "upper");
    let d = |row| float(row, "mu_deformation");
    assert!(d(hard) > 0.01, "{}", d(hard));
    // A soft rough body on a hard smooth one: only the smooth body's 2 nm roughness ploughs.
    assert!(d(soft) < 0.05 * d(hard), "{} vs {}", d(soft), d(hard));
    // A rigid flat has no asperity and no slope.
    assert_eq!(d(flat), 0.0);
    assert_eq!(float(flat, "mu_deformation_slope_baseline"), 0.0);
}

#[test]
fn an_angle_without_its_unit_is_refused() {
    let text = GROUND.replace("sliding_direction: 90 deg", "sliding_direction: 1.57");
    let message = plan_error(&text);
    assert!(
        message.contains("model.ploughing.sliding_direction")
            && message.contains("without its unit")
            && message.contains("'1.57 deg' or '1.57 rad'"),
        "{message}"
    );
    let wrong = GROUND.replace("sliding_direction: 90 deg", "sliding_direction: 90 um");
    let message = plan_error(&wrong);
    assert!(
        message.contains("is a length") && message.contains("angle"),
        "{message}"
    );
}
