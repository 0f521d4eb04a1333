//! Every statistical integral against an independent slow quadrature: composite Simpson on a
//! graded grid, written here separately from the library's adaptive Gauss–Kronrod. Agreement is
//! required to 1e-8 of ∫|integrand| (= relative for the positive integrands; the literal Q_max
//! integrand changes sign, so its own absolute scale is the meaningful reference). The library
//! integrates to 1e-10 relative and the Simpson grids below are fine enough to be far below 1e-8.

use asperity_numerics::friction::adhesion::{
    contacting_adhesion_ratio, lennard_jones_adhesion_ratio,
};
use asperity_numerics::friction::laws::chang_etsion_bogy::{
    ceb_area_ratio, ceb_load_ratio, ceb_static_friction_ratio,
};
use asperity_numerics::friction::laws::kogut_etsion::{
    ke_area_ratio, ke_load_ratio, ke_static_friction_ratio,
};
use asperity_numerics::friction::{
    AdhesionBeyondFits, AdhesionParameters, Material, StaticFrictionForm, StatisticalModel,
    SummitStatistics,
};

use super::law_support::{statistical, Model, Options};

/// A statistical model with the law and options it was built with.
struct Case {
    kind: Model,
    options: Options,
    m: StatisticalModel,
}

/// Steel-like model with a prescribed plasticity index (σ = 1 µm, β = 0.04, E = 115 GPa, H = 2 GPa).
fn model(psi: f64, kind: Model, options: Options) -> Case {
    let material = Material::new(115e9, 2e9, 0.3).unwrap_or_else(|e| panic!("{e}"));
    let sigma = 1e-6;
    let beta: f64 = 0.04;
    let sigma_s = sigma * (1.0 - 0.8968 / (768.0 * std::f64::consts::PI * beta * beta)).sqrt();
    let c = 2.0 * material.composite_modulus
        / (std::f64::consts::PI * material.hardness_factor() * material.hardness);
    let radius = sigma_s * c * c / (psi * psi);
    let summits = SummitStatistics::from_explicit(sigma, radius, beta / (radius * sigma))
        .unwrap_or_else(|e| panic!("{e}"));
    let adhesion = AdhesionParameters::new(0.5, 0.158e-9).unwrap_or_else(|e| panic!("{e}"));
    let m = statistical(kind, summits, material, adhesion, 1e-4, options)
        .unwrap_or_else(|e| panic!("{e}"));
    Case { kind, options, m }
}

/// A single-asperity law x ↦ ratio.
type Law = Box<dyn Fn(f64) -> f64>;

fn gaussian(z: f64, s: f64) -> f64 {
    (-0.5 * (z / s).powi(2)).exp() / (s * (2.0 * std::f64::consts::PI).sqrt())
}

/// Composite Simpson of f on [a, b] with `n` (even) subintervals, graded as a + (b − a)u⁴ when
/// `graded` (for the x^b behaviour at a). Returns (∫f, ∫|f|).
fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, n: usize, graded: bool) -> (f64, f64) {
    let g = |u: f64| {
        if graded {
            f(a + (b - a) * u.powi(4)) * (b - a) * 4.0 * u.powi(3)
        } else {
            f(a + (b - a) * u) * (b - a)
        }
    };
    let h = 1.0 / n as f64;
    let (mut sum, mut sum_abs) = (0.0, 0.0);
    for i in 0..=n {
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let v = g(i as f64 * h);
        sum += w * v;
        sum_abs += w * v.abs();
    }
    (sum * h / 3.0, sum_abs * h / 3.0)
}

/// ∫_{d}^{zmax} law((z − d)/wc) φ(z) dz, taken in x = (z − d)/wc, split at the law's breakpoints
/// and around the Gaussian peak. Simpson evaluates segment end points, where the fits jump: the law
/// is evaluated at x clamped 1e-12 of the segment width inside the segment, so each segment sees
/// its own branch (the Gaussian factor uses the exact x).
fn slow_contact(c: &Case, d: f64, law: &dyn Fn(f64) -> f64) -> (f64, f64) {
    let m = &c.m;
    let s = m.summit_std_star();
    let wc = m.critical_interference_star();
    let x_max = (d.max(0.0) + 40.0 * s - d) / wc;
    let mut cuts: Vec<f64> = vec![1.0, 6.0, 110.0];
    // The full-stick laws break at ω* = 1, 110 (stick fit) and ω*_JG = 1.9, elsewhere in x.
    if c.kind == Model::FullStick {
        cuts.extend(m.laws.load_breaks());
    }
    cuts.extend(
        [-3.0 * s, 0.0, 3.0 * s, 10.0 * s]
            .iter()
            .map(|z| (z - d) / wc),
    );
    cuts.retain(|x| *x > 0.0 && *x < x_max);
    cuts.push(0.0);
    cuts.push(x_max);
    cuts.sort_by(f64::total_cmp);
    let mut total = (0.0, 0.0);
    for (i, w) in cuts.windows(2).enumerate() {
        let (xa, xb) = (w[0], w[1]);
        let delta = 1e-12 * (xb - xa);
        let f = |x: f64| law(x.clamp(xa + delta, xb - delta)) * gaussian(d + wc * x, s) * wc;
        let (v, a) = simpson(&f, xa, xb, 20_000, i == 0);
        total = (total.0 + v, total.1 + a);
    }
    total
}

