//! The high-plasticity friction models through the engine: statistical full stick (against the
//! library), per contact spot (full stick, junction shear, KE) on a ground-steel contact, the
//! honest-output columns and the spec errors.

use crate::nodes_common;
use asperity::engine::execute::NodeOutcome;
use asperity::friction::{
    static_friction, AdhesionBeyondFits, AdhesionParameters, FullStick, FullStickOptions, Material,
    SolveSettings, SpectralMoments, StatisticalModel, SummitStatistics,
};
use asperity::materials::{find_material, BodyMaterial, MaterialPair};
use nodes_common::{boolean, column, float, int, outcomes, plan_error, run, text};

/// Two ground-steel surfaces (ψ ≈ 40–60), contact at 20 MPa with fields, and one friction node per
/// model and method.
const GROUND: &str = r#"
study: ground
nodes:
  a:
    surface:
      synthetic: {grid: [96, 96], size: [53.4 um, 53.4 um], sq: 1.19 um, hurst: 0.8,
                  correlation_length: 20 um, short_wavelength_cutoff: 2.5 um, seed: 1}
  b:
    surface:
      synthetic: {grid: [96, 96], size: [53.4 um, 53.4 um], sq: 0.38 um, hurst: 0.85,
                  correlation_length: 15 um, short_wavelength_cutoff: 2.5 um, seed: 2}
  pair:
    contact:
      lower: a
      upper: b
      lower_material: s235jr
      upper_material: s235jr
      nominal_pressures: [20 MPa]
      fields: true
  stick_statistical:
    friction: {model: full_stick, lower: a, upper: b, contact: pair,
               lower_material: s235jr, upper_material: s235jr}
  ke_statistical:
    friction: {lower: a, upper: b, contact: pair, lower_material: s235jr, upper_material: s235jr}
  stick_spots:
    friction: {method: per_spot, model: full_stick, contact: pair, spots_table: true,
               lower_material: s235jr, upper_material: s235jr}
  ke_spots:
    friction: {method: per_spot, contact: pair, lower_material: s235jr, upper_material: s235jr}
  shear:
    friction: {model: junction_shear, contact: pair, lower_material: s235jr,
               upper_material: s235jr}
  stick_summits:
    friction: {method: per_summit, model: full_stick, contact: pair,
               lower_material: s235jr, upper_material: s235jr}
  stick_curve:
    friction: {model: full_stick, lower: a, upper: b, lower_material: s235jr,
               upper_material: s235jr, nominal_pressures: [0.2 MPa, 2 MPa, 20 MPa]}
"#;

fn by_model<'a>(rows: &[&'a NodeOutcome], method: &str, model: &str) -> &'a NodeOutcome {
    rows.iter()
        .copied()
        .find(|o| text(o, "method") == method && text(o, "model") == model)
        .unwrap_or_else(|| panic!("no {method} {model} row"))
}

fn moments(o: &NodeOutcome) -> SpectralMoments {
    SpectralMoments::new(float(o, "m0"), float(o, "m2"), float(o, "m4")).unwrap()
}

#[test]
fn ground_steel_gives_positive_labelled_coefficients_under_every_high_plasticity_model() {
    let (plan, report) = run(GROUND, "ground");
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let rows = outcomes(&plan, &report, "friction");
    for o in &rows {
        let mu = float(o, "mu_s");
        assert!(mu >= 0.0 && !boolean(o, "mu_s_floored") || mu == 0.0);
        let share = float(o, "load_share_beyond_fit");
        assert!((0.0..=1.0).contains(&share), "{share}");
    }
    for o in &rows {
        eprintln!(
            "{} {}: mu_s {} beyond fit {}",
            text(o, "method"),
            text(o, "model"),
            float(o, "mu_s"),
            float(o, "load_share_beyond_fit")
        );
    }
    for (method, model, basis) in [
        ("statistical", "full_stick", "parameterised_unverified"),
        ("per_spot", "full_stick", "parameterised_unverified"),
        ("per_spot", "junction_shear", "textbook_law"),
    ] {
        let o = by_model(&rows, method, model);
        let mu = float(o, "mu_s");
        assert!((0.05..1.5).contains(&mu), "{method} {model}: μ_s = {mu}");
        assert_eq!(text(o, "model_basis"), basis);
    }
    // KE at this plasticity index: almost all load beyond x = 6.
    let ke = by_model(&rows, "statistical", "kogut_etsion");
    assert!(float(ke, "load_share_beyond_fit") > 0.9);
    assert!(float(ke, "plasticity_index") > 20.0);
}

/// The node's statistical full-stick μ_s is the library's, bit for bit.
#[test]
fn statistical_full_stick_equals_the_library() {
    let (plan, report) = run(GROUND, "ground-library");
    let surfaces = outcomes(&plan, &report, "surface");
    let rows = outcomes(&plan, &report, "friction");
    let stick = by_model(&rows, "statistical", "full_stick");
    let summits = SummitStatistics::from_spectral_moments(
        &moments(surfaces[0]).combined_with(&moments(surfaces[1])),
    )
    .unwrap();
    let s235 = BodyMaterial::new(find_material("s235jr").unwrap().constants).unwrap();
    let material = Material::from_pair(&MaterialPair::new(s235, Some(s235))).unwrap();
    let options = FullStickOptions {
        yield_strength: Some(material.tabor_yield_strength()),
        ..FullStickOptions::default()
    };
    let area = 53.4e-6 * 53.4e-6;
    let model = StatisticalModel::new(
        std::sync::Arc::new(FullStick::new(&material, options).unwrap()),
        summits,
        material,
        AdhesionParameters::new(0.5, 0.158e-9).unwrap(),
        area,
        AdhesionBeyondFits::default(),
    )
    .unwrap();
    let load = float(stick, "external_load");
    let library = static_friction(&model, load, &SolveSettings::default()).unwrap();
    assert_eq!(float(stick, "mu_s"), library.mu_s.unwrap());
    assert_eq!(
        float(stick, "load_share_beyond_fit"),
        library.load_beyond_fit / library.contact_load
    );
}

