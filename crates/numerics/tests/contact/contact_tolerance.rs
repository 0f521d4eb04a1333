//! The solver's tolerance range: a tolerance below what f64 residuals resolve (or not a
//! number, or ≥ 1) is refused by `ContactSolver::new` with a typed error, never a panic in the
//! approach search, and the smallest accepted tolerance is reached on rough elastic–plastic
//! contacts by both solution paths.

use asperity_numerics::contact::{
    BadOption, Boundary, CompositeGap, ContactError, ContactMaterial, ContactProblem,
    ContactSolver, SolveStrategy, SolverOptions, MIN_TOLERANCE,
};
use asperity_numerics::surface::synthetic::{generate_synthetic_surface, SyntheticSurfaceSpec};

/// A rough contact of `n²` points (Sq 1 µm on 0.5 mm, H = 0.8) against a flat, steel with a
/// flow pressure of 1 GPa.
fn problem(n: usize) -> ContactProblem {
    let surface = generate_synthetic_surface(&SyntheticSurfaceSpec {
        nx: n,
        ny: n,
        lx: 0.5e-3,
        ly: 0.5e-3,
        sq: 1e-6,
        hurst: 0.8,
        correlation_length: 40e-6,
        short_wavelength_cutoff: None,
        anisotropy: None,
        seed: 3,
    })
    .unwrap();
    let gap = CompositeGap::against_flat(&surface).unwrap();
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 1e9).unwrap();
    ContactProblem::new(gap, material, Boundary::Periodic)
}

fn options(tolerance: f64, strategy: SolveStrategy) -> SolverOptions {
    SolverOptions {
        tolerance,
        strategy,
        ..SolverOptions::default()
    }
}

#[test]
fn tolerances_the_solver_cannot_reach_are_refused_with_a_typed_error() {
    let strategies = [SolveStrategy::ApproachSearch, SolveStrategy::Auto];
    for tolerance in [1e-16, 1e-300, 0.0, -1e-6, 1.0, f64::NAN, f64::INFINITY] {
        for strategy in strategies {
            match ContactSolver::new(problem(32), options(tolerance, strategy)) {
                Err(ContactError::BadOption(BadOption { name, reason, .. })) => {
                    assert_eq!(name, "tolerance");
                    assert!(reason.contains("1e-12"), "{reason}");
                }
                other => panic!("tolerance {tolerance}: {other:?}"),
            }
        }
    }
}

#[test]
fn the_smallest_accepted_tolerance_is_reached_by_both_paths() {
    for strategy in [SolveStrategy::ApproachSearch, SolveStrategy::Auto] {
        let mut solver =
            ContactSolver::new(problem(128), options(MIN_TOLERANCE, strategy)).unwrap();
        // 0.9 of the flow pressure: nearly saturated, where the approach search takes over.
        for nominal in [20e6, 0.9e9] {
            let step = solver.solve(nominal).unwrap();
            assert!(
                step.residuals.max() <= MIN_TOLERANCE,
                "{strategy:?} at {nominal} Pa: {:?}",
                step.residuals
            );
        }
    }
}
