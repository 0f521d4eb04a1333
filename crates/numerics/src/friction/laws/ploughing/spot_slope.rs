//! The geometry of each contact spot in a sliding direction (docs/friction-models.md,
//! "Deformation part"): the tilt of the composite topography over the spot's footprint, the
//! spot's attack slope and its groove ploughing ratio, the inputs of the deformation laws
//! ([`super::closed_forms`], [`super::deformation`]).
//!
//! Inputs: the labels of [`crate::friction::contact_spots::label_spots`], the spots of
//! [`crate::friction::contact_spots::measure_spots`] (for their highest point) and the undeformed composite
//! height `z = z1 + z2` (m, peaks up) on spacings `dx`, `dy` (m); the sliding direction `d` at
//! the angle ψ from +x towards +y ([`SlidingDirection`]). Offsets are taken from the spot's
//! highest point (minimum image on periodic grids).
//!
//! **Tilt** (the junction plane). A least-squares plane `z ≈ c₀ + c₁ i + c₂ j` (`i`, `j` column
//! and row offsets in pixels) is fitted to the composite height over the spot's own points (its
//! footprint). Its gradient `g = (c₁/dx, c₂/dy)` is the mean slope of the topography under the
//! junction on the spot's own scale, not the pixel gradient. When the footprint's points are
//! collinear (one pixel, a straight line of pixels) the plane is fitted over the footprint and
//! its 8-neighbour ring (clipped at the edges of open grids), as the paraboloid of the radius is,
//! and the spot says so (`dilated`). `tan θ = g · d`, positive when the topography rises in the
//! sliding direction (an up-slope junction).
//!
//! **Boundary level.** The spot's edge (its points with a 4-neighbour outside it) lies just
//! inside the line where the contact ends, its 4-neighbour ring (the points outside it with a
//! 4-neighbour in it) just outside. The boundary height `z_b` and distance `r_b` (from the
//! highest point, m) are the means of the edge's and the ring's means.
//!
//! **Attack slope** (the flank). `tan α = (z_peak − z_b)/r_b`, with `z_peak − z_b` the height of
//! the cap (the spot's penetration). For a cone whose apex is the highest point it is the flank
//! slope exactly, at any resolution; for a paraboloid cap about `a/(2R)`; for a one-pixel spot
//! the slope to its four neighbours.
//!
//! **Groove ploughing ratio** (Bowden–Tabor, measured). The cross-section of the groove the spot
//! would plough along `d` is the silhouette of its cap above `z_b` seen along `d`. It is sampled
//! on lines along `d` through the highest point and parallel to it, `δt = dx |sin ψ| + dy |cos ψ|`
//! apart (a pixel's extent across `d`), at points `δu = dx |cos ψ| + dy |sin ψ|` apart along each
//! line, wherever the nearest grid point is in the spot; heights between grid points are
//! bilinear. For ψ = 0 the lines are the rows and the points the grid points. With `S_k` the
//! highest sample of line `k`, `A_side = Σ_k max(0, S_k − z_b) δt`, and the ratio is
//! `2 A_side / A`, the groove cross-section over half the footprint: the ploughing friction of
//! the spot's own cap ([`super::closed_forms`]), which is `(2/π) tan α` for a cone and the
//! sphere's law for a spherical cap, and which differs along and across the lay of an elongated
//! asperity.
//!
//! Spots are measured in parallel; the result does not depend on the thread count. Their
//! dependence on the sampling interval is measured in docs/friction-models.md.

use ndarray::ArrayView2;
use rayon::prelude::*;

use crate::friction::contact_spots::{step, ContactSpot, Members, SpotLabels};
use crate::friction::error::{require_positive, FrictionError};
use crate::friction::laws::spot::{SlidingDirection, SpotSlope};

/// Sums of the least-squares plane of one spot.
#[derive(Debug, Clone, Copy, Default)]
struct PlaneSums {
    n: f64,
    i: f64,
    j: f64,
    ii: f64,
    ij: f64,
    jj: f64,
    z: f64,
    iz: f64,
    jz: f64,
}

