//! The friction-law registry is consistent: unique names and columns, every law builds at its
//! defaults for a steel pair, offers what each of its methods needs, reports every parameter it
//! declares, and refuses what its ranges exclude.

use std::collections::HashSet;
use std::sync::Arc;

use asperity_numerics::friction::laws::{
    find_law, LawInputs, LawParameters, ParameterKind, ParameterValue,
};
use asperity_numerics::friction::{FrictionLaw, Material, Method, SpotLoad, LAWS, TABOR_FACTOR};

fn steel_inputs(parameters: LawParameters) -> LawInputs {
    let material = Material::new(115e9, 1.96e9, 0.3).unwrap_or_else(|e| panic!("{e}"));
    let yield_strength = material.hardness / TABOR_FACTOR;
    LawInputs {
        material,
        yield_strength,
        shear_strength: yield_strength / 3f64.sqrt(),
        parameters,
    }
}

#[test]
fn names_and_columns_are_unique() {
    let mut names = HashSet::new();
    for law in LAWS {
        assert!(names.insert(law.name), "{} twice", law.name);
        assert!(!law.methods.is_empty(), "{} has no method", law.name);
        let mut columns = HashSet::new();
        for p in law.parameters {
            assert!(
                columns.insert(p.column),
                "{}: column {}",
                law.name,
                p.column
            );
            assert!(law.parameter(p.name).is_some());
        }
        assert_eq!(find_law(law.name).map(|l| l.name), Some(law.name));
    }
    assert!(find_law("kogut-etsion").is_none());
}

#[test]
fn every_law_builds_and_serves_its_methods() {
    let spot = SpotLoad {
        load: 1e-3,
        area: 1e-10,
        radius: Some(20e-6),
        pixels: 9,
        summits: 1,
    };
    for law in LAWS {
        let built: Arc<dyn FrictionLaw> = Arc::from(
            (law.build)(&steel_inputs(law.default_parameters()))
                .unwrap_or_else(|e| panic!("{}: {e}", law.name)),
        );
        assert_eq!(built.descriptor().name, law.name);
        let asperity = Arc::clone(&built).asperity_laws();
        for method in Method::ALL {
            if law.supports(method) && method.needs_asperity_laws() {
                let laws = asperity
                    .as_ref()
                    .unwrap_or_else(|| panic!("{}: no asperity laws for {method:?}", law.name));
                assert!(laws.load_ratio(2.0) > 0.0 && laws.fit_limit() > 0.0);
            }
        }
        if law.supports(Method::PerSpot) {
            let q = built
                .spot_friction(&spot, None)
                .unwrap_or_else(|| panic!("{}", law.name));
            assert!(q.friction_force.is_finite() && q.friction_force >= 0.0);
        }
        let reported: Vec<&str> = built.reported_values().iter().map(|v| v.column).collect();
        for p in law.parameters {
            assert!(reported.contains(&p.column), "{}: {}", law.name, p.column);
        }
        // A law reads a sliding direction exactly when it declares one: the others have none in
        // their parameters, key or row.
        assert_eq!(
            built.sliding_direction().is_some(),
            reported.contains(&"sliding_direction"),
            "{}",
            law.name
        );
        assert!(law.mu_s_max > 0.0 && law.mu_s_max <= 1.5, "{}", law.name);
    }
}

/// Each parameter's range: its default lies inside; values outside are refused by the
/// declaration, and a law built from an out-of-range value directly is an error, not a number.
#[test]
fn parameter_ranges_hold() {
    for law in LAWS {
        for p in law.parameters {
            match p.kind {
                ParameterKind::Number { default, range, .. } => {
                    assert!(range.contains(default), "{}.{}", law.name, p.name);
                    let outside = if range.max.is_finite() {
                        range.max + 1.0
                    } else {
                        range.min - 1.0
                    };
                    assert!(p.number(outside).is_err(), "{}.{}", law.name, p.name);
                    assert!(p.number(f64::NAN).is_err());
                    let mut parameters = law.default_parameters();
                    assert!(parameters.set(p.name, ParameterValue::Number(outside)));
                    assert!((law.build)(&steel_inputs(parameters)).is_err());
                }
                ParameterKind::Choice { options, default } => {
                    assert!(options.contains(&default));
                    assert!(p.choice("no-such-option").is_err());
                }
            }
        }
    }
}
