//! Criterion benchmark of the restricted matrix's product (`free_set.rs`): `w = A t` with a
//! symmetric matrix stored as its packed lower triangle against the dense row-major product it
//! replaced, bit-identical, at the orders of the full-size ground validation (3 500 moving points,
//! and 4 967 at the cap `|M|² ≤ 2N` of a 3512² grid), on 1 and 2 threads.
//! `cargo bench -p asperity-numerics --bench packed_symmetric`.

use asperity_numerics::contact::PackedSymmetric;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use rayon::prelude::*;

/// Coefficient-like entries: `1/(1 + |i − j|)`, seeded signs of `t`.
fn problem(n: usize) -> (PackedSymmetric, Vec<f64>, Vec<f64>) {
    let packed = PackedSymmetric::from_lower(n, |i, j| 1.0 / (1.0 + (i - j) as f64));
    let dense: Vec<f64> = (0..n * n).map(|k| packed.get(k / n, k % n)).collect();
    let t = (0..n)
        .map(|k| ((k * 7919) % 1000) as f64 / 500.0 - 1.0)
        .collect();
    (packed, dense, t)
}

/// The dense row-major product: each row's sum in ascending order.
fn dense_product(dense: &[f64], t: &[f64], w: &mut [f64]) {
    w.par_iter_mut()
        .zip(dense.par_chunks(t.len()))
        .for_each(|(wi, row)| *wi = row.iter().zip(t).map(|(a, b)| a * b).sum());
}

fn products(c: &mut Criterion) {
    let mut group = c.benchmark_group("restricted matrix product");
    for n in [3500, 4967] {
        let (packed, dense, t) = problem(n);
        let mut w = vec![0.0; n];
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let id = format!("{n} points, {threads} threads");
            group.bench_function(BenchmarkId::new("dense", &id), |b| {
                b.iter(|| pool.install(|| dense_product(&dense, &t, &mut w)))
            });
            group.bench_function(BenchmarkId::new("packed", &id), |b| {
                b.iter(|| pool.install(|| packed.multiply(&t, &mut w)))
            });
        }
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = products
}
criterion_main!(benches);
