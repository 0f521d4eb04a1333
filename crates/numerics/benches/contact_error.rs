//! Run time against error of the contact solver: one table, grid size × tolerance.
//!
//! `cargo bench -p asperity-numerics --bench contact_error` (Hertz up to 512², rough up to 1024²);
//! `CONTACT_BENCH_LARGE=1 cargo bench -p asperity-numerics --bench contact_error` adds Hertz 1024² and rough 2048²
//! and 4096²; `CONTACT_BENCH_GRIDS=256,512,1024,2048` picks the rough grids explicitly (the
//! finest one is the reference); `CONTACT_BENCH_MIXED=0` (or `1`) solves with
//! `SolverOptions::mixed_precision` off (on). Release profile; medians of several solves on
//! small grids.
//!
//! * `hertz`: paraboloid on a non-periodic grid with `a = n/4 · dx`; relative errors of the
//!   contact radius `a` (from the contact area), the approach `δ = a²/R` and the mean contact
//!   pressure (`2p₀/3`) against the closed form. (The peak pressure is checked in
//!   tests/contact_validation.rs.)
//! * `rough`: self-affine periodic surface (H = 0.8, wavelengths 1 mm … 10 µm, S_q = 1 µm) on a
//!   1 mm square against a flat, steel–steel (E* = 115 GPa), p_lim = 4 GPa, 20 MPa nominal,
//!   solved from a cold start; errors of A/A₀ and θ against a solve of the same surface on the
//!   finest grid with tolerance 1e-9 (`ref`, in double precision throughout).
//! * `warm`: the same 20 MPa step warm-started from the converged 15 MPa step (a load curve).
//!
//! Columns: CG iterations, CG iterations of the multilevel start on the coarser grids (`coarse`,
//! cold steps only; their time is in `t_solve`), CG iterations of the moving points alone
//! (`free`, products with the restricted operator; their time is in `t_solve`), FFT pairs per
//! iteration (half the 2-D FFTs of
//! the solve / iterations), time per solve, time per iteration (`t_solve / iters`, so it includes
//! the coarse levels), `t_fft` = one forward + inverse real FFT pair on the grid
//! the solver transforms (2n × 2n for the non-periodic DC-FFT; the median of three pairs timed
//! right after each solve of the row, so both see the same machine load),
//! `ratio = t_iter / t_fft`.

use std::f64::consts::PI;
use std::time::Instant;

use asperity_numerics::contact::{
    Boundary, CompositeGap, ContactMaterial, ContactProblem, ContactSolver, LoadStep, RealFft2d,
    SolverOptions,
};
use asperity_numerics::fft2::fast_even_length;
use asperity_numerics::surface::HeightMap;
use ndarray::Array2;
use rustfft::num_complex::Complex;
use rustfft::FftPlanner;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One forward + inverse FFT pair on the solver's grid, timed right after every solve so that
/// `t_fft` and `t_solve` of a row see the same machine load (this machine is shared).
struct FftClock {
    fft: RealFft2d,
    data: Vec<f64>,
    samples: Vec<f64>,
}

impl FftClock {
    fn new(n: usize) -> Self {
        Self {
            fft: RealFft2d::new(n, n),
            data: (0..n * n).map(|i| (i % 17) as f64).collect(),
            samples: Vec::new(),
        }
    }

    /// Times three FFT pairs, on a rayon worker thread as the solver runs.
    fn tick(&mut self) {
        rayon::scope(|_| {
            for _ in 0..3 {
                let t = Instant::now();
                self.fft.round_trip(&mut self.data).unwrap();
                self.samples.push(t.elapsed().as_secs_f64());
            }
        });
    }

    /// Median of the pairs timed since the last call.
    fn take_median(&mut self) -> f64 {
        median(std::mem::take(&mut self.samples))
    }
}

/// Solves `reps` times from a cold start, each followed by [`FftClock::tick`]; returns the last
/// step and the median time.
fn timed_solve(
    solver: &mut ContactSolver,
    pressure: f64,
    reps: usize,
    clock: &mut FftClock,
) -> (LoadStep, f64) {
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..reps {
        solver.reset();
        let t = Instant::now();
        let step = solver.solve(pressure).unwrap();
        times.push(t.elapsed().as_secs_f64());
        last = Some(step);
        clock.tick();
    }
    (last.unwrap(), median(times))
}

fn reps(n: usize) -> usize {
    match n {
        0..=512 => 5,
        513..=1024 => 3,
        _ => 1,
    }
}

