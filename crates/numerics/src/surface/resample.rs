//! Cropping and resampling of height maps.
//!
//! * [`crop`]: a pixel window; spacings unchanged.
//! * [`decimate`]: keeps every `step_x`-th column and `step_y`-th row starting at index 0; the
//!   spacings become `step·d`. No anti-alias filtering is done: apply an S-filter
//!   ([`crate::surface::gaussian_low_pass`]) with a cutoff of at least `2·step·d` first if the
//!   surface has content at the removed scales.
//! * [`resample_bilinear`]: a new grid of `nx' × ny'` points spanning the same extent from the first to
//!   the last point, `dx' = (nx−1)·dx/(nx'−1)`; heights by bilinear interpolation of the four
//!   surrounding points. A new point is missing if any of the corners that carry a non-zero weight is
//!   missing (missing data are never interpolated across).

use super::{HeightMap, HeightMapError};
use ndarray::{s, Array2};

/// Why a crop or resampling was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ResampleError {
    #[error("crop window x {ix0}..{ix0}+{nx}, y {iy0}..{iy0}+{ny} exceeds the {grid_nx} × {grid_ny} grid")]
    WindowOutOfBounds {
        ix0: usize,
        iy0: usize,
        nx: usize,
        ny: usize,
        grid_nx: usize,
        grid_ny: usize,
    },
    #[error("decimation steps must be ≥ 1, got ({step_x}, {step_y})")]
    BadStep { step_x: usize, step_y: usize },
    #[error("target grid {nx} × {ny} is too large to allocate")]
    TooLarge { nx: usize, ny: usize },
    #[error("resampled map is invalid: {0}")]
    HeightMap(#[from] HeightMapError),
}

/// The window of `nx × ny` points whose first point is `(ix0, iy0)`.
pub fn crop(
    map: &HeightMap,
    ix0: usize,
    iy0: usize,
    nx: usize,
    ny: usize,
) -> Result<HeightMap, ResampleError> {
    let fits = |start: usize, len: usize, n: usize| start.checked_add(len).is_some_and(|e| e <= n);
    if !fits(ix0, nx, map.nx()) || !fits(iy0, ny, map.ny()) {
        return Err(ResampleError::WindowOutOfBounds {
            ix0,
            iy0,
            nx,
            ny,
            grid_nx: map.nx(),
            grid_ny: map.ny(),
        });
    }
    let window = map
        .heights()
        .slice(s![iy0..iy0 + ny, ix0..ix0 + nx])
        .to_owned();
    Ok(HeightMap::new(window, map.dx(), map.dy())?)
}

/// Every `step_x`-th column and `step_y`-th row (from index 0); spacings multiplied by the steps.
pub fn decimate(map: &HeightMap, step_x: usize, step_y: usize) -> Result<HeightMap, ResampleError> {
    if step_x == 0 || step_y == 0 {
        return Err(ResampleError::BadStep { step_x, step_y });
    }
    let kept = map.heights().slice(s![..;step_y, ..;step_x]).to_owned();
    Ok(HeightMap::new(
        kept,
        map.dx() * step_x as f64,
        map.dy() * step_y as f64,
    )?)
}

/// Bilinear resampling onto `nx × ny` points spanning the same extent (see the module docs).
pub fn resample_bilinear(
    map: &HeightMap,
    nx: usize,
    ny: usize,
) -> Result<HeightMap, ResampleError> {
    if nx < 2 || ny < 2 {
        return Err(HeightMapError::TooSmall { nx, ny }.into());
    }
    if nx
        .checked_mul(ny)
        .and_then(|n| n.checked_mul(std::mem::size_of::<f64>()))
        .is_none_or(|bytes| bytes > isize::MAX as usize)
    {
        return Err(ResampleError::TooLarge { nx, ny });
    }
    let z = map.heights();
    let ratio_x = (map.nx() - 1) as f64 / (nx - 1) as f64;
    let ratio_y = (map.ny() - 1) as f64 / (ny - 1) as f64;
    let locate = |i: usize, ratio: f64, n_old: usize| {
        let t = i as f64 * ratio;
        let i0 = (t.floor() as usize).min(n_old - 2);
        (i0, t - i0 as f64)
    };
    let out = Array2::from_shape_fn((ny, nx), |(iy, ix)| {
        let (jx, fx) = locate(ix, ratio_x, map.nx());
        let (jy, fy) = locate(iy, ratio_y, map.ny());
        let corners = [
            ((1.0 - fx) * (1.0 - fy), z[[jy, jx]]),
            (fx * (1.0 - fy), z[[jy, jx + 1]]),
            ((1.0 - fx) * fy, z[[jy + 1, jx]]),
            (fx * fy, z[[jy + 1, jx + 1]]),
        ];
        corners
            .iter()
            .filter(|(w, _)| *w != 0.0)
            .map(|(w, h)| w * h)
            .sum()
    });
    Ok(HeightMap::new(out, map.dx() * ratio_x, map.dy() * ratio_y)?)
}
