//! Spectrum twins (`surface::twins::spectrum_twin`): the twin's PSD is the measured one within a
//! periodogram's standard error, the twin of a self-affine surface agrees with the self-affine
//! route, the bytes are reproducible, and bad input fails with a clear error.

use std::f64::consts::PI;

use asperity_numerics::contact::{
    Boundary as ContactBoundary, CompositeGap, ContactMaterial, ContactProblem, ContactSolver,
    SolverOptions,
};
use asperity_numerics::surface::spectral::{periodogram, HurstFit, Periodogram, Window};
use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec,
};
use asperity_numerics::surface::twins::{
    fit_twin_model, measure_texture, spectrum_twin, synthetic_twin, Extrapolation,
    MeasuredSpectrum, SpectrumTwinError, SpectrumTwinSpec, SpectrumValue, TextureOptions, TwinGrid,
};
use asperity_numerics::surface::{
    crop, gaussian_high_pass, gradient_statistics, Boundary, DifferenceScheme, HeightMap,
};

/// A "measured" map: a 128² window (0.25 mm) of a 256² anisotropic self-affine surface (lay at
/// 30°, aspect 4), so it is not periodic and has a direction, like a ground surface, with an
/// L-filter of a fifth of its side, as a measured map is preprocessed (without it the window
/// holds half a correlation length along the lay, and the Hann estimate of those longest waves
/// alone misses the map's Sq² by 40 %).
fn measured_map() -> HeightMap {
    let surface = generate_synthetic_surface(&SyntheticSurfaceSpec {
        nx: 256,
        ny: 256,
        lx: 0.5e-3,
        ly: 0.5e-3,
        sq: 1e-6,
        hurst: 0.7,
        correlation_length: 40e-6,
        short_wavelength_cutoff: None,
        anisotropy: Some(Anisotropy {
            aspect_ratio: 4.0,
            angle: PI / 6.0,
        }),
        seed: 11,
    })
    .unwrap();
    gaussian_high_pass(&crop(&surface, 40, 70, 128, 128).unwrap(), 50e-6).unwrap()
}

fn spec(nx: usize, lx: f64, seed: u64) -> SpectrumTwinSpec {
    SpectrumTwinSpec {
        nx,
        ny: nx,
        lx,
        ly: lx,
        sq: None,
        short_wavelength_cutoff: None,
        extrapolation: Extrapolation::Zero,
        seed,
    }
}

/// A bin of wavevectors: `|q|` in a tenth of a decade, the angle of `q` (folded to
/// `(−90°, 90°]`) in one of four 45° sectors.
fn bin_of(qx: f64, qy: f64) -> (i64, i64) {
    let (qx, qy) = if qx < 0.0 || (qx == 0.0 && qy < 0.0) {
        (-qx, -qy)
    } else {
        (qx, qy)
    };
    let radial = (10.0 * qx.hypot(qy).log10()).floor() as i64;
    let sector = ((qy.atan2(qx) + PI / 2.0) / (PI / 4.0)).floor().min(3.0) as i64;
    (radial, sector)
}

/// Sum of `C` and number of modes per bin of a periodogram, over `q_low ≤ |q| ≤ q_high` (both
/// signs of `qx`).
fn binned(
    p: &Periodogram,
    q_low: f64,
    q_high: f64,
) -> std::collections::BTreeMap<(i64, i64), (f64, f64)> {
    let mut bins = std::collections::BTreeMap::new();
    for ((j, i), c) in p.c.indexed_iter() {
        let (qx, qy) = p.wavevector(j, i);
        let q = qx.hypot(qy);
        if q < q_low || q > q_high {
            continue;
        }
        let m = p.multiplicity(i);
        let entry = bins.entry(bin_of(qx, qy)).or_insert((0.0, 0.0));
        entry.0 += m * c;
        entry.1 += m;
    }
    bins
}

