//! Summit identification on analytic surfaces and small hand-built cases.

use asperity_numerics::surface::{find_summits, Boundary, HeightMap, SummitOptions};
use ndarray::Array2;
use std::f64::consts::PI;

/// `z = A sin(kx·x + φ) sin(ky·y + φ)` with `nx_period`/`ny_period` points per wavelength and `periods`
/// wavelengths in each direction; the phase shift `φ` is a whole number of pixels.
fn product_of_sines(
    amplitude: f64,
    (nx_period, ny_period): (usize, usize),
    periods: usize,
    (dx, dy): (f64, f64),
    shift_pixels: usize,
) -> HeightMap {
    let z = Array2::from_shape_fn((ny_period * periods, nx_period * periods), |(iy, ix)| {
        let u = 2.0 * PI * (ix + shift_pixels) as f64 / nx_period as f64;
        let v = 2.0 * PI * (iy + shift_pixels) as f64 / ny_period as f64;
        amplitude * u.sin() * v.sin()
    });
    HeightMap::new(z, dx, dy).unwrap()
}

// Maxima of sin u sin v: (u, v) = (π/2, π/2) and (3π/2, 3π/2) per period cell, so 2 per λx·λy;
// there ∇²z = −A (kx² + ky²) and the Hessian is diagonal (z_xy ∝ cos u cos v = 0). On the grid the
// second differences are exact up to the factor s² = (sin(θ/2)/(θ/2))², θ = k·d, so
// R = 2/(A (kx² sx² + ky² sy²)) exactly, and the continuous 2/(A (kx² + ky²)) within ≈ θ²/12.
#[test]
fn product_of_sines_summits_match_analytic_count_and_radius() {
    let a = 1e-7;
    let (nxp, nyp, periods) = (32usize, 16usize, 3usize);
    let (dx, dy) = (1e-6, 2e-6);
    let map = product_of_sines(a, (nxp, nyp), periods, (dx, dy), 0);
    let (lx, ly) = (nxp as f64 * dx, nyp as f64 * dy);
    let (kx, ky) = (2.0 * PI / lx, 2.0 * PI / ly);
    let sinc2 = |t: f64| ((t / 2.0).sin() / (t / 2.0)).powi(2);
    let (cx, cy) = (a * kx * kx * sinc2(kx * dx), a * ky * ky * sinc2(ky * dy));
    for boundary in [Boundary::Periodic, Boundary::Open] {
        let options = SummitOptions {
            boundary,
            ..SummitOptions::default()
        };
        let found = find_summits(&map, options).unwrap();
        let stats = found.statistics;
        assert_eq!(stats.count, 2 * periods * periods, "{boundary:?}");
        for s in &found.summits {
            // Round-off in differences of heights ~1e-7 m: 1e-9 relative on curvatures.
            assert!((s.height - a).abs() < 1e-12 * a);
            assert!(s.slope.abs() < 1e-9 * a * kx);
            assert!((s.radius - 2.0 / (cx + cy)).abs() < 1e-9 * s.radius);
            let [k1, k2] = s.principal_curvatures;
            assert!((k1 - cx.max(cy)).abs() < 1e-9 * k1 && (k2 - cx.min(cy)).abs() < 1e-9 * k1);
            assert_eq!(s.x, s.ix as f64 * dx);
            let quarter = (s.ix % nxp, s.iy % nyp);
            assert!(quarter == (nxp / 4, nyp / 4) || quarter == (3 * nxp / 4, 3 * nyp / 4));
        }
        // Continuous radius: θx = 2π/32 gives (θ²/12) 0.32 %, θy = 2π/16 gives 1.3 %; their weighted
        // mean is below 1.3 %, allow 1.5 %.
        let continuous = 2.0 / (a * (kx * kx + ky * ky));
        let mean_radius = stats.mean_radius.unwrap();
        assert!(
            (mean_radius / continuous - 1.0).abs() < 0.015,
            "{mean_radius} vs {continuous}"
        );
        assert!(stats.height_std.unwrap() < 1e-12 * a);
        let (nx, ny) = (map.nx(), map.ny());
        let candidates = match boundary {
            Boundary::Periodic => nx * ny,
            Boundary::Open => (nx - 2) * (ny - 2),
        };
        assert_eq!(stats.candidate_count, candidates);
        let density = stats.count as f64 / (candidates as f64 * dx * dy);
        assert!((stats.density - density).abs() < 1e-12 * density);
        if boundary == Boundary::Periodic {
            // η = 2/(λx λy) exactly on the periodic grid.
            assert!((stats.density - 2.0 / (lx * ly)).abs() < 1e-9 * stats.density);
        }
    }
}

