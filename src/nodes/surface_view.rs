//! What a surface node gives its consumers, in one place: the names under which the `surface`
//! kind stores its heights and the metrics other kinds read (it writes them with these
//! constants), and [`SurfaceView`], the typed view the contact and friction kinds read.

use ndarray::{ArrayView2, Ix2};

use crate::engine::artifact::Artifact;
use crate::engine::node::NodeError;
use crate::engine::value::Value;

/// The height array (m, `[[iy, ix]]`).
pub(crate) use crate::vocabulary::arrays::HEIGHTS;
/// Grid size and spacings (m) among the surface's metrics.
pub(crate) use crate::vocabulary::metrics::{DX, DY, GRID_NX, GRID_NY};
/// Isotropic profile spectral moments m0 (m²), m2, m4 (m⁻²); with the suffix `_x` or `_y`
/// the moments along one axis.
pub(crate) use crate::vocabulary::surface_metrics::{M0, M2, M4};

/// A surface node's grid, heights (when loaded) and isotropic spectral moments (when defined:
/// a map with missing points has none).
#[derive(Debug, Clone)]
pub(crate) struct SurfaceView<'a> {
    pub heights: Option<ArrayView2<'a, f64>>,
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    /// (m0, m2, m4).
    pub moments: Option<(f64, f64, f64)>,
}

impl<'a> SurfaceView<'a> {
    /// The view of a surface node's artifact; `role` names it in errors ("lower").
    pub(crate) fn of(surface: &'a Artifact, role: &str) -> Result<Self, NodeError> {
        let fail = |m: String| NodeError::new(format!("{role} surface: {m}"));
        let float = |name: &str| match surface.metric(name).map(|f| &f.value) {
            Some(Value::Float(v)) => Some(*v),
            _ => None,
        };
        let int = |name: &str| match surface.metric(name).map(|f| &f.value) {
            Some(Value::Int(v)) => usize::try_from(*v).ok(),
            _ => None,
        };
        let heights = surface
            .arrays
            .get(HEIGHTS)
            .map(|a| a.view().into_dimensionality::<Ix2>())
            .transpose()
            .map_err(|e| fail(e.to_string()))?;
        let moments = match (float(M0), float(M2), float(M4)) {
            (Some(m0), Some(m2), Some(m4)) => Some((m0, m2, m4)),
            _ => None,
        };
        Ok(Self {
            heights,
            nx: int(GRID_NX).ok_or_else(|| fail(format!("no {GRID_NX}")))?,
            ny: int(GRID_NY).ok_or_else(|| fail(format!("no {GRID_NY}")))?,
            dx: float(DX).ok_or_else(|| fail(format!("no {DX}")))?,
            dy: float(DY).ok_or_else(|| fail(format!("no {DY}")))?,
            moments,
        })
    }

    /// The section's area nx·dx · ny·dy (m²).
    pub(crate) fn area(&self) -> f64 {
        self.nx as f64 * self.dx * self.ny as f64 * self.dy
    }
}
