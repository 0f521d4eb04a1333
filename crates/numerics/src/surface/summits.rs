//! Summits (asperity peaks) of a height map: 8-neighbour local maxima with their height, slope and
//! curvature, for the deterministic per-summit friction stage (docs/friction-models.md).
//!
//! **Definition.** Points are ordered by height, ties broken by raster index (`iy·nx + ix`, the earlier
//! point counts as higher). A summit is a valid point that is higher in this order than each of its 8
//! neighbours, all of which must exist and be valid: summits next to a missing point are skipped, and
//! with [`Boundary::Open`] points on the grid border are not candidates, while [`Boundary::Periodic`]
//! wraps the neighbourhood around. The order makes the result deterministic: of two equal neighbouring
//! heights only one can be a summit (a flat top yields at most one summit per raster-first point).
//!
//! **Per summit** (heights relative to the mean of the valid heights — the mean plane; remove form first
//! if a levelled reference is wanted), with central differences and `dx`, `dy` separately:
//! `z_x = (z_{x+1} − z_{x−1})/(2dx)`, `z_xx = (z_{x+1} − 2z + z_{x−1})/dx²`, likewise in y, and
//! `z_xy = (z_{x+1,y+1} − z_{x+1,y−1} − z_{x−1,y+1} + z_{x−1,y−1})/(4 dx dy)`:
//! slope `|∇z| = sqrt(z_x² + z_y²)`; radius of curvature `R = 1/(−½ ∇²z) = −2/(z_xx + z_yy)`
//! (always finite and > 0 at a strict local maximum, since `z_xx, z_yy < 0` there); principal
//! curvatures `κ1 ≥ κ2`, the eigenvalues of `−H` (`H` the Hessian, so a convex cap has `κ > 0`), with
//! `R = 2/(κ1 + κ2)`.
//!
//! **Prominence** (optional, computed when [`SummitOptions::min_prominence`] is set): the topographic
//! prominence over the 8-connected graph of valid points — the height of the summit above the highest
//! saddle ("col") through which a higher summit can be reached. The highest summit of a connected
//! region gets its height above the region's lowest point. Computed exactly by a union–find sweep over
//! the points in descending order, `O(N log N)`.
//!
//! **Summary**: count; areal density `η = count / (candidate_count · dx · dy)`, where the candidates are
//! the points that could be summits (valid, inside the border rule, with 8 valid neighbours); mean
//! radius; mean and standard deviation (population) of the summit heights.

use super::amplitude::valid_mean_min_max;
use super::gradient::neighbour_index;
use super::order::descending_key;
use super::{Boundary, HeightMap};
use rayon::slice::ParallelSliceMut;

/// Options of [`find_summits`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SummitOptions {
    /// Border treatment (see the module documentation).
    pub boundary: Boundary,
    /// Keep only summits at least this high above the mean plane (m).
    pub min_height: Option<f64>,
    /// Keep only summits with at least this topographic prominence (m).
    pub min_prominence: Option<f64>,
}

/// One summit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summit {
    /// Column index.
    pub ix: usize,
    /// Row index.
    pub iy: usize,
    /// Position `ix·dx` (m).
    pub x: f64,
    /// Position `iy·dy` (m).
    pub y: f64,
    /// Height above the mean plane (m).
    pub height: f64,
    /// Local slope `|∇z|` from central differences (m/m).
    pub slope: f64,
    /// Radius of curvature `R = −2/∇²z` (m).
    pub radius: f64,
    /// Principal curvatures `[κ1, κ2]`, `κ1 ≥ κ2`, of the cap (1/m; positive = convex).
    pub principal_curvatures: [f64; 2],
    /// Topographic prominence (m), when it was requested through `min_prominence`.
    pub prominence: Option<f64>,
}

