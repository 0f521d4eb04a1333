//! What a contact is solved from and how long each stage takes: the problem of its upstream
//! surfaces (read in place), the heights kept with its fields, and the stages' clock.

use std::time::Instant;

use super::super::contact_view::{COMPOSITE_HEIGHT, HEIGHT_UPPER};
use super::super::surface_view::SurfaceView;
use super::ContactTask;
use crate::contact::{CompositeGap, ContactProblem, HeightsView};
use crate::engine::artifact::Artifact;
use crate::engine::node::NodeError;

/// The wall time of a contact's stages, each logged as a debug event when it ends (`-vv`).
pub(super) struct StageClock {
    started: Instant,
    last: Instant,
}

impl StageClock {
    pub(super) fn start() -> Self {
        let now = Instant::now();
        Self {
            started: now,
            last: now,
        }
    }

    /// Ends the stage `name` (begun when the one before ended).
    pub(super) fn stage(&mut self, name: &str) {
        let now = Instant::now();
        tracing::debug!(
            stage = name,
            seconds = (now - self.last).as_secs_f64(),
            since_start = (now - self.started).as_secs_f64(),
            "contact stage"
        );
        self.last = now;
    }
}

/// The contact problem of a task's upstream surfaces, with what the outputs need of it.
pub(super) struct ProblemSetup {
    pub(super) problem: ContactProblem,
    pub(super) composite_modulus: f64,
    /// (dx, dy) of the grid (m).
    pub(super) spacing: (f64, f64),
}

/// The heights and spacing of the surface `input` (`role` names it in errors).
fn heights<'a>(input: &'a Artifact, role: &str) -> Result<HeightsView<'a>, NodeError> {
    let view = SurfaceView::of(input, role)?;
    let heights = view
        .heights
        .ok_or_else(|| NodeError::new(format!("{role} surface: no height array")))?;
    Ok(HeightsView {
        heights,
        dx: view.dx,
        dy: view.dy,
    })
}

impl ContactTask {
    /// The gap of the upstream surface(s), read in place (the gap is the one new map), the
    /// material pair and the boundary.
    pub(super) fn problem(&self, inputs: &[&Artifact]) -> Result<ProblemSetup, NodeError> {
        let (lower, upper) = self.surfaces(inputs)?;
        let gap = CompositeGap::from_height_views(lower, upper)
            .map_err(|e| NodeError::new(format!("gap: {e}")))?;
        Ok(ProblemSetup {
            problem: ContactProblem::new(gap, self.material, self.boundary()),
            composite_modulus: self.material.composite_modulus(),
            spacing: (lower.dx, lower.dy),
        })
    }

    /// The lower surface and the upper one (none against a flat).
    fn surfaces<'a>(
        &self,
        inputs: &[&'a Artifact],
    ) -> Result<(HeightsView<'a>, Option<HeightsView<'a>>), NodeError> {
        let lower = heights(
            inputs
                .first()
                .ok_or_else(|| NodeError::new("no lower surface"))?,
            "lower",
        )?;
        let upper = match (self.material.pair().upper(), inputs.get(1)) {
            (Some(_), Some(input)) => Some(heights(input, "upper")?),
            _ => None,
        };
        Ok((lower, upper))
    }

    /// The composite height z₁ + z₂ the contact was solved on (the lower heights against a
    /// flat) and the upper body's heights z₂, as arrays of `artifact`, from the surfaces.
    pub(super) fn store_heights(
        &self,
        inputs: &[&Artifact],
        artifact: &mut Artifact,
    ) -> Result<(), NodeError> {
        let (lower, upper) = self.surfaces(inputs)?;
        let composite = match upper {
            Some(upper) => {
                artifact.arrays.insert(
                    String::from(HEIGHT_UPPER),
                    upper.heights.to_owned().into_dyn(),
                );
                &lower.heights + &upper.heights
            }
            None => lower.heights.to_owned(),
        };
        artifact
            .arrays
            .insert(String::from(COMPOSITE_HEIGHT), composite.into_dyn());
        Ok(())
    }
}
