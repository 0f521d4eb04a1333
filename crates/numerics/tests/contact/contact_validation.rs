//! Validation of the contact solver against closed-form solutions and physical limits.

use std::f64::consts::PI;

use asperity_numerics::contact::{
    Boundary, CompositeGap, ContactMaterial, ContactProblem, ContactSolver, FieldRequest, LoadStep,
    SolvePath, SolveStrategy, SolverOptions,
};
use asperity_numerics::surface::HeightMap;
use ndarray::Array2;

/// Deterministic rough surface: a sum of `modes` random-phase cosines on integer wave numbers
/// (periodic on the grid) with amplitudes `∝ |k|^(−1−H)`, H = 0.8, scaled to rms `sq` (m).
/// Random numbers from a 64-bit LCG (Knuth's MMIX constants).
pub(super) fn rough_surface(n: usize, dx: f64, sq: f64, seed: u64, modes: usize) -> HeightMap {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let kmax = (n / 4).max(2) as f64;
    let waves: Vec<(f64, f64, f64, f64)> = (0..modes)
        .map(|_| {
            let kx = (uniform() * 2.0 * kmax).floor() - kmax;
            let ky = (uniform() * kmax).floor() + 1.0;
            let k = (kx * kx + ky * ky).sqrt();
            (kx, ky, k.powf(-1.8), 2.0 * PI * uniform())
        })
        .collect();
    let mut z = Array2::from_shape_fn((n, n), |(iy, ix)| {
        waves
            .iter()
            .map(|&(kx, ky, amp, phase)| {
                amp * (2.0 * PI * (kx * ix as f64 + ky * iy as f64) / n as f64 + phase).cos()
            })
            .sum::<f64>()
    });
    let mean = z.mean().unwrap();
    let rms = z.mapv(|v| (v - mean).powi(2)).mean().unwrap().sqrt();
    z.mapv_inplace(|v| (v - mean) * sq / rms);
    HeightMap::new(z, dx, dx).unwrap()
}

fn options(tolerance: f64, fields: FieldRequest) -> SolverOptions {
    SolverOptions {
        tolerance,
        fields,
        ..SolverOptions::default()
    }
}

#[test]
fn hertz_sphere_on_non_periodic_grid() {
    // Paraboloid g₀ = r²/2R against a flat, R = 10 mm, E* = 100 GPa, 128² pixels of 1 µm; the
    // load is chosen for a = 32 µm = 32 dx (a/dx ≥ 25 as in the acceptance criterion).
    let (n, dx, radius, e_star) = (128usize, 1e-6, 1e-2, 1e11);
    let a_target: f64 = 32e-6;

    let force = 4.0 * e_star * a_target.powi(3) / (3.0 * radius);
    let side = n as f64 * dx;
    let nominal = force / (side * side);
    let c = (n / 2) as f64;
    let gap = Array2::from_shape_fn((n, n), |(iy, ix)| {
        let r2 = ((ix as f64 - c).powi(2) + (iy as f64 - c).powi(2)) * dx * dx;
        r2 / (2.0 * radius)
    });
    let material = ContactMaterial::against_rigid_flat(e_star, f64::INFINITY).unwrap();
    let problem =
        ContactProblem::from_gap_array(gap.view(), dx, dx, material, Boundary::NonPeriodic)
            .unwrap();
    let mut solver = ContactSolver::new(problem, options(1e-8, FieldRequest::ALL)).unwrap();
    let step = solver.solve(nominal).unwrap();
    let a = (step.area_fraction * side * side / PI).sqrt();
    let p0 = 3.0 * force / (2.0 * PI * a_target * a_target);
    let delta = a_target * a_target / radius;
    let fields = step.fields.unwrap();
    let pressure = fields.pressure.unwrap();
    let peak = pressure[[n / 2, n / 2]];
    // Acceptance criterion of the issue: radius within 1 %, peak pressure and approach 0.5 %.
    assert!((a - a_target).abs() < 0.01 * a_target, "a = {a}");
    assert!((peak - p0).abs() < 0.005 * p0, "p0 = {peak} vs {p0}");
    assert!(
        (step.approach - delta).abs() < 0.005 * delta,
        "δ = {} vs {delta}",
        step.approach
    );
    // Force balance to the solver tolerance (1e-8) plus summation round-off.
    let mean = pressure.mean().unwrap();
    assert!((mean - nominal).abs() < 1e-8 * nominal);
}

