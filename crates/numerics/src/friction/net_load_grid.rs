//! The net load P(d*) − F_s(d*) of a statistical model on a grid of the dimensionless separation
//! d*, evaluated lazily. The separation solve of [`mod@super::static_friction`] needs the sign of
//! P − F_s − F at every grid point (to find the brackets and count the roots); for a compressive
//! load F > 0 most points are decided by the contact load P alone, from two bounds:
//!
//! * raising d* lowers the interference of every summit, and the load laws increase between
//!   their breaks and drop by the factor κ at most ([`ModelLaws::load_drop_bound`]), so
//!   P(d*) ≤ P(d_k*)/κ for d* ≥ d_k* and P(d*) ≥ κP(d_k*) for d* ≤ d_k*;
//! * 0 ≤ F_s ≤ F_s,max, the adhesion of every summit at its largest
//!   ([`StatisticalModel::adhesion_force_bound`]).
//!
//! So every point above a point with P < κF lies below the load (P − F_s ≤ P < F), and every
//! point below a point with κP > F + F_s,max lies above it. The two such points nearest the
//! load are found by bisection over the grid (P only); the points between them are evaluated
//! (P, then F_s where P ≥ F). Both bounds carry a relative margin of 10⁻⁶ for the 1e-10
//! quadrature error. A tensile load F < 0 needs P − F_s everywhere.
//!
//! Every value the table holds is an exact evaluation of the model at its d* (quadrature to
//! 1e-10), made once, when a scan first needs it; the brackets, the roots counted and therefore
//! the solution are those of the fully tabulated grid.
//!
//! [`ModelLaws::load_drop_bound`]: super::model_laws::ModelLaws::load_drop_bound

use super::error::FrictionError;
use super::root_finding::golden_minimum;
use super::solve_settings::SolveSettings;
use super::statistical_integrals::StatisticalModel;

/// Relative margin of the bounds, far above the quadrature error.
const BOUND_MARGIN: f64 = 1e-6;

/// Net load P(d*) − F_s(d*) in N.
pub fn net_load(model: &StatisticalModel, d_star: f64) -> Result<f64, FrictionError> {
    Ok(model.contact_load(d_star)?.value - model.adhesion_force(d_star)?.total())
}

/// One grid point and what is known of it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct GridPoint {
    d_star: f64,
    /// Contact load P (N), once evaluated.
    contact_load: Option<f64>,
    /// P − F_s (N), once evaluated.
    net_load: Option<f64>,
}

impl GridPoint {
    fn unevaluated(d_star: f64) -> Self {
        Self {
            d_star,
            contact_load: None,
            net_load: None,
        }
    }
}

/// How many grid points have been evaluated (a diagnostic of the lazy scan).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GridEvaluations {
    /// Points in the grid.
    pub points: usize,
    /// Points whose contact load P is known.
    pub contact_load: usize,
    /// Points whose net load P − F_s is known.
    pub net_load: usize,
}

/// P − F_s on a d* grid, reusable across loads of the SAME model (the table only holds exact
/// evaluations of that model; the solver keeps it so).
#[derive(Debug, Clone, PartialEq)]
pub struct NetLoadGrid {
    /// Ascending in d*.
    points: Vec<GridPoint>,
    /// κ of the model's load law.
    load_drop: f64,
    /// F_s,max of the model (`None`: unbounded).
    adhesion_bound: Option<f64>,
}

/// The sign of P − F_s − F at a point (−1, 0 or 1).
fn sign(value: f64) -> i8 {
    if value > 0.0 {
        1
    } else if value < 0.0 {
        -1
    } else {
        0
    }
}

impl NetLoadGrid {
    /// Lay out the grid on the default range of `settings` (nothing is evaluated yet).
    pub fn new(model: &StatisticalModel, settings: &SolveSettings) -> Result<Self, FrictionError> {
        let step = settings.validated()?.grid_step;
        let hi = settings.d_star_max_in_summit_std * model.summit_std_star();
        let mut points = Vec::new();
        let mut d = settings.d_star_min;
        while d <= hi + 0.5 * step {
            points.push(GridPoint::unevaluated(d));
            d += step;
        }
        Ok(Self {
            points,
            load_drop: model.laws.load_drop_bound(),
            adhesion_bound: model.adhesion_force_bound(),
        })
    }

