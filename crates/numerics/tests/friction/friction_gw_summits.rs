//! GW functions, Nayak/McCool summit statistics and material inputs.

use asperity_numerics::friction::{
    gw_function, FrictionError, Material, SpectralMoments, SummitStatistics,
};
use asperity_numerics::materials::{BodyConstants, BodyMaterial, MaterialPair};

/// Reference value printed with a given number of significant digits: the tolerance is half a unit
/// in the last printed digit (plus 1 % of it for the rounding of our own value).
fn assert_printed(value: f64, printed: f64, last_digit: f64) {
    assert!(
        (value - printed).abs() <= 0.505 * last_digit,
        "{value} vs printed {printed}"
    );
}

#[test]
fn gw_function_reference_values() {
    let f = |n: f64, t: f64| gw_function(n, t).map(|o| o.value).unwrap_or(f64::INFINITY);
    assert_printed(f(1.0, 0.0), 0.39894, 1e-5);
    assert_printed(f(1.5, 0.0), 0.43002, 1e-5);
    assert_printed(f(1.5, 1.0), 0.075668, 1e-6);
    assert_printed(f(1.5, 2.0), 0.0066482, 1e-7);
    assert_printed(f(1.5, 3.0), 2.6397e-4, 1e-8);
}

/// F_1(t) = φ(t) − t·Q(t) in closed form; the quadrature's 1e-10 relative tolerance allows 2e-10.
#[test]
fn gw_function_one_matches_closed_form() {
    for &t in &[-3.0f64, -1.0, 0.0, 0.5, 2.0, 5.0, 8.0] {
        let phi = (-0.5 * t * t).exp() / (2.0 * std::f64::consts::PI).sqrt();
        let tail = asperity_numerics::friction::upper_tail_probability(t);
        let exact = phi - t * tail;
        let value = gw_function(1.0, t)
            .map(|o| o.value)
            .unwrap_or(f64::INFINITY);
        assert!(
            (value - exact).abs() <= 2e-10 * exact,
            "t = {t}: {value} vs {exact}"
        );
    }
}

#[test]
fn gw_function_rejects_negative_order() {
    assert!(matches!(
        gw_function(-0.5, 0.0),
        Err(FrictionError::InvalidParameter { name: "n", .. })
    ));
}

fn moments_with_alpha(sigma: f64, m2: f64, alpha: f64) -> (f64, f64, f64) {
    let m0 = sigma * sigma;
    (m0, m2, alpha * m2 * m2 / m0)
}

/// McCool's β forms versus the moment forms. α = 768πβ² is an identity (1e-12 for rounding);
/// the printed constants 3.717e-4 and 0.045944 are rounded to 4–5 digits, hence 1e-4 and 2e-5.
#[test]
fn mccool_identities_agree_with_moment_forms() {
    for &alpha in &[1.5, 3.0, 10.0, 50.0] {
        let (m0, m2, m4) = moments_with_alpha(1e-6, 2e-3, alpha);
        let s = SummitStatistics::from_moments(m0, m2, m4).unwrap_or_else(|e| panic!("{e}"));
        let beta = s.beta;
        assert!((768.0 * std::f64::consts::PI * beta * beta / s.alpha - 1.0).abs() < 1e-12);
        assert!((s.alpha / alpha - 1.0).abs() < 1e-12);
        let ratio = (1.0 - 3.717e-4 / (beta * beta)).sqrt();
        assert!(
            (s.sigma_s / s.sigma / ratio - 1.0).abs() < 1e-4,
            "alpha {alpha}"
        );
        assert!((s.y_s / s.sigma / (0.045944 / beta) - 1.0).abs() < 2e-5);
        // The explicit constructor reproduces the same surface (identities, rounding only).
        let e = SummitStatistics::from_explicit(s.sigma, s.radius, s.density)
            .unwrap_or_else(|e| panic!("{e}"));
        assert!((e.sigma_s / s.sigma_s - 1.0).abs() < 1e-12);
        assert!((e.y_s / s.y_s - 1.0).abs() < 1e-12);
        assert!((e.alpha / s.alpha - 1.0).abs() < 1e-12);
    }
}

