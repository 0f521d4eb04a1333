//! Synthetic twins: measure → fit against Sq → generate at new Sq, with extrapolation flags.

use asperity_numerics::surface::spectral::{
    AcfBoundary, HurstFitOptions, Window, ISO_ACF_THRESHOLD,
};
use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec,
};
use asperity_numerics::surface::twins::{
    fit_twin_model, measure_texture, synthetic_twin, MeasuredTexture, TextureOptions, TwinError,
    TwinGrid, TwinWarning,
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
        Err(TwinError::CalibrationFailed { .. })
    ));
}
