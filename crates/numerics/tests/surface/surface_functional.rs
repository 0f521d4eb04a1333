//! ISO 25178-2 functional and volume parameters against closed forms: two-level surfaces (exact)
//! and Gaussian heights (within sampling error).

use asperity_numerics::surface::{
    functional_parameters, FunctionalError, FunctionalOptions, FunctionalParameters, HeightMap,
    MaterialRatioCurve,
};
use ndarray::Array2;
use rand_chacha::rand_core::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn map_of(z: Array2<f64>) -> HeightMap {
    HeightMap::new(z, 1e-6, 1e-6).unwrap()
}

/// A 100 × 100 map whose first `high_rows` rows stand `h` above the others, shuffled in no way:
/// the material ratio curve depends on the heights only.
fn two_level(high_rows: usize, h: f64) -> HeightMap {
    map_of(Array2::from_shape_fn((100, 100), |(iy, _)| {
        if iy < high_rows {
            h
        } else {
            0.0
        }
    }))
}

fn close(actual: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{what}: {actual:e}, expected {expected:e} ± {tolerance:e}"
    );
}

/// 30 % plateaus of height h on a 70 % floor: the 40 % secant of least gradient lies on the floor
/// (gradient 0), so the core is the floor: Sk = 0, Smr1 = 0.3 (the plateaus above it), Smr2 = 1,
/// Spk = 2·(0.3 h)/0.3 = 2h, Svk = 0, Sxp = Smc(2.5 %) − Smc(50 %) = h, Vmp = 0 (flat above 10 %),
/// Vmc = Vm(80 %) = 0.3 h, Vvc = Vv(10 %) = 0.7 h, Vvv = 0.
#[test]
fn two_level_plateaus_have_the_closed_form_parameters() {
    let h = 2e-6;
    let p = functional_parameters(&two_level(30, h), FunctionalOptions::default()).unwrap();
    let eps = 1e-12;
    close(p.sk, 0.0, eps, "Sk");
    close(p.smr1, 0.3, eps, "Smr1");
    close(p.smr2, 1.0, eps, "Smr2");
    close(p.spk, 2.0 * h, eps, "Spk");
    close(p.svk, 0.0, eps, "Svk");
    close(p.sxp, h, eps, "Sxp");
    close(p.vmp, 0.0, eps, "Vmp");
    close(p.vmc, 0.3 * h, eps, "Vmc");
    close(p.vvc, 0.7 * h, eps, "Vvc");
    close(p.vvv, 0.0, eps, "Vvv");
    close(p.core_top, -0.3 * h, eps, "core top (floor from the mean)");
}

/// 30 % pits of depth h in a 70 % plateau, the mirror image: the core is the plateau, Smr1 = 0,
/// Spk = 0, Smr2 = 0.7, Svk = 2·(0.3 h)/0.3 = 2h, Sxp = 0, Vmp = 0, Vmc = Vm(80 %) = 0.7 h,
/// Vvc = Vv(10 %) = 0.3 h, Vvv = Vv(80 %) = 0 (Smc(80 %) is the pits' floor).
#[test]
fn two_level_pits_have_the_closed_form_parameters() {
    let h = 2e-6;
    let p = functional_parameters(&two_level(70, h), FunctionalOptions::default()).unwrap();
    let eps = 1e-12;
    close(p.sk, 0.0, eps, "Sk");
    close(p.smr1, 0.0, eps, "Smr1");
    close(p.smr2, 0.7, eps, "Smr2");
    close(p.spk, 0.0, eps, "Spk");
    close(p.svk, 2.0 * h, eps, "Svk");
    close(p.sxp, 0.0, eps, "Sxp");
    close(p.vmp, 0.0, eps, "Vmp");
    close(p.vmc, 0.7 * h, eps, "Vmc");
    close(p.vvc, 0.3 * h, eps, "Vvc");
    close(p.vvv, 0.0, eps, "Vvv");
}

/// Standard normal upper tail Q(t) = erfc(t/√2)/2 and density φ(t).
fn upper_tail(t: f64) -> f64 {
    0.5 * libm::erfc(t / std::f64::consts::SQRT_2)
}

fn density(t: f64) -> f64 {
    (-0.5 * t * t).exp() / (2.0 * std::f64::consts::PI).sqrt()
}

