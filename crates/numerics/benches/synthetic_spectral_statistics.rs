//! Spectral statistics of synthetic surfaces at 1024² and 4096²
//! (`cargo bench -p asperity-numerics --bench synthetic_spectral_statistics`).

use std::hint::black_box;

use asperity_numerics::surface::spectral::{
    autocorrelation, hurst_exponent, radial_psd, spectral_moments, texture_direction, AcfBoundary,
    HurstFitOptions, MomentMethod, Window, ISO_ACF_THRESHOLD,
};
use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec,
};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

fn surface(n: usize) -> asperity_numerics::surface::HeightMap {
    let spec = SyntheticSurfaceSpec {
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
    };
    generate_synthetic_surface(&spec).expect("valid benchmark spec")
}

fn statistics(c: &mut Criterion) {
    let mut group = c.benchmark_group("spectral_statistics");
    for n in [1024usize, 4096] {
        if n >= 4096 {
            group.sample_size(10);
        }
        let map = surface(n);
        let id = |name: &str| BenchmarkId::new(name, format!("{n}x{n}"));
        group.bench_with_input(id("radial_psd_hann"), &map, |b, m| {
            b.iter(|| radial_psd(black_box(m), Window::Hann))
        });
        group.bench_with_input(id("hurst_fit"), &map, |b, m| {
            b.iter(|| hurst_exponent(black_box(m), HurstFitOptions::default()))
        });
        group.bench_with_input(id("acf_zero_padded_sal_str"), &map, |b, m| {
            b.iter(|| {
                autocorrelation(black_box(m), AcfBoundary::ZeroPadded)
                    .and_then(|acf| acf.texture(ISO_ACF_THRESHOLD))
            })
        });
        group.bench_with_input(id("texture_direction"), &map, |b, m| {
            b.iter(|| texture_direction(black_box(m), Window::Hann))
        });
        group.bench_with_input(id("moments_finite_difference"), &map, |b, m| {
            b.iter(|| spectral_moments(black_box(m), MomentMethod::FiniteDifference))
        });
        group.bench_with_input(id("moments_spectrum"), &map, |b, m| {
            b.iter(|| spectral_moments(black_box(m), MomentMethod::Spectrum))
        });
    }
    group.finish();
}

criterion_group!(benches, statistics);
criterion_main!(benches);