pub(super) fn westergaard_problem(
    n: usize,
    amplitude: f64,
    e_star: f64,
    plim: f64,
) -> ContactProblem {
    let dx = 1e-6;
    let lambda = n as f64 * dx;
    let z = Array2::from_shape_fn((4, n), |(_, ix)| {
        amplitude * (2.0 * PI * ix as f64 * dx / lambda).cos()
    });
    let surface = HeightMap::new(z, dx, dx).unwrap();
    let gap = CompositeGap::against_flat(&surface).unwrap();
    let material = ContactMaterial::against_rigid_flat(e_star, plim).unwrap();
    ContactProblem::new(gap, material, Boundary::Periodic)
}

#[test]
fn westergaard_full_contact_matches_to_round_off() {
    // p = p̄ + p* cos(2πx/λ), p* = π E* Δ / λ, for p̄ ≥ p* (Westergaard 1939; Johnson 1985 §13.2).
    let (n, amplitude, e_star) = (256, 1e-7, 1e11);
    let p_star = PI * e_star * amplitude / (n as f64 * 1e-6);
    let mut solver = ContactSolver::new(
        westergaard_problem(n, amplitude, e_star, f64::INFINITY),
        options(1e-12, FieldRequest::ALL),
    )
    .unwrap();
    let nominal = 1.5 * p_star;
    let step = solver.solve(nominal).unwrap();
    assert_eq!(step.area_fraction, 1.0);
    let pressure = step.fields.unwrap().pressure.unwrap();
    for ((_, ix), &p) in pressure.indexed_iter() {
        let exact = nominal + p_star * (2.0 * PI * ix as f64 / n as f64).cos();
        // Round-off of FFTs on 256 points relative to p*.
        assert!(
            (p - exact).abs() < 1e-9 * p_star,
            "ix = {ix}: {p} vs {exact}"
        );
    }
}

#[test]
fn westergaard_partial_contact_width_within_one_pixel() {
    // p̄ = p* sin²(π a / λ) for the contact half-width a (Johnson 1985, eq. 13.13).
    let (n, amplitude, e_star) = (512, 1e-7, 1e11);
    let lambda = n as f64 * 1e-6;
    let p_star = PI * e_star * amplitude / lambda;
    let mut solver = ContactSolver::new(
        westergaard_problem(n, amplitude, e_star, f64::INFINITY),
        options(1e-8, FieldRequest::NONE),
    )
    .unwrap();
    let steps = solver
        .solve_load_steps(&[0.05 * p_star, 0.2 * p_star, 0.5 * p_star])
        .unwrap();
    for step in &steps.steps {
        let half_width = 0.5 * step.area_fraction * lambda;
        let exact = lambda / PI * (step.nominal_pressure / p_star).sqrt().asin();
        assert!(
            (half_width - exact).abs() <= 1e-6,
            "p̄/p* = {}: a = {half_width} vs {exact}",
            step.nominal_pressure / p_star
        );
    }
}

fn rough_pair() -> (HeightMap, HeightMap) {
    (
        rough_surface(64, 1e-6, 0.5e-6, 1, 40),
        rough_surface(64, 1e-6, 0.3e-6, 2, 40),
    )
}