/// The height c with Q(c) = mr, by bisection (Q is decreasing).
fn height_at_ratio(mr: f64) -> f64 {
    let (mut lo, mut hi) = (-10.0, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if upper_tail(mid) > mr {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The parameters of heights N(0, 1), from the curve Smc(mr) = Q⁻¹(mr):
/// * the curve is point-symmetric about (50 %, 0) and its gradient smallest there, so the 40 %
///   secant of least gradient spans [30 %, 70 %]; the least-squares line over it passes through
///   (50 %, 0) with the gradient g = ∫(mr − ½) Q⁻¹(mr) dmr / ∫(mr − ½)² dmr over [0.3, 0.7]
///   (Simpson's rule, 400 intervals), so c_top = −g/2 = −c_bottom and Sk = −g;
/// * Smr1 = Q(c_top), Smr2 = 1 − Smr1; with E[(Z − t)⁺] = φ(t) − t Q(t),
///   Spk = Svk = 2 E[(Z − c_top)⁺]/Smr1;
/// * Sxp = Q⁻¹(0.025) − Q⁻¹(0.5) = Q⁻¹(0.025);
/// * Vm(p) = E[(Z − c)⁺], Vv(p) = E[(c − Z)⁺] = φ(c) + c (1 − Q(c)) at c = Q⁻¹(p).
fn gaussian_expectation() -> FunctionalParameters {
    let above = |t: f64| density(t) - t * upper_tail(t);
    let below = |t: f64| density(t) + t * (1.0 - upper_tail(t));
    let sk = -least_squares_gradient(0.3, 0.7);
    let top = sk / 2.0;
    let smr1 = upper_tail(top);
    let tail = 2.0 * above(top) / smr1;
    let (c10, c80) = (height_at_ratio(0.1), height_at_ratio(0.8));
    FunctionalParameters {
        sk,
        spk: tail,
        svk: tail,
        smr1,
        smr2: 1.0 - smr1,
        sxp: height_at_ratio(0.025),
        vmp: above(c10),
        vmc: above(c80) - above(c10),
        vvc: below(c10) - below(c80),
        vvv: below(c80),
        core_top: top,
        core_bottom: -top,
    }
}

/// The gradient of the least-squares line through Q⁻¹ over [a, b] (Simpson's rule).
fn least_squares_gradient(a: f64, b: f64) -> f64 {
    let intervals = 400;
    let h = (b - a) / intervals as f64;
    let centre = 0.5 * (a + b);
    let covariance: f64 = (0..=intervals)
        .map(|i| {
            let mr = a + i as f64 * h;
            let weight = match i {
                0 => 1.0,
                i if i == intervals => 1.0,
                i if i % 2 == 1 => 4.0,
                _ => 2.0,
            };
            weight * (mr - centre) * height_at_ratio(mr)
        })
        .sum::<f64>()
        * h
        / 3.0;
    covariance / ((b - a).powi(3) / 12.0)
}

/// 2¹⁸ independent N(0, 1) heights (Box–Muller on ChaCha8), scaled by `sigma`.
fn gaussian_heights(sigma: f64, seed: u64) -> HeightMap {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut uniform = move || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    let z = Array2::from_shape_simple_fn((512, 512), || {
        let (u, v): (f64, f64) = (1.0 - uniform(), uniform());
        sigma * (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    });
    map_of(z)
}

/// Gaussian heights of standard deviation σ give σ times [`gaussian_expectation`] within the
/// sampling error of N = 2¹⁸ independent heights. A quantile at ratio p has the standard error
/// √(p(1−p)/N)/φ(Q⁻¹(p)): 0.26 % of σ at 30 % and 70 % (Sk: ≈ 0.35 % relative; tolerance 1 %,
/// which the secant's Sk, 1.9 % higher than the least-squares line's, exceeds), 0.5 % of σ at
/// 2.5 % (Sxp: 0.27 %; tolerance 1.5 %); Smr1 ≈ 9.9 % has the standard error
/// √(Smr1(1−Smr1)/N) = 0.06 % absolute (0.6 % relative, which Spk and Svk inherit), and a volume
/// moves by the ratio times the quantile's error (Vmp ≈ 0.047 σ: 0.7 % relative). Tolerance 3 %
/// for those, 0.2 % absolute for Smr1, Smr2: four or more standard errors each. The parameters
/// are compared in units of the sample's own standard deviation, so that its 0.14 % error does
/// not add. A wrong window (e.g. 0–40 %), a missing factor 2 in Spk or a swapped p/q moves a
/// parameter far more. (Measured with seed 7: Sk 0.12 %, Spk 0.68 %, Vmp 0.87 %.)
#[test]
fn gaussian_heights_match_the_normal_distribution_within_sampling_error() {
    let sigma = 1.5e-6;
    let map = gaussian_heights(sigma, 7);
    let z = map.heights();
    let mean = z.sum() / z.len() as f64;
    let s = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / z.len() as f64).sqrt();
    let p = functional_parameters(&map, FunctionalOptions::default()).unwrap();
    let e = gaussian_expectation();
    let relative = |actual: f64, expected: f64, tolerance: f64, what: &str| {
        let err = (actual / s - expected).abs() / expected;
        assert!(
            err <= tolerance,
            "{what}: {:.5} σ, expected {expected:.5} σ ({err:.4} > {tolerance})",
            actual / s
        );
    };
    relative(p.sk, e.sk, 0.01, "Sk");
    relative(p.sxp, e.sxp, 0.015, "Sxp");
    for (actual, expected, what) in [
        (p.spk, e.spk, "Spk"),
        (p.svk, e.svk, "Svk"),
        (p.vmp, e.vmp, "Vmp"),
        (p.vmc, e.vmc, "Vmc"),
        (p.vvc, e.vvc, "Vvc"),
        (p.vvv, e.vvv, "Vvv"),
    ] {
        relative(actual, expected, 0.03, what);
    }
    close(p.smr1, e.smr1, 2e-3, "Smr1");
    close(p.smr2, e.smr2, 2e-3, "Smr2");
    // The expectation itself: the least-squares gradient lies between the curve's gradients at
    // the region's centre (√(2π) = 2.5066) and at its ends (1/φ(0.5244) = 2.8758), below the
    // secant's 2 Q⁻¹(0.3)/0.4 = 2.6220; Sxp = Q⁻¹(0.025) = 1.9600 from tables.
    assert!(e.sk > 2.5066 && e.sk < 2.6220, "Gaussian Sk/σ = {}", e.sk);
    close(e.sxp, 1.959_964, 1e-5, "Gaussian Sxp/σ");
    eprintln!("Gaussian expectation (σ = 1): {e:?}");
}

#[test]
fn missing_points_are_left_out_of_the_curve() {
    let mut z = Array2::from_shape_fn((10, 10), |(iy, _)| if iy < 3 { 1e-6 } else { 0.0 });
    let reference = functional_parameters(&map_of(z.clone()), FunctionalOptions::default());
    z[[0, 0]] = f64::NAN;
    z[[9, 9]] = f64::NAN;
    let curve = MaterialRatioCurve::of(&map_of(z)).unwrap();
    assert_eq!(curve.len(), 98);
    assert!(reference.is_ok());
}

#[test]
fn the_curve_falls_from_the_highest_to_the_lowest_point() {
    let curve = MaterialRatioCurve::from_heights([3.0, 1.0, 2.0, 0.0].into_iter()).unwrap();
    // Mean 1.5: heights 1.5, 0.5, −0.5, −1.5 at mid-ratios 12.5, 37.5, 62.5, 87.5 %.
    close(curve.height_at(0.0), 1.5, 1e-15, "Smc(0)");
    close(curve.height_at(0.25), 1.0, 1e-15, "Smc(25 %)");
    close(curve.height_at(1.0), -1.5, 1e-15, "Smc(100 %)");
    close(curve.ratio_at_or_above(0.5), 0.5, 1e-15, "Smr(0.5)");
    close(curve.ratio_above(0.5), 0.25, 1e-15, "share above 0.5");
    let (mr, c) = curve.sampled(5);
    assert_eq!(mr, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    assert!(c.windows(2).all(|w| w[0] >= w[1]), "{c:?}");
}

#[test]
fn bad_ratios_and_too_few_points_are_errors() {
    let map = two_level(30, 1e-6);
    let options = FunctionalOptions {
        volume_p: 0.9,
        ..FunctionalOptions::default()
    };
    assert!(matches!(
        functional_parameters(&map, options),
        Err(FunctionalError::InvalidRatio {
            name: "volume_p",
            ..
        })
    ));
    let nan = map_of(Array2::from_elem((2, 2), f64::NAN));
    assert_eq!(
        functional_parameters(&nan, FunctionalOptions::default()),
        Err(FunctionalError::TooFewPoints)
    );
}
