//! A friction row says how far to trust it: a row computed on a flagged contact is flagged with
//! the contact's reason; a row with more than half its load beyond its law's fit, without a
//! radius or on merged spots is flagged with that share; no row is `ok` with μ_s above what its
//! law describes, over loads from 1e-6·H to 0.95·H, nor with a local μ quantile above it on coarse
//! grids; each reason is one sentence, the beyond-fit one naming the row's law alone; adhesion carrying more than half the load is
//! flagged; so is a ploughing row with more than half its load beyond the ploughing regime.

use crate::nodes_common;
use asperity::engine::execute::{NodeOutcome, RunReport};
use asperity::engine::plan::Plan;
use asperity::friction::find_law;
use nodes_common::{float, outcomes, rough_and_smooth, run, text};

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
        assert_one_sentence_per_reason(model, &row.flags);
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
                    .any(|f| f.contains("largest friction coefficient")),
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

/// A row's flags: each reason once, none in the wording of a failure ("is outside ≤ 0.5", which
/// the flag's sentence says in words), so that the `message` joining them repeats no clause.
fn assert_one_sentence_per_reason(model: &str, flags: &[String]) {
    for (i, flag) in flags.iter().enumerate() {
        assert!(!flag.contains(" is outside "), "{model}: {flag}");
        assert!(!flags[i + 1..].contains(flag), "{model}: twice: {flag}");
    }
}

/// The campaign's shrunk quickstart (a 33² and a 30² grid of 0.125 mm), with two rough bodies:
/// the spots are few and many are lightly loaded, where full stick, junction shear and KE give
/// local μ_i = Q_i/P_i far above any friction coefficient (count quantiles of 14–61 were `ok`).
const COARSE: &str = r#"
study: coarse
parameters:
  product:
    n: [30, 33]
nodes:
  lower:
    surface:
      synthetic: {grid: ["${n}", "${n}"], size: [0.125 mm, 0.125 mm], sq: 0.05 um, hurst: 0.8,
                  correlation_length: 40 um, anisotropy: {ratio: 4, angle: 0 deg}, seed: 1}
  upper:
    surface:
      synthetic: {grid: ["${n}", "${n}"], size: [0.125 mm, 0.125 mm], sq: 0.03 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 2}
  contact:
    contact: {lower: lower, upper: upper, lower_material: s235jr, upper_material: s235jr,
              nominal_pressures: [5 MPa, 10 MPa, 20 MPa], fields: true}
  per_summit:
    friction: {method: per_summit, contact: contact, lower_material: s235jr,
               upper_material: s235jr}
  stick_per_spot:
    friction: {method: per_spot, model: full_stick, contact: contact, lower_material: s235jr,
               upper_material: s235jr}
  junction_shear:
    friction: {model: junction_shear, contact: contact, lower_material: s235jr,
               upper_material: s235jr}
"#;

/// No `ok` row (nor `ok` load step) has μ_s or a local μ quantile above the bound its law
/// states; the quantiles are weighted by load, so the median lies within the spots' range and a
/// flagged quantile names itself.
#[test]
fn no_ok_row_has_a_local_mu_quantile_beyond_its_law() {
    let (plan, report) = run(COARSE, "coarse");
    let rows = friction_rows(&plan, &report);
    assert_eq!(rows.len(), 6);
    let mut flagged_quantiles = 0;
    for row in rows {
        let model = text(row, "model");
        let bound = find_law(model).unwrap().mu_s_max;
        assert_one_sentence_per_reason(model, &row.flags);
        let above: Vec<&str> = ["mu_s", "local_mu_p10", "local_mu_median", "local_mu_p90"]
            .into_iter()
            .filter(|c| float(row, c) > bound)
            .collect();
        if row.flags.is_empty() {
            assert!(
                above.is_empty(),
                "{model}: an ok row with {above:?} > {bound}"
            );
        }
        for column in above {
            assert!(
                row.flags
                    .iter()
                    .any(|f| f.contains(&format!("`{column}` = ")) && f.contains("largest")),
                "{model}: {column} above {bound} without its flag: {:?}",
                row.flags
            );
            flagged_quantiles += usize::from(column.starts_with("local_mu"));
        }
        let (p10, median, p90) = (
            float(row, "local_mu_p10"),
            float(row, "local_mu_median"),
            float(row, "local_mu_p90"),
        );
        assert!(0.0 <= p10 && p10 <= median && median <= p90, "{model}");
    }
    assert!(
        flagged_quantiles > 0,
        "no quantile above its law: pick a coarser case"
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
        // The sentence names the row's law and where its range ends, no other law.
        let flag = row
            .flags
            .iter()
            .find(|f| f.contains("load_share_beyond_fit") && f.contains("more than half"))
            .unwrap_or_else(|| panic!("no beyond-fit flag: {:?}", row.flags));
        assert!(flag.contains("`model: kogut_etsion`") && flag.contains("x = ω/ω_c = 6"));
        assert!(
            !flag.contains("CEB") && !flag.contains("full stick"),
            "{flag}"
        );
        assert_one_sentence_per_reason("kogut_etsion", &row.flags);
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
/// The nodes beside the bodies of `nodes_common::rough_and_smooth`.
const REGIME: &str = r#"
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
    let (plan, report) = run(&rough_and_smooth("regime", REGIME), "regime");
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
