//! Contact spots of a solved boundary-element contact (docs/friction-models.md, "Per contact
//! spot"): the connected components of the points in contact, with their area, load, highest
//! point and a radius of curvature from the composite topography, and the Lennard-Jones adhesion
//! of the points out of contact.
//!
//! Inputs are plain arrays `[[iy, ix]]` of one solved contact: the pressure `p` (Pa), the
//! undeformed composite height `z = z1 + z2` (m, peaks up) and the gap after loading `g` (m),
//! with the spacings `dx`, `dy` (m).
//!
//! **Spots.** A point is in contact when `p > 0` (a NaN or negative pressure is not). Spots are the
//! connected components of those points, 4- or 8-connected ([`Connectivity`]); on periodic grids
//! the neighbourhood wraps around the edges, so a spot crossing x = 0 or y = 0 is one spot. Spot
//! ids are `0..count` in the order of each spot's first point in row-major order (the smallest
//! `iy·nx + ix` of any member): the labelling depends on the input only.
//!
//! **Labelling** ([`label_spots`]) is one raster scan with a union–find over provisional labels
//! (the root of a set is its smallest label, which is the label of the set's first point in
//! raster order), the wrap-around unions on periodic grids and one relabelling pass: O(N) time,
//! serial, no allocation per point.
//!
//! **Per spot** ([`measure_spots`], [`contact_spots`]): points, area `A = n dx dy`, load
//! `P = Σ p dx dy`, highest point of `z` (ties: the first in raster order), highest pressure, and
//! the radius of curvature of the least-squares paraboloid
//!
//! `z(i, j) ≈ c0 + c1 i + c2 j + c3 i² + c4 i j + c5 j²`,
//!
//! fitted to the composite height over the spot's points and their 8-neighbour ring (so one pixel
//! is fitted over its 3 × 3 neighbourhood and a line of pixels is not degenerate), with `i`, `j`
//! the column and row offsets in pixels from the spot's highest point (minimum-image offsets on
//! periodic grids; on open grids the ring is clipped at the edges). The mean curvature is
//! `κ = c3/dx² + c5/dy² = (z_xx + z_yy)/2` and the radius `R = −1/κ` when `κ < 0`, `None` when
//! `κ ≥ 0` (a saddle or valley) or when the 6 × 6 normal equations are singular (fewer than six
//! independent points, e.g. a corner pixel of an open grid). The normal equations are built in
//! offsets scaled to `[−1, 1]` and heights relative to the highest point, and solved by Gaussian
//! elimination with partial pivoting. A spot wider than half a period on a periodic grid has no
//! unique minimum image and its radius is not meaningful. One-pixel spots are resolution-limited:
//! count and report them rather than trust their radius. Nor is the radius meaningful when the
//! spot holds two or more summits of the composite height (its points higher than each of their
//! 8-neighbours): several asperities have merged into one junction (`summits`).

use ndarray::{Array2, ArrayView2};
use rayon::prelude::*;

use super::error::{require_non_negative, require_positive, FrictionError};
use super::material::AdhesionParameters;
use super::paraboloid_fit::NormalEquations;
use crate::contact::PointMap;

/// Which neighbours join two contact points into one spot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Connectivity {
    /// The four edge neighbours (±x, ±y).
    Four,
    /// The four edge and the four corner neighbours.
    Eight,
}

/// The spot of every grid point, from [`label_spots`].
#[derive(Debug, Clone, PartialEq)]
pub struct SpotLabels {
    labels: Array2<u32>,
    count: usize,
    periodic: bool,
    /// The points of every spot, gathered once for everything that walks the spots.
    members: Members,
}

impl SpotLabels {
    /// The label of the points out of contact.
    pub const OUTSIDE: u32 = u32::MAX;

    /// Spot id of every point `[[iy, ix]]` (`0..count`), [`Self::OUTSIDE`] out of contact.
    pub fn labels(&self) -> ArrayView2<'_, u32> {
        self.labels.view()
    }

    /// Number of spots.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Whether the spots were joined across the edges of a periodic grid.
    pub fn periodic(&self) -> bool {
        self.periodic
    }

    /// The points of every spot.
    pub(crate) fn members(&self) -> &Members {
        &self.members
    }

    /// Spot id of the point `(iy, ix)`; `None` out of contact or out of the grid.
    pub fn spot_at(&self, iy: usize, ix: usize) -> Option<usize> {
        self.labels
            .get([iy, ix])
            .filter(|&&l| l != Self::OUTSIDE)
            .map(|&l| l as usize)
    }
}

