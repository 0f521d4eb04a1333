//! Contact spots of a solved contact: labelling (wrap-around, connectivity, deterministic ids
//! against a flood-fill reference), per-spot sums, the paraboloid radius (exact for quadratic
//! heights), and the Lennard-Jones adhesion of the gap.

use asperity_numerics::friction::contact_spots::{
    adhesion_from_gap, contact_spots, label_spots, measure_spots, Connectivity, ContactSpot,
    SpotLabels,
};
use asperity_numerics::friction::{AdhesionParameters, FrictionError};
use ndarray::Array2;
use std::collections::VecDeque;

const DX: f64 = 1.0e-6;
const DY: f64 = 1.5e-6;

/// Minimum-image offset on a periodic axis of `n` points, plain otherwise.
fn image(d: isize, n: usize, periodic: bool) -> isize {
    let n = n as isize;
    let r = d.rem_euclid(n);
    match (periodic, 2 * r > n) {
        (false, _) => d,
        (true, true) => r - n,
        (true, false) => r,
    }
}

/// Heights `z0 + tx x + ty y − (a x² + b x y + c y²)` about the point `(cy, cx)` (x, y in metres).
#[derive(Clone, Copy)]
struct Quadric {
    a: f64,
    b: f64,
    c: f64,
    tilt: (f64, f64),
    periodic: bool,
}

impl Quadric {
    fn round(radius: f64, periodic: bool) -> Self {
        let a = 1.0 / (2.0 * radius);
        Self {
            a,
            b: 0.0,
            c: a,
            tilt: (0.0, 0.0),
            periodic,
        }
    }

    fn heights(self, shape: (usize, usize), centre: (usize, usize)) -> Array2<f64> {
        Array2::from_shape_fn(shape, |(iy, ix)| {
            let x = image(ix as isize - centre.1 as isize, shape.1, self.periodic) as f64 * DX;
            let y = image(iy as isize - centre.0 as isize, shape.0, self.periodic) as f64 * DY;
            3e-6 + self.tilt.0 * x + self.tilt.1 * y
                - (self.a * x * x + self.b * x * y + self.c * y * y)
        })
    }
}

/// Pressure 10⁶ (k + 1) Pa on the k-th point of `cells`, 0 elsewhere.
fn pressure_on(shape: (usize, usize), cells: &[(usize, usize)]) -> Array2<f64> {
    let mut p = Array2::zeros(shape);
    for (k, &cell) in cells.iter().enumerate() {
        p[cell] = 1.0e6 * (1.0 + k as f64);
    }
    p
}

/// The points within `r` pixels of `centre` (minimum image when periodic).
fn disc(
    shape: (usize, usize),
    centre: (usize, usize),
    r: f64,
    periodic: bool,
) -> Vec<(usize, usize)> {
    let mut cells = Vec::new();
    for iy in 0..shape.0 {
        for ix in 0..shape.1 {
            let x = image(ix as isize - centre.1 as isize, shape.1, periodic) as f64;
            let y = image(iy as isize - centre.0 as isize, shape.0, periodic) as f64;
            if x * x + y * y <= r * r {
                cells.push((iy, ix));
            }
        }
    }
    cells
}

fn spots(cells: &[(usize, usize)], z: &Array2<f64>, periodic: bool) -> Vec<ContactSpot> {
    let p = pressure_on(z.dim(), cells);
    contact_spots(p.view(), z.view(), DX, DY, periodic, Connectivity::Eight).unwrap()
}

fn assert_radius(spot: &ContactSpot, expected: f64) {
    let r = spot.radius.expect("a convex spot has a radius");
    assert!(
        ((r - expected) / expected).abs() < 1e-9,
        "R = {r}, expected {expected}"
    );
}

#[test]
fn paraboloid_radius_is_recovered() {
    let q = Quadric::round(2e-4, false);
    let (shape, centre) = ((48, 64), (20, 30));
    let cells = disc(shape, centre, 6.0, false);
    let found = spots(&cells, &q.heights(shape, centre), false);
    assert_eq!(found.len(), 1);
    let spot = found[0];
    assert_eq!(spot.pixels, cells.len());
    assert_eq!(spot.peak, centre);
    assert!((spot.area - cells.len() as f64 * DX * DY).abs() < 1e-24);
    assert!(spot.radius_points > spot.pixels);
    assert_radius(&spot, 2e-4);
}

