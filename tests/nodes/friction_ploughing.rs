//! `model: ploughing` through the engine on a ground-steel contact: the row's adhesion and
//! deformation parts add up to μ_s, the adhesion part is junction shear's μ_s, the sliding
//! direction is a column, the spots table carries each spot's geometry and deformation force,
//! the lay makes the groove law direction-dependent, and an angle needs its unit.

use crate::nodes_common;
use asperity::engine::execute::{NodeOutcome, RunReport};
use asperity::engine::plan::Plan;
use nodes_common::{column, float, plan_error, run, text};

/// A ground pair with the lay along x, contact at 20 MPa with fields, junction shear and the
/// ploughing law along and across the lay.
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
  shear:
    friction: {model: junction_shear, contact: pair, lower_material: s235jr,
               upper_material: s235jr}
  along:
    friction: {model: ploughing, contact: pair, spots_table: true, lower_material: s235jr,
               upper_material: s235jr}
  across:
    friction: {model: {ploughing: {sliding_direction: 90 deg}}, contact: pair,
               lower_material: s235jr, upper_material: s235jr}
  tilted:
    friction: {model: {ploughing: {deformation: tilted_junction}}, contact: pair,
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

#[test]
fn ploughing_rows_split_mu_into_adhesion_and_deformation() {
    let (plan, report) = run(GROUND, "ploughing");
    let [shear, along, across, tilted] =
        ["shear", "along", "across", "tilted"].map(|n| named(&plan, &report, n));
    for row in [along, across, tilted] {
        assert_eq!(text(row, "model_basis"), "textbook_law");
        let (a, d) = (float(row, "mu_adhesion"), float(row, "mu_deformation"));
        assert!((a + d - float(row, "mu_s_computed")).abs() < 1e-12);
        // The adhesion part is junction shear's coefficient on the same spots.
        assert!((a - float(shear, "mu_s")).abs() < 1e-12 * a);
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
    // The tilted junctions' first-order terms cancel: a small part either way.
    assert!(float(tilted, "mu_deformation").abs() < 0.5 * d_along);
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