#[test]
fn plastic_limits_hold() {
    let (a, b) = rough_pair();
    let gap = CompositeGap::from_surfaces(&a, &b).unwrap();
    let plim = 4e9;
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, plim).unwrap();
    let problem = ContactProblem::new(gap.clone(), material, Boundary::Periodic);
    let mut solver = ContactSolver::new(problem, options(1e-7, FieldRequest::ALL)).unwrap();
    let loads = [0.01 * plim, 0.1 * plim, 0.5 * plim, 0.9 * plim, 0.95 * plim];
    let curve = solver.solve_load_steps(&loads).unwrap();
    for step in &curve.steps {
        let fields = step.fields.as_ref().unwrap();
        let pressure = fields.pressure.as_ref().unwrap();
        assert!(pressure.iter().all(|&p| (0.0..=plim).contains(&p)));
        // Force balance to the tolerance 1e-7 plus summation round-off.
        let mean = pressure.mean().unwrap();
        assert!((mean - step.nominal_pressure).abs() < 1e-7 * step.nominal_pressure);
        // A/A₀ ≥ p̄/p_lim because p ≤ p_lim.
        assert!(step.area_fraction >= step.nominal_pressure / plim);
        assert!(step.stress_ratio <= 1.0);
    }
    let last = curve.steps.last().unwrap();
    // Near the fully plastic limit almost all contact is saturated: θ → 1, A/A₀ → p̄/p_lim.
    assert!(last.stress_ratio > 0.97, "θ = {}", last.stress_ratio);
    assert!(
        last.area_fraction - 0.95 < 0.03,
        "A/A₀ = {}",
        last.area_fraction
    );

    // p_lim far above every elastic pressure reproduces the purely elastic solution.
    let elastic =
        ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, f64::INFINITY).unwrap();
    let high = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 1e15).unwrap();
    let solve = |m| {
        let mut s = ContactSolver::new(
            ContactProblem::new(gap.clone(), m, Boundary::Periodic),
            options(1e-9, FieldRequest::ALL),
        )
        .unwrap();
        s.solve(50e6).unwrap()
    };
    let (e, h) = (solve(elastic), solve(high));
    assert_eq!(h.plastic_area_share, 0.0);
    assert_eq!(e.area_fraction, h.area_fraction);
    let (pe, ph) = (
        e.fields.unwrap().pressure.unwrap(),
        h.fields.unwrap().pressure.unwrap(),
    );
    let peak = pe.iter().copied().fold(0.0, f64::max);
    for (x, y) in pe.iter().zip(&ph) {
        // Both converged to 1e-9 of S_q in the gap: pressures agree far below 1e-6 of the peak.
        assert!((x - y).abs() < 1e-6 * peak);
    }
}

#[test]
fn swapping_the_surfaces_gives_the_same_answer() {
    let (a, b) = rough_pair();
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 70e9, 0.33, 3e9).unwrap();
    let solve = |first: &HeightMap, second: &HeightMap, m: ContactMaterial| {
        let gap = CompositeGap::from_surfaces(first, second).unwrap();
        let mut s = ContactSolver::new(
            ContactProblem::new(gap, m, Boundary::Periodic),
            options(1e-8, FieldRequest::ALL),
        )
        .unwrap();
        s.solve(100e6).unwrap()
    };
    let ab = solve(&a, &b, material);
    let swapped = ContactMaterial::from_young_poisson(70e9, 0.33, 210e9, 0.3, 3e9).unwrap();
    let ba = solve(&b, &a, swapped);
    assert_eq!(ab.area_fraction, ba.area_fraction);
    assert_eq!(ab.approach, ba.approach);
    let (fa, fb) = (ab.fields.unwrap(), ba.fields.unwrap());
    assert_eq!(fa.pressure, fb.pressure);
    assert_eq!(fa.deformation_first, fb.deformation_second);
    assert_eq!(fa.deformation_second, fb.deformation_first);
}

#[test]
fn contact_area_grows_monotonically_with_load() {
    for seed in [3, 4] {
        let surface = rough_surface(64, 1e-6, 1e-6, seed, 48);
        let gap = CompositeGap::against_flat(&surface).unwrap();
        let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 5e9).unwrap();
        let mut solver = ContactSolver::new(
            ContactProblem::new(gap, material, Boundary::Periodic),
            options(1e-7, FieldRequest::NONE),
        )
        .unwrap();
        let loads: Vec<f64> = (1..=12).map(|k| 1e6 * 2f64.powi(k)).collect();
        let curve = solver.solve_load_steps(&loads).unwrap();
        for pair in curve.steps.windows(2) {
            assert!(pair[1].area_fraction >= pair[0].area_fraction);
            assert!(pair[1].approach > pair[0].approach);
            assert!(pair[1].mean_separation < pair[0].mean_separation);
        }
    }
}

