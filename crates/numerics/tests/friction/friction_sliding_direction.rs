//! The sliding direction on synthetic surfaces under a rigid–perfectly-plastic contact (the
//! points above a bearing level carry the flow pressure, the plastic-saturated limit of the
//! ground-steel contacts), a hard rough upper body on a soft flat, through the production path:
//! reversing the direction equals sliding over the mirror image, the angle moves μ_s on isotropic
//! surfaces only within the spread of realisations (and far beyond it across the lay of an
//! anisotropic one), and the fronts' attack slope and groove grow as the sampling interval
//! shrinks.

use crate::ploughing_support::{parts, ploughing, Pair, H, HARD};
use asperity_numerics::friction::BodyHardness;
use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec,
};
use ndarray::{s, Array2};
use std::f64::consts::PI;

const SIDE: f64 = 512e-6;
/// Share of the points in contact (the bearing area of the rigid–plastic contact).
const BEARING: f64 = 0.05;

fn surface(n: usize, seed: u64, anisotropy: Option<Anisotropy>) -> Array2<f64> {
    generate_synthetic_surface(&SyntheticSurfaceSpec {
        nx: n,
        ny: n,
        lx: SIDE,
        ly: SIDE,
        sq: 1e-6,
        hurst: 0.8,
        correlation_length: SIDE / 8.0,
        short_wavelength_cutoff: None,
        anisotropy,
        seed,
    })
    .unwrap()
    .into_heights()
}

/// The rigid–plastic contact of the hard rough upper body `z` on a soft flat, on spacing `d`
/// (periodic; the pixel spacing of the support is replaced by `d`).
fn contact(z: Array2<f64>) -> Pair {
    let mut sorted: Vec<f64> = z.iter().copied().collect();
    sorted.sort_by(f64::total_cmp);
    let level = sorted[((1.0 - BEARING) * sorted.len() as f64) as usize];
    let cells = z
        .indexed_iter()
        .filter(|(_, &h)| h > level)
        .map(|(at, _)| at)
        .collect();
    Pair {
        lower: Array2::zeros(z.dim()),
        upper: z,
        cells,
        hardness: BodyHardness {
            lower: H,
            upper: HARD,
        },
        periodic: true,
    }
}

/// μ_s of the groove law at ψ.
fn mu(pair: &Pair, spacing: f64, psi: f64) -> f64 {
    parts(&pair.friction_on(ploughing("groove", psi, 1.0).as_ref(), (spacing, spacing))).1
}

#[test]
fn reversing_the_direction_equals_sliding_over_the_mirror_image() {
    let z = surface(128, 7, None);
    let d = SIDE / 128.0;
    let original = contact(z.clone());
    // Columns reversed: (x, y) → (−x, y); both axes reversed: a half turn.
    let mirror = contact(z.slice(s![.., ..;-1]).to_owned());
    let turned = contact(z.slice(s![..;-1, ..;-1]).to_owned());
    for law in ["groove", "cone", "sphere"] {
        for psi in [0.0, 0.4, 2.0] {
            let at = |pair: &Pair, psi: f64| {
                parts(&pair.friction_on(ploughing(law, psi, 1.0).as_ref(), (d, d))).1
            };
            let on_mirror = at(&mirror, psi);
            // Same spots in another raster order: sums in another order only.
            assert!(
                (on_mirror - at(&original, PI - psi)).abs() < 1e-12 * on_mirror,
                "{law} ψ = {psi}"
            );
            let on_turned = at(&turned, psi);
            assert!((on_turned - at(&original, psi + PI)).abs() < 1e-12 * on_turned);
        }
    }
    // The loaded front reads the direction on one realisation: ψ and ψ + π differ, so the
    // checks above are not satisfied by any constant.
    assert!((mu(&original, d, 0.0) - mu(&original, d, PI)).abs() > 1e-6);
}

/// μ_s of the groove law at the angles `psis` on 8 realisations of 256² points: `[seed][angle]`.
fn realisations(anisotropy: Option<Anisotropy>, psis: &[f64]) -> Vec<Vec<f64>> {
    (1..=8)
        .map(|seed| {
            let pair = contact(surface(256, seed, anisotropy));
            psis.iter()
                .map(|&psi| mu(&pair, SIDE / 256.0, psi))
                .collect()
        })
        .collect()
}

/// Mean over the realisations at each angle, and the standard deviation over the realisations
/// at the first angle.
fn mean_and_spread(mu: &[Vec<f64>]) -> (Vec<f64>, f64) {
    let n = mu.len() as f64;
    let means: Vec<f64> = (0..mu[0].len())
        .map(|k| mu.iter().map(|row| row[k]).sum::<f64>() / n)
        .collect();
    let var = mu
        .iter()
        .map(|row| (row[0] - means[0]).powi(2))
        .sum::<f64>()
        / (n - 1.0);
    (means, var.sqrt())
}

#[test]
fn angle_moves_mu_only_within_the_spread_on_isotropic_surfaces() {
    let psis = [0.0, PI / 4.0, PI / 2.0, 3.0 * PI / 4.0, PI, 5.0 * PI / 3.0];
    let (means, spread) = mean_and_spread(&realisations(None, &psis));
    for (psi, mean) in psis.iter().zip(&means) {
        assert!(
            (mean - means[0]).abs() < spread,
            "ψ = {psi}: {means:?}, {spread}"
        );
    }
    // The same surfaces with their lay along x (correlation 4 times longer along it): across the
    // lay the caps are short and steep, μ_s moves by tens of spreads.
    let lay = Some(Anisotropy {
        aspect_ratio: 4.0,
        angle: 0.0,
    });
    let (means, spread) = mean_and_spread(&realisations(lay, &[0.0, PI / 2.0]));
    assert!(means[1] - means[0] > 20.0 * spread, "{means:?}, {spread}");
}

#[test]
fn attack_slope_and_groove_grow_as_the_sampling_interval_shrinks() {
    // One surface sampled at 4, 2 and 1 µm (docs/friction-models.md, "Checks on the production
    // path"; the ground validation's resolution series is in docs/studies.md).
    let fine = surface(512, 3, None);
    let mut rows = Vec::new();
    for step in [4usize, 2, 1] {
        let d = SIDE / 512.0 * step as f64;
        let pair = contact(fine.slice(s![..;step, ..;step]).to_owned());
        let found = pair.friction_on(ploughing("cone", 0.0, 1.0).as_ref(), (d, d));
        let (cone, _) = parts(&found);
        let groove = mu(&pair, d, 0.0) - 0.2;
        rows.push((cone, groove));
    }
    for pair in rows.windows(2) {
        assert!(pair[1].0 > pair[0].0 && pair[1].1 > pair[0].1, "{rows:?}");
    }
}
