//! Tests of the 2-D real FFT.

use ndarray::Array2;

use super::*;

fn signal(nx: usize, ny: usize) -> Vec<f64> {
    (0..nx * ny)
        .map(|i| ((i * 7919) % 101) as f64 / 101.0 - 0.5)
        .collect()
}

#[test]
fn round_trip_is_identity() {
    for (nx, ny) in [(8, 8), (9, 6), (16, 5), (1, 4), (40, 70)] {
        let x = signal(nx, ny);
        let mut y = x.clone();
        let mut fft = RealFft2d::new(nx, ny);
        fft.round_trip(&mut y).unwrap();
        for (a, b) in x.iter().zip(&y) {
            // Round-off of two O(n log n) transforms on O(1) data.
            assert!((a - b).abs() < 1e-13, "{nx}×{ny}: {a} vs {b}");
        }
    }
}

#[test]
fn wrong_lengths_are_errors() {
    let mut fft = RealFft2d::new(4, 3);
    assert!(fft.forward(&[0.0; 11]).is_err());
    assert!(fft.round_trip(&mut [0.0; 13]).is_err());
    let mut out = [0.0; 6];
    assert!(fft.convolve(&[0.0; 6], &[0.0; 9], &mut out, 3, 2).is_ok());
    assert!(fft.convolve(&[0.0; 6], &[0.0; 8], &mut out, 3, 2).is_err());
    assert!(fft
        .convolve(&[0.0; 10], &[0.0; 9], &mut [0.0; 10], 5, 2)
        .is_err());
}

#[test]
fn padded_convolution_matches_direct_sum() {
    // Linear convolution of a 5 × 3 block with an even 3 × 3 stencil through a 10 × 6 padded
    // grid: the padding leaves room for the stencil, so nothing wraps around.
    let (cols, rows, nx, ny) = (5, 3, 10, 6);
    let input = signal(cols, rows);
    let mut stencil = vec![0.0; nx * ny];
    stencil[0] = 2.0;
    stencil[1] = -1.0;
    stencil[nx - 1] = -1.0;
    stencil[nx] = 0.5;
    stencil[(ny - 1) * nx] = 0.5;
    let mut fft = RealFft2d::new(nx, ny);
    let kernel = spectral_kernel(&mut fft, &stencil);
    let mut out = vec![0.0; cols * rows];
    fft.convolve(&input, &kernel, &mut out, cols, rows).unwrap();
    let at = |ix: isize, iy: isize| {
        if ix < 0 || iy < 0 || ix >= cols as isize || iy >= rows as isize {
            0.0
        } else {
            input[iy as usize * cols + ix as usize]
        }
    };
    for iy in 0..rows as isize {
        for ix in 0..cols as isize {
            let direct = 2.0 * at(ix, iy) - at(ix - 1, iy) - at(ix + 1, iy)
                + 0.5 * at(ix, iy - 1)
                + 0.5 * at(ix, iy + 1);
            let got = out[iy as usize * cols + ix as usize];
            // Round-off of an FFT pair on O(1) data.
            assert!(
                (direct - got).abs() < 1e-13,
                "({ix}, {iy}): {direct} vs {got}"
            );
        }
    }
}

/// The normalised real spectrum of an even stencil: the kernel `convolve` takes.
fn spectral_kernel(fft: &mut RealFft2d, stencil: &[f64]) -> Vec<f64> {
    let (nx, ny) = fft.shape();
    let norm = 1.0 / (nx * ny) as f64;
    fft.forward(stencil)
        .unwrap()
        .iter()
        .map(|c| c.re * norm)
        .collect()
}

/// Even stencil on an `nx × ny` grid (`s(x, y) = s(−x, y) = s(x, −y)`, real spectrum).
fn even_stencil(nx: usize, ny: usize) -> Vec<f64> {
    (0..nx * ny)
        .map(|i| {
            let (x, y) = (i % nx, i / nx);
            let (x, y) = (x.min(nx - x), y.min(ny - y));
            1.0 / (1.0 + (x * x + 3 * y * y) as f64)
        })
        .collect()
}