#[test]
fn approach_search_agrees_with_constrained_cg() {
    let (a, b) = rough_pair();
    let gap = CompositeGap::from_surfaces(&a, &b).unwrap();
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 4e9).unwrap();
    let solve = |strategy| {
        let mut s = ContactSolver::new(
            ContactProblem::new(gap.clone(), material, Boundary::Periodic),
            SolverOptions {
                strategy,
                ..options(1e-9, FieldRequest::ALL)
            },
        )
        .unwrap();
        s.solve(0.3 * 4e9).unwrap()
    };
    let cg = solve(SolveStrategy::ConstrainedCg);
    let search = solve(SolveStrategy::ApproachSearch);
    assert_eq!(cg.path, SolvePath::ConstrainedCg);
    assert_eq!(search.path, SolvePath::ApproachSearch);
    // Both solutions satisfy the complementarity conditions to 1e-9 S_q: approaches agree to a
    // few times that.
    let sq = 0.58e-6;
    assert!((cg.approach - search.approach).abs() < 1e-7 * sq);
    assert!((cg.area_fraction - search.area_fraction).abs() <= 2.0 / 4096.0);
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let (a, b) = rough_pair();
    let gap = CompositeGap::from_surfaces(&a, &b).unwrap();
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 4e9).unwrap();
    let solve = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut s = ContactSolver::new(
                ContactProblem::new(gap.clone(), material, Boundary::NonPeriodic),
                options(1e-8, FieldRequest::ALL),
            )
            .unwrap();
            s.solve_load_steps(&[50e6, 200e6]).unwrap()
        })
    };
    // Fixed-block reductions and per-row/column transforms: bit-identical results.
    assert_eq!(solve(1), solve(3));
}

/// A 512² rough surface against a flat, steel on steel, elastic (no flow pressure): A/A₀ of a
/// few per cent at 50 MPa.
pub(super) fn elastic_rough_contact() -> (CompositeGap, ContactMaterial) {
    let surface = rough_surface(512, 1e-6, 1e-6, 11, 400);
    let gap = CompositeGap::against_flat(&surface).unwrap();
    let material =
        ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, f64::INFINITY).unwrap();
    (gap, material)
}

/// The cold 50 MPa step of [`elastic_rough_contact`] with `options`.
fn elastic_step(boundary: Boundary, options: SolverOptions) -> LoadStep {
    let (gap, material) = elastic_rough_contact();
    ContactSolver::new(ContactProblem::new(gap, material, boundary), options)
        .unwrap()
        .solve(50e6)
        .unwrap()
}

/// Two solves of one problem to ε = 1e-7 found the same contact: A/A₀ may differ by the points
/// whose gap is within ε·h of closing, the approach by ~ε·h.
fn assert_same_contact(a: &LoadStep, b: &LoadStep, boundary: Boundary) {
    let relative = (a.area_fraction - b.area_fraction).abs() / b.area_fraction;
    assert!(relative < 1e-3, "{boundary:?}: A/A₀ differs by {relative}");
    assert!((a.approach - b.approach).abs() < 1e-12);
}

#[test]
fn multilevel_start_converges_to_the_same_contact_in_fewer_fine_iterations() {
    // 512² elastic rough contact (coarse grid 256²) against a flat at A/A₀ of a few per cent,
    // periodic and non-periodic, both starts converged to ε = 1e-7; the fine iterations must
    // fall (elastic cold starts are where the multilevel start pays).
    for boundary in [Boundary::Periodic, Boundary::NonPeriodic] {
        let solve = |multilevel: bool| {
            let options = SolverOptions {
                multilevel,
                ..options(1e-7, FieldRequest::NONE)
            };
            elastic_step(boundary, options)
        };
        let (single, multi) = (solve(false), solve(true));
        assert_eq!(single.coarse_iterations, 0);
        assert!(multi.coarse_iterations > 0, "{boundary:?}: no coarse level");
        assert!(
            multi.iterations < single.iterations,
            "{boundary:?}: {} fine iterations with the multilevel start, {} without",
            multi.iterations,
            single.iterations
        );
        assert_same_contact(&multi, &single, boundary);
    }
}

