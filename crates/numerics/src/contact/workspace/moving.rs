//! The points the free-set iteration (`contact/free_set.rs`) works on, and its pressures written
//! back.

use super::{contact_points, Workspace, BLOCK};

impl Workspace {
    /// The points whose pressure the CG would move next (flat indices, ascending): the free
    /// points `0 < p < p_lim`, the saturated points with an open gap `g₀ + u − offset − δ > 0`
    /// and the points out of contact recorded with a negative gap by the last
    /// [`Self::out_of_contact_pass`] (contact lists must be current, `u` exact).
    pub(in crate::contact) fn moving_points(&self, offset: f64, delta: f64) -> Vec<usize> {
        let (p, plim, g0, u) = (&self.p, self.plim, &self.g0, &self.u);
        let mut points: Vec<usize> = self
            .blocks
            .iter()
            .enumerate()
            .flat_map(|(b, block)| {
                let base = b * BLOCK;
                let entering = block.entering.iter().map(move |&(l, _)| base + l as usize);
                contact_points(base, &block.contact)
                    .filter(|&i| p[i] < plim || g0[i] + u[i] - offset - delta > 0.0)
                    .chain(entering)
            })
            .collect();
        points.sort_unstable();
        points
    }

    /// `p[points[k]] ← values[k]` (in `[0, p_lim]`); the contact lists are rebuilt (`u` is left
    /// stale).
    pub(in crate::contact) fn set_pressures(&mut self, points: &[usize], values: &[f64]) {
        for (&i, &v) in points.iter().zip(values) {
            debug_assert!((0.0..=self.plim).contains(&v));
            self.p[i] = v;
        }
        self.rebuild_contact();
    }
}