#[test]
fn zero_rows_match_direct_circular_sum() {
    // Block rows 1 and 3 are zero (skipped by the row pass) and the block is padded in both
    // directions; the result must still be the circular convolution with the stencil.
    let (cols, rows, nx, ny) = (6, 5, 12, 10);
    let mut input = signal(cols, rows);
    for iy in [1, 3] {
        input[iy * cols..(iy + 1) * cols].fill(0.0);
    }
    let stencil = even_stencil(nx, ny);
    let mut fft = RealFft2d::new(nx, ny);
    let kernel = spectral_kernel(&mut fft, &stencil);
    let mut out = vec![0.0; cols * rows];
    fft.convolve(&input, &kernel, &mut out, cols, rows).unwrap();
    for iy in 0..rows {
        for ix in 0..cols {
            let mut direct = 0.0;
            for jy in 0..rows {
                for jx in 0..cols {
                    let (dx, dy) = ((ix + nx - jx) % nx, (iy + ny - jy) % ny);
                    direct += input[jy * cols + jx] * stencil[dy * nx + dx];
                }
            }
            let got = out[iy * cols + ix];
            // Round-off of an FFT pair on O(1) data summed over 30 terms.
            assert!(
                (direct - got).abs() < 1e-13,
                "({ix}, {iy}): {direct} vs {got}"
            );
        }
    }
}

#[test]
fn split_convolution_matches_convolve_and_parseval() {
    // Padded blocks (with a zero row), a full odd grid and a full even grid.
    for (cols, rows, nx, ny) in [(6, 5, 12, 10), (7, 9, 7, 9), (8, 8, 8, 8)] {
        let mut input = signal(cols, rows);
        input[cols..2 * cols].fill(0.0);
        let mut fft = RealFft2d::new(nx, ny);
        let kernel = spectral_kernel(&mut fft, &even_stencil(nx, ny));
        let mut whole = vec![0.0; cols * rows];
        fft.convolve(&input, &kernel, &mut whole, cols, rows)
            .unwrap();
        let energy = fft.start_convolve(&input, &kernel, cols, rows).unwrap();
        let mut split = vec![0.0; cols * rows];
        fft.finish_convolve(&kernel, &mut split, cols, rows)
            .unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&whole), bits(&split), "{nx}×{ny}");
        let direct: f64 = input.iter().zip(&whole).map(|(a, b)| a * b).sum();
        let scale: f64 = input.iter().zip(&whole).map(|(a, b)| (a * b).abs()).sum();
        // Round-off of an FFT pair and two sums on O(1) data.
        assert!(
            (energy - direct).abs() < 1e-13 * scale,
            "{nx}×{ny}: {energy} vs {direct}"
        );
    }
}