/// ∫_{zlow}^{d} LJ(1 + (d − z)/ε*) φ(z) dz on a grid graded geometrically towards z = d.
fn slow_non_contact(m: &StatisticalModel, d: f64) -> (f64, f64) {
    let s = m.summit_std_star();
    let eps = m.adhesion.equilibrium_distance / m.summits.sigma;
    let z_low = d.min(0.0) - 40.0 * s;
    let f = |z: f64| lennard_jones_adhesion_ratio(1.0 + (d - z) / eps) * gaussian(z, s);
    let mut cuts = vec![d];
    let mut gap = eps;
    while d - gap > z_low {
        cuts.push(d - gap);
        gap *= 4.0;
    }
    cuts.push(z_low);
    cuts.sort_by(f64::total_cmp);
    let mut total = (0.0, 0.0);
    for w in cuts.windows(2) {
        let (v, a) = simpson(&f, w[0], w[1], 2_000, false);
        total = (total.0 + v, total.1 + a);
    }
    total
}

fn assert_agrees(what: &str, library: f64, slow: (f64, f64)) {
    assert!(
        (library - slow.0).abs() <= 1e-8 * slow.1,
        "{what}: library {library:e} vs Simpson {:e} (scale {:e})",
        slow.0,
        slow.1
    );
}

fn check_all(c: &Case, d: f64) {
    let m = &c.m;
    let count = m.summits.density * m.nominal_area;
    let k = m.material.hardness_factor();
    let load_scale = count * m.critical.load;
    let area_scale = count * m.critical.area;
    let adhesion_scale = count * 2.0 * std::f64::consts::PI * m.summits.radius * m.adhesion.energy;
    let eps_wc = m.adhesion.equilibrium_distance / m.critical.interference;
    let beyond = c.options.adhesion_beyond_fits;
    let form = c.options.static_friction_form;
    let tag = format!("{:?} psi={:.2} d*={d}", c.kind, m.plasticity_index);
    let (p_law, a_law, q_law): (Law, Law, Law) = match c.kind {
        Model::KogutEtsion => (
            Box::new(move |x| ke_load_ratio(x, k)),
            Box::new(ke_area_ratio),
            Box::new(move |x| ke_static_friction_ratio(x, form)),
        ),
        Model::ChangEtsionBogy => (
            Box::new(ceb_load_ratio),
            Box::new(ceb_area_ratio),
            Box::new(ceb_static_friction_ratio),
        ),
        Model::FullStick => {
            // The laws themselves are checked in friction_full_stick.rs; here only the
            // integration over the summit heights.
            let laws = std::sync::Arc::clone(&m.laws);
            let (area, friction) = (laws.clone(), laws.clone());
            (
                Box::new(move |x| laws.load_ratio(x)),
                Box::new(move |x| area.area_ratio(x)),
                Box::new(move |x| friction.friction_ratio(x)),
            )
        }
    };
    let lib = |r: Result<
        asperity_numerics::friction::IntegralValue,
        asperity_numerics::friction::FrictionError,
    >| { r.map(|v| v.value).unwrap_or_else(|e| panic!("{tag}: {e}")) };
    let p = lib(m.contact_load(d));
    let sp = slow_contact(c, d, &*p_law);
    assert_agrees(&format!("P {tag}"), p / load_scale, sp);
    let a = lib(m.contact_area(d));
    assert_agrees(
        &format!("A {tag}"),
        a / area_scale,
        slow_contact(c, d, &*a_law),
    );
    let q = lib(m.static_friction_force(d));
    assert_agrees(
        &format!("Q {tag}"),
        q / load_scale,
        slow_contact(c, d, &*q_law),
    );
    let fs = m.adhesion_force(d).unwrap_or_else(|e| panic!("{tag}: {e}"));
    let sc = slow_contact(c, d, &|x| contacting_adhesion_ratio(x, eps_wc, beyond));
    assert_agrees(
        &format!("Fs contacting {tag}"),
        fs.contacting.value / adhesion_scale,
        sc,
    );
    assert_agrees(
        &format!("Fs non-contacting {tag}"),
        fs.non_contacting.value / adhesion_scale,
        slow_non_contact(m, d),
    );
}

#[test]
fn kogut_etsion_integrals_match_simpson() {
    for &psi in &[0.5, 2.0, 8.0] {
        let m = model(psi, Model::KogutEtsion, Options::default());
        for &d in &[-1.0, 0.7, 2.5] {
            check_all(&m, d);
        }
    }
}

#[test]
fn kogut_etsion_options_match_simpson() {
    let options = Options {
        static_friction_form: StaticFrictionForm::Clipped,
        adhesion_beyond_fits: AdhesionBeyondFits::ExtendLastFit,
    };
    let m = model(30.0, Model::KogutEtsion, options);
    for &d in &[-0.5, 1.5] {
        check_all(&m, d);
    }
}

#[test]
fn ceb_integrals_match_simpson() {
    for &psi in &[0.8, 4.0] {
        let m = model(psi, Model::ChangEtsionBogy, Options::default());
        for &d in &[-0.5, 1.5, 3.5] {
            check_all(&m, d);
        }
    }
}

/// Full stick at a low, a moderate and a ground-steel plasticity index (ψ = 45: the elastic–
/// plastic band is a sliver of the Gaussian, the case the law breakpoints exist for).
#[test]
fn full_stick_integrals_match_simpson() {
    for &psi in &[0.5, 8.0, 45.0] {
        let m = model(psi, Model::FullStick, Options::default());
        for &d in &[-1.0, 0.7, 2.5] {
            check_all(&m, d);
        }
    }
}
