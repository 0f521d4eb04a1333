//! Amplitude and hybrid statistics, form removal, Gaussian filter, filling and resampling on analytic
//! surfaces, plus reference values of two real text-matrix files.

use crate::common;
use asperity_numerics::surface::{
    amplitude_statistics, crop, decimate, fill_missing, gaussian_band_pass, gaussian_high_pass,
    gaussian_low_pass, gradient_statistics, remove_plane, remove_polynomial_form,
    resample_bilinear, Boundary, DifferenceScheme, FillError, FillOptions, HeightMap,
    ResampleError, GAUSSIAN_ALPHA,
};
use ndarray::Array2;
use std::f64::consts::PI;

/// `z = A sin(2π x/λ) sin(2π y/λ)` on a periodic grid of `periods` wavelengths of `per_period` points.
fn product_of_sines(amplitude: f64, per_period: usize, periods: usize, dx: f64) -> HeightMap {
    let n = per_period * periods;
    let k = 2.0 * PI / (per_period as f64 * dx);
    let z = Array2::from_shape_fn((n, n), |(iy, ix)| {
        amplitude * (k * ix as f64 * dx).sin() * (k * iy as f64 * dx).sin()
    });
    HeightMap::new(z, dx, dx).unwrap()
}

fn assert_rel(actual: f64, expected: f64, rtol: f64, what: &str) {
    let err = ((actual - expected) / expected).abs();
    assert!(
        err <= rtol,
        "{what}: {actual:e} vs {expected:e}, relative error {err:e} > {rtol:e}"
    );
}

// Continuous values for z = A sin u sin v over whole periods (u, v independent and uniform):
//   mean(z²) = A² ⟨sin²⟩² = A²/4                   → Sq = A/2
//   mean|z| = A ⟨|sin|⟩² = A (2/π)²                  → Sa = 4A/π²
//   mean(z³) = A³ ⟨sin³⟩² = 0                        → Ssk = 0
//   mean(z⁴) = A⁴ ⟨sin⁴⟩² = A⁴ (3/8)² = 9A⁴/64        → Sku = (9/64)/(1/16) = 2.25
//   ∂z/∂x = A k cos u sin v: mean((∂z/∂x)² + (∂z/∂y)²) = 2 · A²k²/4 → Sdq = A k/√2.
// On N points per period the discrete means of sin², sin³, sin⁴ equal the continuous ones exactly
// (N > 4: the harmonics of sin⁴ are below N), while ⟨|sin|⟩_N = (2/N) cot(π/N) (sum of a geometric
// series over the positive half period), which tends to 2/π with relative error ≈ (π/N)²/3.
#[test]
fn product_of_sines_amplitude_parameters() {
    let (a, n, dx) = (2e-7, 32, 1e-6);
    let map = product_of_sines(a, n, 2, dx);
    let s = amplitude_statistics(&map, Boundary::Periodic).unwrap();
    assert_eq!((s.valid_count, s.missing_count), (64 * 64, 0));
    // Round-off of a few thousand terms: 1e-12 relative is ~1e4 ulp of margin.
    assert!(s.mean.abs() < 1e-12 * a);
    assert_rel(s.sq, a / 2.0, 1e-12, "Sq");
    let mean_abs_sin = 2.0 / n as f64 / (PI / n as f64).tan();
    assert_rel(s.sa, a * mean_abs_sin * mean_abs_sin, 1e-12, "Sa discrete");
    // Continuous 4A/π² within the derived discretisation error 2·(π/N)²/3 = 0.64 %, allow 0.7 %.
    assert_rel(s.sa, 4.0 * a / (PI * PI), 0.007, "Sa continuous");
    assert!(s.ssk.unwrap().abs() < 1e-12);
    assert_rel(s.sku.unwrap(), 2.25, 1e-12, "Sku");
    // The grid contains the points sin u = sin v = ±1, so Sp = Sv = A exactly.
    assert_rel(s.sp, a, 1e-12, "Sp");
    assert_rel(s.sv, a, 1e-12, "Sv");
    assert_rel(s.sz, 2.0 * a, 1e-12, "Sz");
}