#[test]
fn preconditioned_iteration_converges_to_the_same_elastic_contact_in_fewer_transforms() {
    // 512² elastic rough contact against a flat, periodic and non-periodic, from the multilevel
    // start (one coarse grid, 256²), where the fine iteration is preconditioned; both converged
    // to ε = 1e-7. A preconditioned iteration costs one more FFT pair; the iterations must fall
    // by more than that costs. The coarsest grid starts rigid-plastic and is never
    // preconditioned, so its iterations are the same.
    for boundary in [Boundary::Periodic, Boundary::NonPeriodic] {
        let solve = |preconditioned: bool| {
            let options = SolverOptions {
                preconditioned,
                ..options(1e-7, FieldRequest::NONE)
            };
            elastic_step(boundary, options)
        };
        let (plain, preconditioned) = (solve(false), solve(true));
        assert!(plain.coarse_iterations > 0, "{boundary:?}: no coarse level");
        assert_eq!(preconditioned.coarse_iterations, plain.coarse_iterations);
        assert!(
            preconditioned.fft_transforms < plain.fft_transforms,
            "{boundary:?}: {} transforms ({} iterations) preconditioned, {} ({}) plain",
            preconditioned.fft_transforms,
            preconditioned.iterations,
            plain.fft_transforms,
            plain.iterations
        );
        assert_same_contact(&preconditioned, &plain, boundary);
        assert!(preconditioned.residuals.max() <= 1e-7);
    }
}

#[test]
fn elastic_load_steps_each_start_from_the_coarse_grids_capped_ones_warm() {
    // An elastic contact takes the multilevel start at every step of a load curve: its 50 MPa
    // step after 25 MPa is the cold 50 MPa step, bit for bit. A capped contact keeps the warm
    // start: no coarse iterations after its first step.
    let options = options(1e-7, FieldRequest::NONE);
    for boundary in [Boundary::Periodic, Boundary::NonPeriodic] {
        let (gap, material) = elastic_rough_contact();
        let mut solver =
            ContactSolver::new(ContactProblem::new(gap, material, boundary), options).unwrap();
        let curve = solver.solve_load_steps(&[25e6, 50e6]).unwrap();
        assert!(curve.steps[1].coarse_iterations > 0, "{boundary:?}");
        assert_eq!(
            curve.steps[1],
            elastic_step(boundary, options),
            "{boundary:?}"
        );
    }
    let (_, gap, material) = saturated_rough_contact();
    let problem = ContactProblem::new(gap, material, Boundary::Periodic);
    let curve = ContactSolver::new(problem, options)
        .unwrap()
        .solve_load_steps(&[5e6, 10e6])
        .unwrap();
    assert_eq!(curve.steps[1].coarse_iterations, 0);
}

#[test]
fn contacts_with_a_flow_pressure_are_not_preconditioned() {
    // The option only applies to elastic contacts: a capped step is bit-identical either way.
    let (_, gap, material) = saturated_rough_contact();
    let solve = |preconditioned: bool| {
        let options = SolverOptions {
            preconditioned,
            ..options(1e-6, FieldRequest::NONE)
        };
        let problem = ContactProblem::new(gap.clone(), material, Boundary::Periodic);
        ContactSolver::new(problem, options)
            .unwrap()
            .solve(10e6)
            .unwrap()
    };
    assert_eq!(solve(true), solve(false));
}

/// A 512² rough surface against a flat, steel on steel capped at 1 GPa: most of its contact
/// area is at p_lim at the loads of the tests below.
fn saturated_rough_contact() -> (HeightMap, CompositeGap, ContactMaterial) {
    let surface = rough_surface(512, 1e-6, 1e-6, 5, 400);
    let gap = CompositeGap::against_flat(&surface).unwrap();
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 1e9).unwrap();
    (surface, gap, material)
}