/// The twin's periodogram (no window: it is periodic) against the measured one (Hann window), in
/// bins of a tenth of a decade in `|q|` and four 45° sectors in direction, over the measured band
/// from twice its lowest wavenumber to its Nyquist wavenumber. In each bin holding `n ≥ 20`
/// measured modes the mean measured `C` has the standard error `C̄/√M` of a mean of `M = n/4.5`
/// independent exponentially distributed periodogram values (the modes `q` and `−q` are one
/// value; the Hann window joins 2.25 neighbours, `BandCriteria::modes_per_independent`); the
/// twin's mean must lie within 3 of them. Returns the largest deviation in standard errors.
fn psd_deviation(measured: &HeightMap, twin: &HeightMap) -> f64 {
    let pm = periodogram(measured, Window::Hann).unwrap();
    let pt = periodogram(twin, Window::None).unwrap();
    let (lx, ly) = measured.size();
    let q_low = 2.0 * 2.0 * PI / lx.min(ly);
    let q_high = (PI / measured.dx()).min(PI / measured.dy());
    let (bm, bt) = (binned(&pm, q_low, q_high), binned(&pt, q_low, q_high));
    let mut worst: f64 = 0.0;
    let mut bins = 0;
    for (key, (sum_m, n_m)) in &bm {
        if *n_m < 20.0 {
            continue;
        }
        let Some((sum_t, n_t)) = bt.get(key) else {
            panic!("bin {key:?} has no twin mode");
        };
        let (mean_m, mean_t) = (sum_m / n_m, sum_t / n_t);
        let standard_error = mean_m / (n_m / 4.5).sqrt();
        worst = worst.max((mean_t - mean_m).abs() / standard_error);
        bins += 1;
    }
    assert!(bins >= 20, "only {bins} bins compared");
    worst
}

#[test]
fn the_twins_psd_is_the_measured_psd_within_the_periodograms_standard_error() {
    let measured = MeasuredSpectrum::of_map(&measured_map()).unwrap();
    let map = measured_map();
    let (lx, _) = map.size();
    // The measurement's own grid, twice its size at its spacing, and the same size at half its
    // spacing (zero beyond the measured wavelengths).
    for (nx, size) in [(128, lx), (256, 2.0 * lx), (256, lx)] {
        let twin = spectrum_twin(std::slice::from_ref(&measured), &spec(nx, size, 5)).unwrap();
        let deviation = psd_deviation(&map, &twin.surface);
        assert!(
            deviation < 3.0,
            "{nx} points over {size}: {deviation} standard errors"
        );
        // The grid holds the measured spectrum's power (twice the size loses the few modes
        // next to q = 0), which the Hann estimate puts 7 % below the map's Sq².
        let share = (twin.spectrum_sq / twin.measured_spectrum_sq).powi(2);
        assert!(
            (share - 1.0).abs() < 0.02,
            "{nx}, {size}: grid power share {share}"
        );
        let estimate = (twin.measured_spectrum_sq / twin.measured_sq).powi(2);
        assert!((estimate - 0.933).abs() < 0.001, "{estimate}");
        assert!((twin.sq / map_sq(&map) - 1.0).abs() < 1e-12);
    }
}

fn map_sq(map: &HeightMap) -> f64 {
    let z = map.heights();
    let mean = z.sum() / z.len() as f64;
    (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / z.len() as f64).sqrt()
}

/// At half the measured spacing the wavevectors beyond the measured Nyquist rectangle hold
/// nothing (`zero`) or exactly the fitted power law (`power_law`), scaled with the rest.
#[test]
fn beyond_the_measured_sampling_the_twin_holds_zero_or_the_fitted_tail() {
    let map = measured_map();
    let (lx, _) = map.size();
    let q_nyquist = PI / map.dx();
    let plain = MeasuredSpectrum::of_map(&map).unwrap();
    // A tail q^−3.4 through the measured spectrum at 0.9 of the Nyquist wavenumber along x.
    let SpectrumValue::Measured(at_edge) = plain.at(0.9 * q_nyquist, 0.0) else {
        panic!("inside the measured band");
    };
    let slope = -3.4;
    let prefactor = at_edge / (0.9 * q_nyquist).powf(slope);
    let tail = HurstFit {
        hurst: -slope / 2.0 - 1.0,
        slope,
        prefactor,
        q_min: 0.2 * q_nyquist,
        q_max: q_nyquist,
        points: 10,
        r_squared: 1.0,
    };
    let measured = plain.with_tail(tail);
    for extrapolation in [Extrapolation::Zero, Extrapolation::PowerLaw] {
        let twin = spectrum_twin(
            std::slice::from_ref(&measured),
            &SpectrumTwinSpec {
                extrapolation,
                ..spec(256, lx, 5)
            },
        )
        .unwrap();
        let scale2 = (twin.sq / twin.spectrum_sq).powi(2);
        let p = periodogram(&twin.surface, Window::None).unwrap();
        let largest = p.c.iter().copied().fold(0.0, f64::max);
        let mut beyond = 0;
        for ((j, i), c) in p.c.indexed_iter() {
            let (qx, qy) = p.wavevector(j, i);
            let inside = |q: f64| q.abs() <= q_nyquist * (1.0 + 1e-9);
            if inside(qx) && inside(qy) {
                continue;
            }
            beyond += 1;
            let expected = match extrapolation {
                Extrapolation::Zero => 0.0,
                Extrapolation::PowerLaw => scale2 * prefactor * qx.hypot(qy).powf(slope),
            };
            // Round-off of the transforms: 1e-12 of the largest mode's power.
            assert!(
                (c - expected).abs() <= 1e-6 * expected + 1e-12 * largest,
                "{extrapolation:?} at ({qx}, {qy}): {c} vs {expected}"
            );
        }
        assert!(
            beyond > 10_000 && twin.modes.shorter > 20_000,
            "{beyond}, {:?}",
            twin.modes
        );
        let share = twin.modes.extrapolated_power_share;
        match extrapolation {
            Extrapolation::Zero => assert_eq!(share, 0.0),
            Extrapolation::PowerLaw => assert!(share > 0.0 && share < 1.0, "{share}"),
        }
    }
}

