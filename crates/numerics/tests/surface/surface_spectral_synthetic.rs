//! Synthetic surfaces: validation, exact Sq, determinism, model autocorrelation.

use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, model_autocorrelation, Anisotropy, SyntheticError,
    SyntheticSurfaceSpec,
};

fn spec(n: usize) -> SyntheticSurfaceSpec {
    SyntheticSurfaceSpec {
        nx: n,
        ny: n,
        lx: 1e-3,
        ly: 1e-3,
        sq: 1.19e-6,
        hurst: 0.8,
        correlation_length: 50e-6,
        short_wavelength_cutoff: None,
        anisotropy: None,
        seed: 7,
    }
}

fn rms_and_mean(z: &ndarray::Array2<f64>) -> (f64, f64) {
    let n = z.len() as f64;
    let mean = z.sum() / n;
    let rms = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    (rms, mean)
}

#[test]
fn sq_is_exact_and_mean_is_zero() {
    for (nx, ny) in [(128, 128), (96, 70), (33, 17)] {
        let mut s = spec(nx);
        s.ny = ny;
        s.ly = 0.7e-3;
        let map = generate_synthetic_surface(&s).unwrap();
        assert_eq!((map.nx(), map.ny()), (nx, ny));
        assert_eq!(map.dx(), s.lx / nx as f64);
        let (rms, mean) = rms_and_mean(map.heights());
        // Normalisation is exact up to summation round-off over ≤ 2e4 points.
        assert!((rms / s.sq - 1.0).abs() < 1e-12, "Sq {rms}");
        assert!(mean.abs() < 1e-12 * s.sq, "mean {mean}");
    }
}

#[test]
fn same_seed_same_surface_other_seed_other_surface() {
    let a = generate_synthetic_surface(&spec(64)).unwrap();
    let b = generate_synthetic_surface(&spec(64)).unwrap();
    assert!(a
        .heights()
        .iter()
        .zip(b.heights())
        .all(|(x, y)| x.to_bits() == y.to_bits()));
    let mut other = spec(64);
    other.seed = 8;
    let c = generate_synthetic_surface(&other).unwrap();
    let differing = a
        .heights()
        .iter()
        .zip(c.heights())
        .filter(|(x, y)| x != y)
        .count();
    assert!(differing > 64 * 64 - 10);
}

#[test]
fn result_does_not_depend_on_thread_count() {
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let a = single.install(|| generate_synthetic_surface(&spec(64)).unwrap());
    let b = generate_synthetic_surface(&spec(64)).unwrap();
    assert!(a
        .heights()
        .iter()
        .zip(b.heights())
        .all(|(x, y)| x.to_bits() == y.to_bits()));
}

/// Pins a few heights so a change of the numerics (which must bump the node's implementation
/// version) is deliberate. Tolerance: relative 1e-9 allows only floating-point round-off of
/// other platforms' libm/FFT kernels, far below any algorithmic change.
#[test]
fn pinned_values() {
    let map = generate_synthetic_surface(&spec(32)).unwrap();
    let z = map.heights();
    let pinned = [((0, 0), PIN_00), ((5, 17), PIN_5_17), ((31, 3), PIN_31_3)];
    for ((iy, ix), expected) in pinned {
        let got = z[[iy, ix]];
        assert!(
            (got - expected).abs() <= 1e-9 * expected.abs(),
            "({iy},{ix}): {got:e}"
        );
    }
}

const PIN_00: f64 = 5.84432985923907e-7;
const PIN_5_17: f64 = -2.145595611861731e-6;
const PIN_31_3: f64 = -1.960352128763401e-6;

/// The same seed gives the same Fourier modes on every grid of one size: with a short-wavelength
/// cutoff that a 64² grid resolves (λs > 2·dx₆₄), the 64² surface samples the 256² surface at
/// every fourth point, and an anisotropic, rotated one too. Tolerance: relative 1e-12 of Sq
/// allows FFT round-off over 256² points, far below any change of the realisation.
#[test]
fn coarse_and_fine_grids_sample_one_surface() {
    for anisotropy in [
        None,
        Some(Anisotropy {
            aspect_ratio: 4.0,
            angle: 17.0f64.to_radians(),
        }),
    ] {
        let fine_spec = SyntheticSurfaceSpec {
            short_wavelength_cutoff: Some(2.5 * 1e-3 / 64.0),
            anisotropy,
            ..spec(256)
        };
        let coarse_spec = SyntheticSurfaceSpec {
            nx: 64,
            ny: 64,
            ..fine_spec.clone()
        };
        let fine = generate_synthetic_surface(&fine_spec).unwrap();
        let coarse = generate_synthetic_surface(&coarse_spec).unwrap();
        let worst = coarse
            .heights()
            .indexed_iter()
            .map(|((iy, ix), z)| (z - fine.heights()[[4 * iy, 4 * ix]]).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-12 * fine_spec.sq, "worst difference {worst:e} m");
    }
}