/// Junction shear is τ_s A_true/(F_n − F_a) of the row's own values; the spot table adds up to
/// the row and counts its one-pixel spots.
#[test]
fn per_spot_rows_are_consistent_with_their_spots() {
    let (plan, report) = run(GROUND, "ground-spots");
    let rows = outcomes(&plan, &report, "friction");
    let shear = by_model(&rows, "per_spot", "junction_shear");
    let k = find_material("s235jr").unwrap().constants.hardness.unwrap() / 2.8 / 3f64.sqrt();
    let expected = k * float(shear, "real_area") / float(shear, "external_load");
    assert!((float(shear, "mu_s") - expected).abs() <= 1e-12 * expected);
    // τ_s = c·k with c = 1 is the law's parameter column.
    let params = plan
        .nodes
        .iter()
        .map(|n| n.task.params())
        .find(|p| p.iter().any(|f| f.name == "interface_factor"))
        .unwrap();
    let tau = params.iter().find(|f| f.name == "shear_strength").unwrap();
    assert_eq!(tau.value, asperity::engine::value::Value::Float(k));
    let stick = by_model(&rows, "per_spot", "full_stick");
    let loads = column(stick, "spots", "normal_force");
    assert_eq!(loads.len() as i64, int(stick, "spot_count"));
    let sum: f64 = loads.iter().sum();
    assert!((sum - float(stick, "normal_load")).abs() <= 1e-9 * sum);
    let pixels = column(stick, "spots", "area");
    let smallest = pixels.iter().copied().fold(f64::INFINITY, f64::min);
    let one_pixel = pixels.iter().filter(|a| **a == smallest).count() as f64;
    assert!(int(stick, "one_pixel_spots") as f64 <= one_pixel);
    // The contact carries 20 MPa over the section: Σ P_i is that load.
    let applied = 20e6 * float(stick, "section_area");
    assert!(
        (sum - applied).abs() <= 1e-6 * applied,
        "{sum} vs {applied}"
    );
}

/// Full stick per summit carries tangential load at ground-steel ψ (KE per summit does not), and
/// its μ(F) curve falls with the load towards the asymptote a = 0.27 of μ(P*).
#[test]
fn full_stick_per_summit_and_curve() {
    let (plan, report) = run(GROUND, "ground-curve");
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let rows = outcomes(&plan, &report, "friction");
    let summits = by_model(&rows, "per_summit", "full_stick");
    let mu = float(summits, "mu_s");
    assert!(
        (0.05..1.5).contains(&mu),
        "per summit full stick μ_s = {mu}"
    );
    let curve = rows
        .iter()
        .find(|o| text(o, "method") == "statistical" && column(o, "curve", "mu_s").len() == 3)
        .expect("the statistical node of three loads");
    let mu = column(curve, "curve", "mu_s");
    assert_eq!(mu.len(), 3);
    assert!(mu.windows(2).all(|w| w[1] < w[0]), "{mu:?}");
    assert!(mu.iter().all(|m| *m > 0.27), "{mu:?}");
    assert_eq!(column(curve, "curve", "mu_s_computed"), mu);
}

#[test]
fn spec_errors_name_the_field_and_the_fix() {
    let cases = [
        (
            GROUND.replace(
                "friction: {model: junction_shear,",
                "friction: {model: junction_shear, method: statistical,",
            ),
            "use `method: per_spot`",
        ),
        (
            GROUND.replace(
                "friction: {model: full_stick, lower: a, upper: b, contact: pair,\n               lower_material: s235jr, upper_material: s235jr}",
                "friction: {model: full_stick, lower: a, upper: b, contact: pair,\n               lower_material: {name: s235jr, poisson_ratio: 0.1}, upper_material: s235jr}",
            ),
            "Poisson ratio in [0.2, 0.5)",
        ),
        (
            GROUND.replace(
                "friction: {method: per_spot, contact: pair,",
                "friction: {method: per_spot, stick_law: {a: 0.3}, contact: pair,",
            ),
            "has moved into the model's parameter block: write `model: {full_stick: {a: 0.27, b: 0.35}}`",
        ),
        (
            GROUND.replace(
                "friction: {lower: a, upper: b, contact: pair,",
                "friction: {spots_table: true, lower: a, upper: b, contact: pair,",
            ),
            "only available with `method: per_spot`",
        ),
        (
            GROUND.replace("spots_table: true,", "spot_connectivity: 6,"),
            "is not one of: 4, 8",
        ),
    ];
    for (study, expected) in cases {
        let message = plan_error(&study);
        assert!(message.contains(expected), "{expected}: {message}");
    }
}
