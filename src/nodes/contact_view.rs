//! What a contact node gives its consumers, in one place: the names under which the `contact`
//! kind stores its maps and grid metrics (it writes them with these constants), the layout of
//! the pressure of its earlier load steps, [`ContactView`], the typed view of the final step the
//! per-summit and per-spot friction methods read, and [`StepPressure`], an earlier load step.
//!
//! The cache keeps a contact's pressure maps only; its displacements and composite height are
//! derived from them and the surfaces when a consumer needs them (`ContactTask::derive_arrays`),
//! and the gap, deformations and plastic penetration of every step point by point from those
//! ([`ContactView::of`], [`StepPressure::view`]).

use ndarray::{Array2, ArrayD, ArrayView2, Axis, Ix2, Ix3};

use crate::contact::{ContactMaterial, PointFields, PointMap, StepField};
use crate::engine::artifact::{Artifact, ColumnData};
use crate::engine::node::NodeError;
use crate::engine::value::Value;

/// The composite displacement of each load step before the final one, `[[step, iy, ix]]` (m),
/// which the contact derives once for all its consumers ([`StepPressure::view`] reads it).
pub(crate) use crate::vocabulary::arrays::STEP_DISPLACEMENTS;
/// The final step's maps (pressure in Pa and composite displacement `u = K p` in m,
/// `[[iy, ix]]`), the composite height z₁ + z₂ (m) the contact was solved on (the lower heights
/// against a flat) and the upper body's heights z₂ (m; only with an upper surface).
pub(crate) use crate::vocabulary::arrays::{
    COMPOSITE_HEIGHT, DISPLACEMENT, HEIGHT_UPPER, PRESSURE,
};
use crate::vocabulary::metrics::APPROACH;
/// Among the contact's metrics: grid spacings (m), the final nominal pressure (Pa) and the share
/// of the section in contact (points with p > 0).
pub(crate) use crate::vocabulary::metrics::{AREA_FRACTION, DX, DY, NOMINAL_PRESSURE};

/// The array holding the pressure of load step `step` before the final one (whose pressure is
/// [`PRESSURE`]).
pub(crate) fn step_pressure_name(step: usize) -> String {
    format!("{}{step}", crate::vocabulary::arrays::PRESSURE_STEP_PREFIX)
}

/// The nominal pressure (Pa) of each load step a contact solved, first to last (its load-curve
/// table; the last is the final step's, [`NOMINAL_PRESSURE`] among its metrics).
pub(crate) fn step_nominal_pressures(contact: &Artifact) -> Result<Vec<f64>, NodeError> {
    let column = contact
        .tables
        .get(crate::vocabulary::tables::LOAD_CURVE)
        .and_then(|t| t.columns.iter().find(|c| c.name == NOMINAL_PRESSURE))
        .map(|c| &c.data);
    match column {
        Some(ColumnData::Float(p)) if !p.is_empty() => Ok(p.clone()),
        _ => Err(NodeError::new(
            "the contact node has no load curve with its nominal pressures",
        )),
    }
}

/// The contact points of a pressure map as stored for an earlier load step: a `2 × m` array, row
/// 0 the flat indices `iy·nx + ix` of the points with `p > 0` (exact in f64 up to 2⁵³ points),
/// row 1 their pressures. A few per cent of the section is in contact, so a step costs memory
/// and cache in proportion to its contact area rather than to the grid.
pub(crate) fn contact_points(pressure: ArrayView2<f64>) -> ArrayD<f64> {
    let (index, value): (Vec<f64>, Vec<f64>) = pressure
        .iter()
        .enumerate()
        .filter(|(_, &p)| p > 0.0)
        .map(|(i, &p)| (i as f64, p))
        .unzip();
    let m = index.len();
    Array2::from_shape_vec((2, m), [index, value].concat())
        .map(Array2::into_dyn)
        .unwrap_or_else(|_| unreachable!("2 × m values in a 2 × m array"))
}

/// `pressure` (its grid's shape kept, all of it overwritten) set to the pressure map whose
/// contact points are `points` ([`contact_points`]).
pub(crate) fn fill_pressure_of_contact_points(
    points: &ArrayD<f64>,
    pressure: &mut Array2<f64>,
) -> Result<(), NodeError> {
    let bad = |why: &str| NodeError::new(format!("contact pressure of a load step: {why}"));
    let points = points
        .view()
        .into_dimensionality::<Ix2>()
        .map_err(|_| bad("not a 2 × m array"))?;
    if points.nrows() != 2 {
        return Err(bad("not a 2 × m array"));
    }
    let flat = pressure
        .as_slice_mut()
        .ok_or_else(|| bad("the map is not one contiguous array"))?;
    flat.fill(0.0);
    for (&index, &p) in points.row(0).iter().zip(points.row(1)) {
        let slot = (index >= 0.0 && index.fract() == 0.0)
            .then(|| flat.get_mut(index as usize))
            .flatten()
            .ok_or_else(|| bad("a point index outside the grid"))?;
        *slot = p;
    }
    Ok(())
}