// Central differences of sin(kx) give cos(kx)·sin(k dx)/dx, forward differences give a cosine shifted by
// dx/2 times sin(k dx/2)/(dx/2); on a periodic grid the discrete mean square is then exactly
// (A k/√2 · factor)², with factor sin(θ)/θ (θ = k dx) or sin(θ/2)/(θ/2).
#[test]
fn product_of_sines_sdq_matches_closed_form() {
    let (a, n, dx) = (2e-7, 32, 1e-6);
    let map = product_of_sines(a, n, 2, dx);
    let k = 2.0 * PI / (n as f64 * dx);
    let theta = k * dx;
    let exact = a * k / 2f64.sqrt();
    let central = gradient_statistics(&map, DifferenceScheme::Central, Boundary::Periodic).unwrap();
    assert_eq!(central.point_count, 64 * 64);
    assert_rel(
        central.sdq,
        exact * theta.sin() / theta,
        1e-12,
        "Sdq central, discrete",
    );
    // Second-order discretisation error θ²/6 = 0.64 % for 32 points per wavelength; allow 0.7 %.
    assert_rel(central.sdq, exact, 0.007, "Sdq central, continuous");
    let forward = gradient_statistics(&map, DifferenceScheme::Forward, Boundary::Periodic).unwrap();
    let half = theta / 2.0;
    assert_rel(
        forward.sdq,
        exact * half.sin() / half,
        1e-12,
        "Sdq forward, discrete",
    );
    // Interior-only (open boundary) central Sdq differs by edge sampling only: the 62×62 interior
    // still averages over almost two full periods; 2 % bounds the missing-row effect (2/64 of rows).
    let open = gradient_statistics(&map, DifferenceScheme::Central, Boundary::Open).unwrap();
    assert_eq!(open.point_count, 62 * 62);
    assert_rel(open.sdq, exact, 0.02, "Sdq central, open");
    // Sdr ≈ Sdq²/2 for small slopes (next term −⟨g⁴⟩/8 is below 1 % here: slopes < 0.06).
    assert_rel(
        central.sdr_percent / 100.0,
        central.sdq.powi(2) / 2.0,
        0.01,
        "Sdr",
    );
}

// A tilted plane z = c + a x + b y has the exact gradient (a, b) under both schemes, anisotropic pixels
// included: Sdq = sqrt(a² + b²), Sdr = sqrt(1 + a² + b²) − 1.
#[test]
fn plane_gradient_is_exact_with_anisotropic_pixels() {
    let (a, b, dx, dy) = (0.3, -0.7, 1e-6, 3e-6);
    let z = Array2::from_shape_fn((9, 13), |(iy, ix)| {
        2e-6 + a * ix as f64 * dx + b * iy as f64 * dy
    });
    let map = HeightMap::new(z, dx, dy).unwrap();
    for scheme in [DifferenceScheme::Central, DifferenceScheme::Forward] {
        let g = gradient_statistics(&map, scheme, Boundary::Open).unwrap();
        // Differences of values ~1e-5 m divided by 1e-6 m: round-off ~1e-10 relative.
        assert_rel(g.sdq, (a * a + b * b).sqrt(), 1e-9, "plane Sdq");
        assert_rel(
            g.sdr_percent,
            100.0 * ((1.0 + a * a + b * b).sqrt() - 1.0),
            1e-9,
            "plane Sdr",
        );
    }
    let forward = gradient_statistics(&map, DifferenceScheme::Forward, Boundary::Open).unwrap();
    assert_eq!(forward.point_count, 12 * 8);
}

