//! A friction row says how far to trust it: a row computed on a flagged contact is flagged with
//! the contact's reason; a row with more than half its load beyond its law's fit, without a
//! radius or on merged spots is flagged with that share; no row is `ok` with μ_s above what its
//! law describes, over loads from 1e-6·H to 0.95·H; adhesion carrying more than half the load is
//! flagged; so is a ploughing row with more than half its load beyond the ploughing regime.

use crate::nodes_common;
use asperity::engine::execute::{NodeOutcome, RunReport};
use asperity::engine::plan::Plan;
use asperity::friction::find_law;
use nodes_common::{float, outcomes, run, text};

/// The friction outcomes with their model, in plan order.
fn friction_rows<'a>(plan: &Plan, report: &'a RunReport) -> Vec<&'a NodeOutcome> {
    outcomes(plan, report, "friction")
}

/// A synthetic surface against a rigid flat (S235JR, H = 1.96 GPa) at nominal pressures from
/// 1e-6·H to 0.95·H, every per-spot law on it.
const SWEEP: &str = r#"
study: sweep
parameters:
  product:
    load: [1.96 kPa, 196 kPa, 19.6 MPa, 196 MPa, 784 MPa, 1372 MPa, 1862 MPa]
nodes:
  rough:
    surface:
      synthetic: {grid: [128, 128], size: [256 um, 256 um], sq: 1 um, hurst: 0.8,
                  correlation_length: 32 um, seed: 9}
  pressed:
    contact: {lower: rough, lower_material: s235jr, nominal_pressures: ["${load}"],
              fields: true}
  stick:
    friction: {method: per_spot, model: full_stick, contact: pressed, lower_material: s235jr}
  ke:
    friction: {method: per_spot, model: kogut_etsion, contact: pressed,
               lower_material: s235jr}
  ceb:
    friction: {method: per_spot, model: chang_etsion_bogy, contact: pressed,
               lower_material: s235jr}
  shear:
    friction: {model: junction_shear, contact: pressed, lower_material: s235jr}
  plough:
    friction: {model: ploughing, contact: pressed, lower_material: s235jr}
"#;

#[test]
fn no_row_is_ok_beyond_what_its_law_describes_from_light_to_saturated_loads() {
    let (plan, report) = run(SWEEP, "sweep");
    let rows = friction_rows(&plan, &report);
    assert_eq!(rows.len(), 35);
    let mut merged_flags = 0;
    for row in rows {
        let model = text(row, "model");
        let mu = float(row, "mu_s");
        let bound = find_law(model).unwrap().mu_s_max;
        if row.flags.is_empty() {
            assert!(mu <= bound, "{model}: an ok row with μ_s = {mu} > {bound}");
            for share in [
                "load_share_beyond_fit",
                "load_share_without_radius",
                "load_share_merged",
            ] {
                assert!(
                    float(row, share) <= 0.5,
                    "{model}: an ok row with {share} > 0.5"
                );
            }
        }
        if mu > bound {
            assert!(
                row.flags
                    .iter()
                    .any(|f| f.contains("largest static friction coefficient")),
                "{model}: μ_s = {mu} without its flag: {:?}",
                row.flags
            );
        }
        if float(row, "load_share_merged") > 0.5 {
            merged_flags += 1;
            assert!(row.flags.iter().any(|f| f.contains("merged spots")));
        }
    }
    // Saturated loads merge the spots: the single-asperity laws say so.
    assert!(
        merged_flags >= 3,
        "{merged_flags} rows with most load on merged spots"
    );
}

/// A ground pair sampled steeply enough that the contact is flagged for its slope, with the KE
/// law (all load beyond x = 6 at this plasticity index) per spot and statistically.
const STEEP: &str = r#"
study: steep
nodes:
  a:
    surface:
      synthetic: {grid: [64, 64], size: [35.58 um, 35.58 um], sq: 1.5 um, hurst: 0.8,
                  correlation_length: 20 um, short_wavelength_cutoff: 2.5 um, seed: 3}
  b:
    surface:
      synthetic: {grid: [64, 64], size: [35.58 um, 35.58 um], sq: 1.19 um, hurst: 0.8,
                  correlation_length: 20 um, short_wavelength_cutoff: 2.5 um, seed: 4}
  pair:
    contact: {lower: a, upper: b, lower_material: s235jr, upper_material: s235jr,
              nominal_pressures: [20 MPa], fields: true}
  ke_spots:
    friction: {method: per_spot, contact: pair, lower_material: s235jr,
               upper_material: s235jr}
  ke_statistical:
    friction: {lower: a, upper: b, contact: pair, lower_material: s235jr,
               upper_material: s235jr}
