//! The mixed-precision solve (`SolverOptions::mixed_precision`: single-precision transforms,
//! then a double-precision polish) against the double-precision solve and closed forms, on the
//! solver's own path (`ContactSolver`, multilevel start and preconditioner as a study runs it).

use std::f64::consts::PI;

use asperity_numerics::contact::{
    Boundary, CompositeGap, ContactMaterial, ContactProblem, ContactSolver, FieldRequest, LoadStep,
    SolverOptions,
};
use ndarray::Array2;

use super::contact_validation::{elastic_rough_contact, rough_surface, westergaard_problem};

/// The race's accuracy rule: A/A₀ within 0.5 % of the double-precision solve's.
const AREA_MATCH: f64 = 5e-3;

fn options(tolerance: f64, mixed_precision: bool) -> SolverOptions {
    SolverOptions {
        tolerance,
        mixed_precision,
        fields: FieldRequest::ALL,
        ..SolverOptions::default()
    }
}

/// `problem` solved at the nominal pressure `load` to `tolerance`, in double precision and
/// mixed; both must meet the tolerance on their reported (double-precision) residuals.
fn both(problem: &ContactProblem, load: f64, tolerance: f64) -> (LoadStep, LoadStep) {
    let solve = |mixed: bool| {
        let step = ContactSolver::new(problem.clone(), options(tolerance, mixed))
            .unwrap()
            .solve(load)
            .unwrap();
        let r = step.residuals.max();
        assert!(
            r <= tolerance,
            "mixed {mixed}: residual {r:e} > {tolerance:e}"
        );
        step
    };
    (solve(false), solve(true))
}

/// The mixed solve found the double solve's contact: A/A₀ within [`AREA_MATCH`]; its pressures
/// are not bit-identical (the single-precision transforms ran) and differ by at most
/// `pressure_bound` of the largest pressure.
fn assert_same_contact(double: &LoadStep, mixed: &LoadStep, pressure_bound: f64, case: &str) {
    let area = (mixed.area_fraction - double.area_fraction).abs() / double.area_fraction;
    assert!(area <= AREA_MATCH, "{case}: A/A₀ differs by {area:e}");
    let pressure = |s: &LoadStep| s.fields.as_ref().unwrap().pressure.clone().unwrap();
    let (pd, pm) = (pressure(double), pressure(mixed));
    assert_ne!(
        pd, pm,
        "{case}: the mixed solve is bit-identical to the double one"
    );
    let peak = pd.iter().copied().fold(0.0, f64::max);
    let largest = pd
        .iter()
        .zip(&pm)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
        / peak;
    assert!(
        largest <= pressure_bound,
        "{case}: pressures differ by {largest:e} of the peak"
    );
}

#[test]
fn mixed_precision_meets_the_hertz_closed_form() {
    // The paraboloid of `hertz_sphere_on_non_periodic_grid` (non-periodic, a = 32 dx on 128²)
    // to ε = 1e-8: contact radius within 1 %, peak pressure and approach within 0.5 % of Hertz
    // (the discretisation error, as for the double solve); force balance to ε.
    let (n, dx, radius, e_star) = (128usize, 1e-6, 1e-2, 1e11);
    let a_target: f64 = 32e-6;
    let force = 4.0 * e_star * a_target.powi(3) / (3.0 * radius);
    let side = n as f64 * dx;
    let nominal = force / (side * side);
    let c = (n / 2) as f64;
    let gap = Array2::from_shape_fn((n, n), |(iy, ix)| {
        ((ix as f64 - c).powi(2) + (iy as f64 - c).powi(2)) * dx * dx / (2.0 * radius)
    });
    let material = ContactMaterial::against_rigid_flat(e_star, f64::INFINITY).unwrap();
    let problem =
        ContactProblem::from_gap_array(gap.view(), dx, dx, material, Boundary::NonPeriodic)
            .unwrap();
    let (double, mixed) = both(&problem, nominal, 1e-8);
    let p0 = 3.0 * force / (2.0 * PI * a_target * a_target);
    let delta = a_target * a_target / radius;
    let a = (mixed.area_fraction * side * side / PI).sqrt();
    let pressure = mixed.fields.as_ref().unwrap().pressure.clone().unwrap();
    assert!((a - a_target).abs() < 0.01 * a_target, "a = {a}");
    let peak = pressure[[n / 2, n / 2]];
    assert!((peak - p0).abs() < 0.005 * p0, "p0 = {peak} vs {p0}");
    assert!((mixed.approach - delta).abs() < 0.005 * delta);
    assert!((pressure.mean().unwrap() - nominal).abs() < 1e-8 * nominal);
    // Both converged to ε = 1e-8 of the gap scale: the pressures agree to far below 1e-5.
    assert_same_contact(&double, &mixed, 1e-5, "hertz");
}

