//! Tests of the influence operator: closed forms, the single-precision transforms and their
//! switching, the preconditioner, the restricted coefficients.

use super::*;

/// The rows of the `nx`-wide row-major grid `values`, as a [`RowSource`].
fn rows_of(values: &[f64], nx: usize) -> impl RowSource + '_ {
    move |r: usize, row: &mut [f64]| {
        row.copy_from_slice(&values[r * nx..][..nx]);
        true
    }
}

/// A [`RowSink`] that writes each output row as it comes.
fn copy(_: usize, values: &[f64], out: &mut [f64]) -> f64 {
    out.copy_from_slice(values);
    0.0
}

#[test]
fn pixel_influence_matches_numerical_integration() {
    // ∫∫ 1/(π r) over a 1 × 2 rectangle, midpoint rule with 400 × 800 cells, at points inside,
    // on the edge and far away. The midpoint rule on the 1/r singularity converges like h;
    // 2e-3 relative covers h = 1/400.
    let (dx, dy) = (1.0, 2.0);
    for (x, y) in [(0.0, 0.0), (0.5, 0.3), (3.0, -2.0), (10.0, 7.0)] {
        let (n, m) = (400, 800);
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..m {
                let xi = -0.5 * dx + (i as f64 + 0.5) * dx / n as f64;
                let eta = -0.5 * dy + (j as f64 + 0.5) * dy / m as f64;
                sum += 1.0 / ((x - xi).powi(2) + (y - eta).powi(2)).sqrt();
            }
        }
        let numeric = sum * dx * dy / (n * m) as f64 / PI;
        let exact = pixel_influence(x, y, dx, dy);
        assert!(
            (numeric - exact).abs() < 2e-3 * exact,
            "({x}, {y}): {numeric} vs {exact}"
        );
    }
}

#[test]
fn periodic_operator_reproduces_sinusoid_compliance() {
    // u = 2 p* / (E* q) cos(q x) for p = p* cos(q x) (Westergaard); exact on the grid.
    let (nx, ny, dx) = (32, 4, 1e-6);
    let e_star = 1e11;
    let mut op = InfluenceOperator::new(nx, ny, dx, dx, e_star, Boundary::Periodic, false).unwrap();
    let q = 2.0 * PI * 3.0 / (nx as f64 * dx);
    let p: Vec<f64> = (0..nx * ny)
        .map(|i| 1e6 * (q * (i % nx) as f64 * dx).cos())
        .collect();
    let mut u = vec![0.0; nx * ny];
    op.apply(&p, &mut u).unwrap();
    for (pi, ui) in p.iter().zip(&u) {
        let expected = 2.0 * pi / (e_star * q);
        assert!((ui - expected).abs() < 1e-12 * 2e6 / (e_star * q));
    }
}

/// The measured size of the ground-validation study (3512² points of 0.556 µm, S235JR on
/// S235JR): its padded kernel has round-off values below `f32`'s range, negligible beside
/// its largest, and the operator still has single-precision transforms (`transforms.rs`).
#[test]
fn the_measured_grid_has_single_precision_transforms() {
    let (n, dx, e_star) = (3512, 1.953e-3 / 3512.0, 1.1538e11);
    let op = InfluenceOperator::new(n, n, dx, dx, e_star, Boundary::Periodic, false).unwrap();
    assert!(op.has_single());
}

/// A switch of precision gives back the buffers of the precision left; the transforms
/// after it give the bits of an operator that never switched, and a transform started
/// before it cannot be finished after it.
#[test]
fn switching_precision_keeps_the_bits_and_drops_a_started_transform() {
    let (nx, ny) = (24, 37);
    let operator =
        || InfluenceOperator::new(nx, ny, 1e-6, 1e-6, 1.1e11, Boundary::Periodic, false).unwrap();
    let p: Vec<f64> = (0..nx * ny).map(|i| ((i * 37) % 11) as f64 * 1e6).collect();
    let fill = rows_of(&p, nx);
    let apply = |op: &mut InfluenceOperator| {
        let mut u = vec![0.0; nx * ny];
        op.apply_rows_into(&fill, &mut u, &copy).unwrap();
        u.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    };
    let mut single = operator();
    assert!(single.has_single());
    single.set_precision(Precision::Single);
    let (in_single, in_double) = (apply(&mut single), apply(&mut operator()));
    assert_ne!(in_single, in_double);
    let mut switching = operator();
    for _ in 0..2 {
        switching.set_precision(Precision::Single);
        assert_eq!(apply(&mut switching), in_single);
        switching.set_precision(Precision::Double);
        assert_eq!(apply(&mut switching), in_double);
    }
    switching.start_apply(&p).unwrap();
    switching.set_precision(Precision::Single);
    assert!(switching.finish_apply(&mut vec![0.0; nx * ny]).is_err());
}