// Missing points are excluded, never counted as zeros: the statistics equal those of the list of valid
// heights, computed here directly, and differ from the zero-filled surface.
#[test]
fn missing_points_are_excluded() {
    let mut z = Array2::from_shape_fn((20, 30), |(iy, ix)| {
        1e-6 * (1.0 + 0.3 * (ix as f64 * 0.7).sin() + 0.2 * ((iy * ix) as f64 * 0.11).cos())
    });
    let holes = [(3, 4), (3, 5), (10, 10), (19, 29), (0, 0)];
    for &(iy, ix) in &holes {
        z[[iy, ix]] = f64::NAN;
    }
    let map = HeightMap::new(z.clone(), 1e-6, 1e-6).unwrap();
    let s = amplitude_statistics(&map, Boundary::Open).unwrap();
    let valid: Vec<f64> = z.iter().copied().filter(|h| !h.is_nan()).collect();
    let n = valid.len() as f64;
    let mean = valid.iter().sum::<f64>() / n;
    let sq = (valid.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / n).sqrt();
    let sa = valid.iter().map(|h| (h - mean).abs()).sum::<f64>() / n;
    assert_eq!((s.valid_count, s.missing_count), (600 - 5, 5));
    assert_rel(s.mean, mean, 1e-12, "mean");
    assert_rel(s.sq, sq, 1e-12, "Sq");
    assert_rel(s.sa, sa, 1e-12, "Sa");
    let zero_filled = HeightMap::new(z.mapv(|h| if h.is_nan() { 0.0 } else { h }), 1e-6, 1e-6);
    let wrong = amplitude_statistics(&zero_filled.unwrap(), Boundary::Open).unwrap();
    assert!((wrong.sq - s.sq).abs() > 0.01 * s.sq);
    // Central gradients need the 4 axial neighbours valid: 28×18 interior minus the points next to
    // (3,4), (3,5), (10,10) (the border holes only touch border points). (3,4),(3,5) remove themselves
    // and 6 neighbours: (2,4),(2,5),(4,4),(4,5),(3,3),(3,6); (10,10) removes itself and 4 neighbours.
    assert_eq!(s.gradient_point_count, 28 * 18 - 8 - 5);
    let all_missing = HeightMap::new(Array2::from_elem((3, 3), f64::NAN), 1.0, 1.0).unwrap();
    assert!(amplitude_statistics(&all_missing, Boundary::Open).is_err());
}

#[test]
fn flat_surface_has_undefined_skewness_not_nan() {
    let map = HeightMap::new(Array2::from_elem((4, 5), 3e-6), 1e-6, 1e-6).unwrap();
    let s = amplitude_statistics(&map, Boundary::Open).unwrap();
    assert_eq!((s.sq, s.ssk, s.sku, s.sdq), (0.0, None, None, Some(0.0)));
}

// A plane with holes is removed to round-off; a quadratic needs degree 2, which removes it to round-off.
#[test]
fn form_removal_is_exact_for_plane_and_quadratic() {
    let (dx, dy) = (0.5e-6, 2e-6);
    let quadratic =
        |x: f64, y: f64| 1e-6 + 0.02 * x - 0.01 * y + 3e3 * x * x - 1e3 * x * y + 5e2 * y * y;
    let plane = |x: f64, y: f64| -4e-6 + 0.02 * x - 0.01 * y;
    for (surface, degree) in [(&plane as &dyn Fn(f64, f64) -> f64, 1), (&quadratic, 2)] {
        let mut z =
            Array2::from_shape_fn((40, 50), |(iy, ix)| surface(ix as f64 * dx, iy as f64 * dy));
        z[[5, 7]] = f64::NAN;
        z[[30, 40]] = f64::NAN;
        let map = HeightMap::new(z, dx, dy).unwrap();
        let scale = amplitude_statistics(&map, Boundary::Open).unwrap().sz;
        let removed = remove_polynomial_form(&map, degree).unwrap();
        // Round-off of normal equations with a Legendre basis (condition number ~10): 1e-12 of the
        // form's height range.
        assert!(
            removed.residual_rms < 1e-12 * scale,
            "degree {degree}: {}",
            removed.residual_rms
        );
        assert!(removed.surface.heights()[[5, 7]].is_nan());
        assert_eq!(removed.surface.missing_count(), 2);
        if degree == 2 {
            let plane_only = remove_plane(&map).unwrap();
            assert!(plane_only.residual_rms > 1e-3 * scale);
            assert_eq!(removed.terms.len(), 6);
        }
    }
}

