//! What happened to one instance: its status and the row data for the tables.

use std::collections::BTreeMap;

use crate::artifact::Table;
use crate::value::Field;

/// What happened to one instance.
#[derive(Debug, Clone, PartialEq)]
pub enum NodeStatus {
    Computed,
    Cached,
    Failed(String),
    /// Not computed because an upstream instance failed.
    Skipped(String),
}

impl NodeStatus {
    /// `"ok"`, `"failed"` or `"skipped"`; [`NodeOutcome::label`] adds `"flagged"`.
    pub fn label(&self) -> &'static str {
        match self {
            NodeStatus::Computed | NodeStatus::Cached => "ok",
            NodeStatus::Failed(_) => "failed",
            NodeStatus::Skipped(_) => "skipped",
        }
    }

    /// The failure message, empty when ok.
    pub fn message(&self) -> &str {
        match self {
            NodeStatus::Failed(m) | NodeStatus::Skipped(m) => m,
            _ => "",
        }
    }
}

/// The outcome of one instance: its status and the row data for the tables.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeOutcome {
    pub status: NodeStatus,
    pub metrics: Vec<Field>,
    pub tables: BTreeMap<String, Table>,
    /// The artifact's flags ([`crate::artifact::Artifact::flags`]): why its values must be read with care.
    pub flags: Vec<String>,
    /// Compute time (when computed now) or the recorded compute time (when cached), seconds.
    pub compute_seconds: f64,
}

impl NodeOutcome {
    /// The `status` column of tables: `"flagged"` for a computed or cached instance with flags,
    /// otherwise [`NodeStatus::label`].
    pub fn label(&self) -> &'static str {
        match self.status {
            NodeStatus::Computed | NodeStatus::Cached if !self.flags.is_empty() => "flagged",
            _ => self.status.label(),
        }
    }

    /// The `message` column: the flags joined by "; " when flagged, the failure message when
    /// failed or skipped, empty when ok.
    pub fn message(&self) -> String {
        match self.status {
            NodeStatus::Computed | NodeStatus::Cached => self.flags.join("; "),
            _ => self.status.message().to_string(),
        }
    }

    /// `true` when the instance computed (or was cached) with flags.
    pub fn is_flagged(&self) -> bool {
        self.label() == "flagged"
    }
}