/// Deterministic pseudo-random number in [0, 1) from a wave vector (SplitMix64 hash).
fn hash01(kx: i64, ky: i64) -> f64 {
    let mut z =
        (kx as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (ky as u64).wrapping_add(0x1234_5678);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// The same continuous self-affine surface sampled on an `n × n` grid over `side` metres:
/// Fourier modes `|k| ≤ 100` cycles per side, amplitude `∝ max(|k|, 4)^(−1.8)`, random phases;
/// scaled to S_q = 1 µm.
fn self_affine(n: usize, side: f64) -> HeightMap {
    const KMAX: i64 = 100;
    let mut spectrum = vec![Complex::new(0.0, 0.0); n * n];
    let mut power = 0.0;
    for ky in -KMAX..=KMAX {
        for kx in -KMAX..=KMAX {
            let k = ((kx * kx + ky * ky) as f64).sqrt();
            if k == 0.0 || k > KMAX as f64 {
                continue;
            }
            // Hermitian symmetry: the mode (−kx, −ky) is the conjugate of (kx, ky).
            let (cx, cy, sign) = if (ky, kx) > (0, 0) {
                (kx, ky, 1.0)
            } else {
                (-kx, -ky, -1.0)
            };
            let amp = k.max(4.0).powf(-1.8);
            let phase = 2.0 * PI * hash01(cx, cy) * sign;
            let ix = kx.rem_euclid(n as i64) as usize;
            let iy = ky.rem_euclid(n as i64) as usize;
            spectrum[iy * n + ix] = Complex::from_polar(amp, phase);
            power += amp * amp;
        }
    }
    let mut planner = FftPlanner::<f64>::new();
    let fft = planner.plan_fft_inverse(n);
    for row in spectrum.chunks_mut(n) {
        fft.process(row);
    }
    let mut column = vec![Complex::new(0.0, 0.0); n];
    for ix in 0..n {
        for iy in 0..n {
            column[iy] = spectrum[iy * n + ix];
        }
        fft.process(&mut column);
        for iy in 0..n {
            spectrum[iy * n + ix] = column[iy];
        }
    }
    let scale = 1e-6 / power.sqrt();
    let z = Array2::from_shape_fn((n, n), |(iy, ix)| spectrum[iy * n + ix].re * scale);
    HeightMap::new(z, side / n as f64, side / n as f64).unwrap()
}

/// The solver's options at `tolerance`; `CONTACT_BENCH_MIXED=1` or `0` sets
/// `SolverOptions::mixed_precision` (default: the solver's default).
fn options(tolerance: f64) -> SolverOptions {
    let defaults = SolverOptions::default();
    let mixed_precision = match std::env::var("CONTACT_BENCH_MIXED").as_deref() {
        Ok("1") => true,
        Ok("0") => false,
        _ => defaults.mixed_precision,
    };
    SolverOptions {
        tolerance,
        mixed_precision,
        ..defaults
    }
}

fn print_row(case: &str, n: usize, tol: f64, step: &LoadStep, t: f64, fft: f64, errors: &str) {
    let iterations = step.iterations.max(1) as f64;
    let per_iter = t / iterations;
    println!(
        "| {case:<5} | {n:>5}² | {tol:>7.0e} | {:>5} | {:>6} | {:>4} | {:>5.2} | {:>10.1} | {:>9.2} | {:>8.2} | {:>5.2} | {:?} | {errors} |",
        step.iterations,
        step.coarse_iterations,
        step.free_set_iterations,
        step.fft_transforms as f64 / 2.0 / iterations,
        t * 1e3,
        per_iter * 1e3,
        fft * 1e3,
        per_iter / fft,
        step.path,
    );
}

/// Rough grids: `CONTACT_BENCH_GRIDS` if set, else 256²–1024² (to 4096² with `large`).
fn rough_grids(large: bool) -> Vec<usize> {
    match std::env::var("CONTACT_BENCH_GRIDS") {
        Ok(list) => list
            .split(',')
            .filter_map(|v| v.trim().parse().ok())
            .collect(),
        Err(_) if large => vec![256, 512, 1024, 2048, 4096],
        Err(_) => vec![256, 512, 1024],
    }
}

/// `CONTACT_BENCH_SWEEP=N`: the rough surface on an `N × N` grid loaded cold from 0.5 % to 95 %
/// of `p_lim` (tolerance 1e-5); one line per load with the path and iterations.
fn load_sweep(n: usize) {
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 4e9).unwrap();
    let gap = CompositeGap::against_flat(&self_affine(n, 1e-3)).unwrap();
    let problem = ContactProblem::new(gap, material, Boundary::Periodic);
    let mut solver = ContactSolver::new(problem, options(1e-5)).unwrap();
    for ratio in [0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 0.95] {
        solver.reset();
        let start = Instant::now();
        match solver.solve(ratio * 4e9) {
            Ok(step) => println!(
                "p/p_lim {ratio:>5}: {:?}, {} iterations, {} FFT pairs, {:.0} ms, A/A₀ = {:.4}, plastic share {:.3}",
                step.path,
                step.iterations,
                step.fft_transforms / 2,
                start.elapsed().as_secs_f64() * 1e3,
                step.area_fraction,
                step.plastic_area_share
            ),
            Err(e) => println!("p/p_lim {ratio:>5}: {e}"),
        }
    }
}

fn main() {
    if let Some(n) = std::env::var("CONTACT_BENCH_SWEEP")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        load_sweep(n);
        return;
    }
    let large = std::env::var("CONTACT_BENCH_LARGE").is_ok_and(|v| v == "1");
    let tolerances = [1e-3, 1e-5, 1e-7];
    println!("threads: {}", rayon::current_num_threads());
    println!("| case  |  grid  |   tol   | iters | coarse | free | pairs/it | t_solve ms | t_iter ms | t_fft ms | ratio | path | errors |");
    println!("|-------|--------|---------|-------|--------|------|----------|------------|-----------|----------|-------|------|--------|");

    hertz_rows(large, &tolerances);
    rough_rows(large, &tolerances);
}