/// One contact spot (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSpot {
    /// Number of points in contact.
    pub pixels: usize,
    /// True contact area `pixels · dx · dy` (m²).
    pub area: f64,
    /// Load carried `Σ p dx dy` (N).
    pub load: f64,
    /// The point of highest composite height `(iy, ix)`.
    pub peak: (usize, usize),
    /// Highest pressure in the spot (Pa).
    pub max_pressure: f64,
    /// Radius of curvature `R = −1/κ` of the fitted paraboloid (m); `None` when `κ ≥ 0` or the
    /// fit is singular.
    pub radius: Option<f64>,
    /// Number of points of the fit (the spot and its 8-neighbour ring).
    pub radius_points: usize,
    /// Summits of the composite height in the spot: its points higher than each of their
    /// 8-neighbours (those in the grid; wrapped on periodic grids). Two or more: the spot is
    /// several asperities merged into one, whose single radius means nothing.
    pub summits: usize,
}

/// Whether a point with pressure `p` is in contact.
fn in_contact(p: f64) -> bool {
    p > 0.0
}

/// Union–find over provisional labels; a root is always the smallest label of its set.
#[derive(Default)]
struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    fn new_label(&mut self) -> u32 {
        let label = self.parent.len() as u32;
        self.parent.push(label);
        label
    }

    fn find(&mut self, mut label: u32) -> u32 {
        loop {
            let parent = self.parent[label as usize];
            if parent == label {
                return label;
            }
            let grand = self.parent[parent as usize];
            self.parent[label as usize] = grand;
            label = grand;
        }
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra < rb {
            self.parent[rb as usize] = ra;
        } else if rb < ra {
            self.parent[ra as usize] = rb;
        }
    }

    /// Final ids in the order of the roots, which is the order of each set's first point.
    fn renumber(&mut self) -> (Vec<u32>, usize) {
        let mut table = vec![0u32; self.parent.len()];
        let mut count = 0u32;
        for label in 0..self.parent.len() {
            let root = self.find(label as u32) as usize;
            table[label] = if root == label {
                count += 1;
                count - 1
            } else {
                table[root]
            };
        }
        (table, count as usize)
    }

    /// Label of the contact point `(iy, ix)` from its neighbours already scanned (left and the row
    /// above), merging their sets; a new label if it has none.
    fn label_point(&mut self, labels: &Array2<u32>, iy: usize, ix: usize, eight: bool) -> u32 {
        let mut label = SpotLabels::OUTSIDE;
        let mut merge = |other: u32| {
            if other != SpotLabels::OUTSIDE {
                if label == SpotLabels::OUTSIDE {
                    label = other;
                } else {
                    self.union(label, other);
                }
            }
        };
        if ix > 0 {
            merge(labels[[iy, ix - 1]]);
        }
        if iy > 0 {
            merge(labels[[iy - 1, ix]]);
            if eight && ix > 0 {
                merge(labels[[iy - 1, ix - 1]]);
            }
            if eight && ix + 1 < labels.ncols() {
                merge(labels[[iy - 1, ix + 1]]);
            }
        }
        if label == SpotLabels::OUTSIDE {
            self.new_label()
        } else {
            label
        }
    }

    /// Joins the sets that touch across the edges of a periodic grid: the last column with the
    /// first (rows shifted by −1, 0, +1 with 8-connectivity) and the last row with the first.
    fn wrap(&mut self, labels: &Array2<u32>, eight: bool) {
        let (ny, nx) = labels.dim();
        let shifts = if eight { 3 } else { 1 };
        let mut join = |a: u32, b: u32| {
            if a != SpotLabels::OUTSIDE && b != SpotLabels::OUTSIDE {
                self.union(a, b);
            }
        };
        for iy in 0..ny {
            for s in [0, 1, ny - 1].into_iter().take(shifts) {
                join(labels[[iy, nx - 1]], labels[[(iy + s) % ny, 0]]);
            }
        }
        for ix in 0..nx {
            for s in [0, 1, nx - 1].into_iter().take(shifts) {
                join(labels[[ny - 1, ix]], labels[[0, (ix + s) % nx]]);
            }
        }
    }
}

