//! The loaded front of each contact spot: the geometry of a ploughing body's deformed surface
//! ahead of its asperity's tip along the direction it moves, the input of the deformation laws
//! ([`super::closed_forms`], [`super::deformation`]; docs/friction-models.md, "Deformation
//! part").
//!
//! Inputs: the labels of [`crate::friction::contact_spots::label_spots`], the two bodies of the
//! contact solution ([`ContactBodies`]), the ploughing body `b` and the direction m it moves in
//! relative to the other body ([`crate::friction::bodies::motion`]), the spacings `dx`, `dy`
//! (m). All heights are the body's deformed outward surface w_b (its asperities point towards the
//! other body), taken relative to its highest point in the spot, the **tip**; offsets from the
//! tip are minimum images on periodic grids. A point is **ahead** of the tip when its offset
//! along m, u = (x − x_tip)·m, is ≥ 0 (|u| below 1e-9 of a pixel counts as 0).
//!
//! * **Front area** A_f: the spot's points ahead of the tip, those with u = 0 counted half, times
//!   dx dy, so that the fronts of m and −m add up to the spot's area (Bowden–Tabor's loaded half,
//!   πa²/2 for a disc centred on the tip). Its radius a_f = √(2A_f/π) (the half-disc's).
//! * **Front boundary**: the spot's edge points (a 4-neighbour outside it) and its 4-neighbour
//!   ring (outside, a 4-neighbour in it) that lie ahead; the boundary level w_f and distance r_f
//!   are the means of the edge's and the ring's means of height and distance from the tip (the
//!   ring's alone when no edge point lies ahead).
//! * **Cap height** h = w_tip − w_f: how far the asperity stands out of the front boundary, the
//!   penetration of its groove; negative on a surface that is concave there.
//! * **Attack slope** tan α = h / r_f: for a cone whose apex is the tip, its flank slope exactly.
//! * **Groove ratio** A_side/A_f: the silhouette of the cap above w_f seen along m, sampled on
//!   lines along m a third of the smaller spacing apart, at points a third of the smaller spacing
//!   apart from the tip's cross-line forward (heights bilinear; a sample counts when its nearest
//!   grid point is in the spot): A_side = Σ_lines max(0, highest sample − w_f)·δ. This is the
//!   Bowden–Tabor ratio of the spot's own cap: (2/π) tan α for a cone, the sphere's law for a
//!   spherical cap, direction-dependent on an elongated or skewed one.
//! * **Front sphere**: the sphere through the tip and the front boundary, a cap of height h over
//!   the front radius a_f: R_f = (a_f² + h²)/(2h) (h > 0).
//! * **Degree of penetration** D_p = max(h, 0)/a_f (Hokkirigawa & Kato's groove depth over
//!   contact radius).
//!
//! Spots are measured in parallel; the result does not depend on the thread count.

use rayon::prelude::*;

use crate::friction::bodies::ContactBodies;
use crate::friction::contact_spots::{step, SpotLabels};
use crate::friction::error::{require_positive, FrictionError};
use crate::friction::laws::spot::{FrontGeometry, SlidingDirection};
use crate::materials::Side;

/// The four edge neighbours.
const FOUR: [(isize, isize); 4] = [(-1, 0), (1, 0), (0, -1), (0, 1)];

/// Running means of height (relative to the tip) and distance from it.
#[derive(Debug, Clone, Copy, Default)]
struct Mean {
    n: f64,
    z: f64,
    r: f64,
}

impl Mean {
    fn add(&mut self, z: f64, r: f64) {
        self.n += 1.0;
        self.z += z;
        self.r += r;
    }

    fn get(&self) -> Option<(f64, f64)> {
        (self.n > 0.0).then(|| (self.z / self.n, self.r / self.n))
    }
}

/// What measuring one spot's front reads.
struct Front<'a, 'm> {
    labels: &'a SpotLabels,
    bodies: &'a ContactBodies<'m>,
    side: Side,
    motion: SlidingDirection,
    spacing: (f64, f64),
    /// |u| below this is 0 (m).
    tolerance: f64,
}

impl Front<'_, '_> {
    fn nx(&self) -> usize {
        self.labels.labels().ncols()
    }

    fn coords(&self, at: u32) -> (usize, usize) {
        (at as usize / self.nx(), at as usize % self.nx())
    }