/// Amplitude of `sin(2π i/period)` in samples `lo..hi` (a whole number of periods) by projection.
fn sine_amplitude(values: &[f64], period: usize, lo: usize, hi: usize) -> f64 {
    let sum: f64 = (lo..hi)
        .map(|i| values[i] * (2.0 * PI * i as f64 / period as f64).sin())
        .sum();
    2.0 * sum / (hi - lo) as f64
}

// ISO 16610-61 Gaussian transmission exp(−π (α λc/λ)²): 50 % at λ = λc, → 100 % for λ ≫ λc and → 0 for
// λ ≪ λc. The sampled kernel has σ ≈ 7.5 samples, so aliasing (exp(−2π²σ²)) and truncation at ±λc
// (weight 6.5e-7) are far below the 1e-3 tolerance used; the brief's criterion is 0.5 ± 0.01.
#[test]
fn gaussian_filter_transmission() {
    let dx = 1e-6;
    let cutoff = 40e-6;
    for (period, n_periods) in [(40usize, 12usize), (8, 60), (200, 3), (400, 4)] {
        let n = period * n_periods;
        let z = Array2::from_shape_fn((6, n), |(_, ix)| {
            1e-7 * (2.0 * PI * ix as f64 / period as f64).sin()
        });
        let map = HeightMap::new(z, dx, 2e-6).unwrap();
        let expected = (-PI * (GAUSSIAN_ALPHA * cutoff / (period as f64 * dx)).powi(2)).exp();
        let low = gaussian_low_pass(&map, cutoff).unwrap();
        let high = gaussian_high_pass(&map, cutoff).unwrap();
        // Interior: whole periods at least one cutoff (40 samples) away from both ends, where the
        // renormalised edge window does not reach.
        let margin = period * 40usize.div_ceil(period);
        let (lo, hi) = (margin, n - margin);
        let row_low: Vec<f64> = low.heights().row(3).to_vec();
        let row_high: Vec<f64> = high.heights().row(3).to_vec();
        let t = sine_amplitude(&row_low, period, lo, hi) / 1e-7;
        assert!(
            (t - expected).abs() < 1e-3,
            "λ = {period} µm: T = {t}, expected {expected}"
        );
        let t_high = sine_amplitude(&row_high, period, lo, hi) / 1e-7;
        assert!((t_high - (1.0 - expected)).abs() < 1e-3);
        if period == 40 {
            assert!((expected - 0.5).abs() < 1e-12);
        }
    }
}

// The y pass uses dy: a sinusoid along y with λ = λc is halved too.
#[test]
fn gaussian_filter_along_y_uses_dy() {
    let (dy, period, n) = (0.5e-6, 80usize, 80 * 8);
    let z = Array2::from_shape_fn((n, 5), |(iy, _)| {
        (2.0 * PI * iy as f64 / period as f64).sin()
    });
    let map = HeightMap::new(z, 3e-6, dy).unwrap();
    let low = gaussian_low_pass(&map, period as f64 * dy).unwrap();
    let col: Vec<f64> = low.heights().column(2).to_vec();
    let t = sine_amplitude(&col, period, period, n - period);
    assert!((t - 0.5).abs() < 1e-3, "T = {t}");
}

// S-L band pass = S-filter then L-filter: interior transmission T_s(λ)·(1 − T_c(λ)).
#[test]
fn gaussian_band_pass_is_product_of_transmissions() {
    let (dx, period, n) = (1e-6, 20usize, 20 * 30);
    let z = Array2::from_shape_fn((4, n), |(_, ix)| {
        (2.0 * PI * ix as f64 / period as f64).sin()
    });
    let map = HeightMap::new(z, dx, dx).unwrap();
    let (short, long) = (8e-6, 50e-6);
    let band = gaussian_band_pass(&map, short, long).unwrap();
    let t = |c: f64| (-PI * (GAUSSIAN_ALPHA * c / (period as f64 * dx)).powi(2)).exp();
    let expected = t(short) * (1.0 - t(long));
    let row: Vec<f64> = band.heights().row(1).to_vec();
    let got = sine_amplitude(&row, period, 60, n - 60);
    assert!((got - expected).abs() < 1e-3, "{got} vs {expected}");
}