// Shifted so that maxima sit on the first row/column: the periodic wrap finds them, the open boundary
// excludes the border ones.
#[test]
fn border_summits_wrap_or_are_excluded() {
    let map = product_of_sines(1e-7, (16, 16), 2, (1e-6, 1e-6), 4);
    // Maxima at (ix + 4) ≡ 4 (mod 16) → ix ∈ {0, 16}, and (ix + 4) ≡ 12 → ix ∈ {8, 24}; same for iy.
    let periodic = SummitOptions {
        boundary: Boundary::Periodic,
        ..SummitOptions::default()
    };
    assert_eq!(find_summits(&map, periodic).unwrap().statistics.count, 8);
    let open = find_summits(&map, SummitOptions::default()).unwrap();
    // Excluded: the 3 maxima at ix = 0 or iy = 0 among (0|16, 0|16).
    assert_eq!(open.statistics.count, 5);
    assert!(open.summits.iter().all(|s| s.ix > 0 && s.iy > 0));
    // Isotropic case of the radius: R = 1/(A k²) continuous, 1/(A k² s²) on the grid with
    // s = sin(θ/2)/(θ/2), θ = 2π/16: the discretisation error θ²/12 = 1.3 %.
    let k = 2.0 * PI / 16e-6;
    let half = PI / 16.0;
    let discrete = 1.0 / (1e-7 * k * k * (half.sin() / half).powi(2));
    for s in &open.summits {
        assert!((s.radius - discrete).abs() < 1e-9 * discrete);
        assert!((s.radius * 1e-7 * k * k - 1.0).abs() < 0.014);
    }
}

// A tilt ε·x does not move the maximum pixel (ε dx is below the curvature drop A(1 − cos kdx)), and
// the central-difference slope at the summit is exactly ε since the sine part is symmetric there.
#[test]
fn slope_at_summit_of_tilted_surface() {
    let (a, dx, eps) = (1e-7, 1e-6, 5e-4);
    let base = product_of_sines(a, (32, 32), 2, (dx, dx), 0);
    let tilted = base.heights() + &Array2::from_shape_fn((64, 64), |(_, ix)| eps * ix as f64 * dx);
    let map = HeightMap::new(tilted, dx, dx).unwrap();
    let found = find_summits(&map, SummitOptions::default()).unwrap();
    assert_eq!(found.statistics.count, 8);
    for s in &found.summits {
        // Differences of heights ~1e-7 m over 2 µm: round-off ≪ 1e-6 of ε.
        assert!((s.slope - eps).abs() < 1e-6 * eps, "slope {}", s.slope);
    }
}

// Ties: equal neighbours never both count; the raster-earlier point wins, so a 2×2 plateau gives one
// summit at its first point.
#[test]
fn plateaus_give_one_deterministic_summit() {
    let mut z = Array2::zeros((6, 7));
    for (iy, ix) in [(2, 2), (2, 3), (3, 2), (3, 3)] {
        z[[iy, ix]] = 1.0;
    }
    let map = HeightMap::new(z, 1.0, 1.0).unwrap();
    let found = find_summits(&map, SummitOptions::default()).unwrap();
    let at: Vec<(usize, usize)> = found.summits.iter().map(|s| (s.ix, s.iy)).collect();
    assert_eq!(at, vec![(2, 2)]);
}

// A maximum next to a missing point is skipped, and so is every point next to the hole; the hole is
// never read as zero (a zero there would make (5, 5) a maximum, of a surface at −1).
#[test]
fn summits_next_to_missing_points_are_skipped() {
    let mut z = Array2::from_elem((9, 9), -1.0);
    z[[2, 2]] = 0.5;
    z[[5, 5]] = -0.5;
    z[[5, 6]] = f64::NAN;
    let map = HeightMap::new(z, 1.0, 1.0).unwrap();
    let found = find_summits(&map, SummitOptions::default()).unwrap();
    let at: Vec<(usize, usize)> = found.summits.iter().map(|s| (s.ix, s.iy)).collect();
    assert_eq!(at, vec![(2, 2)]);
    // 7×7 interior minus the hole's 3×3 neighbourhood (all interior).
    assert_eq!(found.statistics.candidate_count, 49 - 9);
}