#[test]
fn row_sources_give_the_bits_of_the_dense_block() {
    // A sparse block supplied row by row from its list of nonzero points, as the contact solver
    // supplies pressures: the same bits as the dense block, for the whole convolution and for
    // the quadratic form of the first half.
    for (cols, rows, nx, ny) in [(6, 5, 12, 10), (7, 9, 7, 9)] {
        let points: Vec<(usize, f64)> = (0..cols * rows)
            .filter(|i| i % 4 == 1)
            .map(|i| (i, 1.0 + (i % 5) as f64))
            .collect();
        let mut dense = vec![0.0; cols * rows];
        for &(i, v) in &points {
            dense[i] = v;
        }
        let rows_of = |r: usize, row: &mut [f64]| {
            row.fill(0.0);
            let mut nonzero = false;
            for &(i, v) in points.iter().filter(|(i, _)| i / cols == r) {
                row[i % cols] = v;
                nonzero = true;
            }
            nonzero
        };
        let mut fft = RealFft2d::new(nx, ny);
        let kernel = spectral_kernel(&mut fft, &even_stencil(nx, ny));
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let mut from_dense = vec![0.0; cols * rows];
        let mut from_rows = vec![0.0; cols * rows];
        fft.convolve(&dense, &kernel, &mut from_dense, cols, rows)
            .unwrap();
        let copy = |_: usize, values: &[f64], out: &mut [f64]| {
            out.copy_from_slice(values);
            0.0
        };
        fft.convolve_rows_into(&rows_of, &kernel, &mut from_rows, cols, rows, &copy)
            .unwrap();
        assert_eq!(bits(&from_dense), bits(&from_rows), "{nx}×{ny}");
        let dense_energy = fft.start_convolve(&dense, &kernel, cols, rows).unwrap();
        let rows_energy = fft
            .start_convolve_rows(&rows_of, &kernel, cols, rows)
            .unwrap();
        assert_eq!(dense_energy.to_bits(), rows_energy.to_bits(), "{nx}×{ny}");
    }
}

#[test]
fn row_sinks_see_the_rows_of_the_result() {
    // A sink that accumulates `out −= 2 · values` and returns the row sum gets exactly the rows
    // `convolve` writes, for the whole convolution and for the second half.
    for (cols, rows, nx, ny) in [(6, 5, 12, 10), (7, 9, 7, 9)] {
        let input = signal(cols, rows);
        let mut fft = RealFft2d::new(nx, ny);
        let kernel = spectral_kernel(&mut fft, &even_stencil(nx, ny));
        let mut whole = vec![0.0; cols * rows];
        fft.convolve(&input, &kernel, &mut whole, cols, rows)
            .unwrap();
        let start = signal(rows, cols);
        let expected: Vec<f64> = start.iter().zip(&whole).map(|(s, w)| s - 2.0 * w).collect();
        let sums: Vec<f64> = whole.chunks(cols).map(|r| r.iter().sum()).collect();
        let sink = |_: usize, values: &[f64], out: &mut [f64]| {
            out.iter_mut().zip(values).for_each(|(o, &v)| *o -= 2.0 * v);
            values.iter().sum()
        };
        let mut updated = start.clone();
        let got = fft
            .convolve_rows_into(
                &dense_rows(&input),
                &kernel,
                &mut updated,
                cols,
                rows,
                &sink,
            )
            .unwrap();
        assert_eq!(got, &sums[..], "{nx}×{ny}");
        assert_eq!(updated, expected, "{nx}×{ny}");
        fft.start_convolve(&input, &kernel, cols, rows).unwrap();
        let mut updated = start.clone();
        let got = fft
            .finish_convolve_into(&kernel, &mut updated, cols, rows, &sink)
            .unwrap();
        assert_eq!(got, &sums[..], "{nx}×{ny}");
        assert_eq!(updated, expected, "{nx}×{ny}");
    }
}

/// The bits of a convolution, its quadratic form, a round trip and a forward transform in the
/// precision `T` on `threads` threads (odd block heights, so that packed rows leave a row
/// without a partner, and a zero pair of rows).
fn bits_on_threads<T: Real>(threads: usize) -> Vec<u64> {
    let (cols, rows, nx, ny) = (21, 35, 42, 70);
    let mut input = signal(cols, rows);
    input[6 * cols..8 * cols].fill(0.0);
    let kernel: Vec<T> = signal(nx / 2 + 1, ny).into_iter().map(T::of).collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut fft = RealFft2d::<T>::in_precision(nx, ny, false);
        let mut out = vec![0.0; cols * rows];
        fft.convolve(&input, &kernel, &mut out, cols, rows).unwrap();
        let energy = fft.start_convolve(&input, &kernel, cols, rows).unwrap();
        out.push(energy);
        let mut grid = signal(nx, ny);
        fft.round_trip(&mut grid).unwrap();
        out.extend(grid);
        out.extend(
            fft.forward(&signal(nx, ny))
                .unwrap()
                .iter()
                .map(|c| (c.re + c.im).into()),
        );
        out.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    })
}

