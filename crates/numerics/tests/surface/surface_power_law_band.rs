//! The search for the widest power-law band of a PSD: an exact power law, a power law between a
//! roll-off plateau and a noise floor, and a spectrum with no power law.

use asperity_numerics::surface::spectral::{
    find_power_law_band, BandCriteria, BandSearchError, PsdTable,
};

/// Rows at q = k·dq (k = 1 … n) with C(q) from `c` and the modes of a full annulus (2πk).
fn table(n: usize, dq: f64, c: impl Fn(f64) -> f64) -> PsdTable {
    let q: Vec<f64> = (1..=n).map(|k| k as f64 * dq).collect();
    PsdTable {
        c: q.iter().map(|&q| c(q)).collect(),
        modes: (1..=n)
            .map(|k| (2.0 * std::f64::consts::PI * k as f64) as usize)
            .collect(),
        q,
    }
}

#[test]
fn an_exact_power_law_is_one_band_over_the_whole_range_with_its_exponent() {
    let h = 0.7;
    let psd = table(512, 1e4, |q| q.powf(-2.0 - 2.0 * h));
    let fit = find_power_law_band(&psd, 1e4, 5.12e6, BandCriteria::default()).unwrap();
    assert!((fit.hurst - h).abs() < 1e-9, "H = {}", fit.hurst);
    assert_eq!((fit.q_min, fit.q_max), (1e4, 5.12e6));
    assert!(fit.r_squared > 1.0 - 1e-12 && fit.max_residual_decades < 1e-9);
}

/// A plateau below q_r = 10⁵ (the roll-off), C ∝ q^−3.6 (H = 0.8) up to q_n = 2·10⁶, then a
/// flat noise floor: the band found lies between the two knees. Its ends may reach a little
/// past them, where a bin's departure is within its sampling error (3 σ: at q ≈ 7·10⁴, 43
/// modes, σ = 0.14 decade), which biases H by up to 0.15 here (found: 0.69 from q = 7·10⁴).
#[test]
fn the_band_lies_between_the_roll_off_and_the_noise_floor() {
    let (q_r, q_n) = (1e5, 2e6);
    let psd = table(1000, 1e4, |q| {
        let power = |q: f64| q.powf(-3.6);
        power(q.max(q_r)).max(power(q_n))
    });
    let fit = find_power_law_band(&psd, 1e4, 1e7, BandCriteria::default()).unwrap();
    assert!((fit.hurst - 0.8).abs() < 0.15, "{fit:?}");
    assert!(fit.q_min >= 0.5 * q_r && fit.q_min <= 1.6 * q_r, "{fit:?}");
    assert!(fit.q_max <= 1.3 * q_n && fit.q_max >= 0.6 * q_n, "{fit:?}");
    let plateau_only = find_power_law_band(&psd, 1e4, q_r, BandCriteria::default());
    assert!(plateau_only.is_err(), "{plateau_only:?}");
}

/// A spectrum that bends everywhere (a Gaussian roll-off, C = exp(−(q/q₀)²)) has no band of
/// half a decade within the tolerances: the error names the best band and its fit.
#[test]
fn a_curved_spectrum_has_no_band_and_the_error_names_the_best_one() {
    let psd = table(400, 1e4, |q| (-(q / 1e6).powi(2)).exp() * 1e-30);
    match find_power_law_band(&psd, 1e5, 4e6, BandCriteria::default()) {
        Err(BandSearchError::NoPowerLaw { best, .. }) => {
            assert!(best.decades() >= 0.5, "{best:?}");
            assert!(
                best.max_residual_ratio > 1.0 || best.r_squared < 0.95,
                "{best:?}"
            );
            let text = find_power_law_band(&psd, 1e5, 4e6, BandCriteria::default())
                .unwrap_err()
                .to_string();
            assert!(
                text.contains("the best one") && text.contains("R²"),
                "{text}"
            );
        }
        other => panic!("expected no band, got {other:?}"),
    }
    let narrow = find_power_law_band(&psd, 1e5, 2e5, BandCriteria::default());
    assert!(
        matches!(narrow, Err(BandSearchError::TooNarrow { .. })),
        "{narrow:?}"
    );
}

/// A white-noise spectrum (H = −1) is no power-law band however straight.
#[test]
fn a_flat_noise_floor_is_not_a_band() {
    let psd = table(400, 1e4, |_| 1e-30);
    assert!(find_power_law_band(&psd, 1e4, 4e6, BandCriteria::default()).is_err());
}
