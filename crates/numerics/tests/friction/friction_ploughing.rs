//! The deformation part of friction: the ploughing and inclined-junction laws against their
//! closed forms and the reference's check values, each spot's plane, tilt and attack slope on
//! shapes where they are known exactly, and a rigid–perfectly-plastic sphere, cone and inclined
//! flat through the whole per-spot chain (spots, slopes, adhesion part, deformation part).

use asperity_numerics::friction::contact_spots::{label_spots, measure_spots, Connectivity};
use asperity_numerics::friction::laws::ploughing::closed_forms::{
    cone_ploughing, sphere_ploughing, tilted_junction,
};
use asperity_numerics::friction::{
    deformation_friction, per_spot_friction, spot_slopes, DeformationLaw, DeformationResult,
    DeformationSpot, JunctionShear, SlidingDirection, SpotLoad, SpotSlope,
};
use ndarray::Array2;
use std::f64::consts::{FRAC_2_PI, PI};

const DX: f64 = 1.0e-6;
const DY: f64 = 1.5e-6;
/// Flow pressure of the rigid–perfectly-plastic flat (Pa) and interfacial shear strength: the
/// adhesion part of junction shear is then τ/H = 0.2 on every spot.
const H: f64 = 3.0e9;
const TAU: f64 = 0.2 * H;

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

#[test]
fn cone_ploughing_is_two_over_pi_tan_alpha() {
    // Reference check value: α = 5° gives 0.0557.
    assert!((cone_ploughing(5f64.to_radians().tan()) - 0.0557).abs() < 5e-5);
    for deg in [1.0f64, 10.0, 30.0, 60.0] {
        let t = deg.to_radians().tan();
        // One product: the law and the expression agree to the last bit.
        assert_eq!(cone_ploughing(t), 2.0 / PI * t);
    }
    assert_eq!(cone_ploughing(0.0), 0.0);
}

/// The groove cross-section over half the projected area, evaluated as the circular segment.
fn sphere_by_segment(a: f64, r: f64) -> f64 {
    let segment = r * r * (a / r).asin() - a * (r * r - a * a).sqrt();
    segment / (PI * a * a / 2.0)
}

#[test]
fn sphere_ploughing_matches_the_segment_and_its_small_contact_limit() {
    for x in [0.02, 0.1, 0.5, 0.9] {
        // Two algebraically equal forms; rounding of either is below 1e-15/x².
        let mu = sphere_ploughing(x).unwrap();
        assert!(
            rel(mu, sphere_by_segment(x * 3e-5, 3e-5)) < 1e-12,
            "a/R = {x}"
        );
    }
    assert!(
        rel(sphere_ploughing(1.0).unwrap(), 1.0) < 1e-15,
        "a hemisphere gives 1"
    );
    // Series and closed form meet at a/R = 0.01: the series' first omitted term is
    // (2/π)·(5/72)·x⁷ ≈ 4e-16 against μ ≈ 4e-3, the closed form loses ~1e-12 to cancellation.
    let (below, above) = (sphere_ploughing(0.01 - 1e-15), sphere_ploughing(0.01));
    assert!(rel(below.unwrap(), above.unwrap()) < 1e-11);
    // μ/(4x/(3π)) = 1 + 3x²/10 + O(x⁴).
    for x in [1e-3, 3e-3, 0.02] {
        let ratio = sphere_ploughing(x).unwrap() / (4.0 * x / (3.0 * PI));
        assert!((ratio - 1.0 - 0.3 * x * x).abs() < x.powi(4), "a/R = {x}");
    }
    assert!(rel(sphere_ploughing(1e-9).unwrap(), 4e-9 / (3.0 * PI)) < 1e-15);
    assert_eq!(sphere_ploughing(0.0), Some(0.0));
    for outside in [-1e-3, 1.0 + 1e-12, f64::NAN] {
        assert_eq!(sphere_ploughing(outside), None);
    }
}