/// Sdq with central differences over the periodic twin.
fn sdq(map: &HeightMap) -> f64 {
    gradient_statistics(map, DifferenceScheme::Central, Boundary::Periodic)
        .unwrap()
        .sdq
}

/// A/A₀ of `map` pressed against a rigid flat to 20 MPa (steel, flow pressure 2 GPa).
fn area_fraction(map: &HeightMap) -> f64 {
    let gap = CompositeGap::against_flat(map).unwrap();
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 1e15, 0.3, 2e9).unwrap();
    let problem = ContactProblem::new(gap, material, ContactBoundary::Periodic);
    let mut solver = ContactSolver::new(problem, SolverOptions::default()).unwrap();
    solver.solve(20e6).unwrap().area_fraction
}

fn mean_sd(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

/// The twin of a synthetic self-affine surface through the spectrum route agrees with its
/// self-affine twin (texture measured on it, fitted, generated) in Sq, Sdq and the contact's
/// A/A₀: the means over six seeds differ by less than twice the realisations' spread
/// `√(sd₁² + sd₂²)` (Sq is exact in both).
#[test]
fn the_spectrum_route_agrees_with_the_self_affine_route_on_a_self_affine_surface() {
    let (n, side) = (128, 0.25e-3);
    let surface = generate_synthetic_surface(&SyntheticSurfaceSpec {
        nx: n,
        ny: n,
        lx: side,
        ly: side,
        sq: 1e-6,
        hurst: 0.8,
        correlation_length: 40e-6,
        short_wavelength_cutoff: None,
        anisotropy: None,
        seed: 21,
    })
    .unwrap();
    let sq = map_sq(&surface);
    let spectrum = MeasuredSpectrum::of_map(&surface).unwrap();
    let model =
        fit_twin_model(&[measure_texture(&surface, &TextureOptions::default()).unwrap()]).unwrap();
    let seeds = 1..=6u64;
    let spectrum_twins: Vec<HeightMap> = seeds
        .clone()
        .map(|seed| {
            spectrum_twin(std::slice::from_ref(&spectrum), &spec(n, side, seed))
                .unwrap()
                .surface
        })
        .collect();
    let self_affine_twins: Vec<HeightMap> = seeds
        .map(|seed| {
            let grid = TwinGrid {
                nx: n,
                ny: n,
                lx: side,
                ly: side,
                short_wavelength_cutoff: None,
                seed,
            };
            synthetic_twin(&model, sq, &grid, 0.2).unwrap().surface
        })
        .collect();
    for twins in [&spectrum_twins, &self_affine_twins] {
        for t in twins {
            assert!((map_sq(t) / sq - 1.0).abs() < 1e-12);
        }
    }
    for (what, statistic) in [
        ("Sdq", sdq as fn(&HeightMap) -> f64),
        ("A/A0", area_fraction as fn(&HeightMap) -> f64),
    ] {
        let a: Vec<f64> = spectrum_twins.iter().map(statistic).collect();
        let b: Vec<f64> = self_affine_twins.iter().map(statistic).collect();
        let ((mean_a, sd_a), (mean_b, sd_b)) = (mean_sd(&a), mean_sd(&b));
        let spread = (sd_a * sd_a + sd_b * sd_b).sqrt();
        println!("{what}: spectrum {mean_a:.4e} ± {sd_a:.1e}, self-affine {mean_b:.4e} ± {sd_b:.1e}, original {:.4e}", statistic(&surface));
        assert!(
            (mean_a - mean_b).abs() < 2.0 * spread,
            "{what}: spectrum route {mean_a} ± {sd_a}, self-affine route {mean_b} ± {sd_b}"
        );
    }
}

fn bits(map: &HeightMap) -> Vec<u64> {
    map.heights().iter().map(|v| v.to_bits()).collect()
}

/// One seed gives the same bytes on any thread count; another seed other heights; twins of one
/// seed on two grids of the same size share the modes both hold (the coarse twin samples the fine
/// one when the spectrum is cut below the coarse Nyquist wavelength).
#[test]
fn a_seed_gives_the_same_bytes_on_any_thread_count_and_grid() {
    let measured = [MeasuredSpectrum::of_map(&measured_map()).unwrap()];
    let lx = measured_map().size().0;
    let twin = |threads: usize, nx: usize, seed: u64, cutoff: Option<f64>| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let s = SpectrumTwinSpec {
                short_wavelength_cutoff: cutoff,
                ..spec(nx, lx, seed)
            };
            spectrum_twin(&measured, &s).unwrap().surface
        })
    };
    let one = twin(1, 128, 7, None);
    assert_eq!(bits(&one), bits(&twin(3, 128, 7, None)));
    assert_eq!(bits(&one), bits(&twin(1, 128, 7, None)));
    assert_ne!(bits(&one), bits(&twin(1, 128, 8, None)));
    // λs = 6 coarse pixels: every mode lies inside the 64² grid's Nyquist band.
    let cutoff = Some(6.0 * lx / 64.0);
    let (fine, coarse) = (twin(2, 128, 7, cutoff), twin(2, 64, 7, cutoff));
    for ((j, i), z) in coarse.heights().indexed_iter() {
        let f = fine.heights()[[2 * j, 2 * i]];
        assert!((z - f).abs() < 1e-9 * 1e-6, "({j}, {i}): {z} vs {f}");
    }
}