impl PlaneSums {
    fn add(&mut self, (i, j): (f64, f64), z: f64) {
        self.n += 1.0;
        self.i += i;
        self.j += j;
        self.ii += i * i;
        self.ij += i * j;
        self.jj += j * j;
        self.z += z;
        self.iz += i * z;
        self.jz += j * z;
    }

    /// The plane's slopes `(c₁, c₂)` per pixel from the centred normal equations; `None` when the
    /// points are collinear (the 2 × 2 determinant is below 1e-9 of the product of its diagonal).
    fn solve(&self) -> Option<(f64, f64)> {
        let n = self.n;
        let (mi, mj, mz) = (self.i / n, self.j / n, self.z / n);
        let cii = self.ii / n - mi * mi;
        let cjj = self.jj / n - mj * mj;
        let cij = self.ij / n - mi * mj;
        let ciz = self.iz / n - mi * mz;
        let cjz = self.jz / n - mj * mz;
        let det = cii * cjj - cij * cij;
        (det > 1e-9 * cii * cjj)
            .then(|| ((ciz * cjj - cjz * cij) / det, (cjz * cii - ciz * cij) / det))
    }
}

/// Means of height (relative to the highest point) and distance from it over a set of points.
#[derive(Debug, Clone, Copy, Default)]
struct BoundaryMean {
    n: f64,
    z: f64,
    r: f64,
}

impl BoundaryMean {
    fn add(&mut self, z: f64, r: f64) {
        self.n += 1.0;
        self.z += z;
        self.r += r;
    }

    fn mean(&self) -> (f64, f64) {
        (self.z / self.n, self.r / self.n)
    }
}

/// What measuring one spot reads.
struct Grid<'a> {
    labels: &'a SpotLabels,
    height: ArrayView2<'a, f64>,
    spots: &'a [ContactSpot],
    spacing: (f64, f64),
    direction: SlidingDirection,
}

/// The four edge neighbours and the eight neighbours of a point.
const FOUR: [(isize, isize); 4] = [(-1, 0), (1, 0), (0, -1), (0, 1)];