/// Summary of the summits of a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SummitStatistics {
    /// Number of summits kept.
    pub count: usize,
    /// Number of points that could be summits (valid, within the border rule, 8 valid neighbours).
    pub candidate_count: usize,
    /// Areal density `η` (1/m²); `0` if there are no candidates.
    pub density: f64,
    /// Mean radius of curvature (m), `None` without summits.
    pub mean_radius: Option<f64>,
    /// Mean summit height above the mean plane (m), `None` without summits.
    pub mean_height: Option<f64>,
    /// Standard deviation of summit heights `σ_s` (m, population), `None` without summits.
    pub height_std: Option<f64>,
    /// The mean plane: mean of the valid heights (m).
    pub mean_plane: f64,
}

/// Summits and their summary.
#[derive(Debug, Clone, PartialEq)]
pub struct Summits {
    /// Summits in raster order (by `iy`, then `ix`).
    pub summits: Vec<Summit>,
    /// Summary statistics.
    pub statistics: SummitStatistics,
}

/// Why summits could not be identified.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SummitError {
    #[error("the height map has no valid point")]
    NoValidPoints,
    #[error("threshold {name} must be finite, got {value}")]
    BadThreshold { name: &'static str, value: f64 },
}

/// Offsets of the 8 neighbours.
const NEIGHBOURS: [(isize, isize); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// Finds the summits of `map` (see the module documentation for every definition).
pub fn find_summits(map: &HeightMap, options: SummitOptions) -> Result<Summits, SummitError> {
    for (name, value) in [
        ("min_height", options.min_height),
        ("min_prominence", options.min_prominence),
    ] {
        if let Some(v) = value.filter(|v| !v.is_finite()) {
            return Err(SummitError::BadThreshold { name, value: v });
        }
    }
    let (valid, mean, _, _) = valid_mean_min_max(map).ok_or(SummitError::NoValidPoints)?;
    let (nx, ny, dx, dy) = (map.nx(), map.ny(), map.dx(), map.dy());
    let boundary = options.boundary;
    let prominences = options.min_prominence.map(|_| {
        let z = map.heights().as_standard_layout();
        let flat = z
            .as_slice()
            .expect("an array in standard layout is contiguous");
        topographic_prominences(flat, nx, ny, boundary)
    });
    let (columns, rows) = (neighbour_pairs(nx, boundary), neighbour_pairs(ny, boundary));
    let scan = RowScan {
        nx,
        complete: valid == nx * ny,
        spacing: (dx, dy),
        mean,
        columns: &columns,
        options,
        prominences: prominences.as_deref(),
    };
    // Rows in parallel, concatenated in row order: the raster order of a serial scan.
    let per_row = map.map_rows(|iy, flat| match rows[iy] {
        Some((ym, yp)) => scan.row(flat, [ym, iy, yp]),
        None => (Vec::new(), 0),
    });
    let candidate_count = per_row.iter().map(|(_, c)| c).sum();
    let summits: Vec<Summit> = per_row.into_iter().flat_map(|(s, _)| s).collect();
    let statistics = summarise(&summits, candidate_count, dx * dy, mean);
    Ok(Summits {
        summits,
        statistics,
    })
}

/// What every row of [`find_summits`]' scan shares.
struct RowScan<'a> {
    nx: usize,
    /// No point is missing: every point within the border rule is a candidate.
    complete: bool,
    spacing: (f64, f64),
    mean: f64,
    columns: &'a [Option<(usize, usize)>],
    options: SummitOptions,
    prominences: Option<&'a [f64]>,
}