/// Two surfaces: moments add, so σ² = σ1² + σ2² and R⁻² = R1⁻² + R2⁻² (to rounding).
#[test]
fn two_surfaces_combine_by_adding_moments() {
    let (a0, a2, a4) = moments_with_alpha(1.2e-6, 3e-3, 4.0);
    let (b0, b2, b4) = moments_with_alpha(0.4e-6, 1e-3, 8.0);
    let a = SpectralMoments::new(a0, a2, a4).unwrap_or_else(|e| panic!("{e}"));
    let b = SpectralMoments::new(b0, b2, b4).unwrap_or_else(|e| panic!("{e}"));
    let sa = SummitStatistics::from_spectral_moments(&a).unwrap_or_else(|e| panic!("{e}"));
    let sb = SummitStatistics::from_spectral_moments(&b).unwrap_or_else(|e| panic!("{e}"));
    let sum = SummitStatistics::from_spectral_moments(&a.combined_with(&b))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!((sum.sigma.powi(2) / (sa.sigma.powi(2) + sb.sigma.powi(2)) - 1.0).abs() < 1e-12);
    assert!((sum.radius.powi(-2) / (sa.radius.powi(-2) + sb.radius.powi(-2)) - 1.0).abs() < 1e-12);
}

#[test]
fn bandwidth_below_mccool_bound_is_a_typed_error() {
    let (m0, m2, m4) = moments_with_alpha(1e-6, 2e-3, 0.8);
    assert!(matches!(
        SummitStatistics::from_moments(m0, m2, m4),
        Err(FrictionError::BandwidthBelowMcCoolBound { .. })
    ));
    // β = 0.019 < 0.01928 with explicit σ, R, η.
    let sigma = 1e-6;
    let radius = 1e-4;
    let density = 0.019 / (sigma * radius);
    assert!(matches!(
        SummitStatistics::from_explicit(sigma, radius, density),
        Err(FrictionError::BandwidthBelowMcCoolBound { .. })
    ));
    assert!(matches!(
        SummitStatistics::from_moments(1e-12, 0.0, 1.0),
        Err(FrictionError::InvalidParameter { name: "m2", .. })
    ));
}

/// Composite modulus of two steels (E = 210 GPa, ν = 0.3): E/(2(1 − ν²)) = 115.38 GPa;
/// K = 0.454 + 0.41·0.3; ω_c/σ_s = 1/ψ² (identities, 1e-12).
#[test]
fn material_composite_modulus_and_critical_values() {
    let steel = BodyMaterial::new(BodyConstants::with_hardness(210e9, 0.3, 2e9))
        .unwrap_or_else(|e| panic!("{e}"));
    let m = Material::from_pair(&MaterialPair::new(steel, Some(steel)))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!((m.composite_modulus / (210e9 / (2.0 * 0.91)) - 1.0).abs() < 1e-12);
    assert!((m.hardness_factor() - 0.577).abs() < 1e-12);
    let (sigma_s, radius) = (0.9e-6, 2e-4);
    let psi = m.plasticity_index(sigma_s, radius);
    let c = m.critical_values(radius);
    assert!((c.interference / sigma_s * psi * psi - 1.0).abs() < 1e-12);
    let pc = 2.0 / 3.0
        * std::f64::consts::PI
        * m.hardness_factor()
        * m.hardness
        * radius
        * c.interference;
    assert!((c.load / pc - 1.0).abs() < 1e-12);
    assert!((c.area / (std::f64::consts::PI * radius * c.interference) - 1.0).abs() < 1e-12);
}

#[test]
fn material_inputs_are_validated() {
    assert!(matches!(
        Material::new(115e9, 2e9, 0.6),
        Err(FrictionError::InvalidParameter {
            name: "poisson_ratio",
            ..
        })
    ));
    assert!(matches!(
        Material::new(-1.0, 2e9, 0.3),
        Err(FrictionError::InvalidParameter {
            name: "composite_modulus",
            ..
        })
    ));
    assert!(matches!(
        Material::new(115e9, f64::NAN, 0.3),
        Err(FrictionError::InvalidParameter {
            name: "hardness",
            ..
        })
    ));
    // The material bounds: ν in [0, 0.5], the incompressible 0.5 included.
    assert!(Material::new(115e9, 2e9, 0.5).is_ok());
    assert!(matches!(
        Material::new(115e9, 2e9, -0.1),
        Err(FrictionError::InvalidParameter {
            name: "poisson_ratio",
            ..
        })
    ));
    let elastic = BodyMaterial::elastic(210e9, 0.3).unwrap_or_else(|e| panic!("{e}"));
    assert!(matches!(
        Material::from_pair(&MaterialPair::against_rigid(elastic)),
        Err(FrictionError::InvalidParameter {
            name: "hardness",
            ..
        })
    ));
    assert!(matches!(
        asperity_numerics::friction::AdhesionParameters::new(0.5, 0.0),
        Err(FrictionError::InvalidParameter {
            name: "equilibrium_distance",
            ..
        })
    ));
}