#[test]
fn results_are_bit_identical_for_any_thread_count() {
    // The chunking follows the rayon thread count; every 1-D transform (in single precision
    // every pair of rows) must not.
    let (double, single) = (bits_on_threads::<f64>(1), bits_on_threads::<f32>(1));
    for threads in [2, 3] {
        assert!(
            double == bits_on_threads::<f64>(threads),
            "{threads} threads differ from 1"
        );
        assert!(
            single == bits_on_threads::<f32>(threads),
            "{threads} threads differ from 1 in single precision"
        );
    }
}

#[test]
fn single_precision_matches_double_to_its_round_off() {
    // Blocks with zero rows and odd heights (rows without a partner), full odd and even grids,
    // padded columns (37 and 2 · 41 points): the single-precision convolution, its halves and
    // its quadratic form against the double-precision ones. Bound: the round-off of f32
    // (6e-8) in the input and kernel and through two transforms of length ≤ 164 (a few
    // 6e-8 · log₂ 164 ≈ 4.4e-7), relative to the largest value.
    for (cols, rows, nx, ny) in [
        (6, 5, 12, 10),
        (7, 9, 7, 9),
        (8, 8, 8, 8),
        (12, 37, 12, 37),
        (5, 30, 9, 82),
    ] {
        let mut input = signal(cols, rows);
        input[cols..2 * cols].fill(0.0);
        let spectral = spectral_kernel(&mut RealFft2d::new(nx, ny), &even_stencil(nx, ny));
        let mut double = RealFft2d::for_convolution(nx, ny);
        let kernel = double.convolution_kernel(spectral).unwrap();
        let rounded: Vec<f32> = kernel.iter().map(|&k| k as f32).collect();
        let mut single = RealFft2d::<f32>::in_precision(nx, ny, true);
        let mut expected = vec![0.0; cols * rows];
        double
            .convolve(&input, &kernel, &mut expected, cols, rows)
            .unwrap();
        let expected_energy = double.start_convolve(&input, &kernel, cols, rows).unwrap();
        let mut whole = vec![0.0; cols * rows];
        single
            .convolve(&input, &rounded, &mut whole, cols, rows)
            .unwrap();
        let energy = single.start_convolve(&input, &rounded, cols, rows).unwrap();
        let mut split = vec![0.0; cols * rows];
        single
            .finish_convolve(&rounded, &mut split, cols, rows)
            .unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&whole), bits(&split), "{nx}×{ny}");
        let largest = expected.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (a, b) in whole.iter().zip(&expected) {
            assert!((a - b).abs() < 2e-6 * largest, "{nx}×{ny}: {a} vs {b}");
        }
        let scale: f64 = input
            .iter()
            .zip(&expected)
            .map(|(a, b)| (a * b).abs())
            .sum();
        assert!(
            (energy - expected_energy).abs() < 2e-6 * scale,
            "{nx}×{ny}: {energy} vs {expected_energy}"
        );
    }
}

#[test]
fn empty_block_convolves_to_nothing() {
    let mut fft = RealFft2d::new(8, 6);
    let kernel = vec![1.0; fft.spectrum_len()];
    assert!(fft.convolve(&[], &kernel, &mut [], 0, 3).is_ok());
    assert!(fft.convolve(&[], &kernel, &mut [], 4, 0).is_ok());
}

#[test]
fn grid_round_trip_recovers_the_grid() {
    for (ny, nx) in [(6, 8), (5, 7), (4, 9), (2, 2), (37, 20)] {
        let z = Array2::from_shape_fn((ny, nx), |(j, i)| {
            ((i * 7 + j * 3) % 11) as f64 - 0.3 * j as f64
        });
        let half = forward_real_2d(&z).unwrap();
        let back = inverse_real_2d(&half, nx).unwrap() / (nx * ny) as f64;
        // Round-off of a few FFT passes on O(10) values.
        for (a, b) in z.iter().zip(back.iter()) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }
    assert!(inverse_real_2d(&Array2::zeros((3, 4)), 8).is_err());
}