impl RowScan<'_> {
    /// The summits of row `iy` (rows `[ym, iy, yp]` of the row-major grid `flat`) in raster
    /// order, and its candidate count.
    fn row(&self, flat: &[f64], [ym, iy, yp]: [usize; 3]) -> (Vec<Summit>, usize) {
        let (nx, options) = (self.nx, self.options);
        let mut summits = Vec::new();
        let mut candidate_count = 0;
        for (ix, column_pair) in self.columns.iter().enumerate() {
            let Some((xm, xp)) = *column_pair else {
                continue;
            };
            let p = iy * nx + ix;
            let centre = flat[p];
            let q = neighbour_raster([xm, ix, xp], [ym, iy, yp], nx);
            if !self.complete && (centre.is_nan() || q.iter().any(|&j| flat[j].is_nan())) {
                continue;
            }
            candidate_count += 1;
            if !q.iter().all(|&j| ranks_above(centre, p, flat[j], j)) {
                continue;
            }
            let around = q.map(|j| flat[j]);
            let height = centre - self.mean;
            if options.min_height.is_some_and(|t| height < t) {
                continue;
            }
            let prominence = self
                .prominences
                .and_then(|m| m.get(p).copied())
                .filter(|v| !v.is_nan());
            if options
                .min_prominence
                .is_some_and(|t| prominence.is_none_or(|v| v < t))
            {
                continue;
            }
            summits.push(summit_at(
                ix,
                iy,
                self.spacing,
                centre,
                &around,
                height,
                prominence,
            ));
        }
        (summits, candidate_count)
    }
}

/// Raster indices of the 8 neighbours in the order of `NEIGHBOURS`, from the columns
/// `[previous, own, next]` and rows `[previous, own, next]` of a point on a grid `nx` wide.
fn neighbour_raster([xm, ix, xp]: [usize; 3], [ym, iy, yp]: [usize; 3], nx: usize) -> [usize; 8] {
    [
        ym * nx + xm,
        ym * nx + ix,
        ym * nx + xp,
        iy * nx + xm,
        iy * nx + xp,
        yp * nx + xm,
        yp * nx + ix,
        yp * nx + xp,
    ]
}

/// The neighbours (previous, next) of every index along an axis of `n` points, `None` where the
/// boundary leaves one out.
fn neighbour_pairs(n: usize, boundary: Boundary) -> Vec<Option<(usize, usize)>> {
    (0..n)
        .map(|i| {
            Some((
                neighbour_index(i, -1, n, boundary)?,
                neighbour_index(i, 1, n, boundary)?,
            ))
        })
        .collect()
}

/// The summit at `(ix, iy)` with its slope, principal curvatures and radius from central
/// differences over its 8 neighbours `around` (in the order of `NEIGHBOURS`).
fn summit_at(
    ix: usize,
    iy: usize,
    (dx, dy): (f64, f64),
    centre: f64,
    around: &[f64; 8],
    height: f64,
    prominence: Option<f64>,
) -> Summit {
    // around: 0 (−1,−1) 1 (0,−1) 2 (1,−1) 3 (−1,0) 4 (1,0) 5 (−1,1) 6 (0,1) 7 (1,1)
    let zx = (around[4] - around[3]) / (2.0 * dx);
    let zy = (around[6] - around[1]) / (2.0 * dy);
    let zxx = (around[4] - 2.0 * centre + around[3]) / (dx * dx);
    let zyy = (around[6] - 2.0 * centre + around[1]) / (dy * dy);
    let zxy = (around[7] - around[2] - around[5] + around[0]) / (4.0 * dx * dy);
    let half_sum = -(zxx + zyy) / 2.0;
    let half_diff = (((zxx - zyy) / 2.0).powi(2) + zxy * zxy).sqrt();
    Summit {
        ix,
        iy,
        x: ix as f64 * dx,
        y: iy as f64 * dy,
        height,
        slope: (zx * zx + zy * zy).sqrt(),
        radius: 1.0 / half_sum,
        principal_curvatures: [half_sum + half_diff, half_sum - half_diff],
        prominence,
    }
}

/// `true` if the point (height `a`, raster index `p`) ranks above (height `b`, index `q`).
fn ranks_above(a: f64, p: usize, b: f64, q: usize) -> bool {
    a > b || (a == b && p < q)
}

