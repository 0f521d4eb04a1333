//! Benchmarks of the statistical KE 2004 model: one μ_s evaluation (grid + Brent + final
//! integrals, all at 1e-10 relative quadrature tolerance) and a 100-point μ(F) curve.
//! Run: `cargo bench --bench friction`.

use asperity::friction::{
    static_friction, static_friction_curve, AdhesionParameters, AsperityModel, Material,
    ModelOptions, SolveSettings, StatisticalModel, SummitStatistics,
};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// Steel-like pair: E = 115 GPa composite, H = 2 GPa, ν = 0.3, σ = 1 µm, β = 0.04, ψ = 2,
/// Δγ = 0.5 N/m, ε = 0.158 nm, A_n = 1 cm².
fn steel_model() -> Option<StatisticalModel> {
    let material = Material::new(115e9, 2e9, 0.3).ok()?;
    let sigma = 1e-6;
    let beta: f64 = 0.04;
    let sigma_s = sigma * (1.0 - 0.8968 / (768.0 * std::f64::consts::PI * beta * beta)).sqrt();
    let c = 2.0 * material.composite_modulus
        / (std::f64::consts::PI * material.hardness_factor() * material.hardness);
    let psi = 2.0;
    let radius = sigma_s * c * c / (psi * psi);
    let summits = SummitStatistics::from_explicit(sigma, radius, beta / (radius * sigma)).ok()?;
    let adhesion = AdhesionParameters::new(0.5, 0.158e-9).ok()?;
    StatisticalModel::new(
        AsperityModel::KogutEtsion,
        summits,
        material,
        adhesion,
        1e-4,
        ModelOptions::default(),
    )
    .ok()
}

fn bench_friction(c: &mut Criterion) {
    let Some(model) = steel_model() else {
        return;
    };
    let settings = SolveSettings::default();
    let an_h = model.nominal_area * model.material.hardness;
    c.bench_function("mu_s single load (F/AnH = 1e-4)", |b| {
        b.iter(|| static_friction(black_box(&model), black_box(1e-4 * an_h), &settings))
    });
    let loads: Vec<f64> = (0..100)
        .map(|i| an_h * 10f64.powf(-5.0 + 2.0 * f64::from(i) / 99.0))
        .collect();
    c.bench_function("mu(F) curve 100 loads (F/AnH = 1e-5..1e-3)", |b| {
        b.iter(|| static_friction_curve(black_box(&model), black_box(&loads), &settings))
    });
}

criterion_group!(benches, bench_friction);
criterion_main!(benches);
