//! Statistics the iteration measures over the contact set: of the gap (`ContactStats`) and of
//! the free set (`FreeStats`), combined block by block in a fixed order.

/// Statistics of the gap `v = g₀ + u − offset` on the contact set: on the free set
/// `F = {0 < p < p_lim}` of `y = v − δ_prev` and of `v`, on the saturated set of `v`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactStats {
    pub free_y: f64,
    pub free_y2: f64,
    pub free_count: f64,
    pub free_max: f64,
    pub free_min: f64,
    pub sat_max: f64,
}

impl ContactStats {
    pub(super) const EMPTY: Self = Self {
        free_y: 0.0,
        free_y2: 0.0,
        free_count: 0.0,
        free_max: f64::NEG_INFINITY,
        free_min: f64::INFINITY,
        sat_max: f64::NEG_INFINITY,
    };

    pub(super) fn add(&mut self, v: f64, y: f64, p: f64, plim: f64) {
        if p >= plim {
            self.sat_max = self.sat_max.max(v);
        } else {
            self.free_y += y;
            self.free_y2 += y * y;
            self.free_count += 1.0;
            self.free_max = self.free_max.max(v);
            self.free_min = self.free_min.min(v);
        }
    }

    pub(super) fn combine(a: Self, b: &Self) -> Self {
        Self {
            free_y: a.free_y + b.free_y,
            free_y2: a.free_y2 + b.free_y2,
            free_count: a.free_count + b.free_count,
            free_max: a.free_max.max(b.free_max),
            free_min: a.free_min.min(b.free_min),
            sat_max: a.sat_max.max(b.sat_max),
        }
    }
}

/// Free-set statistics of the pressures: `Σ_F p`, `max_F p`, `Σ_{p = p_lim} p`, `|F|`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FreeStats {
    pub free_sum: f64,
    pub free_max: f64,
    pub sat_sum: f64,
    pub free_count: f64,
}

impl FreeStats {
    pub(super) const EMPTY: Self = Self {
        free_sum: 0.0,
        free_max: 0.0,
        sat_sum: 0.0,
        free_count: 0.0,
    };

    /// `Σ p` (saturated and free).
    pub(crate) fn total(&self) -> f64 {
        self.free_sum + self.sat_sum
    }

    pub(super) fn add(&mut self, p: f64, plim: f64) {
        if p >= plim {
            self.sat_sum += p;
        } else if p > 0.0 {
            self.free_sum += p;
            self.free_max = self.free_max.max(p);
            self.free_count += 1.0;
        }
    }

    pub(super) fn combine(a: Self, b: &Self) -> Self {
        Self {
            free_sum: a.free_sum + b.free_sum,
            free_max: a.free_max.max(b.free_max),
            sat_sum: a.sat_sum + b.sat_sum,
            free_count: a.free_count + b.free_count,
        }
    }
}