fn summarise(
    summits: &[Summit],
    candidates: usize,
    pixel_area: f64,
    mean: f64,
) -> SummitStatistics {
    let count = summits.len();
    let n = count as f64;
    let (mean_radius, mean_height, height_std) = if count == 0 {
        (None, None, None)
    } else {
        let mean_h = summits.iter().map(|s| s.height).sum::<f64>() / n;
        let var = summits
            .iter()
            .map(|s| (s.height - mean_h).powi(2))
            .sum::<f64>()
            / n;
        (
            Some(summits.iter().map(|s| s.radius).sum::<f64>() / n),
            Some(mean_h),
            Some(var.sqrt()),
        )
    };
    SummitStatistics {
        count,
        candidate_count: candidates,
        density: if candidates == 0 {
            0.0
        } else {
            n / (candidates as f64 * pixel_area)
        },
        mean_radius,
        mean_height,
        height_std,
        mean_plane: mean,
    }
}

/// Topographic prominence of every peak (point with no higher 8-neighbour in the ranking order) of the
/// valid-point graph, indexed by raster index (`NaN` for points that are not peaks). Union–find sweep in descending order: a point whose ranked-
/// higher neighbours belong to several components is the col of all but the highest of them, whose
/// peaks get prominence `peak − col`; the last surviving peak of each region gets `peak − region min`.
fn topographic_prominences(z: &[f64], nx: usize, ny: usize, boundary: Boundary) -> Vec<f64> {
    let order = descending_order(z);
    const UNSEEN: usize = usize::MAX;
    // Union by size keeps the trees shallow; `peak[root]` is the highest point of the component and
    // `lowest[root]` the last (lowest) point added to it.
    let mut parent = vec![UNSEEN; z.len()];
    let mut size = vec![0usize; z.len()];
    let mut peak = vec![UNSEEN; z.len()];
    let mut lowest = vec![0.0; z.len()];
    let mut prominence = vec![f64::NAN; z.len()];
    let mut roots = Vec::with_capacity(8);
    for &(_, p) in &order {
        let (ix, iy) = (p % nx, p / nx);
        roots.clear();
        for &(ox, oy) in &NEIGHBOURS {
            let (Some(jx), Some(jy)) = (
                neighbour_index(ix, ox, nx, boundary),
                neighbour_index(iy, oy, ny, boundary),
            ) else {
                continue;
            };
            let q = jy * nx + jx;
            if parent[q] != UNSEEN {
                let r = find_root(&mut parent, q);
                if !roots.contains(&r) {
                    roots.push(r);
                }
            }
        }
        let Some(winner) = roots.iter().copied().reduce(|a, b| {
            if ranks_above(z[peak[a]], peak[a], z[peak[b]], peak[b]) {
                a
            } else {
                b
            }
        }) else {
            parent[p] = p;
            size[p] = 1;
            peak[p] = p;
            lowest[p] = z[p];
            continue;
        };
        // `p` is the col of every other component: their peaks' prominence is fixed here.
        let mut root = winner;
        for &r in roots.iter().filter(|&&r| r != winner) {
            prominence[peak[r]] = z[peak[r]] - z[p];
            let (big, small) = if size[root] >= size[r] {
                (root, r)
            } else {
                (r, root)
            };
            parent[small] = big;
            size[big] += size[small];
            root = big;
        }
        peak[root] = peak[winner];
        parent[p] = root;
        size[root] += 1;
        lowest[root] = z[p];
    }
    for &(_, p) in &order {
        if parent[p] == p {
            prominence[peak[p]] = z[peak[p]] - lowest[p];
        }
    }
    prominence
}

/// The valid points of `z` from highest to lowest, ties by ascending raster index (the order
/// of `ranks_above`), each with its sort key.
fn descending_order(z: &[f64]) -> Vec<(u64, usize)> {
    // Sort keys: descending height, then ascending raster index — the same total order as
    // `ranks_above`.
    let mut order: Vec<(u64, usize)> = (0..z.len())
        .filter(|&p| !z[p].is_nan())
        .map(|p| (descending_key(z[p]), p))
        .collect();
    order.par_sort_unstable();
    order
}

/// Root of `p` with path halving.
fn find_root(parent: &mut [usize], mut p: usize) -> usize {
    while parent[p] != p {
        parent[p] = parent[parent[p]];
        p = parent[p];
    }
    p
}
