//! The sliding direction on synthetic surfaces under a rigid–perfectly-plastic contact (the
//! points above a bearing level carry the flow pressure, the plastic-saturated limit of the
//! ground-steel contacts): reversing the direction equals mirroring the surface, the angle moves
//! μ_s on isotropic surfaces only within the spread of realisations (and far beyond it across
//! the lay of an anisotropic one), and the spots' tilt grows as the sampling interval shrinks.

use asperity_numerics::friction::contact_spots::{label_spots, measure_spots, Connectivity};
use asperity_numerics::friction::{
    deformation_friction, per_spot_friction, spot_slopes, ContactSpot, DeformationLaw,
    DeformationSpot, JunctionShear, SlidingDirection, SpotLabels, SpotLoad, SpotSlope,
};
use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec,
};
use ndarray::{s, Array2};
use std::f64::consts::PI;

const H: f64 = 3.0e9;
const TAU: f64 = 0.2 * H;
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

/// The rigid–plastic contact of the periodic composite height `z` on spacing `d`, its spots and
/// their adhesion part (junction shear).
struct Contact {
    z: Array2<f64>,
    d: f64,
    labels: SpotLabels,
    spots: Vec<ContactSpot>,
    adhesion: Vec<f64>,
}

impl Contact {
    fn solve(z: Array2<f64>, d: f64) -> Self {
        let mut sorted: Vec<f64> = z.iter().copied().collect();
        sorted.sort_by(f64::total_cmp);
        let level = sorted[((1.0 - BEARING) * sorted.len() as f64) as usize];
        let p = z.mapv(|h| if h > level { H } else { 0.0 });
        let labels = label_spots(p.view(), true, Connectivity::Four).unwrap();
        let spots = measure_spots(&labels, p.view(), z.view(), d, d).unwrap();
        let loads: Vec<SpotLoad> = spots.iter().map(SpotLoad::from).collect();
        let shear = JunctionShear::new(1.0, TAU).unwrap();
        let adhesion = per_spot_friction(&loads, &shear, 0.0).unwrap();
        let adhesion = adhesion.spots.iter().map(|a| a.friction_force).collect();
        Self {
            z,
            d,
            labels,
            spots,
            adhesion,
        }
    }

    fn slopes(&self, psi: f64) -> Vec<SpotSlope> {
        let direction = SlidingDirection::new(psi).unwrap();
        spot_slopes(
            &self.labels,
            &self.spots,
            self.z.view(),
            (self.d, self.d),
            direction,
        )
        .unwrap()
    }

    fn mu(&self, law: DeformationLaw, psi: f64) -> f64 {
        let input: Vec<DeformationSpot> = self
            .spots
            .iter()
            .zip(self.slopes(psi))
            .zip(&self.adhesion)
            .map(|((spot, slope), &adhesion_friction)| DeformationSpot {
                load: spot.load,
                area: spot.area,
                radius: spot.radius,
                tilt: slope.tilt,
                attack_slope: slope.attack_slope,
                groove_ratio: slope.groove_ratio,
                adhesion_friction,
            })
            .collect();
        deformation_friction(&input, law, 0.0)
            .unwrap()
            .mu_s
            .unwrap()
    }

    /// Load-weighted mean of `f(spot, slope)` along ψ = 0 over the spots where it is defined.
    fn load_mean(&self, f: impl Fn(&ContactSpot, &SpotSlope) -> Option<f64>) -> f64 {
        let (mut sum, mut load) = (0.0, 0.0);
        for (spot, slope) in self.spots.iter().zip(self.slopes(0.0)) {
            if let Some(v) = f(spot, &slope) {
                sum += v * spot.load;
                load += spot.load;
            }
        }
        sum / load
    }
}

const LAWS: [DeformationLaw; 4] = [
    DeformationLaw::TiltedJunction,
    DeformationLaw::ConePloughing,
    DeformationLaw::SpherePloughing,
    DeformationLaw::GroovePloughing,
];