#[test]
fn tilted_junction_is_the_inclined_plane() {
    let five = 5f64.to_radians();
    // Reference check value: μ_a = 0.2, θ = 5° up-slope gives 0.2926.
    let up = tilted_junction(0.2, five.tan()).unwrap();
    assert!((up - 0.2926).abs() < 5e-5);
    // tan(φ ± θ) by the angle sum: a few roundings apart.
    let phi = 0.2f64.atan();
    assert!(rel(up, (phi + five).tan()) < 1e-14);
    let down = tilted_junction(0.2, -five.tan()).unwrap();
    assert!(rel(down, (phi - five).tan()) < 1e-14);
    // A down-slope junction steeper than the friction angle pushes forward.
    assert!(tilted_junction(0.2, -0.3).unwrap() < 0.0);
    assert_eq!(
        tilted_junction(0.2, 0.0),
        Some(0.2),
        "zero slope: adhesion alone"
    );
    // φ + θ ≥ 90°: the junction locks, tan has no finite value.
    assert!(tilted_junction(0.2, 4.9).is_some());
    assert_eq!(tilted_junction(0.2, 5.0), None);
    assert_eq!(tilted_junction(0.2, 6.0), None);
}

/// A rigid–perfectly-plastic contact of the composite height `z`: pressure `H` on `cells`.
struct Section {
    z: Array2<f64>,
    cells: Vec<(usize, usize)>,
    periodic: bool,
}

impl Section {
    fn pressure(&self) -> Array2<f64> {
        let mut p = Array2::zeros(self.z.dim());
        for &c in &self.cells {
            p[c] = H;
        }
        p
    }

    fn slopes(&self, psi: f64) -> Vec<SpotSlope> {
        let p = self.pressure();
        let labels = label_spots(p.view(), self.periodic, Connectivity::Eight).unwrap();
        let spots = measure_spots(&labels, p.view(), self.z.view(), DX, DY).unwrap();
        let direction = SlidingDirection::new(psi).unwrap();
        spot_slopes(&labels, &spots, self.z.view(), (DX, DY), direction).unwrap()
    }

    /// Junction shear as the adhesion part, `law` as the deformation part, sliding along `psi`.
    fn friction(&self, law: DeformationLaw, psi: f64) -> DeformationResult {
        let p = self.pressure();
        let labels = label_spots(p.view(), self.periodic, Connectivity::Eight).unwrap();
        let spots = measure_spots(&labels, p.view(), self.z.view(), DX, DY).unwrap();
        let slopes = self.slopes(psi);
        let loads: Vec<SpotLoad> = spots.iter().map(SpotLoad::from).collect();
        let shear = JunctionShear::new(1.0, TAU).unwrap();
        let adhesion = per_spot_friction(&loads, &shear, 0.0).unwrap();
        let input: Vec<DeformationSpot> = spots
            .iter()
            .zip(&slopes)
            .zip(&adhesion.spots)
            .map(|((spot, slope), a)| DeformationSpot {
                load: spot.load,
                area: spot.area,
                radius: spot.radius,
                tilt: slope.tilt,
                attack_slope: slope.attack_slope,
                groove_ratio: slope.groove_ratio,
                adhesion_friction: a.friction_force,
            })
            .collect();
        deformation_friction(&input, law, 0.0).unwrap()
    }
}

/// Physical position `(x, y)` of `(iy, ix)` relative to `centre`.
fn position(iy: usize, ix: usize, centre: (usize, usize)) -> (f64, f64) {
    (
        (ix as f64 - centre.1 as f64) * DX,
        (iy as f64 - centre.0 as f64) * DY,
    )
}