    /// What has been evaluated so far.
    pub fn evaluations(&self) -> GridEvaluations {
        GridEvaluations {
            points: self.points.len(),
            contact_load: self
                .points
                .iter()
                .filter(|p| p.contact_load.is_some())
                .count(),
            net_load: self.points.iter().filter(|p| p.net_load.is_some()).count(),
        }
    }

    /// d* of point `i`.
    pub(super) fn d_star(&self, i: usize) -> Option<f64> {
        self.points.get(i).map(|p| p.d_star)
    }

    fn contact_load_at(
        &mut self,
        model: &StatisticalModel,
        i: usize,
    ) -> Result<f64, FrictionError> {
        let Some(point) = self.points.get_mut(i) else {
            return Err(outside_grid(i));
        };
        if let Some(p) = point.contact_load {
            return Ok(p);
        }
        let p = model.contact_load(point.d_star)?.value;
        point.contact_load = Some(p);
        Ok(p)
    }

    /// P − F_s at point `i` (evaluated on first use).
    pub(super) fn net_load_at(
        &mut self,
        model: &StatisticalModel,
        i: usize,
    ) -> Result<f64, FrictionError> {
        let p = self.contact_load_at(model, i)?;
        let Some(point) = self.points.get_mut(i) else {
            return Err(outside_grid(i));
        };
        if let Some(net) = point.net_load {
            return Ok(net);
        }
        let net = p - model.adhesion_force(point.d_star)?.total();
        point.net_load = Some(net);
        Ok(net)
    }

    /// Extend the grid downward (steps of 3) until the net load at its low end exceeds `load`.
    pub(super) fn cover_load(
        &mut self,
        model: &StatisticalModel,
        load: f64,
        settings: &SolveSettings,
    ) -> Result<(), FrictionError> {
        loop {
            let Some(d0) = self.d_star(0) else {
                return Ok(());
            };
            if self.surely_above(model, 0, load)? {
                return Ok(());
            }
            let f0 = self.net_load_at(model, 0)?;
            if f0 > load {
                return Ok(());
            }
            if d0 - 3.0 < settings.d_star_floor {
                return Err(FrictionError::LoadAboveSearchRange {
                    load,
                    max_load: f0,
                    d_star_min: d0,
                });
            }
            let mut lower = Vec::new();
            let mut d = d0 - 3.0;
            while d < d0 - 0.5 * settings.grid_step {
                lower.push(GridPoint::unevaluated(d));
                d += settings.grid_step;
            }
            lower.append(&mut self.points);
            self.points = lower;
        }
    }

    /// Add exact evaluations (d*, P, P − F_s) to the table, keeping it sorted; later loads of a
    /// curve then start from narrower brackets.
    pub(super) fn insert(&mut self, evaluations: &[(f64, f64, f64)]) {
        for &(d_star, p, net) in evaluations {
            let index = self.points.partition_point(|point| point.d_star < d_star);
            if self.d_star(index) != Some(d_star) {
                let point = GridPoint {
                    d_star,
                    contact_load: Some(p),
                    net_load: Some(net),
                };
                self.points.insert(index, point);
            }
        }
    }

    /// Whether P − F_s > `load` at every point up to `i` (κP(d_i*) > F + F_s,max).
    fn surely_above(
        &mut self,
        model: &StatisticalModel,
        i: usize,
        load: f64,
    ) -> Result<bool, FrictionError> {
        let Some(adhesion) = self.adhesion_bound else {
            return Ok(false);
        };
        let p = self.contact_load_at(model, i)?;
        Ok(self.load_drop * p > (load + adhesion) * (1.0 + BOUND_MARGIN))
    }

    /// Whether P − F_s < `load` at every point from `i` on (P(d_i*) < κF).
    fn surely_below(
        &mut self,
        model: &StatisticalModel,
        i: usize,
        load: f64,
    ) -> Result<bool, FrictionError> {
        let p = self.contact_load_at(model, i)?;
        Ok(p * (1.0 + BOUND_MARGIN) < self.load_drop * load)
    }