// Three peaks 5, 3, 8 on a ridge of 1s in a floor of 0s (row 2 of a 5×9 grid). Descending sweep: the
// 1 between 5 and 3 is the col of the 3 (prominence 3 − 1 = 2), the 1 between 3|5 and 8 is the col of
// the 5 (prominence 5 − 1 = 4), and the 8 is the highest: 8 − lowest point 0 = 8.
#[test]
fn height_and_prominence_thresholds() {
    let mut z = Array2::zeros((5, 9));
    for (ix, h) in [1.0, 5.0, 1.0, 3.0, 1.0, 8.0, 1.0].into_iter().enumerate() {
        z[[2, ix + 1]] = h;
    }
    let mean = z.sum() / 45.0;
    let map = HeightMap::new(z, 1e-6, 1e-6).unwrap();
    let all = find_summits(&map, SummitOptions::default()).unwrap();
    let heights: Vec<f64> = all.summits.iter().map(|s| s.height + mean).collect();
    assert_eq!(heights, vec![5.0, 3.0, 8.0]);
    assert!(all.summits.iter().all(|s| s.prominence.is_none()));

    let prominent = SummitOptions {
        min_prominence: Some(2.0),
        ..SummitOptions::default()
    };
    let found = find_summits(&map, prominent).unwrap();
    let p: Vec<(usize, f64)> = found
        .summits
        .iter()
        .map(|s| (s.ix, s.prominence.unwrap()))
        .collect();
    assert_eq!(p, vec![(2, 4.0), (4, 2.0), (6, 8.0)]);
    let stricter = SummitOptions {
        min_prominence: Some(3.0),
        ..SummitOptions::default()
    };
    assert_eq!(find_summits(&map, stricter).unwrap().statistics.count, 2);

    let high = SummitOptions {
        min_height: Some(4.0 - mean),
        ..SummitOptions::default()
    };
    let found = find_summits(&map, high).unwrap();
    assert_eq!(found.statistics.count, 2);
    // Mean and population std of summit heights 5 and 8 (about the mean plane).
    assert!((found.statistics.mean_height.unwrap() - (6.5 - mean)).abs() < 1e-12);
    assert!((found.statistics.height_std.unwrap() - 1.5).abs() < 1e-12);

    let bad = SummitOptions {
        min_height: Some(f64::NAN),
        ..SummitOptions::default()
    };
    assert!(find_summits(&map, bad).is_err());
}

/// Pseudo-random value in [0, 1) from an index (SplitMix64 finaliser).
fn hash_unit(i: u64) -> f64 {
    let mut x = i.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^= x >> 31;
    (x >> 11) as f64 / (1u64 << 53) as f64
}

// Independent brute-force prominence on a small random surface with a hole: for a summit p, lower a
// water level through the ranked points one at a time and search (breadth-first, 8-connected, valid
// points at or above the level) for a point ranked above p; the level at which one is first reached
// is the col. The highest summit never finds one: its prominence is its height above the minimum.
#[test]
fn prominence_matches_brute_force_search() {
    let (nx, ny) = (13usize, 11usize);
    let mut z = Array2::from_shape_fn((ny, nx), |(iy, ix)| hash_unit((iy * nx + ix) as u64));
    z[[5, 6]] = f64::NAN;
    let map = HeightMap::new(z.clone(), 1.0, 1.0).unwrap();
    let options = SummitOptions {
        min_prominence: Some(f64::MIN),
        ..SummitOptions::default()
    };
    let found = find_summits(&map, options).unwrap();
    assert!(found.statistics.count >= 5);
    let flat: Vec<f64> = z.iter().copied().collect();
    let mut ranked: Vec<usize> = (0..flat.len()).filter(|&p| !flat[p].is_nan()).collect();
    ranked.sort_by(|&a, &b| flat[b].total_cmp(&flat[a]).then(a.cmp(&b)));
    let rank_of = |p: usize| ranked.iter().position(|&q| q == p).unwrap();
    let lowest = flat[*ranked.last().unwrap()];
    for s in &found.summits {
        let p = s.iy * nx + s.ix;
        let rp = rank_of(p);
        let mut expected = flat[p] - lowest;
        for level in rp + 1..ranked.len() {
            let allowed: Vec<bool> = (0..flat.len())
                .map(|q| !flat[q].is_nan() && rank_of(q) <= level)
                .collect();
            let mut seen = vec![false; flat.len()];
            let mut queue = std::collections::VecDeque::from([p]);
            seen[p] = true;
            let mut reached = false;
            while let Some(q) = queue.pop_front() {
                if rank_of(q) < rp {
                    reached = true;
                    break;
                }
                let (qx, qy) = ((q % nx) as isize, (q / nx) as isize);
                for (ox, oy) in [
                    (-1, -1),
                    (0, -1),
                    (1, -1),
                    (-1, 0),
                    (1, 0),
                    (-1, 1),
                    (0, 1),
                    (1, 1),
                ] {
                    let (jx, jy) = (qx + ox, qy + oy);
                    if jx < 0 || jy < 0 || jx >= nx as isize || jy >= ny as isize {
                        continue;
                    }
                    let j = jy as usize * nx + jx as usize;
                    if allowed[j] && !seen[j] {
                        seen[j] = true;
                        queue.push_back(j);
                    }
                }
            }
            if reached {
                expected = flat[p] - flat[ranked[level]];
                break;
            }
        }
        assert_eq!(
            s.prominence,
            Some(expected),
            "summit at ({}, {})",
            s.ix,
            s.iy
        );
    }
}