    fn in_spot(&self, id: usize, at: u32) -> bool {
        self.labels.labels()[self.coords(at)] as usize == id
    }

    /// The deformed surface at `at`, which must be finite.
    fn surface(&self, at: u32) -> Result<f64, FrictionError> {
        let w = self.bodies.deformed(self.side, self.coords(at));
        if w.is_finite() {
            Ok(w)
        } else {
            Err(FrictionError::InvalidParameter {
                name: "deformed surface",
                value: w,
                expected: "finite heights and deformations at the contact spots and their rings",
            })
        }
    }

    /// Offset `(i, j)` in pixels of `at` from `tip`, minimum image if periodic.
    fn offset(&self, tip: u32, at: u32) -> (f64, f64) {
        let (ny, nx) = self.labels.labels().dim();
        let ((ty, tx), (iy, ix)) = (self.coords(tip), self.coords(at));
        let image = |d: isize, n: usize| {
            let n = n as isize;
            let r = d.rem_euclid(n);
            match (self.labels.periodic(), 2 * r > n) {
                (false, _) => d,
                (true, true) => r - n,
                (true, false) => r,
            }
        };
        let i = image(ix as isize - tx as isize, nx);
        let j = image(iy as isize - ty as isize, ny);
        (i as f64, j as f64)
    }