/// The grid points with `inside(x, y)`.
fn cells_where(
    shape: (usize, usize),
    centre: (usize, usize),
    inside: impl Fn(f64, f64) -> bool,
) -> Vec<(usize, usize)> {
    let mut cells = Vec::new();
    for iy in 0..shape.0 {
        for ix in 0..shape.1 {
            let (x, y) = position(iy, ix, centre);
            if inside(x, y) {
                cells.push((iy, ix));
            }
        }
    }
    cells
}

#[test]
fn rigid_plastic_cone_ploughs_as_the_textbook_cone() {
    let (shape, centre) = ((90, 120), (44, 61));
    let attack = 12f64.to_radians().tan();
    let z = Array2::from_shape_fn(shape, |(iy, ix)| {
        let (x, y) = position(iy, ix, centre);
        2e-5 - x.hypot(y) * attack
    });
    let a = 40e-6;
    let section = Section {
        cells: cells_where(shape, centre, |x, y| x.hypot(y) <= a),
        z,
        periodic: false,
    };
    let slopes = section.slopes(0.0);
    assert_eq!(slopes.len(), 1);
    // Every edge and ring point lies on the cone: the ratio of means is tan α up to rounding.
    assert!(rel(slopes[0].attack_slope.unwrap(), attack) < 1e-12);
    // The cap's height is the drop to the boundary, half a pixel outside the edge on average.
    let cap = slopes[0].cap_height.unwrap() / attack;
    assert!(
        cap > a - 1e-6 && cap < a + 1e-6,
        "boundary at {cap} m, disc radius {a} m"
    );
    // The symmetric footprint has no tilt (rounding of the fit only).
    let (gx, gy) = slopes[0].gradient.unwrap();
    assert!(gx.abs() < 1e-12 && gy.abs() < 1e-12);
    let result = section.friction(DeformationLaw::ConePloughing, 0.0);
    assert!(rel(result.mu_deformation.unwrap(), FRAC_2_PI * attack) < 1e-12);
    // The groove of the cap, sampled at a third of a pixel with bilinear heights above the
    // boundary level half a pixel from the edge of a 40-pixel disc: within 2e-3 in any direction
    // (measured 2.5e-4 along the axes, 8e-4 at 0.5 rad).
    for psi in [0.0, 0.5, PI / 2.0] {
        let groove = section.friction(DeformationLaw::GroovePloughing, psi);
        assert!(
            rel(groove.mu_deformation.unwrap(), FRAC_2_PI * attack) < 2e-3,
            "ψ = {psi}"
        );
    }
    assert!(rel(result.mu_adhesion.unwrap(), 0.2) < 1e-12);
    assert!(rel(result.mu_s.unwrap(), 0.2 + FRAC_2_PI * attack) < 1e-12);
}

#[test]
fn rigid_plastic_sphere_ploughs_as_the_textbook_sphere() {
    let (shape, centre) = ((100, 140), (50, 70));
    let (radius, a) = (4e-4, 40e-6);
    let z = Array2::from_shape_fn(shape, |(iy, ix)| {
        let (x, y) = position(iy, ix, centre);
        (radius * radius - x * x - y * y).sqrt()
    });
    let section = Section {
        cells: cells_where(shape, centre, |x, y| x.hypot(y) <= a),
        z,
        periodic: false,
    };
    let result = section.friction(DeformationLaw::SpherePloughing, 0.0);
    let expected = sphere_ploughing(a / radius).unwrap();
    // a from the pixel count of a disc 40 × 27 pixels wide (area within 0.5 %), R from the
    // paraboloid fitted to a sphere (its r⁴/(8R³) term shifts R by ~(a/R)² = 1 %): within 2 %.
    let mu = result.mu_deformation.unwrap();
    assert!(rel(mu, expected) < 0.02, "μ_p = {mu}, textbook {expected}");
    assert_eq!(result.spots_without_geometry, 0);
    // The cap's own groove needs no radius: within 2e-3 as for the cone (measured 4e-4–7e-4).
    for psi in [0.0, 0.5, PI / 2.0] {
        let groove = section.friction(DeformationLaw::GroovePloughing, psi);
        assert!(
            rel(groove.mu_deformation.unwrap(), expected) < 2e-3,
            "ψ = {psi}"
        );
    }
}