// Normalised convolution: a constant with holes stays exactly constant at valid points (no pull towards
// zero at holes or edges) and the holes stay missing.
#[test]
fn gaussian_filter_ignores_missing_points() {
    let mut z = Array2::from_elem((30, 30), 2e-6);
    z[[10, 10]] = f64::NAN;
    z[[0, 3]] = f64::NAN;
    let map = HeightMap::new(z, 1e-6, 1e-6).unwrap();
    let low = gaussian_low_pass(&map, 8e-6).unwrap();
    assert_eq!(low.missing_count(), 2);
    assert!(low
        .heights()
        .iter()
        .filter(|h| !h.is_nan())
        .all(|h| (h - 2e-6).abs() < 1e-20));
}

// A plane is harmonic, so interior holes are filled with the plane (to the solver tolerance).
#[test]
fn harmonic_fill_reproduces_a_plane_in_interior_holes() {
    let (dx, dy) = (1e-6, 2e-6);
    let plane = |ix: usize, iy: usize| 1e-6 + 0.01 * ix as f64 * dx - 0.02 * iy as f64 * dy;
    let full = Array2::from_shape_fn((30, 40), |(iy, ix)| plane(ix, iy));
    let mut z = full.clone();
    for iy in 5..15 {
        for ix in 10..25 {
            z[[iy, ix]] = f64::NAN;
        }
    }
    z[[20, 30]] = f64::NAN;
    let map = HeightMap::new(z, dx, dy).unwrap();
    let filled = fill_missing(&map, FillOptions::default()).unwrap();
    assert_eq!(filled.filled_count, 151);
    assert_eq!(filled.surface.missing_count(), 0);
    assert!(filled.iterations > 0 && filled.relative_residual <= 1e-10);
    let max_err = (filled.surface.heights() - &full)
        .iter()
        .fold(0.0f64, |m, e| m.max(e.abs()));
    // Relative residual 1e-10 of b (heights ~1e-6 m, condition number ~ hole size² ~ 100): < 1e-13 m.
    assert!(max_err < 1e-13, "max error {max_err:e}");
    let strict = FillOptions {
        tolerance: 1e-12,
        max_iterations: 1,
        ..FillOptions::default()
    };
    assert!(matches!(
        fill_missing(&map, strict),
        Err(FillError::NotConverged { iterations: 1, .. })
    ));
    let none_missing = fill_missing(
        &HeightMap::new(full, dx, dy).unwrap(),
        FillOptions::default(),
    );
    assert_eq!(none_missing.unwrap().iterations, 0);
}

