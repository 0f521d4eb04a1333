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
pub fn slope_baseline(
    bodies: &ContactBodies,
    side: Side,
    direction: SlidingDirection,
    (dx, dy): (f64, f64),
    periodic: bool,
) -> f64 {
    let (ny, nx) = bodies.dim();
    let neighbours = |i: usize, n: usize| {
        if periodic {
            Some(((i + n - 1) % n, (i + 1) % n))
        } else {
            (i > 0 && i + 1 < n).then(|| (i - 1, i + 1))
        }
    };
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
