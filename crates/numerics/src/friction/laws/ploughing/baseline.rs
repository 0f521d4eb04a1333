//! The topography-only baseline of the deformation part: if every spot's attack slope were the
//! rms slope of the ploughing body's surface along the sliding direction, the cone law would
//! give μ_d = (2/π) s_ψ (docs/friction-models.md, "The baseline"). What the contact solution
//! adds to the deformation part is its distance from this number (which asperities carry load,
//! at which slopes, in which regime).
//!
//! s_ψ² is the mean over the section of (∂z_b/∂x cos ψ + ∂z_b/∂y sin ψ)², z_b the undeformed
//! outward heights of the ploughing body ([`ContactBodies::height`]), by central differences
//! ((z[i+1] − z[i−1])/(2h)); on a periodic section the neighbours wrap around, on an open one
//! only interior points contribute. The sign of ψ does not matter: s_ψ = s_{ψ+π}.

use std::f64::consts::FRAC_2_PI;

use crate::friction::bodies::ContactBodies;
use crate::friction::laws::spot::SlidingDirection;
use crate::materials::Side;

/// (2/π) s_ψ of `side`'s surface over the section (0 on a grid without an interior point).
///
/// One pass over the rows, each point's square added in row-major order.
pub fn slope_baseline(
    bodies: &ContactBodies,
    side: Side,
    direction: SlidingDirection,
    (dx, dy): (f64, f64),
    periodic: bool,
) -> f64 {
    let (ny, nx) = bodies.dim();
    let neighbours = |i: usize, n: usize| neighbours(i, n, periodic);
    let columns: Vec<(usize, usize, usize)> = (0..nx)
        .filter_map(|ix| neighbours(ix, nx).map(|(left, right)| (ix, left, right)))
        .collect();
    let (mut above, mut here, mut below) = (vec![0.0; nx], vec![0.0; nx], vec![0.0; nx]);
    let (mut sum, mut count) = (0.0, 0usize);
    for iy in 0..ny {
        let Some((up, down)) = neighbours(iy, ny) else {
            continue;
        };
        bodies.height_row(side, up, &mut above);
        bodies.height_row(side, iy, &mut here);
        bodies.height_row(side, down, &mut below);
        for &(ix, left, right) in &columns {
            let gx = (here[right] - here[left]) / (2.0 * dx);
            let gy = (below[ix] - above[ix]) / (2.0 * dy);
            let s = direction.along((gx, gy));
            sum += s * s;
        }
        count += columns.len();
    }
    if count == 0 {
        0.0
    } else {
        FRAC_2_PI * (sum / count as f64).sqrt()
    }
}

/// The central-difference neighbours `(i − 1, i + 1)` of index `i` of `n`: wrapped around on a
/// periodic section, none at an open section's edges.
fn neighbours(i: usize, n: usize, periodic: bool) -> Option<(usize, usize)> {
    if periodic {
        Some(((i + n - 1) % n, (i + 1) % n))
    } else {
        (i > 0 && i + 1 < n).then(|| (i - 1, i + 1))
    }
}

#[cfg(test)]
mod tests {
    use ndarray::Array2;

    use super::*;
    use crate::friction::bodies::{BodyHardness, BodyMaps};

    /// The definition point by point: central differences of [`ContactBodies::height`].
    fn pointwise(
        bodies: &ContactBodies,
        side: Side,
        direction: SlidingDirection,
        (dx, dy): (f64, f64),
        periodic: bool,
    ) -> f64 {
        let (ny, nx) = bodies.dim();
        let neighbours = |i: usize, n: usize| neighbours(i, n, periodic);
        let z = |iy: usize, ix: usize| bodies.height(side, (iy, ix));
        let (mut sum, mut count) = (0.0, 0usize);
        for iy in 0..ny {
            let Some((up, down)) = neighbours(iy, ny) else {
                continue;
            };
            for ix in 0..nx {
                let Some((left, right)) = neighbours(ix, nx) else {
                    continue;
                };
                let gx = (z(iy, right) - z(iy, left)) / (2.0 * dx);
                let gy = (z(down, ix) - z(up, ix)) / (2.0 * dy);
                let s = direction.along((gx, gy));
                sum += s * s;
                count += 1;
            }
        }
        if count == 0 {
            0.0
        } else {
            FRAC_2_PI * (sum / count as f64).sqrt()
        }
    }

    fn rough((ny, nx): (usize, usize), phase: f64) -> Array2<f64> {
        Array2::from_shape_fn((ny, nx), |(iy, ix)| {
            1e-6 * ((0.7 * ix as f64 + phase).sin() + (1.3 * iy as f64 - phase).cos())
                + 1e-7 * ((ix * 31 + iy * 17) % 13) as f64
        })
    }

    #[test]
    fn rows_give_the_pointwise_sum_bit_for_bit() {
        for shape in [(7, 11), (1, 5), (2, 2), (3, 1), (16, 9)] {
            let composite = rough(shape, 0.3);
            let upper = rough(shape, 1.9);
            let zeros = Array2::zeros(shape);
            for upper in [None, Some(upper.view())] {
                let maps = BodyMaps {
                    composite_height: composite.view(),
                    upper_height: upper,
                    deformation_lower: zeros.view().into(),
                    deformation_upper: None,
                    plastic_penetration: zeros.view().into(),
                };
                let bodies = ContactBodies::new(
                    maps,
                    BodyHardness {
                        lower: 2e9,
                        upper: 3e9,
                    },
                )
                .unwrap();
                for side in [Side::Lower, Side::Upper] {
                    for angle in [0.0, 0.4, -2.0] {
                        let direction = SlidingDirection::new(angle).unwrap();
                        for periodic in [true, false] {
                            let spacing = (0.5e-6, 0.7e-6);
                            let expected = pointwise(&bodies, side, direction, spacing, periodic);
                            let found = slope_baseline(&bodies, side, direction, spacing, periodic);
                            assert_eq!(
                                found.to_bits(),
                                expected.to_bits(),
                                "{shape:?} {side:?} ψ = {angle} periodic {periodic}"
                            );
                        }
                    }
                }
            }
        }
    }
}