#[test]
fn crop_decimate_and_bilinear_resampling() {
    let (dx, dy) = (1e-6, 2e-6);
    let bilinear = |x: f64, y: f64| 1e-6 + 0.01 * x + 0.03 * y + 1e3 * x * y;
    let z = Array2::from_shape_fn((11, 21), |(iy, ix)| {
        bilinear(ix as f64 * dx, iy as f64 * dy)
    });
    let map = HeightMap::new(z, dx, dy).unwrap();

    let window = crop(&map, 3, 2, 5, 4).unwrap();
    assert_eq!((window.nx(), window.ny()), (5, 4));
    assert_eq!(window.heights()[[0, 0]], map.heights()[[2, 3]]);
    assert!(matches!(
        crop(&map, 18, 0, 5, 2),
        Err(ResampleError::WindowOutOfBounds { .. })
    ));

    assert!(matches!(
        resample_bilinear(&map, usize::MAX / 2, 4),
        Err(ResampleError::TooLarge { .. })
    ));
    assert!(decimate(&map, 0, 1).is_err() && decimate(&map, 30, 1).is_err());

    let coarse = decimate(&map, 5, 2).unwrap();
    assert_eq!((coarse.nx(), coarse.ny()), (5, 6));
    assert!((coarse.dx() - 5e-6).abs() < 1e-20 && (coarse.dy() - 4e-6).abs() < 1e-20);
    assert_eq!(coarse.heights()[[1, 1]], map.heights()[[2, 5]]);

    // Bilinear interpolation reproduces a bilinear function exactly (to round-off).
    let fine = resample_bilinear(&map, 41, 16).unwrap();
    assert!((fine.dx() - 0.5e-6).abs() < 1e-18 && (fine.dy() - 20e-6 / 15.0).abs() < 1e-18);
    for ((iy, ix), &h) in fine.heights().indexed_iter() {
        let expected = bilinear(ix as f64 * fine.dx(), iy as f64 * fine.dy());
        assert!((h - expected).abs() < 1e-18, "({ix}, {iy})");
    }
    // A missing point makes the new points that depend on it missing, and only those.
    let mut holed = map.heights().clone();
    holed[[4, 4]] = f64::NAN;
    let holed = resample_bilinear(&HeightMap::new(holed, dx, dy).unwrap(), 41, 11).unwrap();
    // New x = 8 falls exactly on old ix 4 (row iy 4); x = 7, 9 use it with weight 1/2.
    let missing: Vec<(usize, usize)> = holed
        .heights()
        .indexed_iter()
        .filter(|(_, h)| h.is_nan())
        .map(|(p, _)| p)
        .collect();
    assert_eq!(missing, vec![(4, 7), (4, 8), (4, 9)]);
}
/// Minimal parser for the two whitespace-separated text matrices used below (header lines are read by
/// the caller); the real reader lives in `surface::io`.
fn numbers_after_header(text: &str, header_lines: usize) -> (Vec<f64>, usize) {
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(header_lines)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split_whitespace()
                .map(|v| v.parse::<f64>().unwrap())
                .collect()
        })
        .collect();
    let nx = rows[0].len();
    assert!(rows.iter().all(|r| r.len() == nx));
    (rows.concat(), nx)
}

// SOURCES.md, ASSERTED by SurfaceTopography (rtol 1e-7): Sq and forward-difference rms_gradient.
#[test]
fn text_matrix_reference_values() {
    let Some(dir) = common::data_dir() else {
        return;
    };
    // matrix-3: Gwyddion-style, 4 comment lines, heights in m, width 10 µm over 256 columns.
    let text = std::fs::read_to_string(dir.join("txt/matrix-3.txt")).unwrap();
    let (values, nx) = numbers_after_header(&text, 4);
    let dx = 10e-6 / nx as f64;
    let map = HeightMap::new(
        Array2::from_shape_vec((values.len() / nx, nx), values).unwrap(),
        dx,
        dx,
    )
    .unwrap();
    let s = amplitude_statistics(&map, Boundary::Open).unwrap();
    assert_rel(s.sq, 3.522_291_875_019_874e-8, 1e-7, "matrix-3 Sq");
    assert_rel(
        s.rms_gradient_forward.unwrap(),
        0.19235602282848963,
        1e-7,
        "matrix-3 rms_gradient",
    );

    // matrix-4: 4 header lines, w = 75 columns, pixel 3.69862e-7 m, heights × 2.91818e-8 → m.
    let text = std::fs::read_to_string(dir.join("txt/matrix-4.txt")).unwrap();
    let (values, nx) = numbers_after_header(&text, 4);
    assert_eq!(nx, 75);
    let heights = Array2::from_shape_vec((values.len() / nx, nx), values).unwrap() * 2.91818e-8;
    let map = HeightMap::new(heights, 3.69862e-7, 3.69862e-7).unwrap();
    let s = amplitude_statistics(&map, Boundary::Open).unwrap();
    assert_eq!(map.ny(), 305);
    assert_rel(s.sq, 1.1745891510991089e-07, 1e-7, "matrix-4 Sq");
    assert_rel(
        s.rms_gradient_forward.unwrap(),
        0.06776316911544318,
        1e-7,
        "matrix-4 rms_gradient",
    );
}
