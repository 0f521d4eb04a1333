//! The engine's cancellation hook: once `Progress::cancelled` says so, no further instance
//! starts; the report says the run was cancelled, and every instance that finished is a
//! complete, verified cache entry a second run reuses.

use std::sync::atomic::{AtomicUsize, Ordering};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, NodeStatus, Progress};
use asperity::engine::plan::PlannedNode;
use asperity::study_run::{execute_options, load_study};

/// Six independent surfaces.
const STUDY: &str = r#"
study: cancel
parameters:
  product:
    seed: [1, 2, 3, 4, 5, 6]
nodes:
  s:
    surface:
      synthetic: {grid: [32, 32], size: [100 um, 100 um], sq: 1 um, hurst: 0.8,
                  correlation_length: 20 um, seed: "${seed}"}
"#;

/// Cancels once `after` instances have finished.
struct CancelAfter {
    after: usize,
    finished: AtomicUsize,
}

impl Progress for CancelAfter {
    fn start(&self, _: usize) {}
    fn finished(&self, _: &PlannedNode, _: &NodeStatus) {
        self.finished.fetch_add(1, Ordering::SeqCst);
    }
    fn warn(&self, _: &str) {}
    fn cancelled(&self) -> bool {
        self.finished.load(Ordering::SeqCst) >= self.after
    }
}

#[test]
fn a_cancelled_run_starts_nothing_more_and_leaves_complete_entries() {
    let dir = std::env::temp_dir().join(format!("asperity-cancel-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cancel.yaml");
    std::fs::write(&path, STUDY).unwrap();
    let (study, plan) = load_study(&path, &[]).unwrap();
    let cache = Cache::open(&dir.join("cache")).unwrap();
    let options = execute_options(&study, 1 << 30);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let progress = CancelAfter {
        after: 2,
        finished: AtomicUsize::new(0),
    };
    let report = pool
        .install(|| execute(&plan, &cache, &options, &progress))
        .unwrap();
    assert!(report.cancelled && !report.all_ok());
    assert_eq!(report.computed, 2, "{:?}", report.outcomes);
    assert_eq!(report.outcomes.iter().filter(|o| o.is_none()).count(), 4);
    for (node, outcome) in plan.nodes.iter().zip(&report.outcomes) {
        let stored = cache.contains(node.task.kind(), &node.key);
        assert_eq!(stored, outcome.is_some());
        if stored {
            assert!(cache.verify(node.task.kind(), &node.key).unwrap());
        }
    }
    let never = CancelAfter {
        after: usize::MAX,
        finished: AtomicUsize::new(0),
    };
    let again = execute(&plan, &cache, &options, &never).unwrap();
    assert!(!again.cancelled && again.all_ok());
    assert_eq!((again.cached, again.computed), (2, 4));
    let _ = std::fs::remove_dir_all(&dir);
}
