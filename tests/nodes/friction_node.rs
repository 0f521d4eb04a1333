//! The `friction` node through the engine: statistical KE from explicit roughness and from
//! surfaces (against the library), μ(F) curve tables, per-summit on a small contact, materials
//! by name with overrides, and the spec errors.

use crate::nodes_common;
use asperity::engine::execute::NodeOutcome;
use asperity::engine::plan::Plan;
use asperity::engine::value::Value;
use asperity::friction::{
    static_friction, AdhesionBeyondFits, AdhesionParameters, KogutEtsion, Material, SolveSettings,
    SpectralMoments, StaticFrictionForm, StatisticalModel, SummitStatistics,
};
use asperity::materials::{find_material, BodyMaterial, MaterialPair};
use nodes_common::{boolean, column, float, outcomes, plan_error, run, study, text};

/// S235JR against S235JR: composite modulus and the built-in hardness.
fn s235_pair() -> Material {
    let steel = BodyMaterial::new(find_material("s235jr").unwrap().constants).unwrap();
    Material::from_pair(&MaterialPair::new(steel, Some(steel))).unwrap()
}

fn library_mu(summits: SummitStatistics, area: f64, load: f64) -> f64 {
    let model = StatisticalModel::new(
        std::sync::Arc::new(KogutEtsion::new(s235_pair(), StaticFrictionForm::Literal)),
        summits,
        s235_pair(),
        AdhesionParameters::new(0.5, 0.158e-9).unwrap(),
        area,
        AdhesionBeyondFits::default(),
    )
    .unwrap();
    static_friction(&model, load, &SolveSettings::default())
        .unwrap()
        .mu_s
        .unwrap()
}

const EXPLICIT: &str = r#"
study: explicit
nodes:
  ke:
    friction:
      roughness: {sigma: 0.1 um, radius: 100 um, density: 4e9}
      lower_material: s235jr
      upper_material: S235JR
      nominal_area: 1 mm^2
      nominal_pressures: [PRESSURES]
"#;

#[test]
fn statistical_from_explicit_roughness_equals_the_library() {
    let (plan, report) = run(&EXPLICIT.replace("PRESSURES", "20 MPa"), "explicit");
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let row = outcomes(&plan, &report, "friction")[0];
    let summits = SummitStatistics::from_explicit(0.1e-6, 100e-6, 4e9).unwrap();
    // Same inputs, same deterministic solve: bit-identical.
    assert_eq!(float(row, "mu_s"), library_mu(summits, 1e-6, 20.0));
    // One load: a curve of one step, the row.
    assert_eq!(column(row, "curve", "mu_s"), vec![float(row, "mu_s")]);
}

#[test]
fn several_loads_give_a_curve_table_with_the_row_at_the_last_load() {
    let (plan, report) = run(
        &EXPLICIT.replace("PRESSURES", "1 MPa, 5 MPa, 20 MPa"),
        "curve",
    );
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let row = outcomes(&plan, &report, "friction")[0];
    let mu = column(row, "curve", "mu_s");
    let loads = column(row, "curve", "external_load");
    assert_eq!(loads, vec![1.0, 5.0, 20.0]);
    assert_eq!(mu.last().copied(), Some(float(row, "mu_s")));
    // Adhesion matters more at light loads: μ_s falls with the load (KE 2004, Fig. 6 trend).
    assert!(mu.windows(2).all(|w| w[1] < w[0]), "{mu:?}");
    let area = column(row, "curve", "real_area");
    assert!(area.windows(2).all(|w| w[1] > w[0]), "{area:?}");
}

const SURFACES: &str = r#"
study: surfaces
nodes:
  a:
    surface:
      synthetic: {grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: 1.19 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 1}
  b:
    surface:
      synthetic: {grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: 0.38 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 2}
  ke:
    friction:
      lower: a
      upper: b
      lower_material: s235jr
      upper_material: {name: s235jr}
      nominal_pressures: [20 MPa]
"#;

