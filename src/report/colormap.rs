//! A perceptually uniform colour map for height and pressure maps: piecewise-linear
//! interpolation between nine anchor colours sampled from matplotlib's *viridis* (van der Walt &
//! Smith 2015), dark violet (low) to yellow (high), readable in greyscale and with colour-vision
//! deficiencies.

/// The anchor colours at t = 0, 1/8, …, 1.
pub const ANCHORS: [[u8; 3]; 9] = [
    [0x44, 0x01, 0x54],
    [0x47, 0x2c, 0x7a],
    [0x3b, 0x51, 0x8b],
    [0x2c, 0x71, 0x8e],
    [0x21, 0x90, 0x8d],
    [0x27, 0xad, 0x81],
    [0x5c, 0xc8, 0x63],
    [0xaa, 0xdc, 0x32],
    [0xfd, 0xe7, 0x25],
];

/// The colour at `t` in `[0, 1]` (clamped; NaN maps to the low end).
pub fn colour(t: f64) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let position = t * (ANCHORS.len() - 1) as f64;
    let i = (position.floor() as usize).min(ANCHORS.len() - 2);
    let f = position - i as f64;
    let (a, b) = (ANCHORS[i], ANCHORS[i + 1]);
    let mix = |k: usize| (f64::from(a[k]) + f * (f64::from(b[k]) - f64::from(a[k]))).round() as u8;
    [mix(0), mix(1), mix(2)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_map_runs_from_violet_to_yellow_with_rising_lightness() {
        assert_eq!(colour(0.0), ANCHORS[0]);
        assert_eq!(colour(1.0), ANCHORS[8]);
        assert_eq!(colour(0.5), ANCHORS[4]);
        // Rec. 709 luma must rise monotonically so the map reads in greyscale.
        let luma = |c: [u8; 3]| {
            0.2126 * f64::from(c[0]) + 0.7152 * f64::from(c[1]) + 0.0722 * f64::from(c[2])
        };
        let l: Vec<f64> = (0..=20)
            .map(|i| luma(colour(f64::from(i) / 20.0)))
            .collect();
        assert!(l.windows(2).all(|w| w[1] > w[0]), "{l:?}");
    }
}
