//! What a contact node gives its consumers, in one place: the names under which the `contact`
//! kind stores its maps and grid metrics (it writes them with these constants), and
//! [`ContactView`], the typed view the per-summit and per-spot friction methods read.

use ndarray::{ArrayView2, Ix2};

use crate::engine::artifact::Artifact;
use crate::engine::node::NodeError;
use crate::engine::value::Value;

/// Contact pressure of the final step (Pa, `[[iy, ix]]`).
pub(crate) const PRESSURE: &str = "pressure";
/// Gap of the final step (m).
pub(crate) const GAP: &str = "gap";
/// Elastic normal displacement of the lower body (m).
pub(crate) const DEFORMATION_LOWER: &str = "deformation_lower";
/// Elastic normal displacement of the upper body (m; absent for a rigid flat).
pub(crate) const DEFORMATION_UPPER: &str = "deformation_upper";
/// Plastic penetration (m).
pub(crate) const PLASTIC_PENETRATION: &str = "plastic_penetration";
/// The composite height z₁ + z₂ (m) the contact was solved on (the lower heights against a flat).
pub(crate) const COMPOSITE_HEIGHT: &str = "composite_height";
/// Grid spacings (m) among the contact's metrics.
pub(crate) const DX: &str = "dx";
pub(crate) const DY: &str = "dy";
/// The final nominal pressure (Pa) among the contact's metrics.
pub(crate) const NOMINAL_PRESSURE: &str = "nominal_pressure";
/// The share of the section in contact (points with p > 0) among the contact's metrics.
pub(crate) const AREA_FRACTION: &str = "area_fraction";

/// The final step's fields of a contact run with `fields: true`, and its grid.
#[derive(Debug, Clone)]
pub(crate) struct ContactView<'a> {
    pub pressure: ArrayView2<'a, f64>,
    pub gap: ArrayView2<'a, f64>,
    pub deformation_lower: ArrayView2<'a, f64>,
    pub deformation_upper: Option<ArrayView2<'a, f64>>,
    pub plastic_penetration: ArrayView2<'a, f64>,
    pub composite_height: ArrayView2<'a, f64>,
    /// Grid spacings (m).
    pub dx: f64,
    pub dy: f64,
    /// The final nominal pressure (Pa).
    pub nominal_pressure: f64,
    /// The share of the section in contact.
    pub area_fraction: f64,
}

impl<'a> ContactView<'a> {
    /// The view of a contact node's artifact; an error that says how to get the fields when the
    /// contact was run without them.
    pub(crate) fn of(contact: &'a Artifact) -> Result<Self, NodeError> {
        let optional = |name: &str| {
            contact
                .arrays
                .get(name)
                .map(|a| {
                    a.view()
                        .into_dimensionality::<Ix2>()
                        .map_err(|e| NodeError::new(format!("contact array {name}: {e}")))
                })
                .transpose()
        };
        let required = |name: &str| {
            optional(name)?.ok_or_else(|| {
                NodeError::new(format!(
                    "the contact node stored no '{name}' array: run it with `fields: true`"
                ))
            })
        };
        let metric = |name: &str| match contact.metric(name).map(|f| &f.value) {
            Some(Value::Float(v)) => Ok(*v),
            _ => Err(NodeError::new(format!("contact node: no {name}"))),
        };
        Ok(Self {
            pressure: required(PRESSURE)?,
            gap: required(GAP)?,
            deformation_lower: required(DEFORMATION_LOWER)?,
            deformation_upper: optional(DEFORMATION_UPPER)?,
            plastic_penetration: required(PLASTIC_PENETRATION)?,
            composite_height: required(COMPOSITE_HEIGHT)?,
            dx: metric(DX)?,
            dy: metric(DY)?,
            nominal_pressure: metric(NOMINAL_PRESSURE)?,
            area_fraction: metric(AREA_FRACTION)?,
        })
    }
}
