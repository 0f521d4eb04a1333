//! Shards: a deterministic, cost-balanced split of a study's node instances over `N` workers that
//! share one cache (`asperity run STUDY --shard I/N`, Slurm job arrays).
//!
//! **Units of work.** The split is over *sinks* — needed instances no other needed instance
//! depends on (for a `surface → contact` study: the contacts, and surfaces only a table needs).
//! A unit is a sink with its whole upstream closure, so every shard can run its units without
//! waiting for anybody. An upstream instance shared by units on two shards (one surface under
//! many contacts) is computed by whichever shard gets there first; the other finds the published
//! entry, or computes it too and finds the entry already published — publishing is atomic and an
//! existing entry counts as success, so duplicate work wastes time but never conflicts.
//!
//! **Balance.** Each instance costs its [`NodeTask::memory_estimate`] (a grid-size proxy: FFT
//! work grows with the grid). Units are assigned largest first (LPT); each goes to the shard
//! where it raises the load least — load plus the cost of the unit's instances the shard does not
//! hold yet — so units sharing upstream instances tend to land together and duplicates stay rare.
//!
//! **Determinism.** The split depends on the plan only (keys and estimates), not on the cache:
//! shards that start at different times — as job-array tasks do — agree on it even while the
//! cache fills. A shard then loads whatever of its share is already cached and computes the rest.
//!
//! [`NodeTask::memory_estimate`]: crate::node::NodeTask::memory_estimate

use std::collections::HashSet;
use std::fmt;
use std::str::FromStr;

use crate::plan::Plan;

/// Shard `index` of `count` (0 ≤ index < count), written `I/N`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

/// A malformed `I/N` shard specification.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid shard '{text}': {reason} (expected I/N with 0 <= I < N, e.g. 0/4)")]
pub struct ShardParseError {
    pub text: String,
    pub reason: &'static str,
}

impl FromStr for Shard {
    type Err = ShardParseError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let err = |reason| ShardParseError {
            text: text.to_string(),
            reason,
        };
        let (i, n) = text.split_once('/').ok_or_else(|| err("no '/'"))?;
        let index: usize = i.trim().parse().map_err(|_| err("I is not a number"))?;
        let count: usize = n.trim().parse().map_err(|_| err("N is not a number"))?;
        if count == 0 {
            return Err(err("N must be at least 1"));
        }
        if index >= count {
            return Err(err("I must be smaller than N"));
        }
        Ok(Self { index, count })
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The split of a plan's needed instances over `count` shards.
#[derive(Debug, Clone, PartialEq)]
pub struct ShardPlan {
    /// `shards[k]`: instance indices shard `k` runs, upstream-closed and sorted (upstream first).
    pub shards: Vec<Vec<usize>>,
    /// Estimated cost of each shard (sum of its instances' estimates, bytes as a work proxy).
    pub loads: Vec<u64>,
    /// Number of units (sinks with their upstream closure) that were distributed.
    pub units: usize,
}

impl ShardPlan {
    /// Splits `needed` (an upstream-closed instance set, e.g. [`Plan::needed_for`]) over `count`
    /// shards (at least one).
    pub fn split(plan: &Plan, needed: &[usize], count: usize) -> Self {
        let count = count.max(1);
        let needed_set: HashSet<usize> = needed.iter().copied().collect();
        let mut has_dependant: HashSet<usize> = HashSet::new();
        for &i in needed {
            has_dependant.extend(plan.nodes[i].upstream.iter().map(|(_, u)| *u));
        }
        let cost = |i: usize| plan.nodes[i].task.memory_estimate().max(1);
        let mut units: Vec<(u64, String, Vec<usize>)> = needed
            .iter()
            .copied()
            .filter(|i| !has_dependant.contains(i))
            .map(|sink| {
                let closure = plan.upstream_closure(&[sink], Some(&needed_set));
                let total = closure.iter().map(|&i| cost(i)).sum();
                (total, plan.nodes[sink].key.to_hex(), closure)
            })
            .collect();
        // Largest first; equal costs in key order, so the split never depends on plan order.
        units.sort_by(|a, b| b.0.cmp(&a.0).then_with(|| a.1.cmp(&b.1)));
        let mut members: Vec<HashSet<usize>> = vec![HashSet::new(); count];
        let mut loads = vec![0u64; count];
        for (_, _, closure) in &units {
            let mut best = (u64::MAX, 0usize, 0u64);
            for (k, held) in members.iter().enumerate() {
                let extra: u64 = closure
                    .iter()
                    .filter(|i| !held.contains(i))
                    .map(|&i| cost(i))
                    .sum();
                let total = loads[k].saturating_add(extra);
                if total < best.0 {
                    best = (total, k, extra);
                }
            }
            let (_, k, extra) = best;
            loads[k] = loads[k].saturating_add(extra);
            members[k].extend(closure.iter().copied());
        }
        let shards = members
            .into_iter()
            .map(|m| {
                let mut v: Vec<usize> = m.into_iter().collect();
                v.sort_unstable();
                v
            })
            .collect();
        Self {
            shards,
            loads,
            units: units.len(),
        }
    }

    /// The instances of `shard` (empty when the shard has nothing to do or is out of range).
    pub fn nodes(&self, shard: Shard) -> &[usize] {
        self.shards.get(shard.index).map_or(&[], Vec::as_slice)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shard_specifications_parse_and_reject() {
        assert_eq!("0/4".parse(), Ok(Shard { index: 0, count: 4 }));
        assert_eq!(" 3 / 4 ".parse(), Ok(Shard { index: 3, count: 4 }));
        for bad in ["4/4", "1/0", "1", "a/2", "-1/2", ""] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        assert_eq!(Shard { index: 2, count: 5 }.to_string(), "2/5");
    }
}
