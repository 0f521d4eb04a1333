//! Benchmarks of the statistical models: one μ_s evaluation (grid + Brent + final integrals, all
//! at 1e-10 relative quadrature tolerance) and a 100-point μ(F) curve of KE 2004 at ψ = 2, and
//! one full-stick μ_s evaluation at ψ = 2 and at ground-steel ψ = 50. Before timing, each
//! single-load case prints its accuracy (load residual and largest integral error estimate), so
//! time and error are read side by side.
//! Run: `cargo bench -p asperity-numerics --bench friction`.

use std::sync::Arc;

use asperity_numerics::friction::{
    static_friction, static_friction_curve, AdhesionBeyondFits, AdhesionParameters, AsperityLaws,
    FullStick, FullStickOptions, KogutEtsion, Material, SolveSettings, StaticFrictionForm,
    StatisticalModel, SummitStatistics,
};

/// The two laws benchmarked.
#[derive(Clone, Copy)]
enum Kind {
    KogutEtsion,
    FullStick,
}
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// Steel-like pair: E = 115 GPa composite, H = 2 GPa, ν = 0.3, σ = 1 µm, β = 0.04, plasticity
/// index `psi`, Δγ = 0.5 N/m, ε = 0.158 nm, A_n = 1 cm².
fn steel_model(kind: Kind, psi: f64) -> Option<StatisticalModel> {
    let material = Material::new(115e9, 2e9, 0.3).ok()?;
    let sigma = 1e-6;
    let beta: f64 = 0.04;
    let sigma_s = sigma * (1.0 - 0.8968 / (768.0 * std::f64::consts::PI * beta * beta)).sqrt();
    let c = 2.0 * material.composite_modulus
        / (std::f64::consts::PI * material.hardness_factor() * material.hardness);
    let radius = sigma_s * c * c / (psi * psi);
    let summits = SummitStatistics::from_explicit(sigma, radius, beta / (radius * sigma)).ok()?;
    let adhesion = AdhesionParameters::new(0.5, 0.158e-9).ok()?;
    let laws: Arc<dyn AsperityLaws> = match kind {
        Kind::KogutEtsion => Arc::new(KogutEtsion::new(material, StaticFrictionForm::Literal)),
        Kind::FullStick => Arc::new(FullStick::new(&material, FullStickOptions::default()).ok()?),
    };
    StatisticalModel::new(
        laws,
        summits,
        material,
        adhesion,
        1e-4,
        AdhesionBeyondFits::default(),
    )
    .ok()
}

/// One μ_s at F/(A_n H) = 1e-4 (20 MPa against H = 2 GPa is 1e-2; 1e-4 keeps ψ = 2 partial).
fn bench_single_load(c: &mut Criterion, name: &str, model: &StatisticalModel, load_ratio: f64) {
    let settings = SolveSettings::default();
    let load = load_ratio * model.nominal_area * model.material.hardness;
    match static_friction(model, load, &settings) {
        Ok(r) => eprintln!(
            "{name}: mu_s {:?}, load residual {:.1e}, integral error {:.1e}, share beyond fit {:.3}",
            r.mu_s,
            r.status.relative_residual,
            r.status.max_integral_relative_error,
            r.load_beyond_fit / r.contact_load
        ),
        Err(e) => eprintln!("{name}: {e}"),
    }
    c.bench_function(name, |b| {
        b.iter(|| static_friction(black_box(model), black_box(load), &settings))
    });
}

fn bench_friction(c: &mut Criterion) {
    let Some(model) = steel_model(Kind::KogutEtsion, 2.0) else {
        return;
    };
    let settings = SolveSettings::default();
    let an_h = model.nominal_area * model.material.hardness;
    bench_single_load(
        c,
        "mu_s single load (KE, psi 2, F/AnH = 1e-4)",
        &model,
        1e-4,
    );
    for psi in [2.0, 50.0] {
        if let Some(stick) = steel_model(Kind::FullStick, psi) {
            let name = format!("mu_s single load (full stick, psi {psi}, F/AnH = 1e-2)");
            bench_single_load(c, &name, &stick, 1e-2);
        }
    }
    let loads: Vec<f64> = (0..100)
        .map(|i| an_h * 10f64.powf(-5.0 + 2.0 * f64::from(i) / 99.0))
        .collect();
    c.bench_function("mu(F) curve 100 loads (F/AnH = 1e-5..1e-3)", |b| {
        b.iter(|| static_friction_curve(black_box(&model), black_box(&loads), &settings))
    });
}

criterion_group!(benches, bench_friction);
criterion_main!(benches);