/// The `hertz` rows: a paraboloid on a non-periodic grid, a = n/4 pixels.
fn hertz_rows(large: bool, tolerances: &[f64]) {
    let hertz_grids: &[usize] = if std::env::var("CONTACT_BENCH_HERTZ").is_ok_and(|v| v == "0") {
        &[]
    } else if large {
        &[64, 128, 256, 512, 1024]
    } else {
        &[64, 128, 256, 512]
    };
    for &n in hertz_grids {
        let (dx, radius, e_star) = (1e-6, 1e-2, 1e11);
        let a = n as f64 / 4.0 * dx;
        let force = 4.0 * e_star * a.powi(3) / (3.0 * radius);
        let side = n as f64 * dx;
        let c = (n / 2) as f64;
        let gap = Array2::from_shape_fn((n, n), |(iy, ix)| {
            ((ix as f64 - c).powi(2) + (iy as f64 - c).powi(2)) * dx * dx / (2.0 * radius)
        });
        let material = ContactMaterial::against_rigid_flat(e_star, f64::INFINITY).unwrap();
        let mut clock = FftClock::new(fast_even_length(2 * n));
        for &tol in tolerances {
            let problem =
                ContactProblem::from_gap_array(gap.view(), dx, dx, material, Boundary::NonPeriodic)
                    .unwrap();
            let mut solver = ContactSolver::new(problem, options(tol)).unwrap();
            let (step, t) = timed_solve(&mut solver, force / (side * side), reps(n), &mut clock);
            let a_num = (step.area_fraction * side * side / PI).sqrt();
            let p0 = 3.0 * force / (2.0 * PI * a * a);
            let delta = a * a / radius;
            let errors = format!(
                "a {:.2e}, δ {:.2e}, p_mean {:.2e}",
                (a_num - a).abs() / a,
                (step.approach - delta).abs() / delta,
                (step.mean_contact_pressure - 2.0 / 3.0 * p0).abs() / (2.0 / 3.0 * p0)
            );
            print_row("hertz", n, tol, &step, t, clock.take_median(), &errors);
        }
    }
}

/// The `ref`, `rough` and `warm` rows: a self-affine rough surface, elastic–plastic, periodic.
fn rough_rows(large: bool, tolerances: &[f64]) {
    let side = 1e-3;
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 4e9).unwrap();
    let grids = rough_grids(large);
    let Some(&finest) = grids.iter().max() else {
        return;
    };
    let reference = {
        let gap = CompositeGap::against_flat(&self_affine(finest, side)).unwrap();
        let mut solver = ContactSolver::new(
            ContactProblem::new(gap, material, Boundary::Periodic),
            SolverOptions {
                mixed_precision: false,
                ..options(1e-9)
            },
        )
        .unwrap();
        let mut clock = FftClock::new(finest);
        let (step, t) = timed_solve(&mut solver, 20e6, 1, &mut clock);
        print_row(
            "ref",
            finest,
            1e-9,
            &step,
            t,
            clock.take_median(),
            "reference",
        );
        step
    };
    let errors = |step: &LoadStep| {
        format!(
            "A/A₀ {:.2e}, θ {:.2e} (A/A₀ = {:.4}, θ = {:.3})",
            (step.area_fraction - reference.area_fraction).abs() / reference.area_fraction,
            (step.stress_ratio - reference.stress_ratio).abs() / reference.stress_ratio,
            step.area_fraction,
            step.stress_ratio
        )
    };
    for &n in &grids {
        let gap = CompositeGap::against_flat(&self_affine(n, side)).unwrap();
        let mut clock = FftClock::new(n);
        for &tol in tolerances {
            let problem = ContactProblem::new(gap.clone(), material, Boundary::Periodic);
            let mut solver = ContactSolver::new(problem, options(tol)).unwrap();
            let (step, t) = timed_solve(&mut solver, 20e6, reps(n), &mut clock);
            let fft = clock.take_median();
            print_row("rough", n, tol, &step, t, fft, &errors(&step));
            // The 20 MPa step of a load curve, warm-started from 15 MPa.
            let mut times = Vec::new();
            let mut last = None;
            for _ in 0..reps(n) {
                solver.reset();
                solver.solve(15e6).unwrap();
                let start = Instant::now();
                let step = solver.solve(20e6).unwrap();
                times.push(start.elapsed().as_secs_f64());
                last = Some(step);
                clock.tick();
            }
            if let Some(step) = last {
                let fft = clock.take_median();
                print_row("warm", n, tol, &step, median(times), fft, &errors(&step));
            }
        }
    }
}