#[test]
fn statistical_from_two_surfaces_uses_combined_moments() {
    let (plan, report) = run(SURFACES, "surfaces");
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let s = outcomes(&plan, &report, "surface");
    let moments = |o: &NodeOutcome| {
        SpectralMoments::new(float(o, "m0"), float(o, "m2"), float(o, "m4")).unwrap()
    };
    let combined = moments(s[0]).combined_with(&moments(s[1]));
    let summits = SummitStatistics::from_spectral_moments(&combined).unwrap();
    let area = 0.25e-3 * 0.25e-3;
    let row = outcomes(&plan, &report, "friction")[0];
    // At this plasticity index the literal KE 2004 Q_max is negative: the table keeps the
    // computed value in `mu_s_computed` and reports μ_s = 0 with the flag set.
    let computed = library_mu(summits, area, 20e6 * area);
    assert!(computed < 0.0, "{computed}");
    assert_eq!(float(row, "mu_s_computed"), computed);
    assert_eq!(float(row, "mu_s"), 0.0);
    assert!(boolean(row, "mu_s_floored"));
    assert_eq!(float(row, "gw_sigma"), summits.sigma);
    assert!(float(row, "load_share_beyond_fit") > 0.9);
    assert_eq!(text(row, "model_basis"), "published_fits");
}

const PER_SUMMIT: &str = r#"
study: per_summit
nodes:
  # A fine finish (plasticity index ≈ 1.5): the contacting summits are elastic or elastic-plastic
  # with x ≤ 6, the range where the KE Q_max fits carry tangential load. (At ground-steel
  # roughness, ψ of 10-70, almost every summit is beyond x = 6 and μ_s is ~0; see the docs.)
  a:
    surface:
      synthetic: {grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: 0.05 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 1}
  pair:
    contact:
      lower: a
      lower_material: s235jr
      nominal_pressures: [20 MPa]
      fields: FIELDS
  summits:
    friction:
      method: per_summit
      contact: pair
      lower_material: s235jr
      summits_table: true
  ke:
    friction:
      lower: a
      contact: pair
      lower_material: s235jr
"#;

#[test]
fn per_summit_on_a_small_contact_gives_a_sane_coefficient() {
    let (plan, report) = run(&PER_SUMMIT.replace("FIELDS", "true"), "per-summit");
    assert!(report.all_ok(), "{:?}", report.outcomes);
    let rows = outcomes(&plan, &report, "friction");
    let per = rows
        .iter()
        .find(|o| o.tables.contains_key("summits"))
        .unwrap();
    let mu = float(per, "mu_s");
    // Static friction coefficients of dry steel contacts lie well inside (0, 2).
    assert!(mu.is_finite() && mu > 0.0 && mu < 2.0, "μ_s = {mu}");
    assert!(float(per, "contacts") >= 1.0);
    let p10 = float(per, "local_mu_p10");
    let p90 = float(per, "local_mu_p90");
    assert!(p10 <= float(per, "local_mu_median") && float(per, "local_mu_median") <= p90);
    let forces = column(per, "summits", "normal_force");
    assert!(forces.iter().all(|f| *f >= 0.0));
    // The statistical node takes the contact's final nominal pressure as its load.
    let ke = rows
        .iter()
        .find(|o| text(o, "method") == "statistical")
        .unwrap();
    assert_eq!(float(ke, "nominal_pressure"), 20e6);
}

#[test]
fn per_summit_needs_contact_fields() {
    let message = plan_error(&PER_SUMMIT.replace("FIELDS", "false"));
    assert!(
        message.contains("contact node 'pair': add `fields: true`"),
        "{message}"
    );
}

