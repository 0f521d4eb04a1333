//! Single-asperity laws: values and the documented behaviour at the breakpoints x = 1, 6, 110.

use asperity::friction::asperity_laws::{
    ceb_area_ratio, ceb_load_ratio, ceb_static_friction_ratio, contacting_adhesion_ratio,
    ke_area_ratio, ke_load_ratio, ke_static_friction_ratio, lennard_jones_adhesion_ratio,
};
use asperity::friction::{AdhesionBeyondFits, DeformationState, StaticFrictionForm};

/// K for ν = 0.3.
const K: f64 = 0.577;

/// Values are compared to the fit formulas to 1e-12 relative (pure arithmetic); the jumps are the
/// documented ones, checked to the 4 printed digits.
fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs()
}

#[test]
fn load_fits_at_breakpoints_belong_to_the_lower_range() {
    let above = |x: f64| x * (1.0 + 1e-12);
    // x = 1: Hertz at the breakpoint, 1.03 x^1.425 just above (a 3 % jump).
    assert!(close(ke_load_ratio(1.0, K), 1.0, 1e-12));
    assert!(close(ke_load_ratio(above(1.0), K), 1.03, 1e-9));
    // x = 6: 13.23 (1–6 fit) → 13.46 (6–110 fit).
    assert!(close(ke_load_ratio(6.0, K), 1.03 * 6f64.powf(1.425), 1e-12));
    assert!(close(ke_load_ratio(6.0, K), 13.234, 1e-4));
    assert!(close(ke_load_ratio(above(6.0), K), 13.457, 1e-4));
    // x = 110: 530.2 (6–110 fit) → (3/K)·110 = 571.9 (fully plastic).
    assert!(close(ke_load_ratio(110.0, K), 530.16, 1e-4));
    assert!(close(ke_load_ratio(above(110.0), K), 3.0 / K * 110.0, 1e-9));
    assert_eq!(ke_load_ratio(0.0, K), 0.0);
    assert_eq!(ke_load_ratio(-1.0, K), 0.0);
}

#[test]
fn area_fits_at_breakpoints() {
    let above = |x: f64| x * (1.0 + 1e-12);
    assert!(close(ke_area_ratio(1.0), 1.0, 1e-12));
    assert!(close(ke_area_ratio(above(1.0)), 0.93, 1e-9));
    assert!(close(ke_area_ratio(6.0), 7.1197, 1e-4));
    assert!(close(ke_area_ratio(above(6.0)), 7.3264, 1e-4));
    assert!(close(ke_area_ratio(110.0), 205.38, 1e-4));
    assert!(close(ke_area_ratio(above(110.0)), 220.0, 1e-9));
}

/// The reference's consistency check: for ε/ω_c ≈ 0.004 the contacting adhesion pieces nearly join
/// at x = 1 (4.86 → 4.65, within 5 %) and at x = 6 (8.798 → 8.791, within 0.2 %).
#[test]
fn adhesion_fits_nearly_join_for_small_eps_over_omega_c() {
    let hold = AdhesionBeyondFits::HoldAtX110;
    let e = 0.004;
    let (a1, b1) = (
        contacting_adhesion_ratio(1.0, e, hold),
        contacting_adhesion_ratio(1.0 + 1e-12, e, hold),
    );
    assert!(close(a1, 0.98 * e.powf(-0.29), 1e-12));
    assert!((a1 - b1).abs() < 0.05 * a1);
    let (a6, b6) = (
        contacting_adhesion_ratio(6.0, e, hold),
        contacting_adhesion_ratio(6.0 + 1e-11, e, hold),
    );
    assert!((a6 - b6).abs() < 0.002 * a6);
    // Beyond x = 110: held at the x = 110 value, or the 6–110 fit extended.
    let at110 = contacting_adhesion_ratio(110.0, e, hold);
    assert_eq!(contacting_adhesion_ratio(500.0, e, hold), at110);
    let extended = contacting_adhesion_ratio(500.0, e, AdhesionBeyondFits::ExtendLastFit);
    assert!(close(
        extended,
        1.19 * 500f64.powf(0.093) * e.powf(-0.332),
        1e-12
    ));
    assert_eq!(contacting_adhesion_ratio(0.0, e, hold), 0.0);
}

/// LJ/DMT force is 2πRΔγ at contact (h = ε) and decays as (4/3)(ε/h)².
#[test]
fn lennard_jones_force() {
    assert!(close(lennard_jones_adhesion_ratio(1.0), 1.0, 1e-15));
    // At h = 50ε the repulsive term is (1/4)·50⁻⁶ = 1.6e-11 of the attractive one.
    let h = 50.0;
    assert!(close(
        lennard_jones_adhesion_ratio(h),
        4.0 / 3.0 / (h * h),
        2e-11
    ));
    assert!(!close(
        lennard_jones_adhesion_ratio(h),
        4.0 / 3.0 / (h * h),
        1e-11
    ));
}

/// Q_max polynomial: 0.53 at x = 1 (0.52 just below), peak 0.947 near x = 2.58, zero at x = 4.2946,
/// negative up to 6 in the literal form, clipped to 0 in the clipped form, 0 beyond 6.
#[test]
fn static_friction_polynomial_shape() {
    let lit = StaticFrictionForm::Literal;
    let clip = StaticFrictionForm::Clipped;
    assert!(close(ke_static_friction_ratio(1.0, lit), 0.52, 1e-12));
    assert!(close(
        ke_static_friction_ratio(1.0 + 1e-12, lit),
        0.53,
        1e-9
    ));
    assert!(close(ke_static_friction_ratio(2.5821, lit), 0.94695, 1e-5));
    assert!(ke_static_friction_ratio(4.29, lit) > 0.0);
    assert!(ke_static_friction_ratio(4.30, lit) < 0.0);
    assert!(ke_static_friction_ratio(6.0, lit) < 0.0);
    assert_eq!(ke_static_friction_ratio(5.0, clip), 0.0);
    assert_eq!(ke_static_friction_ratio(6.0 + 1e-9, lit), 0.0);
}

/// CEB: Hertz to x = 1, then P/P_c = 1.5(2x − 1) (a jump 1 → 1.5), A/A_c = 2x − 1 (continuous);
/// tangential load only for x ≤ 1.
#[test]
fn ceb_laws() {
    assert!(close(ceb_load_ratio(1.0), 1.0, 1e-15));
    assert!(close(ceb_load_ratio(1.0 + 1e-12), 1.5, 1e-9));
    assert!(close(ceb_area_ratio(1.0 + 1e-12), 1.0, 1e-9));
    assert!(close(ceb_area_ratio(3.0), 5.0, 1e-15));
    assert!(close(ceb_static_friction_ratio(1.0), 0.52, 1e-12));
    assert_eq!(ceb_static_friction_ratio(1.0 + 1e-12), 0.0);
}

#[test]
fn deformation_states_by_breakpoint() {
    use DeformationState::*;
    let s = DeformationState::from_interference_ratio;
    assert_eq!(s(-0.1), NotInContact);
    assert_eq!(s(0.0), NotInContact);
    assert_eq!(s(1.0), Elastic);
    assert_eq!(s(1.5), ElasticPlastic);
    assert_eq!(s(110.0), ElasticPlastic);
    assert_eq!(s(110.5), FullyPlastic);
}