type Mutation = Box<dyn Fn(&mut SyntheticSurfaceSpec)>;

#[test]
fn invalid_parameters_are_named() {
    let cases: Vec<(&str, Mutation)> = vec![
        ("nx", Box::new(|s| s.nx = 1)),
        ("ny", Box::new(|s| s.ny = 0)),
        ("lx", Box::new(|s| s.lx = -1.0)),
        ("ly", Box::new(|s| s.ly = f64::NAN)),
        ("sq", Box::new(|s| s.sq = 0.0)),
        ("sq", Box::new(|s| s.sq = 1e-300)),
        ("sq", Box::new(|s| s.sq = 1e302)),
        ("sq", Box::new(|s| s.sq = 2e-3)),
        ("lx", Box::new(|s| s.lx = 1e307)),
        ("ly", Box::new(|s| s.ly = 1e-300)),
        (
            "correlation_length",
            Box::new(|s| s.correlation_length = 1e300),
        ),
        ("hurst", Box::new(|s| s.hurst = 0.0)),
        ("hurst", Box::new(|s| s.hurst = 1.2)),
        (
            "correlation_length",
            Box::new(|s| s.correlation_length = f64::INFINITY),
        ),
        (
            "short_wavelength_cutoff",
            Box::new(|s| s.short_wavelength_cutoff = Some(2e-3)),
        ),
        (
            "short_wavelength_cutoff",
            Box::new(|s| s.short_wavelength_cutoff = Some(1e-9)),
        ),
        (
            "anisotropy.aspect_ratio",
            Box::new(|s| {
                s.anisotropy = Some(Anisotropy {
                    aspect_ratio: 0.0,
                    angle: 0.0,
                })
            }),
        ),
        (
            "anisotropy.angle",
            Box::new(|s| {
                s.anisotropy = Some(Anisotropy {
                    aspect_ratio: 2.0,
                    angle: f64::NAN,
                })
            }),
        ),
    ];
    for (name, mutate) in cases {
        let mut s = spec(16);
        mutate(&mut s);
        match generate_synthetic_surface(&s) {
            Err(SyntheticError::InvalidParameter { name: got, .. }) => assert_eq!(got, name),
            other => panic!("{name}: expected InvalidParameter, got {other:?}"),
        }
    }
    let mut huge = spec(16);
    huge.nx = 1 << 20;
    huge.ny = 1 << 20;
    assert!(matches!(
        generate_synthetic_surface(&huge),
        Err(SyntheticError::TooLarge { .. })
    ));
    let message = {
        let mut s = spec(16);
        s.hurst = 1.5;
        generate_synthetic_surface(&s).unwrap_err().to_string()
    };
    assert!(message.contains("hurst") && message.contains("1.5") && message.contains("0 < H ≤ 1"));
}

/// Lag (in points, linearly interpolated) at which an ACF along one axis first drops to 0.2.
fn decay_points(values: impl Iterator<Item = f64>) -> f64 {
    let values: Vec<f64> = values.collect();
    let k = values.iter().take_while(|r| **r > 0.2).count();
    let (before, after) = (values[k - 1], values[k]);
    (k - 1) as f64 + (before - 0.2) / (before - after)
}

#[test]
fn model_acf_follows_anisotropy() {
    let mut s = spec(512);
    s.correlation_length = 200e-6;
    s.anisotropy = Some(Anisotropy {
        aspect_ratio: 4.0,
        angle: 0.0,
    });
    let acf = model_autocorrelation(&s).unwrap();
    assert_eq!(acf[[0, 0]], 1.0);
    let along_x = decay_points(acf.row(0).iter().copied());
    let along_y = decay_points(acf.column(0).iter().copied());
    let ratio = along_x / along_y;
    // The model is an affine stretch of an isotropic spectrum, so the decay lengths scale with
    // the roll-off lengths; the ratio differs from 4 only by the grid's finite q-resolution
    // (along_y spans ~10 points; linear interpolation of the crossing), allow 5 %.
    assert!((ratio / 4.0 - 1.0).abs() < 0.05, "x {along_x} y {along_y}");
    s.anisotropy = Some(Anisotropy {
        aspect_ratio: 4.0,
        angle: 90.0f64.to_radians(),
    });
    let rotated = model_autocorrelation(&s).unwrap();
    // A 90° rotation maps the x axis onto y exactly (same grid); round-off only.
    assert!((decay_points(rotated.column(0).iter().copied()) - along_x).abs() < 1e-9);
    assert!((decay_points(rotated.row(0).iter().copied()) - along_y).abs() < 1e-9);
}