/// Labels the contact spots: connected components of the points with `p > 0`, joined across the
/// edges when `periodic`, ids in the order of each spot's first point in row-major order.
///
/// Fails only for a grid of 2³² − 1 points or more (labels are `u32`).
pub fn label_spots(
    pressure: ArrayView2<f64>,
    periodic: bool,
    connectivity: Connectivity,
) -> Result<SpotLabels, FrictionError> {
    let (ny, nx) = pressure.dim();
    if ny * nx >= SpotLabels::OUTSIDE as usize {
        return Err(FrictionError::InvalidParameter {
            name: "pressure (grid points)",
            value: (ny * nx) as f64,
            expected: "fewer than 2^32 - 1 points",
        });
    }
    let eight = connectivity == Connectivity::Eight;
    let mut labels = Array2::from_elem((ny, nx), SpotLabels::OUTSIDE);
    let mut sets = UnionFind::default();
    for (iy, row) in pressure.outer_iter().enumerate() {
        for (ix, &p) in row.iter().enumerate() {
            if in_contact(p) {
                labels[[iy, ix]] = sets.label_point(&labels, iy, ix, eight);
            }
        }
    }
    if periodic && ny * nx > 0 {
        sets.wrap(&labels, eight);
    }
    let (table, count) = sets.renumber();
    labels.mapv_inplace(|l| {
        table
            .get(l as usize)
            .copied()
            .unwrap_or(SpotLabels::OUTSIDE)
    });
    let members = Members::gather(&labels, count);
    Ok(SpotLabels {
        labels,
        count,
        periodic,
        members,
    })
}

/// Labels the spots and measures them: [`label_spots`] then [`measure_spots`].
pub fn contact_spots(
    pressure: ArrayView2<f64>,
    composite_height: ArrayView2<f64>,
    dx: f64,
    dy: f64,
    periodic: bool,
    connectivity: Connectivity,
) -> Result<Vec<ContactSpot>, FrictionError> {
    let labels = label_spots(pressure, periodic, connectivity)?;
    measure_spots(&labels, pressure, composite_height, dx, dy)
}

/// Area, load, highest point, highest pressure and radius of every labelled spot, in id order
/// (see the module documentation for the fit); `labels` from [`label_spots`] of this `pressure`.
/// Spots of every size are fitted over their points and ring. Spots are measured in parallel;
/// the result does not depend on the thread count.
///
/// Errors: arrays of another shape than the labels, `dx` or `dy` not finite and > 0, a composite
/// height that is not finite at a spot or its ring.
pub fn measure_spots(
    labels: &SpotLabels,
    pressure: ArrayView2<f64>,
    composite_height: ArrayView2<f64>,
    dx: f64,
    dy: f64,
) -> Result<Vec<ContactSpot>, FrictionError> {
    let shape = labels.labels.dim();
    check_shape("pressure", shape, pressure.dim())?;
    check_shape("composite_height", shape, composite_height.dim())?;
    let spacing = (require_positive("dx", dx)?, require_positive("dy", dy)?);
    let members = &labels.members;
    let spot = SpotInput {
        labels,
        pressure,
        height: composite_height,
        spacing,
    };
    (0..labels.count)
        .into_par_iter()
        .map_init(Vec::new, |ring, id| spot.measure(id, members.of(id), ring))
        .collect()
}

fn check_shape(
    name: &'static str,
    expected: (usize, usize),
    found: (usize, usize),
) -> Result<(), FrictionError> {
    if expected == found {
        Ok(())
    } else {
        Err(FrictionError::ShapeMismatch {
            name,
            expected,
            found,
        })
    }
}

/// The points of every spot in raster order, as flat indices `iy·nx + ix` grouped by spot.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Members {
    start: Vec<usize>,
    points: Vec<u32>,
}

impl Members {
    /// The members of the `count` spots of `labels` (ids `0..count`, [`SpotLabels::OUTSIDE`]
    /// out of contact).
    fn gather(labels: &Array2<u32>, count: usize) -> Self {
        let mut start = vec![0usize; count + 1];
        for &l in labels.iter().filter(|&&l| l != SpotLabels::OUTSIDE) {
            start[l as usize + 1] += 1;
        }
        for id in 0..count {
            start[id + 1] += start[id];
        }
        let mut next = start.clone();
        let mut points = vec![0u32; start[count]];
        for (at, &l) in labels.iter().enumerate() {
            if l != SpotLabels::OUTSIDE {
                points[next[l as usize]] = at as u32;
                next[l as usize] += 1;
            }
        }
        Self { start, points }
    }