#[test]
fn saturated_contacts_keep_the_rigid_plastic_start() {
    // 512² rough contact with most of the contact area at p_lim: the coarse grid is solved, its
    // contact found mostly saturated, and the fine grid starts rigid-plastic, so the step is
    // bit-identical to one solved without the multilevel start.
    let (_, gap, material) = saturated_rough_contact();
    let solve = |multilevel: bool| {
        let options = SolverOptions {
            multilevel,
            ..options(1e-6, FieldRequest::NONE)
        };
        let problem = ContactProblem::new(gap.clone(), material, Boundary::Periodic);
        ContactSolver::new(problem, options)
            .unwrap()
            .solve(10e6)
            .unwrap()
    };
    let (single, multi) = (solve(false), solve(true));
    assert!(
        single.plastic_area_share > 0.5,
        "{}",
        single.plastic_area_share
    );
    assert!(multi.coarse_iterations > 0);
    assert_eq!(
        LoadStep {
            coarse_iterations: 0,
            ..multi
        },
        single
    );
}

#[test]
fn saturated_contacts_finish_on_the_free_set() {
    // 512² rough contact, most of it at p_lim, at a load light enough for its free set to be
    // iterated alone (`free_set.rs`): the step converges on the FFT displacement as every step
    // does, and agrees with a solve 1000 times tighter.
    let (surface, gap, material) = saturated_rough_contact();
    let solve = |tolerance: f64| {
        let problem = ContactProblem::new(gap.clone(), material, Boundary::Periodic);
        ContactSolver::new(problem, options(tolerance, FieldRequest::NONE))
            .unwrap()
            .solve(2e6)
            .unwrap()
    };
    let (step, tight) = (solve(1e-6), solve(1e-9));
    assert!(step.plastic_area_share > 0.5, "{}", step.plastic_area_share);
    assert!(
        step.free_set_iterations > 0,
        "the free set was not iterated alone"
    );
    assert!(step.residuals.max() <= 1e-6, "{:?}", step.residuals);
    assert!(tight.residuals.max() <= 1e-9, "{:?}", tight.residuals);
    // A/A₀ counts points: at most one point in a thousand of the contact may differ.
    let relative = (step.area_fraction - tight.area_fraction).abs() / tight.area_fraction;
    assert!(relative < 1e-3, "A/A₀ differs by {relative}");
    let scale = surface
        .heights()
        .iter()
        .fold(0.0f64, |a, &z| a.max(z.abs()));
    assert!((step.approach - tight.approach).abs() < 1e-6 * scale);
}

#[test]
fn the_fields_of_a_consumed_solver_are_those_it_returned() {
    // A capped wavy contact of two elastic bodies in partial contact, so that every field (the
    // plastic penetration and each body's deformation too) has non-zero points.
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 70e9, 0.33, 5e8).unwrap();
    let gap = westergaard_problem(128, 1e-6, 1e11, 2e9).gap().clone();
    let problem = || ContactProblem::new(gap.clone(), material, Boundary::Periodic);
    let fresh = ContactSolver::new(problem(), options(1e-10, FieldRequest::NONE)).unwrap();
    assert!(fresh.last_pressure().is_none());
    assert!(fresh.into_last_fields(FieldRequest::ALL).is_none());
    let mut solver = ContactSolver::new(problem(), options(1e-10, FieldRequest::NONE)).unwrap();
    solver.solve(2e8).unwrap();
    let kept = solver.last_fields(FieldRequest::ALL).unwrap();
    assert_eq!(
        Some(solver.last_pressure().unwrap().to_owned()),
        kept.pressure
    );
    let consumed = solver.into_last_fields(FieldRequest::ALL).unwrap();
    let pairs = [
        (kept.pressure, consumed.pressure),
        (kept.gap, consumed.gap),
        (kept.deformation_first, consumed.deformation_first),
        (kept.deformation_second, consumed.deformation_second),
        (kept.plastic_penetration, consumed.plastic_penetration),
    ];
    for (i, (a, b)) in pairs.into_iter().enumerate() {
        let (a, b) = (a.unwrap(), b.unwrap());
        assert!(a.iter().any(|&x| x != 0.0), "field {i} is all zero");
        assert_eq!(a, b, "field {i}");
    }
}
