//! Synthetic twins: measure → fit against Sq → generate at new Sq, with extrapolation flags.

use asperity_numerics::surface::spectral::{
    AcfBoundary, Autocorrelation, HurstFitOptions, Window, ISO_ACF_THRESHOLD,
};
use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec,
};
use asperity_numerics::surface::twins::{
    correlation_length_along, fit_twin_model, measure_texture, synthetic_twin, Axis,
    CorrelationMethod, MeasuredTexture, TextureOptions, TwinError, TwinGrid, TwinWarning,
    EXTRAPOLATION_MAX_ACF,
};

/// "Measured" ground-like surfaces: lay along x (aspect 2), roll-off λ ∝ Sq^0.5, H = 0.8.
/// On 512² over 1 mm the roll-off wavelengths (λy ≥ 25 pixels) lie above the default Hurst band
/// (4 to 16 pixels), as they must on real measurements for the fit to be meaningful.
fn ground_surface(sq: f64, seed: u64) -> SyntheticSurfaceSpec {
    SyntheticSurfaceSpec {
        nx: 512,
        ny: 512,
        lx: 1e-3,
        ly: 1e-3,
        sq,
        hurst: 0.8,
        correlation_length: 160e-6 * (sq / 1e-6).sqrt(),
        short_wavelength_cutoff: None,
        anisotropy: Some(Anisotropy {
            aspect_ratio: 2.0,
            angle: 0.0,
        }),
        seed,
    }
}

/// The synthetic "measurements" are periodic: no window, periodic ACF.
fn options() -> TextureOptions {
    TextureOptions {
        threshold: ISO_ACF_THRESHOLD,
        boundary: AcfBoundary::Periodic,
        hurst: HurstFitOptions {
            window: Window::None,
            ..Default::default()
        },
    }
}

fn grid(seed: u64) -> TwinGrid {
    TwinGrid {
        nx: 512,
        ny: 512,
        lx: 1e-3,
        ly: 1e-3,
        short_wavelength_cutoff: None,
        seed,
    }
}

fn measured_set() -> Vec<MeasuredTexture> {
    [(0.38e-6, 1), (1.19e-6, 2), (1.50e-6, 3)]
        .into_iter()
        .map(|(sq, seed)| {
            let map = generate_synthetic_surface(&ground_surface(sq, seed)).unwrap();
            measure_texture(&map, &options()).unwrap()
        })
        .collect()
}

#[test]
fn twins_reproduce_the_fitted_statistics() {
    let measured = measured_set();
    let model = fit_twin_model(&measured).unwrap();
    assert!(model.warnings.is_empty());
    // Measured Sq equals the generated one up to round-off.
    assert!((model.sq_range.0 / 0.38e-6 - 1.0).abs() < 1e-12);
    assert!((model.sq_range.1 / 1.50e-6 - 1.0).abs() < 1e-12);
    // Truth: ξ ∝ λ ∝ Sq^0.5. Three surfaces with ~5 % scatter each (see the statistics tests)
    // over ln(1.5/0.38) = 1.37 give an exponent uncertainty of ~0.07; allow 0.15.
    assert!(
        (model.correlation_length_x.exponent - 0.5).abs() < 0.15,
        "{model:?}"
    );
    assert!(
        (model.correlation_length_y.exponent - 0.5).abs() < 0.15,
        "{model:?}"
    );
    // H is constant (0.8); ±0.05 per fit as in the Hurst test.
    assert!((model.hurst.at_reference - 0.8).abs() < 0.05, "{model:?}");

    let twin = synthetic_twin(&model, 1.0e-6, &grid(99), ISO_ACF_THRESHOLD).unwrap();
    assert!(twin.prediction.warnings.is_empty());
    assert!(twin.residual < 1e-3 && twin.iterations <= 50);
    // Sq exact up to round-off.
    let twin_stats = measure_texture(&twin.surface, &options()).unwrap();
    assert!((twin_stats.sq / 1.0e-6 - 1.0).abs() < 1e-12);
    // The twin's measured correlation lengths scatter around the prediction like any
    // realisation around its model ACF (≤ 10 % in the statistics tests); ξx here is ~L/20, a
    // little longer than there, so allow 15 %.
    let p = &twin.prediction;
    assert!((twin_stats.correlation_length_x / p.correlation_length_x - 1.0).abs() < 0.15);
    assert!((twin_stats.correlation_length_y / p.correlation_length_y - 1.0).abs() < 0.15);
    assert!(
        (twin_stats.hurst - p.hurst).abs() < 0.07,
        "{twin_stats:?} vs {p:?}"
    );
}