#[test]
fn bad_input_is_an_error_naming_the_fix() {
    let map = measured_map();
    let (lx, _) = map.size();
    let message = |e: SpectrumTwinError| e.to_string();
    // No map.
    assert!(matches!(
        spectrum_twin(&[], &spec(64, lx, 1)),
        Err(SpectrumTwinError::NoMaps)
    ));
    // Missing points.
    let mut holes = map.heights().clone();
    holes[[3, 4]] = f64::NAN;
    let e = message(
        MeasuredSpectrum::of_map(&HeightMap::new(holes, map.dx(), map.dy()).unwrap()).unwrap_err(),
    );
    assert!(e.contains("missing"), "{e}");
    // The same heights with a lateral unit off by 10³ (mm read as µm): no common band.
    let spectrum = MeasuredSpectrum::of_map(&map).unwrap();
    let far = HeightMap::new(map.heights().clone(), map.dx() * 1e3, map.dy() * 1e3).unwrap();
    let e = message(
        spectrum_twin(
            &[spectrum.clone(), MeasuredSpectrum::of_map(&far).unwrap()],
            &spec(64, lx, 1),
        )
        .unwrap_err(),
    );
    assert!(
        e.contains("share no band") && e.contains("lateral units"),
        "{e}"
    );
    // The same map with heights in nm read as m (10⁹): the rms over the common band differs.
    let tall = HeightMap::new(map.heights() * 1e3, map.dx(), map.dy()).unwrap();
    let e = message(
        spectrum_twin(
            &[spectrum.clone(), MeasuredSpectrum::of_map(&tall).unwrap()],
            &spec(64, lx, 1),
        )
        .unwrap_err(),
    );
    assert!(
        e.contains("factor of 1000") && e.contains("height units"),
        "{e}"
    );
    // A twin far from the measured band: 16 points over 1 m.
    let e = message(spectrum_twin(std::slice::from_ref(&spectrum), &spec(16, 1.0, 1)).unwrap_err());
    assert!(
        e.contains("holds no wavevector the measurement resolved"),
        "{e}"
    );
    // An Sq beyond the twin's side, and a power-law tail without a fit.
    let too_rough = SpectrumTwinSpec {
        sq: Some(1.0),
        ..spec(64, lx, 1)
    };
    let e = message(spectrum_twin(std::slice::from_ref(&spectrum), &too_rough).unwrap_err());
    assert!(e.contains("`sq`") && e.contains("min(lx, ly)"), "{e}");
    let tail = SpectrumTwinSpec {
        extrapolation: Extrapolation::PowerLaw,
        ..spec(64, lx, 1)
    };
    let e = message(spectrum_twin(std::slice::from_ref(&spectrum), &tail).unwrap_err());
    assert!(e.contains("no fitted tail"), "{e}");
}