#[test]
fn forward_matches_direct_dft() {
    let (ny, nx) = (3, 4);
    let z = Array2::from_shape_fn((ny, nx), |(j, i)| (i as f64).sin() + (j * j) as f64);
    let half = forward_real_2d(&z).unwrap();
    for ((j, i), value) in half.indexed_iter() {
        let mut direct = Complex::new(0.0, 0.0);
        for ((y, x), zz) in z.indexed_iter() {
            let phase = -2.0
                * std::f64::consts::PI
                * ((i * x) as f64 / nx as f64 + (j * y) as f64 / ny as f64);
            direct += Complex::from_polar(*zz, phase);
        }
        // Direct O(N²) sum vs FFT: round-off only.
        assert!((direct - value).norm() < 1e-12);
    }
}

#[test]
fn padded_columns_give_the_periodic_convolution() {
    // Columns of 37 and 2 · 41 points have a prime factor above 31, so `for_convolution` pads
    // them; the result must be the periodic convolution the spectral column pass computes, for
    // a full grid and for a block with a zero row, and split into its halves bit for bit.
    for (cols, rows, nx, ny) in [(12, 37, 12, 37), (5, 30, 9, 82), (9, 82, 9, 82)] {
        let mut input = signal(cols, rows);
        input[cols..2 * cols].fill(0.0);
        let mut spectral_fft = RealFft2d::new(nx, ny);
        let spectral = spectral_kernel(&mut spectral_fft, &even_stencil(nx, ny));
        let mut padded_fft = RealFft2d::for_convolution(nx, ny);
        assert!(padded_fft.padded.is_some(), "{nx}×{ny}");
        let kernel = padded_fft.convolution_kernel(spectral.clone()).unwrap();
        assert_eq!(kernel.len(), padded_fft.kernel_len());
        let mut expected = vec![0.0; cols * rows];
        spectral_fft
            .convolve(&input, &spectral, &mut expected, cols, rows)
            .unwrap();
        let expected_energy = spectral_fft
            .start_convolve(&input, &spectral, cols, rows)
            .unwrap();
        let mut whole = vec![0.0; cols * rows];
        padded_fft
            .convolve(&input, &kernel, &mut whole, cols, rows)
            .unwrap();
        let energy = padded_fft
            .start_convolve(&input, &kernel, cols, rows)
            .unwrap();
        let mut split = vec![0.0; cols * rows];
        padded_fft
            .finish_convolve(&kernel, &mut split, cols, rows)
            .unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&whole), bits(&split), "{nx}×{ny}");
        let largest = expected.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (a, b) in whole.iter().zip(&expected) {
            // Round-off of two FFT pairs on O(1) data, relative to the largest value.
            assert!((a - b).abs() < 1e-13 * largest, "{nx}×{ny}: {a} vs {b}");
        }
        let scale: f64 = input.iter().zip(&whole).map(|(a, b)| (a * b).abs()).sum();
        assert!(
            (energy - expected_energy).abs() < 1e-13 * scale,
            "{nx}×{ny}: {energy} vs {expected_energy}"
        );
    }
}

#[test]
fn padded_columns_need_an_even_kernel() {
    let fft = RealFft2d::for_convolution(6, 37);
    let mut kernel = vec![1.0; fft.spectrum_len()];
    kernel[3] = 2.0;
    let message = fft.convolution_kernel(kernel).unwrap_err().to_string();
    assert!(message.contains("not even in ky"), "{message}");
    // Spectral kernels pass through unchanged where the columns are not padded.
    let fft = RealFft2d::for_convolution(6, 32);
    let kernel = signal(4, 32);
    assert_eq!(fft.convolution_kernel(kernel.clone()).unwrap(), kernel);
}