#[test]
fn tilted_rotated_anisotropic_paraboloid_gives_the_mean_curvature() {
    let q = Quadric {
        a: 1.0 / (2.0 * 1e-4),
        b: 1.5e3,
        c: 1.0 / (2.0 * 4e-4),
        tilt: (0.02, -0.01),
        periodic: false,
    };
    let (shape, centre) = ((40, 40), (18, 21));
    let found = spots(
        &disc(shape, centre, 7.0, false),
        &q.heights(shape, centre),
        false,
    );
    assert_eq!(found.len(), 1);
    // R = 2 Rx Ry / (Rx + Ry) without the cross and tilt terms, which change no mean curvature.
    assert_radius(&found[0], 2.0 * 1e-4 * 4e-4 / 5e-4);
    assert_ne!(
        found[0].peak, centre,
        "the tilt moves the highest point of the spot"
    );
}

#[test]
fn one_pixel_spot_is_fitted_over_its_3x3_neighbourhood() {
    let q = Quadric::round(5e-5, false);
    let found = spots(&[(10, 12)], &q.heights((20, 24), (10, 12)), false);
    assert_eq!((found[0].pixels, found[0].radius_points), (1, 9));
    assert_radius(&found[0], 5e-5);
}

#[test]
fn line_of_pixels_is_not_degenerate() {
    let q = Quadric::round(5e-5, false);
    let cells: Vec<_> = (8..13).map(|ix| (6, ix)).collect();
    let found = spots(&cells, &q.heights((16, 24), (6, 10)), false);
    assert_eq!((found[0].pixels, found[0].radius_points), (5, 21));
    assert_radius(&found[0], 5e-5);
}

#[test]
fn corner_pixel_is_singular_on_an_open_grid_and_wraps_on_a_periodic_one() {
    let open = spots(
        &[(0, 0)],
        &Quadric::round(5e-5, false).heights((8, 8), (0, 0)),
        false,
    );
    assert_eq!(open[0].radius_points, 4);
    assert_eq!(open[0].radius, None);
    let wrapped = spots(
        &[(0, 0)],
        &Quadric::round(5e-5, true).heights((8, 8), (0, 0)),
        true,
    );
    assert_eq!(wrapped[0].radius_points, 9);
    assert_radius(&wrapped[0], 5e-5);
}

#[test]
fn saddle_with_positive_mean_curvature_has_no_radius() {
    let (shape, centre) = ((20, 20), (10, 10));
    let cells = disc(shape, centre, 3.0, false);
    let saddle = |a: f64, c: f64| Quadric {
        a,
        b: 0.0,
        c,
        tilt: (0.0, 0.0),
        periodic: false,
    };
    // z = −a x² + |c| y²: κ = −(a + c) ≥ 0 when the upward bend dominates.
    let convex_saddle = spots(&cells, &saddle(1e3, -2e3).heights(shape, centre), false);
    assert_eq!(convex_saddle[0].radius, None);
    let bowl = spots(&cells, &saddle(-1e3, -1e3).heights(shape, centre), false);
    assert_eq!(bowl[0].radius, None);
    // The same saddle with the downward bend dominating keeps a (positive) radius.
    let capped = spots(&cells, &saddle(2e3, -1e3).heights(shape, centre), false);
    assert_radius(&capped[0], 1.0 / 1e3);
}

#[test]
fn spot_crossing_the_edges_is_one_spot_only_on_a_periodic_grid() {
    let shape = (12, 10);
    let across_x: Vec<_> = (3..7)
        .flat_map(|iy| [0, 1, 8, 9].map(|ix| (iy, ix)))
        .collect();
    let across_y: Vec<_> = [0, 11]
        .iter()
        .flat_map(|&iy| (4..6).map(move |ix| (iy, ix)))
        .collect();
    for cells in [across_x, across_y] {
        let p = pressure_on(shape, &cells);
        for connectivity in [Connectivity::Four, Connectivity::Eight] {
            let periodic = label_spots(p.view(), true, connectivity).unwrap();
            assert_eq!(periodic.count(), 1);
            let open = label_spots(p.view(), false, connectivity).unwrap();
            assert_eq!(open.count(), 2);
        }
    }
    // The radius of a wrapped spot uses minimum-image offsets.
    let (shape, centre) = ((24, 20), (12, 0));
    let found = spots(
        &disc(shape, centre, 4.0, true),
        &Quadric::round(1e-4, true).heights(shape, centre),
        true,
    );
    assert_eq!(found.len(), 1);
    assert_radius(&found[0], 1e-4);
}