impl Grid<'_> {
    fn nx(&self) -> usize {
        self.labels.labels().ncols()
    }

    fn coords(&self, at: u32) -> (usize, usize) {
        (at as usize / self.nx(), at as usize % self.nx())
    }

    /// Height at `at` relative to the highest point of `id`; it must be finite.
    fn height(&self, id: usize, at: u32) -> Result<f64, FrictionError> {
        let z = self.height[self.coords(at)];
        if z.is_finite() {
            Ok(z - self.height[self.spots[id].peak])
        } else {
            Err(FrictionError::InvalidParameter {
                name: "composite_height",
                value: z,
                expected: "finite values at the contact spots and their 8-neighbours",
            })
        }
    }

    /// Offset `(i, j)` in pixels of `at` from the highest point of `id`, minimum image if
    /// periodic.
    fn offset(&self, id: usize, at: u32) -> (f64, f64) {
        let (ny, nx) = self.labels.labels().dim();
        let ((py, px), (iy, ix)) = (self.spots[id].peak, self.coords(at));
        let image = |d: isize, n: usize| {
            let n = n as isize;
            let r = d.rem_euclid(n);
            match (self.labels.periodic(), 2 * r > n) {
                (false, _) => d,
                (true, true) => r - n,
                (true, false) => r,
            }
        };
        let i = image(ix as isize - px as isize, nx);
        let j = image(iy as isize - py as isize, ny);
        (i as f64, j as f64)
    }

    /// The offset of `at` from the highest point of `id` in metres.
    fn metres(&self, id: usize, at: u32) -> (f64, f64) {
        let (i, j) = self.offset(id, at);
        (i * self.spacing.0, j * self.spacing.1)
    }

    /// The neighbours `shifts` of `at` that are not in spot `id`, pushed to `out`.
    fn outside(&self, id: usize, at: u32, shifts: &[(isize, isize)], out: &mut Vec<u32>) {
        let (ny, nx) = self.labels.labels().dim();
        let periodic = self.labels.periodic();
        let (iy, ix) = self.coords(at);
        for &(sy, sx) in shifts {
            if let (Some(y), Some(x)) = (step(iy, sy, ny, periodic), step(ix, sx, nx, periodic)) {
                if self.labels.labels()[[y, x]] as usize != id {
                    out.push((y * nx + x) as u32);
                }
            }
        }
    }

    /// Measures spot `id` from its points; `ring` is a reusable buffer.
    fn measure(
        &self,
        id: usize,
        points: &[u32],
        ring: &mut Vec<u32>,
    ) -> Result<SpotSlope, FrictionError> {
        let mut plane = PlaneSums::default();
        let mut edge = BoundaryMean::default();
        ring.clear();
        for &at in points {
            let z = self.height(id, at)?;
            plane.add(self.offset(id, at), z);
            let before = ring.len();
            self.outside(id, at, &FOUR, ring);
            if ring.len() > before {
                let (x, y) = self.metres(id, at);
                edge.add(z, x.hypot(y));
            }
        }
        ring.sort_unstable();
        ring.dedup();
        let mut outer = BoundaryMean::default();
        for &at in ring.iter() {
            let (x, y) = self.metres(id, at);
            outer.add(self.height(id, at)?, x.hypot(y));
        }
        let dilated = plane.solve().is_none();
        if dilated {
            self.dilate(id, points, ring, &mut plane)?;
        }
        let (dx, dy) = self.spacing;
        let gradient = plane.solve().map(|(ci, cj)| (ci / dx, cj / dy));
        let boundary = (outer.n > 0.0).then(|| {
            let ((ze, re), (zr, rr)) = (edge.mean(), outer.mean());
            (0.5 * (ze + zr), 0.5 * (re + rr))
        });
        Ok(SpotSlope {
            gradient,
            tilt: gradient.map(|g| self.direction.along(g)),
            plane_points: plane.n as usize,
            dilated,
            cap_height: boundary.map(|(z, _)| -z),
            attack_slope: boundary.map(|(z, r)| -z / r),
            groove_ratio: boundary
                .map(|(z, _)| self.groove_ratio(id, points, z))
                .transpose()?,
        })
    }

    /// Adds the 8-neighbour ring of the spot to the plane (`ring` is reused).
    fn dilate(
        &self,
        id: usize,
        points: &[u32],
        ring: &mut Vec<u32>,
        plane: &mut PlaneSums,
    ) -> Result<(), FrictionError> {
        let eight: Vec<(isize, isize)> = (-1..=1)
            .flat_map(|sy| (-1..=1).map(move |sx| (sy, sx)))
            .filter(|&s| s != (0, 0))
            .collect();
        ring.clear();
        for &at in points {
            self.outside(id, at, &eight, ring);
        }
        ring.sort_unstable();
        ring.dedup();
        for &at in ring.iter() {
            plane.add(self.offset(id, at), self.height(id, at)?);
        }
        Ok(())
    }

    /// `2 A_side/A` of the spot's cap above the boundary height `level` (relative to the highest
    /// point) along the sliding direction (see the module documentation for the lines).
    fn groove_ratio(&self, id: usize, points: &[u32], level: f64) -> Result<f64, FrictionError> {
        let (dx, dy) = self.spacing;
        let d = self.direction;
        let (du, dt) = (dx.min(dy) / 3.0, dx.min(dy) / 3.0);
        let (mut u_range, mut t_range) = ((f64::MAX, f64::MIN), (f64::MAX, f64::MIN));
        for &at in points {
            let (x, y) = self.metres(id, at);
            let (u, t) = (x * d.cos() + y * d.sin(), d.across((x, y)));
            u_range = (u_range.0.min(u), u_range.1.max(u));
            t_range = (t_range.0.min(t), t_range.1.max(t));
        }
        // Every sample whose nearest point is in the spot: half a pixel beyond the extreme points.
        let pad = dx + dy;
        let steps = |(lo, hi): (f64, f64), h: f64| {
            ((lo - pad) / h).floor() as i64..=((hi + pad) / h).ceil() as i64
        };
        let mut side = 0.0;
        for k in steps(t_range, dt) {
            let mut top = f64::NEG_INFINITY;
            for m in steps(u_range, du) {
                let (u, t) = (m as f64 * du, k as f64 * dt);
                let offset = (u * d.cos() - t * d.sin(), u * d.sin() + t * d.cos());
                if let Some(z) = self.interpolate(id, offset)? {
                    top = top.max(z);
                }
            }
            side += (top - level).max(0.0) * dt;
        }
        Ok(2.0 * side / (points.len() as f64 * dx * dy))
    }

    /// The composite height (relative to the highest point of `id`) at the offset `(x, y)` (m)
    /// from that point, bilinear between the four surrounding points; `None` when the nearest
    /// point is not in the spot.
    fn interpolate(&self, id: usize, (x, y): (f64, f64)) -> Result<Option<f64>, FrictionError> {
        let (ny, nx) = self.labels.labels().dim();
        let periodic = self.labels.periodic();
        let (py, px) = self.spots[id].peak;
        let (fx, fy) = (x / self.spacing.0, y / self.spacing.1);
        let at =
            |sy: isize, sx: isize| match (step(py, sy, ny, periodic), step(px, sx, nx, periodic)) {
                (Some(iy), Some(ix)) => Some((iy * nx + ix) as u32),
                _ => None,
            };
        let nearest = at(fy.round() as isize, fx.round() as isize);
        if nearest.is_none_or(|p| self.labels.labels()[self.coords(p)] as usize != id) {
            return Ok(None);
        }
        let (x0, y0) = (fx.floor(), fy.floor());
        let (wx, wy) = (fx - x0, fy - y0);
        let (x0, y0) = (x0 as isize, y0 as isize);
        let mut z = 0.0;
        for (sy, sx, w) in [
            (y0, x0, (1.0 - wx) * (1.0 - wy)),
            (y0, x0 + 1, wx * (1.0 - wy)),
            (y0 + 1, x0, (1.0 - wx) * wy),
            (y0 + 1, x0 + 1, wx * wy),
        ] {
            if w > 0.0 {
                // A weight > 0 off an open grid: that side is not sampled, the nearest point is.
                let Some(p) = at(sy, sx) else {
                    return Ok(None);
                };
                z += w * self.height(id, p)?;
            }
        }
        Ok(Some(z))
    }
}

