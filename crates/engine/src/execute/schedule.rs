//! What a run must do and in which order: the instances whose arrays a dependant needs, how many
//! dependants each has, and the queue of ready instances (deepest first).

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use crate::cache::Cache;
use crate::hash::NodeKey;
use crate::node::ArrayStorage;
use crate::plan::Plan;

/// Which instances of `needed` must be loaded with their arrays (a dependant will be computed,
/// or derives its arrays from them) and how many dependants each has.
pub(super) fn payload_needs(
    plan: &Plan,
    cache: &Cache,
    needed: &[usize],
) -> (Vec<bool>, Vec<usize>) {
    let n = plan.nodes.len();
    let entries: Vec<(&str, &NodeKey)> = needed
        .iter()
        .map(|&i| (plan.nodes[i].task.kind(), &plan.nodes[i].key))
        .collect();
    let mut in_cache = vec![false; n];
    for (&i, present) in needed.iter().zip(cache.present(&entries)) {
        in_cache[i] = present;
    }
    let mut wants_payload = vec![false; n];
    let mut dependants = vec![0usize; n];
    for &i in needed {
        for (_, u) in &plan.nodes[i].upstream {
            dependants[*u] += 1;
            if !in_cache[i] {
                wants_payload[*u] = true;
            }
        }
    }
    for &i in needed.iter().rev() {
        if wants_payload[i] && matches!(plan.nodes[i].task.array_storage(), ArrayStorage::Derive(_))
        {
            for (_, u) in &plan.nodes[i].upstream {
                wants_payload[*u] = true;
            }
        }
    }
    (wants_payload, dependants)
}

/// The order instances run in: each as soon as its upstream finished, deepest first (see
/// `RunContext::pull`).
pub(super) struct Schedule {
    /// Upstream instances not yet finished.
    pub(super) waiting: Vec<usize>,
    /// The dependants of each instance.
    pub(super) downstream: Vec<Vec<usize>>,
    /// Depth in the DAG (0: no upstream).
    pub(super) level: Vec<usize>,
    /// The instances with nothing to wait for.
    pub(super) ready: BinaryHeap<(usize, Reverse<usize>)>,
}

impl Schedule {
    pub(super) fn of(plan: &Plan, needed: &[usize]) -> Schedule {
        let n = plan.nodes.len();
        let mut waiting = vec![0usize; n];
        let mut downstream: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut level = vec![0usize; n];
        for &i in needed {
            for (_, u) in &plan.nodes[i].upstream {
                waiting[i] += 1;
                downstream[*u].push(i);
                level[i] = level[i].max(level[*u] + 1);
            }
        }
        let ready = needed
            .iter()
            .filter(|&&i| waiting[i] == 0)
            .map(|&i| (level[i], Reverse(i)))
            .collect();
        Schedule {
            waiting,
            downstream,
            level,
            ready,
        }
    }
}