#[test]
fn reversing_the_direction_equals_sliding_over_the_mirror_image() {
    let z = surface(128, 7, None);
    let d = SIDE / 128.0;
    let original = Contact::solve(z.clone(), d);
    // Columns reversed: (x, y) → (−x, y); both axes reversed: a half turn.
    let mirror = Contact::solve(z.slice(s![.., ..;-1]).to_owned(), d);
    let turned = Contact::solve(z.slice(s![..;-1, ..;-1]).to_owned(), d);
    for law in LAWS {
        for psi in [0.0, 0.4, 2.0] {
            let on_mirror = mirror.mu(law, psi);
            // Same spots in another raster order: sums in another order only.
            assert!(
                (on_mirror - original.mu(law, PI - psi)).abs() < 1e-12 * on_mirror,
                "{law:?} ψ = {psi}"
            );
            let on_turned = turned.mu(law, psi);
            assert!((on_turned - original.mu(law, psi + PI)).abs() < 1e-12 * on_turned);
        }
    }
    // The tilted junction does depend on the direction on one realisation: the checks above are
    // not satisfied by any constant.
    let law = DeformationLaw::TiltedJunction;
    assert!((original.mu(law, 0.0) - original.mu(law, PI)).abs() > 1e-6);
}

/// μ_s of `law` at the angles `psis` on 8 realisations of 256² points: `[seed][angle]`.
fn realisations(
    law: DeformationLaw,
    anisotropy: Option<Anisotropy>,
    psis: &[f64],
) -> Vec<Vec<f64>> {
    (1..=8)
        .map(|seed| {
            let contact = Contact::solve(surface(256, seed, anisotropy), SIDE / 256.0);
            psis.iter().map(|&psi| contact.mu(law, psi)).collect()
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
    let psis = [0.0, PI / 4.0, PI / 2.0, 3.0 * PI / 4.0, 5.0 * PI / 3.0];
    let lay = Some(Anisotropy {
        aspect_ratio: 4.0,
        angle: 0.0,
    });
    for law in [
        DeformationLaw::GroovePloughing,
        DeformationLaw::TiltedJunction,
    ] {
        let (means, spread) = mean_and_spread(&realisations(law, None, &psis));
        for (psi, mean) in psis.iter().zip(&means) {
            assert!(
                (mean - means[0]).abs() < spread,
                "{law:?} ψ = {psi}: {means:?}, {spread}"
            );
        }
        // The same surfaces with their lay along x (correlation 4 times longer along it).
        let (means, spread) = mean_and_spread(&realisations(law, lay, &[0.0, PI / 2.0]));
        if law == DeformationLaw::GroovePloughing {
            // Across the lay the caps are short and steep: μ_s moves by tens of spreads.
            assert!(means[1] - means[0] > 20.0 * spread, "{means:?}, {spread}");
        }
    }
}

#[test]
fn attack_slope_and_groove_grow_as_the_sampling_interval_shrinks() {
    // One surface sampled at 4, 2 and 1 µm (docs/friction-models.md has the table).
    let fine = surface(512, 3, None);
    let mut rows = Vec::new();
    for step in [4usize, 2, 1] {
        let z = fine.slice(s![..;step, ..;step]).to_owned();
        let contact = Contact::solve(z, SIDE / 512.0 * step as f64);
        let tilt = contact.load_mean(|_, s| s.gradient.map(|g| g.0.hypot(g.1)));
        let attack = contact.load_mean(|_, s| s.attack_slope);
        let groove = contact.mu(DeformationLaw::GroovePloughing, 0.0) - 0.2;
        // The spots of a plastic truncation sit on summits: their junction planes are nearly
        // level, far flatter than their flanks.
        assert!(tilt < 0.25 * attack, "tilt {tilt}, attack {attack}");
        rows.push((attack, groove));
    }
    for pair in rows.windows(2) {
        assert!(pair[1].0 > pair[0].0 && pair[1].1 > pair[0].1, "{rows:?}");
    }
}
