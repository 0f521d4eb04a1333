//! Per-summit model: per-summit forces from the single-asperity laws, force-weighted μ, states.

use asperity_numerics::friction::adhesion::{
    contacting_adhesion_ratio, lennard_jones_adhesion_ratio,
};
use asperity_numerics::friction::laws::kogut_etsion::{ke_load_ratio, ke_static_friction_ratio};
use asperity_numerics::friction::{
    per_summit_friction, AdhesionBeyondFits, AdhesionParameters, ChangEtsionBogy, DeformationState,
    FrictionError, KogutEtsion, Material, StaticFrictionForm, SummitContact,
};

fn material() -> Material {
    Material::new(115e9, 2e9, 0.3).unwrap_or_else(|e| panic!("{e}"))
}

/// Summits with interferences at x = −0.5 (gap), 0.5, 3, 50, 200 of their own ω_c.
fn summits(m: &Material) -> Vec<SummitContact> {
    [
        (50e-6, -0.5),
        (20e-6, 0.5),
        (80e-6, 3.0),
        (30e-6, 50.0),
        (10e-6, 200.0),
    ]
    .iter()
    .map(|&(radius, x)| SummitContact {
        radius,
        interference: x * m.critical_values(radius).interference,
    })
    .collect()
}

/// Each summit's forces equal the single-asperity laws at its own R_i and x_i (1e-9: x_i is
/// recovered from ω_i/ω_c,i with rounding), and μ = ΣF_f / Σ(F_n − F_a) exactly.
#[test]
fn per_summit_forces_follow_the_laws() {
    let m = material();
    let adhesion = AdhesionParameters::new(0.5, 0.158e-9).unwrap_or_else(|e| panic!("{e}"));
    let input = summits(&m);
    let ke = KogutEtsion::new(m, StaticFrictionForm::Literal);
    let r = per_summit_friction(&input, &ke, &m, &adhesion, AdhesionBeyondFits::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let k = m.hardness_factor();
    for (s, out) in input.iter().zip(&r.summits) {
        let c = m.critical_values(s.radius);
        let x = s.interference / c.interference;
        let unit = 2.0 * std::f64::consts::PI * s.radius * adhesion.energy;
        let fa = if x > 0.0 {
            contacting_adhesion_ratio(
                x,
                adhesion.equilibrium_distance / c.interference,
                AdhesionBeyondFits::HoldAtX110,
            ) * unit
        } else {
            lennard_jones_adhesion_ratio(1.0 - s.interference / adhesion.equilibrium_distance)
                * unit
        };
        assert!(
            (out.normal_force - ke_load_ratio(x, k) * c.load).abs()
                <= 1e-9 * out.normal_force.abs().max(1e-300)
        );
        assert!((out.adhesion_force - fa).abs() <= 1e-9 * fa);
        assert!(
            (out.friction_force
                - ke_static_friction_ratio(x, StaticFrictionForm::Literal) * c.load)
                .abs()
                <= 1e-9 * c.load
        );
    }
    let states: Vec<DeformationState> = r.summits.iter().map(|s| s.state).collect();
    use DeformationState::*;
    assert_eq!(
        states,
        vec![
            NotInContact,
            Elastic,
            ElasticPlastic,
            ElasticPlastic,
            FullyPlastic
        ]
    );
    assert_eq!(r.state_counts, [1, 1, 2, 1]);
    let expected = r.total_friction_force / (r.total_normal_force - r.total_adhesion_force);
    assert_eq!(r.mu_s, Some(expected));
    // The non-contacting summit has no local μ (F_n − F_a < 0), nor has the small elastic summit
    // (R = 20 µm, x = 0.5: its adhesion 1.4e-4 N exceeds its Hertz load 8.5e-5 N); the summary
    // covers the three others.
    assert_eq!(r.summits[0].local_mu, None);
    assert_eq!(r.summits[1].local_mu, None);
    let summary = r.local_mu_summary.unwrap_or_else(|| panic!("summary"));
    assert_eq!(summary.count, 3);
    assert!(summary.min <= summary.median && summary.median <= summary.max);
}

/// Δγ = 0: no adhesion force on any summit; only elastic summits carry Q in the CEB baseline.
#[test]
fn zero_adhesion_and_ceb_baseline() {
    let m = material();
    let adhesion = AdhesionParameters::new(0.0, 0.158e-9).unwrap_or_else(|e| panic!("{e}"));
    let r = per_summit_friction(
        &summits(&m),
        &ChangEtsionBogy::new(m),
        &m,
        &adhesion,
        AdhesionBeyondFits::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(r.summits.iter().all(|s| s.adhesion_force == 0.0));
    for s in &r.summits {
        assert_eq!(s.friction_force > 0.0, s.state == DeformationState::Elastic);
    }
}

#[test]
fn invalid_summits_are_typed_errors() {
    let m = material();
    let adhesion = AdhesionParameters::new(0.5, 0.158e-9).unwrap_or_else(|e| panic!("{e}"));
    let bad = [SummitContact {
        radius: 0.0,
        interference: 1e-9,
    }];
    assert!(matches!(
        per_summit_friction(
            &bad,
            &KogutEtsion::new(m, StaticFrictionForm::Literal),
            &m,
            &adhesion,
            AdhesionBeyondFits::default()
        ),
        Err(FrictionError::InvalidParameter {
            name: "summit radius",
            ..
        })
    ));
    let bad = [SummitContact {
        radius: 1e-5,
        interference: f64::NAN,
    }];
    assert!(per_summit_friction(
        &bad,
        &KogutEtsion::new(m, StaticFrictionForm::Literal),
        &m,
        &adhesion,
        AdhesionBeyondFits::default()
    )
    .is_err());
    let empty = per_summit_friction(
        &[],
        &KogutEtsion::new(m, StaticFrictionForm::Literal),
        &m,
        &adhesion,
        AdhesionBeyondFits::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(empty.mu_s, None);
    assert_eq!(empty.local_mu_summary, None);
}