#[test]
fn extrapolation_and_degenerate_fits_are_flagged() {
    let measured = measured_set();
    let model = fit_twin_model(&measured).unwrap();
    let high = model.predict(3.0e-6).unwrap();
    let (min, max) = model.sq_range;
    assert_eq!(
        high.warnings,
        vec![TwinWarning::Extrapolated {
            sq: 3.0e-6,
            min,
            max
        }]
    );
    assert!(model.predict(0.8e-6).unwrap().warnings.is_empty());

    let single = fit_twin_model(&measured[..1]).unwrap();
    assert_eq!(
        single.warnings,
        vec![TwinWarning::ConstantFit { surfaces: 1 }]
    );
    let p = single.predict(2.0e-6).unwrap();
    // Constant fit: the single surface's values, up to the round-off of exp(ln ξ).
    assert!((p.correlation_length_x / measured[0].correlation_length_x - 1.0).abs() < 1e-12);
    assert!((p.hurst - measured[0].hurst).abs() < 1e-12);

    let mut steep = model.clone();
    steep.hurst.slope = 1.0;
    let clamped = steep.predict(100e-6).unwrap();
    assert_eq!(clamped.hurst, 1.0);
    assert!(clamped
        .warnings
        .iter()
        .any(|w| matches!(w, TwinWarning::HurstClamped { used, .. } if *used == 1.0)));
}

#[test]
fn invalid_twin_inputs_are_errors() {
    assert_eq!(fit_twin_model(&[]), Err(TwinError::NoSurfaces));
    let mut bad = measured_set();
    bad[1].hurst = f64::NAN;
    assert!(matches!(
        fit_twin_model(&bad),
        Err(TwinError::InvalidMeasurement {
            index: 1,
            what: "hurst",
            ..
        })
    ));
    let model = fit_twin_model(&measured_set()).unwrap();
    assert_eq!(model.predict(-1.0), Err(TwinError::InvalidSq(-1.0)));
    // A correlation length of 10 mm cannot be realised on a 1 mm periodic grid.
    let mut huge = model.clone();
    huge.correlation_length_x.at_reference = 10e-3;
    assert!(matches!(
        synthetic_twin(&huge, 1e-6, &grid(1), ISO_ACF_THRESHOLD),
        Err(TwinError::GridTooSmall { .. })
    ));
}

/// An ACF on the periodic lag grid of an `n × n` map with spacing `d`: `f(τx, τy)`.
fn periodic_acf(n: usize, d: f64, f: impl Fn(f64, f64) -> f64) -> Autocorrelation {
    let lag = |i: usize| {
        let k = if i <= n / 2 {
            i as f64
        } else {
            i as f64 - n as f64
        };
        k * d
    };
    let values = ndarray::Array2::from_shape_fn((n, n), |(iy, ix)| f(lag(ix), lag(iy)));
    Autocorrelation::from_periodic_lags(&values, d, d)
}

#[test]
fn an_acf_that_crosses_the_threshold_is_read_at_the_crossing() {
    // exp(−τ/10 µm) crosses 0.2 at 10 µm · ln 5 = 16.09 µm, well inside half of a 128 µm map.
    let acf = periodic_acf(128, 1e-6, |x, y| (-(x * x + y * y).sqrt() / 10e-6).exp());
    let (length, method) = correlation_length_along(&acf, Axis::X, 0.2).unwrap();
    assert_eq!(method, CorrelationMethod::AcfCrossing);
    // Linear interpolation between lags of 1 µm on a convex curve: within 1 % of 16.09 µm.
    assert!(
        (length / (10e-6 * 5f64.ln()) - 1.0).abs() < 0.01,
        "{length}"
    );
}

#[test]
fn a_long_correlation_is_extrapolated_by_the_stretched_exponential() {
    // ACF = exp(−(τ/τc)^1.6) with τc = 60 µm along x on a 128 µm map (half map 64 µm): it falls
    // to exp(−(64/60)^1.6) = 0.35 only, and would cross 0.2 at τc (ln 5)^(1/1.6) = 80.6 µm.
    let (tau_c, alpha) = (60e-6, 1.6);
    let acf = periodic_acf(128, 1e-6, |x, y| {
        (-((x / tau_c).powi(2) + (y / 5e-6).powi(2))
            .sqrt()
            .powf(alpha))
        .exp()
    });
    let (length, method) = correlation_length_along(&acf, Axis::X, 0.2).unwrap();
    let CorrelationMethod::StretchedExponential {
        acf_reached,
        exponent,
    } = method
    else {
        panic!("expected the fit, got {method:?}");
    };
    // Exact data: the fit recovers the law to round-off.
    assert!((exponent - alpha).abs() < 1e-9, "{exponent}");
    assert!((acf_reached - (-(64e-6 / tau_c).powf(alpha)).exp()).abs() < 1e-12);
    let expected = tau_c * 5f64.ln().powf(1.0 / alpha);
    assert!(
        (length / expected - 1.0).abs() < 1e-9,
        "{length} vs {expected}"
    );
    // Along y it crosses within the map.
    let (_, method_y) = correlation_length_along(&acf, Axis::Y, 0.2).unwrap();
    assert_eq!(method_y, CorrelationMethod::AcfCrossing);
}

