//! Stability property tests of the contact solver on small grids.
//!
//! Every generated case must either converge (finite results, bounds and residuals respected) or
//! return the typed [`ContactError::NotConverged`]; never a NaN, never another error.
//! Default: 32 cases per property. Longer sweep:
//! `CONTACT_PROPTEST_CASES=2000 cargo test --release --test contact_stability`.

use std::f64::consts::TAU;

use asperity_numerics::contact::{
    Boundary, CompositeGap, ContactError, ContactMaterial, ContactProblem, ContactSolver,
    FieldRequest, GapError, SolverOptions, Termination,
};
use asperity_numerics::surface::HeightMap;
use ndarray::Array2;
use proptest::prelude::*;

fn cases() -> u32 {
    std::env::var("CONTACT_PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(32)
}

/// Surface families of the sweep.
#[derive(Debug, Clone, Copy)]
enum Shape {
    /// Sum of random-phase cosines from a seeded LCG.
    Random(u64),
    /// All heights zero.
    Flat,
    /// All heights equal to a non-zero constant.
    Constant,
    /// Zero except one high point.
    Spike,
}

fn heights(shape: Shape, n: usize, sq: f64) -> Array2<f64> {
    match shape {
        Shape::Random(seed) => {
            let mut state = seed | 1;
            let mut uniform = move || {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (state >> 11) as f64 / (1u64 << 53) as f64
            };
            let waves: Vec<[f64; 4]> = (0..24)
                .map(|_| {
                    let kx = (uniform() * n as f64).floor() - (n / 2) as f64;
                    let ky = (uniform() * (n / 2) as f64).floor();
                    [kx, ky, uniform() - 0.5, TAU * uniform()]
                })
                .collect();
            Array2::from_shape_fn((n, n), |(iy, ix)| {
                sq * waves
                    .iter()
                    .map(|w| {
                        w[2] * (TAU * (w[0] * ix as f64 + w[1] * iy as f64) / n as f64 + w[3]).cos()
                    })
                    .sum::<f64>()
            })
        }
        Shape::Flat => Array2::zeros((n, n)),
        Shape::Constant => Array2::from_elem((n, n), 3.0 * sq),
        Shape::Spike => {
            let mut z = Array2::zeros((n, n));
            z[[n / 3, n / 2]] = 10.0 * sq;
            z
        }
    }
}

fn shape_strategy() -> impl Strategy<Value = Shape> {
    prop_oneof![
        4 => any::<u64>().prop_map(Shape::Random),
        1 => Just(Shape::Flat),
        1 => Just(Shape::Constant),
        1 => Just(Shape::Spike),
    ]
}

/// Heights whose squares overflow a 64-bit float are refused when the gap is built: every
/// residual of the solver is scaled by the gap's rms, which would be infinite.
#[test]
fn gaps_whose_rms_overflows_are_refused() {
    let z = heights(Shape::Random(7), 16, 1e200);
    let surface = HeightMap::new(z, 1e-6, 1e-6).unwrap();
    match CompositeGap::against_flat(&surface) {
        Err(e @ GapError::Overflow { .. }) => assert!(e.to_string().contains("height unit")),
        other => panic!("expected GapError::Overflow, got {other:?}"),
    }
}

/// A load whose pressures overflow ends the iteration with its own termination, `NonFinite`,
/// instead of being reported as a stall (or iterating on NaN).
#[test]
fn overflowing_pressures_end_as_non_finite() {
    let surface = HeightMap::new(heights(Shape::Random(3), 32, 1e-6), 1e-6, 1e-6).unwrap();
    let gap = CompositeGap::against_flat(&surface).unwrap();
    let material =
        ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, f64::INFINITY).unwrap();
    let problem = ContactProblem::new(gap, material, Boundary::Periodic);
    let mut solver = ContactSolver::new(problem, SolverOptions::default()).unwrap();
    match solver.solve(1e306) {
        Err(ContactError::NotConverged { termination, .. }) => {
            assert_eq!(termination, Termination::NonFinite)
        }
        other => panic!("expected a NonFinite termination, got {other:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn every_case_converges_or_reports_non_convergence(
        shape in shape_strategy(),
        log_n in 3u32..7,
        // Roughness from 1 nm to 1 mm on 1 µm pixels: slopes up to ~10³.
        log_sq in -9.0f64..-3.0,
        // p̄/p_lim from 10⁻⁸ (tiny loads) to 0.95 (nearly fully plastic).
        log_load in -8.0f64..0.0,
        plastic in any::<bool>(),
        periodic in any::<bool>(),
    ) {
        let n = 1usize << log_n;
        let sq = 10f64.powf(log_sq);
        let z = heights(shape, n, sq);
        let surface = HeightMap::new(z, 1e-6, 1e-6).unwrap();
        let gap = CompositeGap::against_flat(&surface).unwrap();
        let plim = if plastic { 4e9 } else { f64::INFINITY };
        let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, plim).unwrap();
        let boundary = if periodic { Boundary::Periodic } else { Boundary::NonPeriodic };
        let nominal = if plastic { 4e9 * 10f64.powf(log_load).min(0.95) } else { 1e9 * 10f64.powf(log_load) };
        let options = SolverOptions { tolerance: 1e-6, max_iterations: 4000, fields: FieldRequest::ALL, ..SolverOptions::default() };
        let mut solver = ContactSolver::new(ContactProblem::new(gap, material, boundary), options).unwrap();
        match solver.solve(nominal) {
            Ok(step) => {
                prop_assert!(step.residuals.max() <= 1e-6);
                for v in [step.area_fraction, step.mean_contact_pressure, step.stress_ratio,
                          step.plastic_area_share, step.mean_separation,
                          step.max_elastic_deformation, step.approach] {
                    prop_assert!(v.is_finite());
                }
                prop_assert!(step.area_fraction > 0.0 && step.area_fraction <= 1.0);
                let fields = step.fields.unwrap();
                let pressure = fields.pressure.unwrap();
                prop_assert!(pressure.iter().all(|&p| (0.0..=plim).contains(&p)));
                for field in [fields.gap, fields.deformation_first, fields.deformation_second,
                              fields.plastic_penetration].into_iter().flatten() {
                    prop_assert!(field.iter().all(|v| v.is_finite()));
                }
            }
            Err(ContactError::NotConverged { residuals, iterations, .. }) => {
                prop_assert!(iterations > 0);
                prop_assert!(!residuals.max().is_nan());
            }
            Err(other) => prop_assert!(false, "unexpected error {other}"),
        }
    }

    #[test]
    fn non_finite_heights_are_rejected_with_their_position(
        log_n in 3u32..6,
        ix in 0usize..64,
        iy in 0usize..64,
        kind in 0u8..3,
        second in any::<bool>(),
    ) {
        let n = 1usize << log_n;
        let (ix, iy) = (ix % n, iy % n);
        let bad = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][kind as usize];
        let clean = HeightMap::new(Array2::zeros((n, n)), 1e-6, 1e-6).unwrap();
        let mut z = Array2::<f64>::zeros((n, n));
        z[[iy, ix]] = bad;
        if bad.is_nan() {
            let dirty = HeightMap::new(z.clone(), 1e-6, 1e-6).unwrap();
            let result = if second {
                CompositeGap::from_surfaces(&clean, &dirty)
            } else {
                CompositeGap::from_surfaces(&dirty, &clean)
            };
            let is_expected = matches!(result, Err(GapError::NonFinite { ix: x, iy: y, .. }) if x == ix && y == iy);
            prop_assert!(is_expected);
        }
        let result = CompositeGap::from_gap_array(z.view(), 1e-6, 1e-6);
        let is_expected = matches!(result, Err(GapError::NonFinite { ix: x, iy: y, .. }) if x == ix && y == iy);
        prop_assert!(is_expected);
    }
}