#[test]
fn preconditioner_inverts_the_periodic_operator() {
    // `M K p = p` for a zero-mean pressure on a periodic grid: `M̂ = 1/K̂` away from q = 0.
    let (nx, ny) = (32, 24);
    let mut op =
        InfluenceOperator::new(nx, ny, 1e-6, 2e-6, 1.2e11, Boundary::Periodic, true).unwrap();
    let p: Vec<f64> = (0..nx * ny)
        .map(|i| {
            let (x, y) = ((i % nx) as f64 / nx as f64, (i / nx) as f64 / ny as f64);
            (2.0 * PI * 3.0 * x).cos() * (2.0 * PI * 2.0 * y).sin() + (2.0 * PI * x).sin()
        })
        .collect();
    let mut u = vec![0.0; nx * ny];
    op.apply(&p, &mut u).unwrap();
    let fill = rows_of(&u, nx);
    let mut back = vec![0.0; nx * ny];
    op.precondition_rows_into(&fill, &mut back, &copy).unwrap();
    let error = p
        .iter()
        .zip(&back)
        .fold(0.0f64, |e, (a, b)| e.max((a - b).abs()));
    assert!(error < 1e-12, "{error}");
}

#[test]
fn non_periodic_operator_matches_direct_sum() {
    // 2 · 6 and 2 · 5 are padded to themselves, 2 · 11 and 2 · 13 to 24 and 28.
    for (nx, ny) in [(6, 5), (11, 13)] {
        non_periodic_operator_matches_direct_sum_on(nx, ny);
    }
}

fn non_periodic_operator_matches_direct_sum_on(nx: usize, ny: usize) {
    let (dx, dy) = (1.0, 1.5);
    let mut op = InfluenceOperator::new(nx, ny, dx, dy, 2.0, Boundary::NonPeriodic, false).unwrap();
    let p: Vec<f64> = (0..nx * ny).map(|i| ((i * 37) % 11) as f64).collect();
    let mut u = vec![0.0; nx * ny];
    op.apply(&p, &mut u).unwrap();
    for (i, &ui) in u.iter().enumerate() {
        let (ix, iy) = ((i % nx) as f64, (i / nx) as f64);
        let direct: f64 = (0..nx * ny)
            .map(|j| {
                let (jx, jy) = ((j % nx) as f64, (j / nx) as f64);
                p[j] * pixel_influence((ix - jx) * dx, (iy - jy) * dy, dx, dy) / 2.0
            })
            .sum();
        // FFT round-off relative to the largest term.
        assert!((ui - direct).abs() < 1e-12 * direct.abs().max(1.0));
    }
    assert!((op.self_influence() - pixel_influence(0.0, 0.0, dx, dy) / 2.0).abs() < 1e-14);
}

#[test]
fn coefficients_apply_the_operator_between_points() {
    // Pressure on a scattered set of points (including both grid edges, so that negative
    // offsets wrap on the periodic grid): the coefficients between the points times the
    // pressures give the FFT operator's displacement there, to FFT round-off.
    let (nx, ny) = (12, 9);
    let points = [0, 5, 11, 13, 40, 59, 71, 96, 100, 107];
    for boundary in [Boundary::Periodic, Boundary::NonPeriodic] {
        let mut op = InfluenceOperator::new(nx, ny, 1e-6, 2e-6, 1e11, boundary, false).unwrap();
        let mut p = vec![0.0; nx * ny];
        for (k, &i) in points.iter().enumerate() {
            p[i] = 1e6 * (1.0 + k as f64);
        }
        let mut u = vec![0.0; nx * ny];
        op.apply(&p, &mut u).unwrap();
        let coords: Vec<(usize, usize)> = points.iter().map(|&i| (i % nx, i / nx)).collect();
        let op = &op;
        let matrix: Vec<f64> = (coords.iter())
            .flat_map(|&a| coords.iter().map(move |&b| op.coefficient_between(a, b)))
            .collect();
        let scale = u.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
        for (row, &a) in matrix.chunks(points.len()).zip(&points) {
            let restricted: f64 = row.iter().zip(&points).map(|(k, &b)| k * p[b]).sum();
            assert!(
                (restricted - u[a]).abs() < 1e-12 * scale,
                "{boundary:?}, point {a}: {restricted} vs {}",
                u[a]
            );
        }
        // Exactly symmetric, as K is.
        let m = points.len();
        for a in 0..m {
            for b in 0..m {
                assert_eq!(matrix[a * m + b], matrix[b * m + a]);
            }
        }
    }
}