#[test]
fn padded_results_are_bit_identical_for_any_thread_count() {
    let (cols, rows, nx, ny) = (10, 70, 20, 74);
    let input = signal(cols, rows);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut fft = RealFft2d::for_convolution(nx, ny);
            let spectral = spectral_kernel(&mut fft, &even_stencil(nx, ny));
            let kernel = fft.convolution_kernel(spectral).unwrap();
            let mut out = vec![0.0; cols * rows];
            fft.convolve(&input, &kernel, &mut out, cols, rows).unwrap();
            out.push(fft.start_convolve(&input, &kernel, cols, rows).unwrap());
            out.extend(kernel);
            out.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        })
    };
    let one = run(1);
    for threads in [2, 3] {
        assert!(one == run(threads), "{threads} threads differ from 1");
    }
}

/// A grid whose spectrum lives in two columns, `kx = 2` (first tile) and `kx = 35` (third tile
/// of 41 columns): the inverse skips the all-zero second tile and still recovers the grid; a
/// real spectrum transforms back to the bits of its complex image.
#[test]
fn zero_column_tiles_are_skipped_exactly() {
    let (ny, nx) = (12, 80);
    let wave = |k: usize, x: usize| 2.0 * std::f64::consts::PI * (k * x) as f64 / nx as f64;
    let z = Array2::from_shape_fn((ny, nx), |(j, i)| {
        wave(2, i).cos() + 0.5 * (wave(35, i) + j as f64).sin()
    });
    let half = forward_real_2d(&z).unwrap();
    assert!(half.column(20).iter().all(|c| c.norm() < 1e-12));
    let cut = Array2::from_shape_fn(half.dim(), |(j, i)| {
        if i == 2 || i == 35 {
            half[[j, i]]
        } else {
            Complex::new(0.0, 0.0)
        }
    });
    let back = inverse_real_2d(&cut, nx).unwrap() / (nx * ny) as f64;
    for (a, b) in z.iter().zip(back.iter()) {
        assert!((a - b).abs() < 1e-12, "{a} vs {b}");
    }
    let power = half.mapv(|c| if c.norm() > 1e-9 { c.norm_sqr() } else { 0.0 });
    let from_real = inverse_real_spectrum_2d(&power, nx).unwrap();
    let from_complex = inverse_real_2d(&power.mapv(|p| Complex::new(p, 0.0)), nx).unwrap();
    let bits = |a: &Array2<f64>| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&from_real), bits(&from_complex));
}

/// Buffers given back and allocated again give the bits of a plan that kept them, for the
/// padded column pass (`ny` with a prime factor above 31) and the spectral one; a forward
/// transform started before the release cannot be finished after it.
#[test]
fn released_buffers_give_the_same_bits_and_drop_a_started_transform() {
    for (nx, ny) in [(12, 37), (16, 10)] {
        let input = signal(nx, ny);
        let stencil = even_stencil(nx, ny);
        let mut kept = RealFft2d::for_convolution(nx, ny);
        let kernel = kept
            .convolution_kernel(spectral_kernel(&mut RealFft2d::new(nx, ny), &stencil))
            .unwrap();
        let mut released = RealFft2d::for_convolution(nx, ny);
        let (mut a, mut b) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        for _ in 0..2 {
            kept.convolve(&input, &kernel, &mut a, nx, ny).unwrap();
            released.release_buffers();
            released.convolve(&input, &kernel, &mut b, nx, ny).unwrap();
            assert_eq!(
                a.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                b.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                "{nx} × {ny}"
            );
        }
        released.start_convolve(&input, &kernel, nx, ny).unwrap();
        released.release_buffers();
        assert!(released.finish_convolve(&kernel, &mut b, nx, ny).is_err());
    }
}
