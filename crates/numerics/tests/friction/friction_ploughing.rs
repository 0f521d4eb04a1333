//! The deformation part of friction through the production path of a study, with both bodies:
//! `per_spot_friction` on a contact section of a lower and an upper body, the `ploughing` law
//! built from the registry (`ploughing_support`). Closed forms of a hard cone and a hard sphere on a soft flat, the
//! swapped pair, equal bodies and the hardness swap; the closed-form laws themselves; the loaded
//! front (ψ and ψ + π differ on a skewed cone, 0 and 2π agree); the regime of penetration.

use crate::ploughing_support::{parts, ploughing, rel, Pair, DX, DY, H, HARD};
use asperity_numerics::friction::laws::ploughing::closed_forms::{
    cone_ploughing, sphere_ploughing,
};
use asperity_numerics::friction::BodyHardness;
use ndarray::Array2;
use std::f64::consts::{FRAC_2_PI, PI};

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

/// Physical position `(x, y)` of `(iy, ix)` relative to `centre`.
fn position(iy: usize, ix: usize, centre: (usize, usize)) -> (f64, f64) {
    (
        (ix as f64 - centre.1 as f64) * DX,
        (iy as f64 - centre.0 as f64) * DY,
    )
}

/// The heights `z(x, y)` on `shape` around `centre`.
fn heights(
    shape: (usize, usize),
    centre: (usize, usize),
    z: impl Fn(f64, f64) -> f64,
) -> Array2<f64> {
    Array2::from_shape_fn(shape, |(iy, ix)| {
        let (x, y) = position(iy, ix, centre);
        z(x, y)
    })
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

const SHAPE: (usize, usize) = (90, 120);
const CENTRE: (usize, usize) = (44, 61);

/// A hard cone of attack slope `attack` (apex at the centre, pointing at the other body) as the
/// upper body on a soft flat lower body, in contact over a disc of radius 40 µm.
fn cone_on_flat(attack: f64, skew: f64, hardness: BodyHardness) -> Pair {
    Pair {
        lower: Array2::zeros(SHAPE),
        upper: heights(SHAPE, CENTRE, |x, y| 2e-5 - x.hypot(y) * attack + skew * x),
        cells: cells_where(SHAPE, CENTRE, |x, y| x.hypot(y) <= 40e-6),
        hardness,
        periodic: false,
    }
}

const UPPER_HARDER: BodyHardness = BodyHardness {
    lower: H,
    upper: HARD,
};

#[test]
fn a_hard_cone_on_a_soft_flat_ploughs_as_the_textbook_cone() {
    let attack = 12f64.to_radians().tan();
    let pair = cone_on_flat(attack, 0.0, UPPER_HARDER);
    let expected = FRAC_2_PI * attack;
    let cone = pair.friction(&*ploughing("cone", 0.0, 1.0));
    let geometry = cone.geometry.as_ref().unwrap();
    assert_eq!(geometry.ploughing.name(), "upper");
    // Every front boundary point lies on the cone: tan α to rounding, the cone law exact.
    let (mu_d, mu_s) = parts(&cone);
    assert!(rel(mu_d, expected) < 1e-12, "{mu_d} vs {expected}");
    assert!(rel(mu_s, 0.2 + expected) < 1e-12);
    // The groove of the front's cap, a third of a pixel sampled: within 2e-3 in any direction.
    for psi in [0.0, 0.5, PI / 2.0, 4.0] {
        let (groove, _) = parts(&pair.friction(&*ploughing("groove", psi, 1.0)));
        assert!(rel(groove, expected) < 2e-3, "ψ = {psi}: {groove}");
    }
    // The baseline: (2/π) × the rms slope along ψ of the cone over the section.
    assert!(geometry.slope_baseline > 0.0);
}

#[test]
fn the_swapped_pair_with_the_direction_reversed_ploughs_the_same() {
    let attack = 8f64.to_radians().tan();
    let pair = cone_on_flat(attack, 0.02, UPPER_HARDER);
    let swapped = pair.swapped();
    for law in ["groove", "cone", "sphere"] {
        for psi in [0.0, 0.7, 2.0] {
            let (d, s) = parts(&pair.friction(&*ploughing(law, psi, 1.0)));
            let (d2, s2) = parts(&swapped.friction(&*ploughing(law, psi + PI, 1.0)));
            assert!(
                rel(s2, s) < 1e-6 && (d2 - d).abs() < 1e-6 * s,
                "{law} ψ = {psi}: {s} vs {s2}"
            );
        }
    }
}

#[test]
fn equal_bodies_share_the_deformation_part_and_a_soft_asperity_ploughs_nothing() {
    let attack = 12f64.to_radians().tan();
    let expected = FRAC_2_PI * attack;
    // Equal hardness: the cone ploughs with half the load's deformation part, the flat with none.
    let equal = BodyHardness { lower: H, upper: H };
    let (mu_d, _) =
        parts(&cone_on_flat(attack, 0.0, equal).friction(&*ploughing("cone", 0.0, 1.0)));
    assert!(rel(mu_d, 0.5 * expected) < 1e-12, "{mu_d}");
    // A soft cone on a hard flat: the flat ploughs and it has no asperity.
    let soft_cone = BodyHardness {
        lower: HARD,
        upper: H,
    };
    let flat = cone_on_flat(attack, 0.0, soft_cone).friction(&*ploughing("groove", 0.0, 1.0));
    assert_eq!(flat.geometry.as_ref().unwrap().ploughing.name(), "lower");
    assert_eq!(parts(&flat).0, 0.0);
    assert_eq!(flat.geometry.unwrap().slope_baseline, 0.0);
}

#[test]
fn a_hard_sphere_ploughs_as_the_textbook_sphere() {
    let (shape, centre) = ((100, 140), (50, 70));
    let (radius, a) = (4e-4, 40e-6);
    let pair = Pair {
        lower: Array2::zeros(shape),
        upper: heights(shape, centre, |x, y| {
            (radius * radius - x * x - y * y).sqrt()
        }),
        cells: cells_where(shape, centre, |x, y| x.hypot(y) <= a),
        hardness: UPPER_HARDER,
        periodic: false,
    };
    let expected = sphere_ploughing(a / radius).unwrap();
    // a_f from the front's pixel count and R of the sphere through the tip and the front
    // boundary (half a pixel inside and outside the disc's edge): within 2 %.
    for psi in [0.0, PI / 2.0] {
        let (mu, _) = parts(&pair.friction(&*ploughing("sphere", psi, 1.0)));
        assert!(rel(mu, expected) < 0.02, "ψ = {psi}: {mu} vs {expected}");
        let (groove, _) = parts(&pair.friction(&*ploughing("groove", psi, 1.0)));
        assert!(rel(groove, expected) < 2e-3, "ψ = {psi}: groove {groove}");
    }
}

#[test]
fn the_loaded_front_tells_a_skewed_cone_forward_from_backward() {
    // z = h − r tan α + c x: along +x the flank falls by tan α − c, along −x by tan α + c.
    let (attack, skew) = (0.2, 0.1);
    let pair = cone_on_flat(attack, skew, UPPER_HARDER);
    for law in ["groove", "cone", "sphere"] {
        let forward = parts(&pair.friction(&*ploughing(law, 0.0, 1.0))).0;
        let backward = parts(&pair.friction(&*ploughing(law, PI, 1.0))).0;
        let around = parts(&pair.friction(&*ploughing(law, 2.0 * PI, 1.0))).0;
        // The upper body slides along +x: its front is the shallow side.
        assert!(backward > 1.2 * forward, "{law}: {forward} vs {backward}");
        assert!(rel(around, forward) < 1e-12, "{law}: 0 and 2π");
    }
    // The cone's front slope, exact: the mean over the front boundary of tan α − c cos θ.
    let forward = parts(&pair.friction(&*ploughing("cone", 0.0, 1.0))).0;
    assert!(forward < FRAC_2_PI * attack && forward > FRAC_2_PI * (attack - skew));
}

#[test]
fn a_penetration_beyond_the_limit_is_outside_the_ploughing_regime() {
    // A cone's degree of penetration is its attack slope (cap height over front radius).
    for (attack, outside) in [(0.05, false), (0.3, true)] {
        let found = cone_on_flat(attack, 0.0, UPPER_HARDER).friction(&*ploughing("cone", 0.0, 0.1));
        let r = &found.result;
        assert_eq!(r.load_outside_regime > 0.0, outside, "tan α = {attack}");
        let penetration = r.spots[0].penetration.unwrap();
        assert!(
            (penetration - attack).abs() < 0.02 * attack,
            "{penetration}"
        );
        assert!(rel(parts(&found).0, cone_ploughing(attack)) < 1e-12);
    }
}

#[test]
fn an_elongated_hard_cap_ploughs_twice_as_hard_across_its_length() {
    // z = −x²/(2Rx) − y²/(2Ry) above −h: semi-axes a = √(2hR), and each direction ploughs as the
    // section's sphere, μ = 4a/(3πR) exactly: along x 0.0424, across 0.0849.
    let (shape, centre) = ((60, 110), (30, 55));
    let (rx, ry, h) = (4e-4, 1e-4, 2e-6);
    let pair = Pair {
        lower: Array2::zeros(shape),
        upper: heights(shape, centre, |x, y| {
            -x * x / (2.0 * rx) - y * y / (2.0 * ry)
        }),
        cells: cells_where(shape, centre, |x, y| {
            x * x / (2.0 * rx) + y * y / (2.0 * ry) <= h
        }),
        hardness: UPPER_HARDER,
        periodic: false,
    };
    let law = |a: f64, r: f64| 4.0 * a / (3.0 * PI * r);
    let (mu_x, _) = parts(&pair.friction(&*ploughing("groove", 0.0, 1.0)));
    let (mu_y, _) = parts(&pair.friction(&*ploughing("groove", PI / 2.0, 1.0)));
    // The short semi-axis spans 13 rows: within 1.5 %.
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
