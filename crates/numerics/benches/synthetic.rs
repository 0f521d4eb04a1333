//! Synthetic surface generation at 512², 1024² and 4096² (`cargo bench -p asperity-numerics --bench synthetic`).

use std::hint::black_box;

use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec,
};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

fn spec(n: usize) -> SyntheticSurfaceSpec {
    SyntheticSurfaceSpec {
        nx: n,
        ny: n,
        lx: 1e-3,
        ly: 1e-3,
        sq: 1.19e-6,
        hurst: 0.8,
        correlation_length: 50e-6,
        short_wavelength_cutoff: None,
        anisotropy: Some(Anisotropy {
            aspect_ratio: 4.0,
            angle: 0.0,
        }),
        seed: 1,
    }
}

fn generation(c: &mut Criterion) {
    let mut group = c.benchmark_group("synthetic_generate");
    for n in [512usize, 1024, 4096] {
        if n >= 4096 {
            group.sample_size(10);
        }
        let s = spec(n);
        group.bench_with_input(
            BenchmarkId::from_parameter(format!("{n}x{n}")),
            &s,
            |b, s| b.iter(|| generate_synthetic_surface(black_box(s))),
        );
    }
    group.finish();
}

criterion_group!(benches, generation);
criterion_main!(benches);