#[test]
fn an_acf_that_hardly_decays_is_an_error_naming_how_far_it_fell() {
    // Waviness left in the map: the ACF stays above 0.5 over half the map.
    let acf = periodic_acf(64, 1e-6, |x, _| (-(x / 200e-6).abs()).exp());
    let err = correlation_length_along(&acf, Axis::X, 0.2).unwrap_err();
    let TwinError::NoDecay {
        axis,
        acf_reached,
        half_map,
        ..
    } = err
    else {
        panic!("{err:?}");
    };
    assert_eq!(axis, "x");
    assert!((half_map - 32e-6).abs() < 1e-12);
    assert!((acf_reached - (-32.0f64 / 200.0).exp()).abs() < 1e-12);
    assert!(acf_reached > EXTRAPOLATION_MAX_ACF);
    assert!(err.to_string().contains("L-filter"), "{err}");
}

#[test]
fn fits_report_their_quality_and_warnings_read_as_sentences() {
    let measured = measured_set();
    let model = fit_twin_model(&measured).unwrap();
    for fit in [
        model.correlation_length_x.fit,
        model.correlation_length_y.fit,
        model.hurst.fit,
    ] {
        // Three surfaces: R² is defined; the synthetic set follows its laws closely.
        let r2 = fit.r_squared.expect("three surfaces give an R²");
        assert!(r2 <= 1.0 && fit.rms_residual >= 0.0, "{fit:?}");
    }
    assert!(model.correlation_length_x.fit.r_squared.unwrap() > 0.9);
    let two = fit_twin_model(&measured[..2]).unwrap();
    assert_eq!(two.hurst.fit.r_squared, None);
    assert!(
        two.hurst.fit.rms_residual < 1e-12,
        "a line through two points"
    );

    let high = model.predict(3.0e-6).unwrap();
    let sentence = high.warnings[0].to_string();
    assert!(
        sentence.starts_with("Sq = 3.00 µm lies outside the measured range"),
        "{sentence}"
    );
    let clamped = TwinWarning::HurstClamped {
        predicted: 2.467875956730113,
        used: 1.0,
    };
    assert_eq!(
        clamped.to_string(),
        "the fitted Hurst exponent at this Sq is 2.468, outside [0.05, 1]; 1 is used"
    );
}

#[test]
fn a_twin_too_large_for_its_grid_names_the_size_that_holds_it() {
    let model = fit_twin_model(&measured_set()).unwrap();
    let mut huge = model.clone();
    huge.correlation_length_x.at_reference = 400e-6;
    huge.correlation_length_y.at_reference = 100e-6;
    let small = TwinGrid {
        nx: 64,
        ny: 64,
        lx: 0.5e-3,
        ly: 0.5e-3,
        short_wavelength_cutoff: None,
        seed: 1,
    };
    let err = synthetic_twin(&huge, model.sq_reference, &small, ISO_ACF_THRESHOLD).unwrap_err();
    let TwinError::GridTooSmall {
        suggested_size,
        suggested_grid,
        ..
    } = err
    else {
        panic!("{err:?}");
    };
    // 8 correlation lengths per side at the spacing given (7.8 µm, finer than ξ/4).
    assert!((suggested_size[0] - 8.0 * 400e-6).abs() < 1e-12);
    assert_eq!(suggested_size[1], 0.8e-3);
    assert_eq!(suggested_grid, [410, 103]);
    // The suggested grid works.
    let fitting = TwinGrid {
        nx: suggested_grid[0],
        ny: suggested_grid[1],
        lx: suggested_size[0],
        ly: suggested_size[1],
        ..small
    };
    let twin = synthetic_twin(&huge, model.sq_reference, &fitting, ISO_ACF_THRESHOLD).unwrap();
    assert!(twin.residual < 1e-3);

    // Correlation lengths finer than the spacing: the suggestion refines the grid to ξ/4.
    let mut fine = model.clone();
    fine.correlation_length_x.at_reference = 4e-6;
    fine.correlation_length_y.at_reference = 4e-6;
    let err = synthetic_twin(&fine, model.sq_reference, &small, ISO_ACF_THRESHOLD).unwrap_err();
    let TwinError::GridTooSmall {
        suggested_size,
        suggested_grid,
        ..
    } = err
    else {
        panic!("{err:?}");
    };
    assert_eq!(suggested_size, [0.5e-3, 0.5e-3]);
    assert_eq!(suggested_grid, [500, 500]);
}
