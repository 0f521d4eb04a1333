//! Amplitude/hybrid statistics, summits and preprocessing at 1024² and 4096² points.
//!
//! Run: `cargo bench -p asperity-numerics --bench surface_stats` (4096² groups use `sample_size(10)`).
//! The surface is a deterministic rough test surface (sum of sines plus hashed noise) with 0.5 %
//! missing points in small holes, so every function runs its missing-point path.

use asperity_numerics::surface::{
    amplitude_statistics, fill_missing, find_summits, gaussian_high_pass, gaussian_low_pass,
    gradient_statistics, remove_plane, remove_polynomial_form, resample_bilinear, Boundary,
    DifferenceScheme, FillOptions, HeightMap, SummitOptions,
};
use criterion::{criterion_group, criterion_main, Criterion};
use ndarray::Array2;
use std::hint::black_box;

/// Pseudo-random value in [−0.5, 0.5) from a point index (SplitMix64 finaliser).
fn hash_noise(i: u64) -> f64 {
    let mut x = i.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^= x >> 31;
    (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
}

fn test_surface(n: usize) -> HeightMap {
    let dx = 0.5e-6;
    let z = Array2::from_shape_fn((n, n), |(iy, ix)| {
        let (x, y) = (ix as f64 * dx, iy as f64 * dx);
        let p = (iy * n + ix) as u64;
        if hash_noise(p ^ 0xABCD) > 0.495 {
            return f64::NAN;
        }
        1e-6 * ((x / 40e-6).sin() * (y / 25e-6).cos() + 0.3 * (x / 7e-6 + y / 11e-6).sin())
            + 0.05e-6 * hash_noise(p)
    });
    HeightMap::new(z, dx, dx).expect("finite test surface")
}

fn bench_size(c: &mut Criterion, n: usize) {
    let map = test_surface(n);
    let dx = map.dx();
    let mut group = c.benchmark_group(format!("surface_stats_{n}"));
    if n >= 4096 {
        group.sample_size(10);
    }
    group.bench_function("amplitude_statistics", |b| {
        b.iter(|| amplitude_statistics(black_box(&map), Boundary::Open))
    });
    group.bench_function("gradient_central", |b| {
        b.iter(|| gradient_statistics(black_box(&map), DifferenceScheme::Central, Boundary::Open))
    });
    group.bench_function("summits", |b| {
        b.iter(|| find_summits(black_box(&map), SummitOptions::default()))
    });
    let with_prominence = SummitOptions {
        min_prominence: Some(1e-9),
        ..SummitOptions::default()
    };
    group.bench_function("summits_with_prominence", |b| {
        b.iter(|| find_summits(black_box(&map), with_prominence))
    });
    group.bench_function("remove_plane", |b| b.iter(|| remove_plane(black_box(&map))));
    group.bench_function("remove_polynomial_degree_3", |b| {
        b.iter(|| remove_polynomial_form(black_box(&map), 3))
    });
    group.bench_function("s_filter_cutoff_5px", |b| {
        b.iter(|| gaussian_low_pass(black_box(&map), 5.0 * dx))
    });
    group.bench_function("l_filter_cutoff_50px", |b| {
        b.iter(|| gaussian_high_pass(black_box(&map), 50.0 * dx))
    });
    group.bench_function("fill_missing", |b| {
        b.iter(|| fill_missing(black_box(&map), FillOptions::default()))
    });
    group.bench_function("resample_bilinear_half", |b| {
        b.iter(|| resample_bilinear(black_box(&map), n / 2, n / 2))
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_size(c, 1024);
    bench_size(c, 4096);
}

criterion_group!(surface_stats, benches);
criterion_main!(surface_stats);
