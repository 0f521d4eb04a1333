//! Criterion benchmark of one load step: 256² self-affine-like periodic surface, elastic–plastic
//! steel–steel contact at 20 MPa. `cargo bench -p asperity-numerics --bench contact`.

use std::f64::consts::PI;

use asperity_numerics::contact::{
    Boundary, CompositeGap, ContactMaterial, ContactProblem, ContactSolver, SolverOptions,
};
use asperity_numerics::surface::HeightMap;
use criterion::{criterion_group, criterion_main, Criterion};
use ndarray::Array2;

/// Sum of 64 random-phase cosines (seeded LCG) with amplitude `∝ |k|^(−1.8)`, S_q ≈ 1 µm.
fn surface(n: usize, side: f64) -> HeightMap {
    let mut state = 12345u64;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let waves: Vec<[f64; 4]> = (0..64)
        .map(|_| {
            let kx = (uniform() * 64.0).floor() - 32.0;
            let ky = (uniform() * 32.0).floor() + 1.0;
            let amp = (kx * kx + ky * ky).sqrt().powf(-1.8);
            [kx, ky, amp, 2.0 * PI * uniform()]
        })
        .collect();
    let z = Array2::from_shape_fn((n, n), |(iy, ix)| {
        waves
            .iter()
            .map(|w| {
                w[2] * (2.0 * PI * (w[0] * ix as f64 + w[1] * iy as f64) / n as f64 + w[3]).cos()
            })
            .sum::<f64>()
    });
    let rms = (z.mapv(|v| v * v).mean().unwrap_or(1.0)).sqrt();
    HeightMap::new(z.mapv(|v| v * 1e-6 / rms), side / n as f64, side / n as f64).unwrap()
}

fn one_load_step(c: &mut Criterion) {
    let gap = CompositeGap::against_flat(&surface(256, 0.25e-3)).unwrap();
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 4e9).unwrap();
    let problem = ContactProblem::new(gap, material, Boundary::Periodic);
    let options = SolverOptions {
        tolerance: 1e-6,
        ..SolverOptions::default()
    };
    let mut solver = ContactSolver::new(problem, options).unwrap();
    c.bench_function("contact 256² periodic elastic-plastic 20 MPa", |b| {
        b.iter(|| {
            solver.reset();
            solver.solve(20e6).unwrap()
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = one_load_step
}
criterion_main!(benches);