#[test]
fn elongated_cap_ploughs_twice_as_hard_across_its_length() {
    // z = −x²/(2Rx) − y²/(2Ry) above −h: semi-axes a = √(2hR), and each direction ploughs as the
    // section's sphere, μ = 4a/(3πR) exactly: along x 0.0424, across 0.0849.
    let (shape, centre) = ((60, 110), (30, 55));
    let (rx, ry, h) = (4e-4, 1e-4, 2e-6);
    let z = Array2::from_shape_fn(shape, |(iy, ix)| {
        let (x, y) = position(iy, ix, centre);
        -x * x / (2.0 * rx) - y * y / (2.0 * ry)
    });
    let section = Section {
        cells: cells_where(shape, centre, |x, y| {
            x * x / (2.0 * rx) + y * y / (2.0 * ry) <= h
        }),
        z,
        periodic: false,
    };
    let law = |a: f64, r: f64| 4.0 * a / (3.0 * PI * r);
    let along = section.friction(DeformationLaw::GroovePloughing, 0.0);
    let across = section.friction(DeformationLaw::GroovePloughing, PI / 2.0);
    let (mu_x, mu_y) = (
        along.mu_deformation.unwrap(),
        across.mu_deformation.unwrap(),
    );
    // The short semi-axis spans 13 rows: within 1.5 % (measured +0.4 % and +0.6 %).
    assert!(
        rel(mu_x, law((2.0 * h * rx).sqrt(), rx)) < 0.015,
        "along: {mu_x}"
    );
    assert!(
        rel(mu_y, law((2.0 * h * ry).sqrt(), ry)) < 0.015,
        "across: {mu_y}"
    );
    assert!(rel(mu_y / mu_x, 2.0) < 0.01);
}

#[test]
fn inclined_flat_junction_gives_the_tilted_junction_law_in_every_direction() {
    let (shape, centre) = ((40, 50), (20, 24));
    let (sx, sy) = (0.08, -0.03);
    let z = Array2::from_shape_fn(shape, |(iy, ix)| {
        let (x, y) = position(iy, ix, centre);
        1e-5 + sx * x + sy * y
    });
    let section = Section {
        cells: cells_where(shape, centre, |x, y| x.hypot(y) <= 8e-6),
        z,
        periodic: false,
    };
    let slope = section.slopes(0.0)[0];
    let (gx, gy) = slope.gradient.unwrap();
    assert!(
        rel(gx, sx) < 1e-10 && rel(gy, sy) < 1e-10,
        "plane exact: {gx}, {gy}"
    );
    assert!(!slope.dilated);
    for psi in [0.0, 0.7, PI / 2.0, PI, 4.0] {
        let tilt = sx * psi.cos() + sy * psi.sin();
        let mu = section.friction(DeformationLaw::TiltedJunction, psi);
        let expected = (0.2 + tilt) / (1.0 - 0.2 * tilt);
        assert!(rel(mu.mu_s.unwrap(), expected) < 1e-10, "ψ = {psi}");
        assert!((mu.mu_deformation.unwrap() - (expected - 0.2)).abs() < 1e-10);
    }
}

#[test]
fn zero_slope_gives_the_adhesion_part_alone() {
    let (shape, centre) = ((30, 30), (15, 15));
    let section = Section {
        z: Array2::from_elem(shape, 2e-6),
        cells: cells_where(shape, centre, |x, y| x.hypot(y) <= 6e-6),
        periodic: true,
    };
    for law in [
        DeformationLaw::TiltedJunction,
        DeformationLaw::ConePloughing,
    ] {
        let result = section.friction(law, 1.1);
        assert_eq!(result.deformation_friction, 0.0);
        assert_eq!(result.mu_s, result.mu_adhesion);
        assert!(rel(result.mu_s.unwrap(), 0.2) < 1e-12);
    }
    // A flat has no convex radius: the sphere law has no geometry and says so.
    let sphere = section.friction(DeformationLaw::SpherePloughing, 0.0);
    assert_eq!(sphere.spots_without_geometry, 1);
    assert_eq!(sphere.load_without_geometry, sphere.total_normal_force);
    assert_eq!(sphere.mu_s, sphere.mu_adhesion);
}