    pub(crate) fn of(&self, id: usize) -> &[u32] {
        &self.points[self.start[id]..self.start[id + 1]]
    }
}

/// What measuring one spot reads.
struct SpotInput<'a> {
    labels: &'a SpotLabels,
    pressure: ArrayView2<'a, f64>,
    height: ArrayView2<'a, f64>,
    spacing: (f64, f64),
}

impl SpotInput<'_> {
    fn nx(&self) -> usize {
        self.labels.labels.ncols()
    }

    fn coords(&self, at: u32) -> (usize, usize) {
        (at as usize / self.nx(), at as usize % self.nx())
    }

    /// The composite height at `at`, which must be finite.
    fn height_at(&self, at: u32) -> Result<f64, FrictionError> {
        let (iy, ix) = self.coords(at);
        let z = self.height[[iy, ix]];
        if z.is_finite() {
            Ok(z)
        } else {
            Err(FrictionError::InvalidParameter {
                name: "composite_height",
                value: z,
                expected: "finite values at the contact spots and their 8-neighbours",
            })
        }
    }

    /// Measures spot `id` from its points; `ring` is a reusable buffer.
    fn measure(
        &self,
        id: usize,
        points: &[u32],
        ring: &mut Vec<u32>,
    ) -> Result<ContactSpot, FrictionError> {
        let (mut sum, mut max_pressure) = (0.0, 0.0f64);
        let (mut peak, mut peak_z) = (0u32, f64::NEG_INFINITY);
        for &at in points {
            let (iy, ix) = self.coords(at);
            let p = self.pressure[[iy, ix]];
            sum += p;
            max_pressure = max_pressure.max(p);
            let z = self.height_at(at)?;
            if z > peak_z {
                (peak, peak_z) = (at, z);
            }
        }
        self.ring(id, points, ring);
        let (dx, dy) = self.spacing;
        Ok(ContactSpot {
            pixels: points.len(),
            area: points.len() as f64 * dx * dy,
            load: sum * dx * dy,
            peak: self.coords(peak),
            max_pressure,
            radius: self.fit_radius(peak, points, ring)?,
            radius_points: points.len() + ring.len(),
            summits: self.summits(points)?,
        })
    }

    /// The points of the spot higher than each of their 8-neighbours in the grid.
    fn summits(&self, points: &[u32]) -> Result<usize, FrictionError> {
        let (ny, nx) = self.labels.labels.dim();
        let periodic = self.labels.periodic;
        let mut count = 0;
        for &at in points {
            let (iy, ix) = self.coords(at);
            let z = self.height_at(at)?;
            let highest = (-1..=1)
                .flat_map(|sy| (-1..=1).map(move |sx| (sy, sx)))
                .filter(|&s| s != (0, 0))
                .filter_map(|(sy, sx)| {
                    Some((step(iy, sy, ny, periodic)?, step(ix, sx, nx, periodic)?))
                })
                .all(|(y, x)| self.height[[y, x]] < z);
            count += usize::from(highest);
        }
        Ok(count)
    }

    /// The 8-neighbours of the spot's points that are not in the spot, sorted, without repeats.
    fn ring(&self, id: usize, points: &[u32], ring: &mut Vec<u32>) {
        let (ny, nx) = self.labels.labels.dim();
        let periodic = self.labels.periodic;
        ring.clear();
        for &at in points {
            let (iy, ix) = self.coords(at);
            // The 3 × 3 block; the point itself is in the spot and skipped like its other points.
            for (sy, sx) in (-1..=1).flat_map(|sy| (-1..=1).map(move |sx| (sy, sx))) {
                let (Some(y), Some(x)) = (step(iy, sy, ny, periodic), step(ix, sx, nx, periodic))
                else {
                    continue;
                };
                if self.labels.labels[[y, x]] as usize != id {
                    ring.push((y * nx + x) as u32);
                }
            }
        }
        ring.sort_unstable();
        ring.dedup();
    }

    /// Offsets `(i, j)` = (column, row) from `from` to `to` in pixels, minimum image if periodic.
    fn offset(&self, from: u32, to: u32) -> (f64, f64) {
        let (ny, nx) = self.labels.labels.dim();
        let ((fy, fx), (ty, tx)) = (self.coords(from), self.coords(to));
        let image = |d: isize, n: usize| {
            let n = n as isize;
            let r = d.rem_euclid(n);
            if !self.labels.periodic {
                d
            } else if 2 * r > n {
                r - n
            } else {
                r
            }
        };
        let i = image(tx as isize - fx as isize, nx);
        let j = image(ty as isize - fy as isize, ny);
        (i as f64, j as f64)
    }

    /// Radius `−1/κ` of the least-squares paraboloid over the spot and its ring, see the module
    /// documentation.
    fn fit_radius(
        &self,
        peak: u32,
        points: &[u32],
        ring: &[u32],
    ) -> Result<Option<f64>, FrictionError> {
        let fit = || points.iter().chain(ring).copied();
        let (mut si, mut sj) = (1.0f64, 1.0f64);
        for at in fit() {
            let (i, j) = self.offset(peak, at);
            (si, sj) = (si.max(i.abs()), sj.max(j.abs()));
        }
        let z0 = self.height_at(peak)?;
        let mut normal = NormalEquations::default();
        for at in fit() {
            let (i, j) = self.offset(peak, at);
            normal.add(i / si, j / sj, self.height_at(at)? - z0);
        }
        let Some(c) = normal.solve() else {
            return Ok(None);
        };
        let (dx, dy) = self.spacing;
        let kappa = c[3] / (si * si * dx * dx) + c[5] / (sj * sj * dy * dy);
        Ok((kappa < 0.0).then(|| -1.0 / kappa))
    }
}