/// The final step's fields of a contact run with `fields: true` (or, from [`StepPressure::view`],
/// another step's), and its grid.
#[derive(Debug, Clone)]
pub struct ContactView<'a> {
    pub pressure: ArrayView2<'a, f64>,
    pub gap: PointMap<'a>,
    pub deformation_lower: PointMap<'a>,
    pub deformation_upper: Option<PointMap<'a>>,
    pub plastic_penetration: PointMap<'a>,
    pub composite_height: ArrayView2<'a, f64>,
    /// The upper body's heights z₂ (outward, towards the lower body); `None` against a flat
    /// (the lower heights are then the composite height).
    pub upper_height: Option<ArrayView2<'a, f64>>,
    /// Grid spacings (m).
    pub dx: f64,
    pub dy: f64,
    /// The final nominal pressure (Pa).
    pub nominal_pressure: f64,
    /// The share of the section in contact.
    pub area_fraction: f64,
}

impl<'a> ContactView<'a> {
    /// The view of the final step of a contact node's artifact, whose contact is one of
    /// `material` (its gap, deformations and plastic penetration derived point by point from
    /// the pressure, the displacement, the composite height and the approach, [`PointFields`]);
    /// an error that says how to get the fields when the contact was run without them.
    pub fn of(contact: &'a Artifact, material: &ContactMaterial) -> Result<Self, NodeError> {
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
        let (pressure, composite_height) = (required(PRESSURE)?, required(COMPOSITE_HEIGHT)?);
        let fields = PointFields::new(
            composite_height,
            pressure,
            required(DISPLACEMENT)?,
            metric(APPROACH)?,
            material,
        )
        .map_err(|e| NodeError::new(format!("maps of the final load step: {e}")))?;
        let derived = |field| PointMap::Derived(fields, field);
        Ok(Self {
            pressure,
            gap: derived(StepField::Gap),
            deformation_lower: derived(StepField::DeformationFirst),
            deformation_upper: Some(derived(StepField::DeformationSecond)),
            plastic_penetration: derived(StepField::PlasticPenetration),
            composite_height,
            upper_height: optional(HEIGHT_UPPER)?,
            dx: metric(DX)?,
            dy: metric(DY)?,
            nominal_pressure: metric(NOMINAL_PRESSURE)?,
            area_fraction: metric(AREA_FRACTION)?,
        })
    }
}

/// Load step `step` before the final one of a contact run with `fields: true`, as its consumers
/// read it (`ContactTask::step_pressure`): the step's pressure map (Pa, `[[iy, ix]]`), approach
/// (m), nominal pressure (Pa) and contact area share. Its gap, deformations and plastic
/// penetration are not stored: [`StepPressure::view`] derives them point by point
/// ([`PointFields`]) from this pressure, the contact's composite height and the step's
/// displacement the contact derived once for all its consumers ([`STEP_DISPLACEMENTS`]), equal
/// bit for bit to the arrays `fields_from_displacement` would write.
#[derive(Debug, Clone, PartialEq)]
pub struct StepPressure {
    /// The load step (0 for the first listed pressure).
    pub step: usize,
    pub pressure: Array2<f64>,
    /// The step's approach (m).
    pub approach: f64,
    /// The step's nominal pressure (Pa).
    pub nominal_pressure: f64,
    /// The step's share of the section in contact.
    pub area_fraction: f64,
    /// The contact's material pair, which splits the displacement between the bodies.
    pub material: ContactMaterial,
}

impl StepPressure {
    /// The view the friction methods read, of this step: its pressure, the maps derived from it,
    /// the contact's composite height and grid spacings.
    pub fn view<'a>(&'a self, contact: &'a Artifact) -> Result<ContactView<'a>, NodeError> {
        let last = ContactView::of(contact, &self.material)?;
        let displacement = earlier_displacement(contact, self.step)?;
        let fields = PointFields::new(
            last.composite_height,
            self.pressure.view(),
            displacement,
            self.approach,
            &self.material,
        )
        .map_err(|e| NodeError::new(format!("maps of load step {}: {e}", self.step)))?;
        let derived = |field| PointMap::Derived(fields, field);
        Ok(ContactView {
            pressure: self.pressure.view(),
            gap: derived(StepField::Gap),
            deformation_lower: derived(StepField::DeformationFirst),
            deformation_upper: Some(derived(StepField::DeformationSecond)),
            plastic_penetration: derived(StepField::PlasticPenetration),
            nominal_pressure: self.nominal_pressure,
            area_fraction: self.area_fraction,
            ..last
        })
    }
}

/// The displacement of earlier load step `step` among the contact's [`STEP_DISPLACEMENTS`].
fn earlier_displacement(contact: &Artifact, step: usize) -> Result<ArrayView2<'_, f64>, NodeError> {
    let all = contact
        .arrays
        .get(STEP_DISPLACEMENTS)
        .ok_or_else(|| {
            NodeError::new(format!(
                "the contact node holds no '{STEP_DISPLACEMENTS}' array: run it with `fields: true`"
            ))
        })?
        .view()
        .into_dimensionality::<Ix3>()
        .map_err(|e| NodeError::new(format!("contact array {STEP_DISPLACEMENTS}: {e}")))?;
    if step >= all.len_of(Axis(0)) {
        return Err(NodeError::new(format!(
            "the contact holds the displacements of {} earlier load steps, not of step {step}",
            all.len_of(Axis(0))
        )));
    }
    Ok(all.index_axis_move(Axis(0), step))
}