#[test]
fn diagonal_neighbours_join_only_with_eight_connectivity() {
    let shape = (6, 7);
    let count = |cells: &[(usize, usize)], periodic, connectivity| {
        let p = pressure_on(shape, cells);
        label_spots(p.view(), periodic, connectivity)
            .unwrap()
            .count()
    };
    for pair in [[(2, 2), (3, 3)], [(2, 5), (3, 4)]] {
        assert_eq!(count(&pair, false, Connectivity::Four), 2);
        assert_eq!(count(&pair, false, Connectivity::Eight), 1);
    }
    for pair in [[(0, 0), (5, 6)], [(0, 6), (1, 0)], [(5, 3), (0, 4)]] {
        assert_eq!(count(&pair, true, Connectivity::Eight), 1, "{pair:?}");
        assert_eq!(count(&pair, true, Connectivity::Four), 2, "{pair:?}");
        assert_eq!(count(&pair, false, Connectivity::Eight), 2, "{pair:?}");
    }
}

/// xorshift64*: a small deterministic stream for the random masks.
fn random_stream(seed: u64) -> impl FnMut() -> u64 {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    move || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        s.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
}

#[test]
fn spot_sums_add_up_to_the_totals_exactly() {
    let mut next = random_stream(7);
    // Integer pressures and power-of-two spacings: every sum is exact in any order.
    let p = Array2::from_shape_fn((40, 50), |_| match next() % 10 {
        0..=3 => (next() % 1000) as f64,
        _ => 0.0,
    });
    let z = Array2::from_shape_fn((40, 50), |_| (next() % 1000) as f64 * 1e-9);
    let (dx, dy) = (0.5, 0.25);
    let found = contact_spots(p.view(), z.view(), dx, dy, true, Connectivity::Four).unwrap();
    assert!(found.len() > 10);
    let total: f64 = found.iter().map(|s| s.load).sum();
    assert_eq!(total, p.sum() * dx * dy);
    let pixels: usize = found.iter().map(|s| s.pixels).sum();
    assert_eq!(pixels, p.iter().filter(|&&v| v > 0.0).count());
    assert_eq!(
        found.iter().map(|s| s.max_pressure).fold(0.0, f64::max),
        p.fold(0.0, |a, &b| b.max(a))
    );
    let labels = label_spots(p.view(), true, Connectivity::Four).unwrap();
    for (id, spot) in found.iter().enumerate() {
        assert_eq!(labels.spot_at(spot.peak.0, spot.peak.1), Some(id));
        let highest = labels
            .labels()
            .indexed_iter()
            .filter(|&(_, &l)| l as usize == id)
            .map(|(at, _)| z[at])
            .fold(f64::MIN, f64::max);
        assert_eq!(z[spot.peak], highest);
    }
}

