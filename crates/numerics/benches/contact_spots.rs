//! Contact spots (`cargo bench -p asperity-numerics --bench contact_spots`): `contact_spots` (labelling, per-spot sums
//! and paraboloid radii), `label_spots` alone, and the whole per-spot friction model (spots, the
//! Lennard-Jones adhesion across the gap and the full-stick law per spot), 8-connected on a
//! periodic grid, at 512² and 3512². Prints the input (contact fraction, spots, one-pixel spots, spots without a radius) and
//! the median of the individual runs; criterion's own estimates follow.
//!
//! Input: a periodic self-affine surface (H = 0.8, roll-off 50 µm, 1 mm period, Sq = 1 µm)
//! cut at its 96th percentile, p = 1.96 GPa (the flow pressure of S235JR) above the cut: about
//! 4 % of the points in contact, in spots as ragged as the surface; the gap is the depth below
//! the lowest contact point. It is not a solved elastic contact, but it has a contact's
//! scale of spot counts and shapes.

use std::hint::black_box;
use std::time::{Duration, Instant};

use asperity_numerics::friction::contact_spots::{contact_spots, label_spots, Connectivity};
use asperity_numerics::friction::{
    per_spot_friction, AdhesionParameters, BodyHardness, BodyMaps, ContactBodies, ContactSection,
    FullStick, FullStickOptions, Material,
};
use asperity_numerics::surface::synthetic::{generate_synthetic_surface, SyntheticSurfaceSpec};
use criterion::{criterion_group, criterion_main, Bencher, Criterion, SamplingMode};
use ndarray::Array2;

/// Composite height and pressure of the synthetic contact on an `n × n` grid, with the spacing.
fn synthetic_contact(n: usize) -> (Array2<f64>, Array2<f64>, f64) {
    let spec = SyntheticSurfaceSpec {
        nx: n,
        ny: n,
        lx: 1e-3,
        ly: 1e-3,
        sq: 1e-6,
        hurst: 0.8,
        correlation_length: 50e-6,
        short_wavelength_cutoff: None,
        anisotropy: None,
        seed: 3,
    };
    let z = generate_synthetic_surface(&spec)
        .expect("valid synthetic spec")
        .into_heights();
    let mut sorted: Vec<f64> = z.iter().copied().collect();
    let rank = sorted.len() * 96 / 100;
    let (_, &mut cut, _) = sorted.select_nth_unstable_by(rank, f64::total_cmp);
    // Fully plastic S235JR points (p = 1.96 GPa) where the surface is above the cut.
    let pressure = z.mapv(|v| if v > cut { 1.96e9 } else { 0.0 });
    (z, pressure, 1e-3 / n as f64)
}

/// Times every run of `f` separately into `runs` (criterion only sees the totals).
fn timed<T>(b: &mut Bencher, runs: &mut Vec<Duration>, mut f: impl FnMut() -> T) {
    b.iter_custom(|iters| {
        let mut total = Duration::ZERO;
        for _ in 0..iters {
            let t = Instant::now();
            black_box(f());
            let elapsed = t.elapsed();
            runs.push(elapsed);
            total += elapsed;
        }
        total
    });
}

/// The per-spot model as the `friction` node runs it, in its one call: spots, adhesion,
/// full-stick law (S235JR against a rigid flat; no deformation maps are needed by the law).
fn per_spot_model(z: &Array2<f64>, p: &Array2<f64>, gap: &Array2<f64>, dx: f64) -> Option<f64> {
    let zero = Array2::zeros(z.dim());
    let maps = BodyMaps {
        composite_height: z.view(),
        upper_height: None,
        deformation_lower: zero.view().into(),
        deformation_upper: None,
        plastic_penetration: zero.view().into(),
    };
    let hardness = BodyHardness {
        lower: 1.96e9,
        upper: f64::INFINITY,
    };
    let section = ContactSection {
        pressure: p.view(),
        gap: gap.view().into(),
        bodies: ContactBodies::new(maps, hardness).ok()?,
        spacing: (dx, dx),
        periodic: true,
        connectivity: Connectivity::Eight,
        adhesion: AdhesionParameters::new(0.5, 0.158e-9).ok()?,
    };
    let material = Material::new(210e9 / (2.0 * (1.0 - 0.09)), 1.96e9, 0.3).ok()?;
    let law = FullStick::new(&material, FullStickOptions::default()).ok()?;
    per_spot_friction(&section, &law).ok()?.result.mu_s
}

fn median(runs: &mut [Duration]) -> Duration {
    runs.sort_unstable();
    runs.get(runs.len() / 2).copied().unwrap_or_default()
}

fn bench_contact_spots(c: &mut Criterion) {
    let mut group = c.benchmark_group("contact_spots");
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    for n in [512usize, 3512] {
        let start = Instant::now();
        let (z, p, dx) = synthetic_contact(n);
        let spots = contact_spots(p.view(), z.view(), dx, dx, true, Connectivity::Eight)
            .expect("valid contact");
        let contact = spots.iter().map(|s| s.pixels).sum::<usize>() as f64 / (n * n) as f64;
        println!(
            "{n}²: input built in {:.2} s; {:.2} % in contact, {} spots, {} of one pixel, {} without a radius",
            start.elapsed().as_secs_f64(),
            100.0 * contact,
            spots.len(),
            spots.iter().filter(|s| s.pixels == 1).count(),
            spots.iter().filter(|s| s.radius.is_none()).count(),
        );
        let mut runs = Vec::new();
        group.bench_function(format!("contact_spots {n}x{n}"), |b| {
            timed(b, &mut runs, || {
                contact_spots(p.view(), z.view(), dx, dx, true, Connectivity::Eight)
            })
        });
        println!(
            "contact_spots {n}²: median {:?} over {} runs",
            median(&mut runs),
            runs.len()
        );
        runs.clear();
        group.bench_function(format!("label_spots {n}x{n}"), |b| {
            timed(b, &mut runs, || {
                label_spots(p.view(), true, Connectivity::Eight)
            })
        });
        println!(
            "label_spots {n}²: median {:?} over {} runs",
            median(&mut runs),
            runs.len()
        );
        runs.clear();
        let cut = z
            .iter()
            .zip(p.iter())
            .filter(|(_, p)| **p > 0.0)
            .map(|(z, _)| *z)
            .fold(f64::INFINITY, f64::min);
        let gap = z.mapv(|v| (cut - v).max(0.0));
        group.bench_function(format!("per_spot full stick {n}x{n}"), |b| {
            timed(b, &mut runs, || per_spot_model(&z, &p, &gap, dx))
        });
        println!(
            "per_spot full stick {n}²: median {:?} over {} runs (mu_s {:?})",
            median(&mut runs),
            runs.len(),
            per_spot_model(&z, &p, &gap, dx)
        );
    }
    group.finish();
}

criterion_group!(benches, bench_contact_spots);
criterion_main!(benches);