/// Index `i + s` on an axis of `n` points, wrapped if periodic, `None` off an open grid.
pub(crate) fn step(i: usize, s: isize, n: usize, periodic: bool) -> Option<usize> {
    let j = i as isize + s;
    if (0..n as isize).contains(&j) {
        Some(j as usize)
    } else if periodic {
        Some(j.rem_euclid(n as isize) as usize)
    } else {
        None
    }
}

/// Lennard-Jones 9-3 (Derjaguin) attraction of the points out of contact (N, attractive
/// positive):
///
/// `F_a = Σ_{p ≤ 0} σ(ε + g) dx dy`, `σ(h) = (8Δγ / 3ε) [(ε/h)³ − (ε/h)⁹]`,
///
/// whose integral from `h = ε` to ∞ is `Δγ` (`σ(ε) = 0`: a point at zero gap out of contact
/// attracts nothing). Negative gaps (solver round-off) count as 0, infinite gaps attract nothing;
/// `0` when `Δγ = 0`. Rows are summed in parallel and the row sums in order, so the result does
/// not depend on the thread count.
///
/// Errors: shapes differ, `dx`, `dy`, `ε` not finite and > 0, `Δγ` not finite and ≥ 0, a NaN gap
/// out of contact.
pub fn adhesion_from_gap<'a>(
    gap: impl Into<PointMap<'a>>,
    pressure: ArrayView2<f64>,
    dx: f64,
    dy: f64,
    adhesion: AdhesionParameters,
) -> Result<f64, FrictionError> {
    let gap = gap.into();
    check_shape("gap", pressure.dim(), gap.dim())?;
    let area = require_positive("dx", dx)? * require_positive("dy", dy)?;
    let energy = require_non_negative("adhesion_energy", adhesion.energy)?;
    let eps = require_positive("equilibrium_distance", adhesion.equilibrium_distance)?;
    if energy == 0.0 {
        return Ok(0.0);
    }
    let row_sums: Vec<f64> = (0..pressure.nrows())
        .into_par_iter()
        .map(|iy| {
            let row = pressure.row(iy);
            (0..row.len())
                .filter(|&ix| !in_contact(row[ix]))
                .map(|ix| {
                    let g = gap.at((iy, ix));
                    let r = eps / (eps + if g < 0.0 { 0.0 } else { g });
                    let r3 = r * r * r;
                    r3 - r3 * r3 * r3
                })
                .sum()
        })
        .collect();
    let force = 8.0 * energy / (3.0 * eps) * row_sums.iter().sum::<f64>() * area;
    if force.is_finite() {
        Ok(force)
    } else {
        Err(FrictionError::InvalidParameter {
            name: "gap",
            value: force,
            expected: "no NaN gap at the points out of contact",
        })
    }
}