#[test]
fn materials_by_name_with_overrides_and_suggestions() {
    let override_study = EXPLICIT.replace("PRESSURES", "20 MPa").replace(
        "upper_material: S235JR",
        "upper_material: {name: 1.0037, youngs_modulus: 205 GPa}",
    );
    let plan = Plan::build(&study(&override_study)).unwrap();
    let params = plan.nodes[0].task.params();
    let Some(Value::Float(e)) = params
        .iter()
        .find(|f| f.name == "composite_modulus")
        .map(|f| &f.value)
    else {
        panic!("no composite modulus")
    };
    let expected = 1.0 / (0.91 / 210e9 + 0.91 / 205e9);
    // Same formula in a different order of operations: a few ulps.
    assert!((e - expected).abs() < 1e-12 * expected, "{e} vs {expected}");
    // A name that looks like a number with a unit is still a name in a node field.
    let plan = Plan::build(&study(
        &EXPLICIT
            .replace("PRESSURES", "20 MPa")
            .replace("upper_material: S235JR", "upper_material: {name: 17-4PH}"),
    ));
    assert!(plan.is_ok(), "{:?}", plan.err());
    let message = plan_error(&EXPLICIT.replace("upper_material: S235JR", "upper_material: s253jr"));
    assert!(
        message.contains("unknown material 's253jr' (did you mean 's235jr'?)"),
        "{message}"
    );
    let message = plan_error(&EXPLICIT.replace(
        "upper_material: S235JR",
        "upper_material: {youngs_modulus: 1 GPa}",
    ));
    assert!(
        message.contains("upper_material.poisson_ratio"),
        "{message}"
    );
}

/// One set of material bounds for every use: ν = 0.5 is accepted (friction and the parser
/// refused it before), a negative ν, a yield strength above the hardness and a shear strength
/// above Tabor's Y = H/2.8 are refused at the material with the bound.
#[test]
fn materials_obey_one_set_of_bounds() {
    let upper = |material: &str| {
        EXPLICIT.replace("PRESSURES", "20 MPa").replace(
            "upper_material: S235JR",
            &format!("upper_material: {material}"),
        )
    };
    let plan = Plan::build(&study(&upper("{name: s235jr, poisson_ratio: 0.5}")));
    assert!(plan.is_ok(), "{:?}", plan.err());
    for (material, field, bound) in [
        (
            "{name: s235jr, poisson_ratio: -0.1}",
            "upper_material.poisson_ratio",
            "in [0, 0.5]",
        ),
        (
            "{name: s235jr, yield_strength: 2.5 GPa}",
            "upper_material.yield_strength",
            "at most hardness",
        ),
        // S235JR: H = 1.96 GPa, so Tabor's Y = 0.70 GPa.
        (
            "{name: s235jr, shear_strength: 1 GPa}",
            "upper_material.shear_strength",
            "at most yield_strength",
        ),
        (
            "{name: s235jr, hardness: 300 GPa}",
            "upper_material.hardness",
            "below youngs_modulus",
        ),
    ] {
        let message = plan_error(&upper(material));
        assert!(
            message.contains(field) && message.contains(bound),
            "{material}: {message}"
        );
    }
}

#[test]
fn materials_can_be_swept_and_give_the_contact_its_flow_pressure() {
    let text = PER_SUMMIT
        .replace("FIELDS", "true")
        .replace(
            "study: per_summit\n",
            "study: per_summit\nparameters:\n  product:\n    mat: [s235jr, aisi630]\n",
        )
        .replace("lower_material: s235jr", "lower_material: ${mat}");
    let plan = Plan::build(&study(&text)).unwrap();
    let flow: Vec<f64> = plan
        .nodes
        .iter()
        .filter(|n| n.task.kind() == "contact")
        .map(|n| {
            match n
                .task
                .params()
                .iter()
                .find(|f| f.name == "flow_pressure")
                .map(|f| &f.value)
            {
                Some(Value::Float(v)) => *v,
                other => panic!("{other:?}"),
            }
        })
        .collect();
    // Rule p_lim = H of the built-in material (200 HV and 434 HV).
    let expected: Vec<f64> = ["s235jr", "17-4ph"]
        .iter()
        .map(|n| find_material(n).unwrap().constants.hardness.unwrap())
        .collect();
    assert_eq!(flow, expected);
}

/// The models table of `docs/study-format.md` is the registry's, as written by
/// `friction_models_markdown()`.
#[test]
fn every_friction_model_is_in_the_documentation() {
    let docs = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/study-format.md"),
    )
    .unwrap();
    let table = asperity::nodes::friction_models_markdown();
    assert!(
        docs.contains(&table),
        "docs/study-format.md must hold the models table as written by friction_models_markdown():\n{table}"
    );
}
