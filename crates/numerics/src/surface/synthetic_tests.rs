//! Tests of `synthetic`: the parallel synthesis against the row-by-row one.

use super::*;

/// The modes as they were drawn before the parallel collection: row by row, each row from
/// a fresh clone of the generator moved to the row's stream.
fn modes_reference(spec: &SyntheticSurfaceSpec) -> Vec<Complex64> {
    let (nx, ny) = (spec.nx, spec.ny);
    let nxh = nx / 2 + 1;
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&spec.seed.to_le_bytes());
    let base = ChaCha8Rng::from_seed(key);
    let mut modes = vec![Complex64::new(0.0, 0.0); ny * nxh];
    for (j, row) in modes.chunks_mut(nxh).enumerate() {
        let mut rng = base.clone();
        rng.set_stream(mode_stream(j, ny));
        let mut next_drawn = 0;
        for (i, mode) in row.iter_mut().enumerate() {
            let shape = spec.model_psd().mode(i, j);
            if shape == 0.0 {
                continue;
            }
            if next_drawn != i {
                rng.set_word_pos(WORDS_PER_MODE * i as u128);
            }
            let (g1, g2) = standard_normal_pair(&mut rng);
            next_drawn = i + 1;
            let amplitude = shape.sqrt();
            *mode = if self_conjugate(i, j, nx, ny) {
                Complex64::new(amplitude * g1, 0.0)
            } else {
                Complex64::new(amplitude * g1, amplitude * g2) * FRAC_1_SQRT_2
            };
        }
    }
    modes
}

/// The heights as they were normalised before: in one serial pass.
fn heights_reference(spec: &SyntheticSurfaceSpec) -> Vec<u64> {
    let mut half =
        Array2::from_shape_vec((spec.ny, spec.nx / 2 + 1), modes_reference(spec)).unwrap();
    enforce_hermitian_columns(&mut half, spec.nx);
    let mut z = inverse_real_2d(&half, spec.nx).unwrap();
    let n = (spec.nx * spec.ny) as f64;
    let mean = z.sum() / n;
    let rms = (z.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n).sqrt();
    let scale = spec.sq / rms;
    z.mapv_inplace(|v| (v - mean) * scale);
    z.iter().map(|v| v.to_bits()).collect()
}

fn spec(nx: usize, ny: usize, cutoff: Option<f64>, seed: u64) -> SyntheticSurfaceSpec {
    SyntheticSurfaceSpec {
        nx,
        ny,
        lx: 1e-4,
        ly: 1e-4 * ny as f64 / nx as f64,
        sq: 1e-6,
        hurst: 0.8,
        correlation_length: 2e-5,
        short_wavelength_cutoff: cutoff,
        anisotropy: Some(Anisotropy {
            aspect_ratio: 3.0,
            angle: 0.3,
        }),
        seed,
    }
}

/// The parallel collection of the modes and the parallel normalisation give the bits of
/// the row-by-row generation and the serial pass: even and odd grids, rows of one chunk or
/// of many (a row is the smallest chunk), modes without power (a cutoff) between and at
/// the start of rows.
#[test]
fn parallel_synthesis_equals_the_row_by_row_one() {
    for (nx, ny, cutoff) in [
        (64, 64, None),
        (63, 50, None),
        (128, 96, Some(4e-6)),
        (257, 130, Some(2.5e-6)),
        (2, 3, None),
    ] {
        let spec = spec(nx, ny, cutoff, 101 + nx as u64);
        let (map, half, _, _) = synthesize(&spec).unwrap();
        let expected = modes_reference(&spec);
        let mut reference_half = Array2::from_shape_vec((ny, nx / 2 + 1), expected).unwrap();
        enforce_hermitian_columns(&mut reference_half, nx);
        assert!(
            half.iter()
                .zip(&reference_half)
                .all(|(a, b)| a.re.to_bits() == b.re.to_bits() && a.im.to_bits() == b.im.to_bits()),
            "{nx} × {ny}: modes"
        );
        let heights: Vec<u64> = map.heights().iter().map(|v| v.to_bits()).collect();
        assert_eq!(heights, heights_reference(&spec), "{nx} × {ny}: heights");
    }
}

/// [`ModeStream::locate`] gives the row and column of every flat index, in order, after a
/// jump and across row ends.
#[test]
fn modes_are_located_by_steps_and_jumps() {
    let base = ChaCha8Rng::from_seed([0u8; 32]);
    for nxh in [1, 2, 5] {
        let mut stream = ModeStream::new(&base);
        for index in (0..40).chain(57..70).chain([3, 4, 100]) {
            assert_eq!(
                stream.locate(index, nxh),
                (index / nxh, index % nxh),
                "{nxh}"
            );
        }
    }
}

/// [`normalise`] sets each value as the serial pass did and sums the squares; an overflow
/// of a square is not finite.
#[test]
fn normalise_matches_the_serial_pass() {
    let values: Vec<f64> = (0..3 * NORMALISE_CHUNK + 17)
        .map(|i| ((i * 7919) % 1001) as f64 * 1e-3 - 0.4)
        .collect();
    let (mean, scale) = (0.0123, 2.5e-6);
    let mut parallel = values.clone();
    let sum = normalise(&mut parallel, mean, scale);
    let serial: Vec<f64> = values.iter().map(|v| (v - mean) * scale).collect();
    assert!(parallel
        .iter()
        .zip(&serial)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    let expected: f64 = serial.iter().map(|h| h * h).sum();
    assert!(
        (sum - expected).abs() <= 1e-12 * expected,
        "{sum} {expected}"
    );
    let mut huge = vec![1.0, 2.0, -3.0];
    assert!(!normalise(&mut huge, 0.0, 1e200).is_finite());
}
