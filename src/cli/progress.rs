//! The progress bar of `asperity run` (indicatif), fed by the engine's progress events.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use asperity::engine::execute::{NodeStatus, Progress};
use asperity::engine::plan::PlannedNode;

/// A progress bar with ETA on stderr (hidden with `--quiet` or when stderr is not a terminal).
pub struct BarProgress {
    bar: ProgressBar,
}

impl BarProgress {
    pub fn new(quiet: bool) -> Self {
        let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
        if quiet {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} nodes, ETA {eta} {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Self { bar }
    }

    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Progress for BarProgress {
    fn start(&self, total: usize) {
        self.bar.set_length(total as u64);
    }

    fn finished(&self, node: &PlannedNode, status: &NodeStatus) {
        tracing::info!(
            kind = node.task.kind(),
            key = %node.key.short(),
            nodes = %node.names.join(","),
            status = ?status,
            "node finished"
        );
        self.bar
            .set_message(format!("{} {}", node.task.kind(), node.names.join(",")));
        self.bar.inc(1);
    }

    fn warn(&self, message: &str) {
        self.bar.suspend(|| eprintln!("warning: {message}"));
    }
}