"#;

#[test]
fn a_row_on_a_flagged_contact_is_flagged_with_its_reason() {
    let (plan, report) = run(STEEP, "steep");
    let contact = &outcomes(&plan, &report, "contact")[0];
    assert!(
        contact
            .flags
            .iter()
            .any(|f| f.contains("composite rms slope")),
        "the contact should be flagged for its slope: {:?}",
        contact.flags
    );
    for row in friction_rows(&plan, &report) {
        assert_eq!(row.label(), "flagged");
        assert!(
            row.flags.iter().any(|f| f.contains(
                "the contact node this row is computed from \
                                                   is flagged"
            ) && f.contains("composite rms slope")),
            "{:?}",
            row.flags
        );
        // KE carries no tangential load beyond x = 6: the share says so in words.
        let beyond = float(row, "load_share_beyond_fit");
        assert!(beyond > 0.5, "{beyond}");
        assert!(row
            .flags
            .iter()
            .any(|f| f.contains("load_share_beyond_fit") && f.contains("more than half")));
    }
}

/// A smooth surface lightly loaded with a strong adhesion energy: the adhesion force is a large
/// part of the contact load.
const STICKY: &str = r#"
study: sticky
nodes:
  smooth:
    surface:
      synthetic: {grid: [64, 64], size: [64 um, 64 um], sq: 5 nm, hurst: 0.8,
                  correlation_length: 16 um, seed: 7}
  touch:
    contact: {lower: smooth, lower_material: s235jr, nominal_pressures: [20 kPa],
              fields: true}
  grip:
    friction: {model: junction_shear, contact: touch, lower_material: s235jr,
               adhesion_energy: 1 N/m}
"#;

#[test]
fn adhesion_carrying_most_of_the_load_is_flagged() {
    let (plan, report) = run(STICKY, "sticky");
    let row = friction_rows(&plan, &report)[0];
    let share = float(row, "adhesion_share");
    let expected = float(row, "adhesion_force") / float(row, "normal_load");
    assert!((share - expected).abs() < 1e-12 * expected);
    assert!(share > 0.5, "adhesion share {share}: pick a stickier case");
    assert!(row
        .flags
        .iter()
        .any(|f| f.contains("adhesion carries more than half")));
}

/// A hard rough bearing steel on a soft aluminium flat (the rough body ploughs) with the
/// ploughing regime's bound far below and far above its spots' degrees of penetration.
const REGIME: &str = r#"
study: regime
nodes:
  rough:
    surface:
      synthetic: {grid: [64, 64], size: [64 um, 64 um], sq: 0.4 um, hurst: 0.8,
                  correlation_length: 16 um, seed: 5}
  smooth:
    surface:
      synthetic: {grid: [64, 64], size: [64 um, 64 um], sq: 2 nm, hurst: 0.8,
                  correlation_length: 16 um, seed: 6}
  pair:
    contact: {lower: rough, upper: smooth, lower_material: aisi52100,
              upper_material: al6061-t6, nominal_pressures: [20 MPa], fields: true}
  tight:
    friction: {model: {ploughing: {penetration_limit: 0.001}}, contact: pair,
               lower_material: aisi52100, upper_material: al6061-t6}
  loose:
    friction: {model: {ploughing: {penetration_limit: 10}}, contact: pair,
               lower_material: aisi52100, upper_material: al6061-t6}
"#;

#[test]
fn a_row_with_most_load_beyond_the_ploughing_regime_is_flagged() {
    let (plan, report) = run(REGIME, "regime");
    let contact = &outcomes(&plan, &report, "contact")[0];
    assert!(contact.flags.is_empty(), "{:?}", contact.flags);
    let node = |name: &str| {
        plan.nodes
            .iter()
            .zip(&report.outcomes)
            .find(|(n, _)| n.names.iter().any(|m| m == name))
            .and_then(|(_, o)| o.as_ref())
            .unwrap()
    };
    let (tight, loose) = (node("tight"), node("loose"));
    let regime = |row: &NodeOutcome| {
        row.flags
            .iter()
            .any(|f| f.contains("load_share_outside_regime") && f.contains("ploughing regime"))
    };
    let share = float(tight, "load_share_outside_regime");
    assert!(share > 0.5, "{share}");
    assert!(regime(tight), "{:?}", tight.flags);
    assert_eq!(float(loose, "load_share_outside_regime"), 0.0);
    assert!(!regime(loose), "{:?}", loose.flags);
    // The bound only says how far to trust the row: the coefficient is the same.
    assert_eq!(float(tight, "mu_s"), float(loose, "mu_s"));
}