/// The geometry of every spot along `direction`, in id order (see the module documentation);
/// `spots` from [`crate::friction::contact_spots::measure_spots`] of these `labels`.
///
/// Errors: a height map of another shape than the labels, a spot list of another length than the
/// labels' count, `dx` or `dy` not finite and > 0, a composite height that is not finite at a
/// spot or its 8-neighbours.
pub fn spot_slopes(
    labels: &SpotLabels,
    spots: &[ContactSpot],
    composite_height: ArrayView2<f64>,
    (dx, dy): (f64, f64),
    direction: SlidingDirection,
) -> Result<Vec<SpotSlope>, FrictionError> {
    let spacing = (require_positive("dx", dx)?, require_positive("dy", dy)?);
    if composite_height.dim() != labels.labels().dim() {
        return Err(FrictionError::ShapeMismatch {
            name: "composite_height",
            expected: labels.labels().dim(),
            found: composite_height.dim(),
        });
    }
    if spots.len() != labels.count() {
        return Err(FrictionError::InvalidParameter {
            name: "spots",
            value: spots.len() as f64,
            expected: "one spot per label (measure_spots of the same labels)",
        });
    }
    let grid = Grid {
        labels,
        height: composite_height,
        spots,
        spacing,
        direction,
    };
    let members = Members::gather(labels);
    (0..labels.count())
        .into_par_iter()
        .map_init(Vec::new, |ring, id| grid.measure(id, members.of(id), ring))
        .collect()
}
