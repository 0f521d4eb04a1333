//! Wall time of the shared 2-D real FFT (`RealFft2d`) on square grids.
//!
//! `cargo bench -p asperity-numerics --bench fft2`; `FFT2_BENCH_GRIDS=512,1024` picks the grid sizes (default
//! 256, 512, 1024, 2048). Release profile; medians (and minima, in parentheses) of repeated calls after one warm-up.
//!
//! * `round_trip`: forward + inverse + normalisation of a full `n × n` grid (the periodic
//!   contact convolution does the same work).
//! * `periodic`: `convolve` of a full `n × n` grid with an even kernel through
//!   `RealFft2d::for_convolution`, as the periodic contact solver does it (its columns are padded
//!   where `n` has a prime factor above 31).
//! * `dc_convolve`: the non-periodic DC-FFT shape, `convolve` of an `n/2 × n/2` block in the
//!   top-left corner of the `n × n` zero-padded grid with a real kernel, output the same block.
//! * `periodic f32`: `periodic` with single-precision transforms
//!   (`RealFft2d::<f32>::in_precision`, the kernel rounded to `f32`), as the contact solver
//!   iterates before its double-precision polish; `error`: its largest deviation from the
//!   `periodic` result relative to that result's largest magnitude.
//!
//! `checksum` folds the bits of one result from a fixed input: equal checksums across builds
//! mean bit-identical results.

use std::time::Instant;

use asperity_numerics::contact::RealFft2d;
use asperity_numerics::fft2::Real;

/// Median and minimum of the samples.
fn median_min(mut v: Vec<f64>) -> (f64, f64) {
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], v[0])
}

fn reps(n: usize) -> usize {
    match n {
        0..=512 => 31,
        513..=1024 => 15,
        _ => 9,
    }
}

fn signal(len: usize) -> Vec<f64> {
    (0..len)
        .map(|i| ((i * 7919) % 101) as f64 / 101.0 - 0.5)
        .collect()
}

fn checksum(values: &[f64]) -> u64 {
    values
        .iter()
        .fold(0u64, |acc, v| acc.rotate_left(5) ^ v.to_bits())
}

fn timed(reps: usize, mut run: impl FnMut()) -> (f64, f64) {
    run();
    median_min(
        (0..reps)
            .map(|_| {
                let t = Instant::now();
                run();
                t.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

fn round_trip(n: usize) -> ((f64, f64), u64) {
    let mut fft = RealFft2d::new(n, n);
    let mut data = signal(n * n);
    fft.round_trip(&mut data).unwrap();
    let sum = checksum(&data);
    let t = timed(reps(n), || fft.round_trip(&mut data).unwrap());
    (t, sum)
}

/// `periodic` in the precision `T`: timings, checksum and the output.
fn periodic<T: Real>(n: usize) -> ((f64, f64), u64, Vec<f64>) {
    let mut fft = RealFft2d::<T>::in_precision(n, n, true);
    let input = signal(n * n);
    let nxc = n / 2 + 1;
    let spectral: Vec<f64> = (0..nxc * n)
        .map(|i| {
            let (kx, ky) = (i / n, i % n);
            let ky = ky.min(n - ky);
            1.0 / ((1 + kx * kx + ky * ky) as f64 * (n * n) as f64)
        })
        .collect();
    let kernel: Vec<T> = RealFft2d::for_convolution(n, n)
        .convolution_kernel(spectral)
        .unwrap()
        .into_iter()
        .map(T::of)
        .collect();
    let mut output = vec![0.0; n * n];
    fft.convolve(&input, &kernel, &mut output, n, n).unwrap();
    let sum = checksum(&output);
    let t = timed(reps(n), || {
        fft.convolve(&input, &kernel, &mut output, n, n).unwrap()
    });
    (t, sum, output)
}

/// Largest deviation of `values` from `reference` relative to the largest `|reference|`.
fn relative_error(values: &[f64], reference: &[f64]) -> f64 {
    let scale = reference.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let error = values
        .iter()
        .zip(reference)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    error / scale
}

fn dc_convolve(n: usize) -> ((f64, f64), u64) {
    let mut fft = RealFft2d::new(n, n);
    let block = n / 2;
    let input = signal(block * block);
    let kernel: Vec<f64> = signal(fft.spectrum_len())
        .iter()
        .map(|v| v / (n * n) as f64)
        .collect();
    let mut output = vec![0.0; block * block];
    fft.convolve(&input, &kernel, &mut output, block, block)
        .unwrap();
    let sum = checksum(&output);
    let t = timed(reps(n), || {
        fft.convolve(&input, &kernel, &mut output, block, block)
            .unwrap()
    });
    (t, sum)
}

fn main() {
    let grids: Vec<usize> = std::env::var("FFT2_BENCH_GRIDS")
        .ok()
        .map(|s| s.split(',').filter_map(|g| g.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![256, 512, 1024, 2048]);
    println!(
        "{:>6} {:>16} {:>18} {:>16} {:>18} {:>16} {:>18} {:>17} {:>8}",
        "n",
        "round_trip ms",
        "checksum",
        "periodic ms",
        "checksum",
        "dc_convolve ms",
        "checksum",
        "periodic f32 ms",
        "error"
    );
    let ms = |t: (f64, f64)| format!("{:>7.3} ({:>6.3})", t.0 * 1e3, t.1 * 1e3);
    for n in grids {
        let (t_rt, sum_rt) = round_trip(n);
        let (t_p, sum_p, double) = periodic::<f64>(n);
        let (t_dc, sum_dc) = dc_convolve(n);
        let (t_s, _, single) = periodic::<f32>(n);
        println!(
            "{n:>6} {} {sum_rt:>18x} {} {sum_p:>18x} {} {sum_dc:>18x} {} {:>8.1e}",
            ms(t_rt),
            ms(t_p),
            ms(t_dc),
            ms(t_s),
            relative_error(&single, &double)
        );
    }
}