/// Components by breadth-first flood fill, numbered in raster order of their first point.
fn reference_labels(mask: &Array2<bool>, periodic: bool, eight: bool) -> Array2<u32> {
    let (ny, nx) = mask.dim();
    let mut out = Array2::from_elem((ny, nx), SpotLabels::OUTSIDE);
    let mut next = 0;
    let mut queue = VecDeque::new();
    let wrap = |i: usize, s: isize, n: usize| {
        let j = i as isize + s;
        match (0..n as isize).contains(&j) {
            true => Some(j as usize),
            false => periodic.then(|| j.rem_euclid(n as isize) as usize),
        }
    };
    for start in (0..ny).flat_map(|iy| (0..nx).map(move |ix| (iy, ix))) {
        if !mask[start] || out[start] != SpotLabels::OUTSIDE {
            continue;
        }
        out[start] = next;
        queue.push_back(start);
        while let Some((iy, ix)) = queue.pop_front() {
            for (sy, sx) in [
                (-1, -1),
                (-1, 0),
                (-1, 1),
                (0, -1),
                (0, 1),
                (1, -1),
                (1, 0),
                (1, 1),
            ] {
                if sy * sx != 0 && !eight {
                    continue;
                }
                if let (Some(y), Some(x)) = (wrap(iy, sy, ny), wrap(ix, sx, nx)) {
                    if mask[[y, x]] && out[[y, x]] == SpotLabels::OUTSIDE {
                        out[[y, x]] = next;
                        queue.push_back((y, x));
                    }
                }
            }
        }
        next += 1;
    }
    out
}

#[test]
fn labels_match_a_flood_fill_reference() {
    let mut next = random_stream(11);
    for (k, shape) in [(1, 1), (1, 9), (9, 1), (2, 2), (3, 5), (17, 23), (40, 31)]
        .iter()
        .cycle()
        .take(70)
        .enumerate()
    {
        let fill = 20 + (k as u64 * 13) % 60;
        let p = Array2::from_shape_fn(*shape, |_| if next() % 100 < fill { 1.0 } else { 0.0 });
        let mask = p.mapv(|v| v > 0.0);
        for periodic in [false, true] {
            for (connectivity, eight) in [(Connectivity::Four, false), (Connectivity::Eight, true)]
            {
                let labels = label_spots(p.view(), periodic, connectivity).unwrap();
                let reference = reference_labels(&mask, periodic, eight);
                assert_eq!(
                    labels.labels(),
                    reference.view(),
                    "{shape:?} periodic {periodic} eight {eight}"
                );
                let count = reference
                    .iter()
                    .filter(|&&l| l != SpotLabels::OUTSIDE)
                    .max()
                    .map_or(0, |&m| m as usize + 1);
                assert_eq!(labels.count(), count);
            }
        }
    }
}

#[test]
fn ids_follow_the_first_point_in_raster_order_after_wrapping() {
    // Spot W = {(5, 0), (5, 9)} joined across x; spot V = {(5, 3)} between its two halves.
    let p = pressure_on((8, 10), &[(5, 9), (5, 3), (5, 0), (7, 7), (0, 7)]);
    let labels = label_spots(p.view(), true, Connectivity::Four).unwrap();
    assert_eq!(labels.count(), 3);
    // (0, 7) is joined to (7, 7) across y and is the first point of all.
    assert_eq!(labels.spot_at(0, 7), Some(0));
    assert_eq!(labels.spot_at(7, 7), Some(0));
    assert_eq!(labels.spot_at(5, 0), Some(1));
    assert_eq!(labels.spot_at(5, 9), Some(1));
    assert_eq!(labels.spot_at(5, 3), Some(2));
    assert_eq!(labels.spot_at(1, 1), None);
    assert_eq!(
        labels,
        label_spots(p.view(), true, Connectivity::Four).unwrap()
    );
}

#[test]
fn empty_contact_gives_no_spots() {
    let p = Array2::from_elem((16, 16), 0.0);
    let z = Array2::from_elem((16, 16), 1e-6);
    assert!(
        contact_spots(p.view(), z.view(), DX, DY, true, Connectivity::Eight)
            .unwrap()
            .is_empty()
    );
    let none = Array2::<f64>::zeros((0, 5));
    assert_eq!(
        label_spots(none.view(), true, Connectivity::Eight)
            .unwrap()
            .count(),
        0
    );
}