    /// The range of points a compressive `load` must scan: from the highest point found
    /// [`Self::surely_above`] (or 0) to the lowest found [`Self::surely_below`] (or the end),
    /// each by bisection (the bounds hold for whichever such point is found), and whether the
    /// first point is known to lie above the load.
    fn compressive_window(
        &mut self,
        model: &StatisticalModel,
        load: f64,
    ) -> Result<(usize, usize, bool), FrictionError> {
        let n = self.points.len();
        let mut first = 0;
        let first_above = self.surely_above(model, 0, load)?;
        if first_above {
            let mut beyond = n;
            while beyond - first > 1 {
                let mid = first + (beyond - first) / 2;
                if self.surely_above(model, mid, load)? {
                    first = mid;
                } else {
                    beyond = mid;
                }
            }
        }
        let mut last = n - 1;
        if self.surely_below(model, last, load)? {
            let mut before = first;
            while last - before > 1 {
                let mid = before + (last - before) / 2;
                if self.surely_below(model, mid, load)? {
                    last = mid;
                } else {
                    before = mid;
                }
            }
        }
        Ok((first, last, first_above))
    }

    /// Sign of P − F_s − `load` at point `i`; a compressive load asks for F_s only where P ≥ F.
    fn sign_at(
        &mut self,
        model: &StatisticalModel,
        i: usize,
        load: f64,
    ) -> Result<i8, FrictionError> {
        if load > 0.0 && self.contact_load_at(model, i)? < load {
            return Ok(-1);
        }
        Ok(sign(self.net_load_at(model, i)? - load))
    }

    /// Brackets [d_i, d_{i+1}] where P − F_s − load changes sign (or is zero at d_i), ascending.
    /// The points outside the window of a compressive load are known to be above it (below the
    /// window) or below it (above the window) and are not evaluated.
    pub(super) fn brackets(
        &mut self,
        model: &StatisticalModel,
        load: f64,
    ) -> Result<Vec<usize>, FrictionError> {
        if self.points.is_empty() {
            return Ok(Vec::new());
        }
        let (first, last, first_above) = if load > 0.0 {
            self.compressive_window(model, load)?
        } else {
            (0, self.points.len() - 1, false)
        };
        let mut brackets = Vec::new();
        let mut previous: Option<i8> = None;
        for i in first..=last {
            let s = if i == first && first_above {
                1
            } else {
                self.sign_at(model, i, load)?
            };
            if previous.is_some_and(|q| q == 0 || q * s < 0) {
                brackets.push(i - 1);
            }
            previous = Some(s);
        }
        Ok(brackets)
    }

    /// Number of distinct roots among `brackets`: sign changes in a cluster of consecutive table
    /// intervals spanning less than 1e-6 in d* (points left by an earlier Brent refinement at the
    /// same load, where quadrature noise can flip the sign) count as one root.
    pub(super) fn count_roots(&self, brackets: &[usize]) -> usize {
        let mut roots = 0;
        let mut cluster_start: Option<f64> = None;
        let mut previous: Option<usize> = None;
        for &i in brackets {
            let (Some(lo), Some(hi)) = (self.d_star(i), self.d_star(i + 1)) else {
                continue;
            };
            let continues = previous.is_some_and(|p| p + 1 == i)
                && cluster_start.is_some_and(|start| hi - start < 1e-6);
            if !continues {
                roots += 1;
                cluster_start = Some(lo);
            }
            previous = Some(i);
        }
        roots
    }

    /// Pull-off load: the minimum of P − F_s, refined by golden section around the grid minimum
    /// (evaluates the whole grid).
    pub fn pull_off_load(&mut self, model: &StatisticalModel) -> Result<f64, FrictionError> {
        let mut minimum: Option<(usize, f64)> = None;
        for i in 0..self.points.len() {
            let net = self.net_load_at(model, i)?;
            if minimum.is_none_or(|(_, m)| net < m) {
                minimum = Some((i, net));
            }
        }
        let Some((i_min, grid_min)) = minimum else {
            return Ok(0.0);
        };
        let lo = self.d_star(i_min.saturating_sub(1)).unwrap_or(0.0);
        let hi = self.d_star(i_min + 1).unwrap_or(lo);
        let (_, f_min, _) = golden_minimum(&mut |d| net_load(model, d), lo, hi, 1e-9)?;
        Ok(f_min.min(grid_min))
    }
}

fn outside_grid(i: usize) -> FrictionError {
    FrictionError::InvalidParameter {
        name: "grid",
        value: i as f64,
        expected: "a point inside the grid",
    }
}