#[test]
fn collinear_footprints_are_fitted_with_their_ring() {
    let (shape, centre) = ((20, 24), (10, 12));
    let (sx, sy) = (0.05, 0.02);
    let z = Array2::from_shape_fn(shape, |(iy, ix)| {
        let (x, y) = position(iy, ix, centre);
        sx * x + sy * y
    });
    let plane = |cells: Vec<(usize, usize)>| {
        let section = Section {
            z: z.clone(),
            cells,
            periodic: false,
        };
        section.slopes(0.0)[0]
    };
    let one = plane(vec![centre]);
    assert_eq!((one.plane_points, one.dilated), (9, true));
    let line = plane((8..13).map(|ix| (10, ix)).collect());
    assert_eq!((line.plane_points, line.dilated), (21, true));
    let diagonal = plane((0..4).map(|k| (8 + k, 9 + k)).collect());
    assert!(diagonal.dilated);
    let block = plane(vec![(10, 12), (10, 13), (11, 12), (11, 13)]);
    assert_eq!((block.plane_points, block.dilated), (4, false));
    for slope in [one, line, diagonal, block] {
        let (gx, gy) = slope.gradient.unwrap();
        assert!(rel(gx, sx) < 1e-10 && rel(gy, sy) < 1e-10);
    }
    // A corner pixel of an open grid: its clipped ring still spans a plane.
    let corner = plane(vec![(0, 0)]);
    assert_eq!((corner.plane_points, corner.dilated), (4, true));
    assert!(rel(corner.gradient.unwrap().0, sx) < 1e-10);
}

#[test]
fn spots_outside_the_range_of_a_law_are_counted() {
    let spot = |radius: Option<f64>, tilt: Option<f64>| DeformationSpot {
        load: 2.0,
        area: PI * 1e-10,
        radius,
        tilt,
        attack_slope: Some(0.1),
        groove_ratio: Some(0.1),
        adhesion_friction: 0.4,
    };
    // a = 1e-5 m above R = 5e-6 m: no spherical cap; μ_a·tan θ ≥ 1: a locked junction.
    let spots = [spot(Some(5e-6), Some(6.0)), spot(Some(1e-4), Some(0.1))];
    let sphere = deformation_friction(&spots, DeformationLaw::SpherePloughing, 0.0).unwrap();
    assert_eq!(
        (sphere.spots_out_of_range, sphere.load_out_of_range),
        (1, 2.0)
    );
    let expected = sphere_ploughing(0.1).unwrap() * 2.0 / 4.0;
    assert!(rel(sphere.mu_deformation.unwrap(), expected) < 1e-15);
    let tilted = deformation_friction(&spots, DeformationLaw::TiltedJunction, 0.0).unwrap();
    assert_eq!(tilted.spots_out_of_range, 1);
    assert!(rel(tilted.mu_adhesion.unwrap(), 0.2) < 1e-15);
    // The denominator is Σ P − F_a: no coefficient once adhesion pulls harder than the load.
    let pulled = deformation_friction(&spots, DeformationLaw::ConePloughing, 4.0).unwrap();
    assert_eq!(pulled.mu_s, None);
    let bad = DeformationSpot {
        attack_slope: Some(-0.1),
        ..spot(None, None)
    };
    assert!(deformation_friction(&[bad], DeformationLaw::ConePloughing, 0.0).is_err());
    assert!(SlidingDirection::new(f64::NAN).is_err());
}