    /// Offset in metres, its distance and its coordinate u along the motion.
    fn place(&self, tip: u32, at: u32) -> ((f64, f64), f64, f64) {
        let (i, j) = self.offset(tip, at);
        let (x, y) = (i * self.spacing.0, j * self.spacing.1);
        let u = x * self.motion.cos() + y * self.motion.sin();
        let u = if u.abs() <= self.tolerance { 0.0 } else { u };
        ((x, y), x.hypot(y), u)
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

    /// The tip: the highest point of the deformed surface (the first in raster order on ties).
    fn tip(&self, points: &[u32]) -> Result<(u32, f64), FrictionError> {
        let mut tip = (points[0], f64::NEG_INFINITY);
        for &at in points {
            let w = self.surface(at)?;
            if w > tip.1 {
                tip = (at, w);
            }
        }
        Ok(tip)
    }

    /// The front of spot `id` from its points; `None` when no ring point lies ahead (a spot
    /// covering a periodic grid). `ring` is a reusable buffer.
    fn measure(
        &self,
        id: usize,
        points: &[u32],
        ring: &mut Vec<u32>,
    ) -> Result<Option<FrontGeometry>, FrictionError> {
        let (tip, w_tip) = self.tip(points)?;
        let (mut edge, mut front_points) = (Mean::default(), 0.0);
        ring.clear();
        for &at in points {
            let (_, r, u) = self.place(tip, at);
            front_points += if u > 0.0 {
                1.0
            } else if u == 0.0 {
                0.5
            } else {
                0.0
            };
            let before = ring.len();
            self.outside(id, at, &FOUR, ring);
            if ring.len() > before && u >= 0.0 {
                edge.add(self.surface(at)? - w_tip, r);
            }
        }
        ring.sort_unstable();
        ring.dedup();
        let mut outer = Mean::default();
        for &at in ring.iter() {
            let (_, r, u) = self.place(tip, at);
            if u >= 0.0 {
                outer.add(self.surface(at)? - w_tip, r);
            }
        }
        let Some((ring_z, ring_r)) = outer.get() else {
            return Ok(None);
        };
        let (level, distance) = edge.get().map_or((ring_z, ring_r), |(z, r)| {
            (0.5 * (z + ring_z), 0.5 * (r + ring_r))
        });
        let (dx, dy) = self.spacing;
        let front_area = front_points * dx * dy;
        let front_radius = (2.0 * front_area / std::f64::consts::PI).sqrt();
        let cap_height = -level;
        Ok(Some(FrontGeometry {
            cap_height,
            attack_slope: cap_height / distance,
            groove_ratio: self.groove_side(id, (tip, w_tip), points, level)? / front_area,
            front_area,
            front_radius,
            penetration: cap_height.max(0.0) / front_radius,
        }))
    }

    /// A_side: the silhouette of the cap above `level` (relative to the tip) seen along the
    /// motion, over the samples ahead of the tip (see the module docs).
    fn groove_side(
        &self,
        id: usize,
        (tip, w_tip): (u32, f64),
        points: &[u32],
        level: f64,
    ) -> Result<f64, FrictionError> {
        let (dx, dy) = self.spacing;
        let m = self.motion;
        let step_length = dx.min(dy) / 3.0;
        let (mut u_max, mut t_range) = (0.0f64, (f64::MAX, f64::MIN));
        for &at in points {
            let (xy, _, u) = self.place(tip, at);
            let t = m.across(xy);
            u_max = u_max.max(u);
            t_range = (t_range.0.min(t), t_range.1.max(t));
        }
        // Every sample whose nearest point is in the spot: half a pixel beyond the extreme points.
        let pad = dx + dy;
        let lines = ((t_range.0 - pad) / step_length).floor() as i64
            ..=((t_range.1 + pad) / step_length).ceil() as i64;
        let samples = ((u_max + pad) / step_length).ceil() as i64;
        let mut side = 0.0;
        for k in lines {
            let t = k as f64 * step_length;
            let mut top = f64::NEG_INFINITY;
            for s in 0..=samples {
                let u = s as f64 * step_length;
                let offset = (u * m.cos() - t * m.sin(), u * m.sin() + t * m.cos());
                if let Some(w) = self.interpolate(id, tip, w_tip, offset)? {
                    top = top.max(w);
                }
            }
            side += (top - level).max(0.0) * step_length;
        }
        Ok(side)
    }

    /// The deformed surface (relative to the tip) at the offset `(x, y)` (m) from the tip,
    /// bilinear between the four surrounding points; `None` when the nearest point is not in
    /// the spot.
    fn interpolate(
        &self,
        id: usize,
        tip: u32,
        w_tip: f64,
        (x, y): (f64, f64),
    ) -> Result<Option<f64>, FrictionError> {
        let (ny, nx) = self.labels.labels().dim();
        let periodic = self.labels.periodic();
        let (py, px) = self.coords(tip);
        let (fx, fy) = (x / self.spacing.0, y / self.spacing.1);
        let at =
            |sy: isize, sx: isize| match (step(py, sy, ny, periodic), step(px, sx, nx, periodic)) {
                (Some(iy), Some(ix)) => Some((iy * nx + ix) as u32),
                _ => None,
            };
        let nearest = at(fy.round() as isize, fx.round() as isize);
        if nearest.is_none_or(|p| !self.in_spot(id, p)) {
            return Ok(None);
        }
        let (x0, y0) = (fx.floor(), fy.floor());
        let (wx, wy) = (fx - x0, fy - y0);
        let (x0, y0) = (x0 as isize, y0 as isize);
        let mut w = 0.0;
        for (sy, sx, weight) in [
            (y0, x0, (1.0 - wx) * (1.0 - wy)),
            (y0, x0 + 1, wx * (1.0 - wy)),
            (y0 + 1, x0, (1.0 - wx) * wy),
            (y0 + 1, x0 + 1, wx * wy),
        ] {
            if weight > 0.0 {
                // A weight > 0 off an open grid: that side is not sampled, the nearest point is.
                let Some(p) = at(sy, sx) else {
                    return Ok(None);
                };
                w += weight * (self.surface(p)? - w_tip);
            }
        }
        Ok(Some(w))
    }
}

/// The front of every spot of `labels` for the ploughing body `side` moving along `motion`, in
/// id order (see the module docs).
///
/// Errors: bodies on another grid than the labels, `dx` or `dy` not finite and > 0, a deformed
/// surface that is not finite at a spot or its ring.
pub fn front_geometry(
    labels: &SpotLabels,
    bodies: &ContactBodies,
    side: Side,
    motion: SlidingDirection,
    (dx, dy): (f64, f64),
) -> Result<Vec<Option<FrontGeometry>>, FrictionError> {
    let spacing = (require_positive("dx", dx)?, require_positive("dy", dy)?);
    if bodies.dim() != labels.labels().dim() {
        return Err(FrictionError::ShapeMismatch {
            name: "contact maps",
            expected: labels.labels().dim(),
            found: bodies.dim(),
        });
    }
    let front = Front {
        labels,
        bodies,
        side,
        motion,
        spacing,
        tolerance: 1e-9 * dx.min(dy),
    };
    let members = labels.members();
    (0..labels.count())
        .into_par_iter()
        .map_init(Vec::new, |ring, id| front.measure(id, members.of(id), ring))
        .collect()
}