#[test]
fn mixed_precision_meets_the_sinusoids_full_contact_pressure() {
    // Westergaard's full contact, p = p̄ + p* cos(2πx/λ) (as in
    // `westergaard_full_contact_matches_to_round_off`), to ε = 1e-12: the polish reaches the
    // closed form to the double solve's round-off.
    let (n, amplitude, e_star) = (256, 1e-7, 1e11);
    let p_star = PI * e_star * amplitude / (n as f64 * 1e-6);
    let mut solver = ContactSolver::new(
        westergaard_problem(n, amplitude, e_star, f64::INFINITY),
        options(1e-12, true),
    )
    .unwrap();
    let nominal = 1.5 * p_star;
    let step = solver.solve(nominal).unwrap();
    assert_eq!(step.area_fraction, 1.0);
    assert!(step.residuals.max() <= 1e-12);
    let pressure = step.fields.unwrap().pressure.unwrap();
    for ((_, ix), &p) in pressure.indexed_iter() {
        let exact = nominal + p_star * (2.0 * PI * ix as f64 / n as f64).cos();
        assert!(
            (p - exact).abs() < 1e-9 * p_star,
            "ix = {ix}: {p} vs {exact}"
        );
    }
}

#[test]
fn mixed_precision_finds_the_same_rough_elastic_contact() {
    // 512² elastic rough contact at 50 MPa (multilevel start, preconditioned fine iteration),
    // periodic and non-periodic, at a loose and a tight tolerance: A/A₀ within 0.5 % of the
    // double solve (at ε = 1e-3 the two may stop at different iterates, each within ε).
    let (gap, material) = elastic_rough_contact();
    for boundary in [Boundary::Periodic, Boundary::NonPeriodic] {
        let problem = ContactProblem::new(gap.clone(), material, boundary);
        for (tolerance, bound) in [(1e-3, 0.1), (1e-7, 1e-4)] {
            let (double, mixed) = both(&problem, 50e6, tolerance);
            assert_same_contact(
                &double,
                &mixed,
                bound,
                &format!("{boundary:?} ε {tolerance:e}"),
            );
        }
    }
}

#[test]
fn mixed_precision_finds_the_same_capped_contact() {
    // Two 64² rough surfaces, steel on steel, p_lim = 4 GPa, from 10 % to 90 % of p_lim, to
    // ε = 1e-7: A/A₀ within 0.5 % of the double solve, the plastic share alike, every pressure
    // within [0, p_lim] and the force balance to ε.
    let gap = CompositeGap::from_surfaces(
        &rough_surface(64, 1e-6, 0.5e-6, 1, 40),
        &rough_surface(64, 1e-6, 0.3e-6, 2, 40),
    )
    .unwrap();
    let plim = 4e9;
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, plim).unwrap();
    let problem = ContactProblem::new(gap, material, Boundary::Periodic);
    for share in [0.1, 0.5, 0.9] {
        let (double, mixed) = both(&problem, share * plim, 1e-7);
        assert_same_contact(&double, &mixed, 1e-4, &format!("p̄ = {share} p_lim"));
        let shares = (mixed.plastic_area_share - double.plastic_area_share).abs();
        assert!(shares <= AREA_MATCH * double.plastic_area_share.max(1e-3));
        let pressure = mixed.fields.unwrap().pressure.unwrap();
        assert!(pressure.iter().all(|&p| (0.0..=plim).contains(&p)));
        let mean = pressure.mean().unwrap();
        assert!((mean - share * plim).abs() < 1e-7 * share * plim);
    }
}