#[test]
fn bad_shapes_spacings_and_heights_are_errors() {
    let p = pressure_on((6, 6), &[(2, 2)]);
    let z = Array2::zeros((6, 6));
    let labels = label_spots(p.view(), false, Connectivity::Four).unwrap();
    let short = Array2::zeros((6, 5));
    assert!(matches!(
        measure_spots(&labels, p.view(), short.view(), DX, DY),
        Err(FrictionError::ShapeMismatch {
            name: "composite_height",
            expected: (6, 6),
            found: (6, 5)
        })
    ));
    assert!(matches!(
        contact_spots(p.view(), z.view(), 0.0, DY, false, Connectivity::Four),
        Err(FrictionError::InvalidParameter { name: "dx", .. })
    ));
    let mut holed = z.clone();
    holed[[3, 3]] = f64::NAN;
    assert!(matches!(
        measure_spots(&labels, p.view(), holed.view(), DX, DY),
        Err(FrictionError::InvalidParameter {
            name: "composite_height",
            ..
        })
    ));
    holed[[3, 3]] = 0.0;
    holed[[4, 4]] = f64::NAN;
    assert!(
        measure_spots(&labels, p.view(), holed.view(), DX, DY).is_ok(),
        "outside the ring"
    );
}

/// σ(h) = (8Δγ/3ε) [(ε/h)³ − (ε/h)⁹].
fn sigma(h: f64, energy: f64, eps: f64) -> f64 {
    8.0 * energy / (3.0 * eps) * ((eps / h).powi(3) - (eps / h).powi(9))
}

#[test]
fn adhesion_of_a_uniform_gap_matches_the_closed_form() {
    let adhesion = AdhesionParameters::new(0.5, 0.158e-9).unwrap();
    let gap = Array2::from_shape_fn((30, 20), |(iy, _)| if iy < 3 { -1e-15 } else { 0.3e-9 });
    let p = pressure_on((30, 20), &[(10, 10), (11, 10), (25, 3)]);
    let force = adhesion_from_gap(gap.view(), p.view(), DX, DY, adhesion).unwrap();
    // 3 rows at zero gap attract nothing (σ(ε) = 0); 3 points in contact do not count.
    let expected = (27.0 * 20.0 - 3.0) * sigma(0.158e-9 + 0.3e-9, 0.5, 0.158e-9) * DX * DY;
    assert!(
        ((force - expected) / expected).abs() < 1e-12,
        "{force} vs {expected}"
    );
    let off = AdhesionParameters::new(0.0, 0.158e-9).unwrap();
    assert_eq!(
        adhesion_from_gap(gap.view(), p.view(), DX, DY, off).unwrap(),
        0.0
    );
    let mut holed = gap.clone();
    holed[[20, 5]] = f64::NAN;
    assert!(adhesion_from_gap(holed.view(), p.view(), DX, DY, adhesion).is_err());
    holed[[20, 5]] = 0.3e-9;
    holed[[10, 10]] = f64::NAN;
    assert!(
        adhesion_from_gap(holed.view(), p.view(), DX, DY, adhesion).is_ok(),
        "in contact"
    );
}

#[test]
fn adhesion_over_a_gap_ramp_integrates_sigma_to_the_energy() {
    // Midpoint rule over g ∈ [0, L]: Σ σ(ε + g_k) h → ∫ σ = Δγ − tail(ε + L), error ≈ h² σ'(ε)/24.
    let (energy, eps) = (0.5, 0.2e-9);
    let (n, length) = (1_000_000usize, 1000.0 * 0.2e-9);
    let h = length / n as f64;
    let gap = Array2::from_shape_fn((1000, 1000), |(iy, ix)| ((iy * 1000 + ix) as f64 + 0.5) * h);
    let p = Array2::zeros((1000, 1000));
    let force = adhesion_from_gap(
        gap.view(),
        p.view(),
        h,
        1.0,
        AdhesionParameters::new(energy, eps).unwrap(),
    )
    .unwrap();
    let top = eps + length;
    let tail = 8.0 * energy / (3.0 * eps)
        * (eps.powi(3) / (2.0 * top * top) - eps.powi(9) / (8.0 * top.powi(8)));
    let exact = energy - tail;
    assert!(((force - exact) / exact).abs() < 2e-6, "{force} vs {exact}");
}

#[test]
fn flat_top_puts_the_peak_at_the_first_point_in_raster_order() {
    let cells = [(3, 4), (3, 5), (4, 3), (4, 4), (4, 5)];
    let z = Array2::from_shape_fn((8, 8), |(iy, _)| if iy < 5 { 2e-6 } else { 1e-6 });
    let found = spots(&cells, &z, false);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].peak, (3, 4));
}
