//! What a contact node gives its consumers, in one place: the names under which the `contact`
//! kind stores its maps and grid metrics (it writes them with these constants), and
//! [`ContactView`], the typed view the per-summit and per-spot friction methods read.

use ndarray::{ArrayView2, Ix2};

use crate::engine::artifact::Artifact;
use crate::engine::node::NodeError;
use crate::engine::value::Value;

/// The final step's maps (pressure in Pa, gap, deformations, plastic penetration in m,
/// `[[iy, ix]]`; no upper deformation against a rigid flat) and the composite height z₁ + z₂ (m)
/// the contact was solved on (the lower heights against a flat).
pub(crate) use crate::vocabulary::arrays::{
    COMPOSITE_HEIGHT, DEFORMATION_LOWER, DEFORMATION_UPPER, GAP, PLASTIC_PENETRATION, PRESSURE,
};
/// Among the contact's metrics: grid spacings (m), the final nominal pressure (Pa) and the share
/// of the section in contact (points with p > 0).
pub(crate) use crate::vocabulary::metrics::{AREA_FRACTION, DX, DY, NOMINAL_PRESSURE};

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
