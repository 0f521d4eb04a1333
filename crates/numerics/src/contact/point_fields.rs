//! The fields of a load step read point by point instead of stored: each value from the step's
//! composite height, pressure and composite displacement when it is read.
//!
//! At a point of composite height `z`, pressure `p` and displacement `u = K p` (see
//! `derived.rs`): the gap `g = (max z − z) + u − δ`, the deformation of the first body
//! `u · c₁/(c₁ + c₂)` and of the second `u · c₂/(c₁ + c₂)` (Johnson 1985, §13.1), the plastic
//! penetration `max(0, −g)` where `p ≥ p_lim` and 0 elsewhere. These functions are the one
//! definition of each field: [`super::fields_from_displacement`] and the solver's fields
//! (`derived.rs`) write their arrays with them, so a value read here equals the stored one bit
//! for bit. A consumer that reads a few fields of many load steps ([`PointFields`]) then needs
//! no array per field and step: only the step's pressure and displacement.

use ndarray::ArrayView2;

use super::error::ContactError;
use super::material::ContactMaterial;

/// The gap `g = (top − z) + u − δ` of a point of composite height `z` and displacement `u`, for
/// the highest composite height `top` and the approach `approach` (m).
pub(super) fn gap(top: f64, z: f64, u: f64, approach: f64) -> f64 {
    (top - z) + u - approach
}

/// A body's deformation, its `share` of the composite displacement `u`.
pub(super) fn deformation(u: f64, share: f64) -> f64 {
    u * share
}

/// The plastic penetration of a point of pressure `p` and gap `g`: `max(0, −g)` where `p = p_lim`
/// (the pressure reaches the cap), 0 elsewhere.
pub(super) fn plastic(p: f64, g: f64, plim: f64) -> f64 {
    if p >= plim {
        (-g).max(0.0)
    } else {
        0.0
    }
}

/// A field of a load step that [`PointFields`] derives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepField {
    /// The gap after loading (m).
    Gap,
    /// The first (lower) body's deformation (m).
    DeformationFirst,
    /// The second (upper) body's deformation (m).
    DeformationSecond,
    /// The plastic penetration (m).
    PlasticPenetration,
}

/// The fields of one load step derived point by point (module docs) from its composite height,
/// pressure and displacement, all `[[iy, ix]]` on one grid.
#[derive(Debug, Clone, Copy)]
pub struct PointFields<'a> {
    composite_height: ArrayView2<'a, f64>,
    pressure: ArrayView2<'a, f64>,
    displacement: ArrayView2<'a, f64>,
    top: f64,
    approach: f64,
    share: f64,
    flow_pressure: f64,
}

impl<'a> PointFields<'a> {
    /// The fields of the step with the composite height `composite_height` (m) the contact was
    /// solved on, the `pressure` (Pa), the composite displacement `displacement = K p` (m) and
    /// the approach `approach` (m) of a contact of `material`. An error when the maps are not
    /// on one grid.
    pub fn new(
        composite_height: ArrayView2<'a, f64>,
        pressure: ArrayView2<'a, f64>,
        displacement: ArrayView2<'a, f64>,
        approach: f64,
        material: &ContactMaterial,
    ) -> Result<Self, ContactError> {
        let shape = composite_height.dim();
        for got in [pressure.dim(), displacement.dim()] {
            if got != shape {
                return Err(ContactError::FieldShape {
                    expected: shape,
                    got,
                });
            }
        }
        let top = composite_height
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        Ok(Self {
            composite_height,
            pressure,
            displacement,
            top,
            approach,
            share: material.first_body_share(),
            flow_pressure: material.flow_pressure(),
        })
    }

    /// The grid, `(ny, nx)`.
    pub fn dim(&self) -> (usize, usize) {
        self.composite_height.dim()
    }

    /// The highest composite height (m).
    pub(super) fn top(&self) -> f64 {
        self.top
    }

    /// `field` at `(iy, ix)`; `None` outside the grid.
    pub fn get(&self, field: StepField, at: (usize, usize)) -> Option<f64> {
        let u = *self.displacement.get(at)?;
        let gap_at = || gap(self.top, self.composite_height[at], u, self.approach);
        Some(match field {
            StepField::Gap => gap_at(),
            StepField::DeformationFirst => deformation(u, self.share),
            StepField::DeformationSecond => deformation(u, 1.0 - self.share),
            StepField::PlasticPenetration => {
                plastic(self.pressure[at], gap_at(), self.flow_pressure)
            }
        })
    }
}

/// One map of a solved load step as its consumers read it, point by point: an array (as the
/// contact stores its final step's maps) or a field derived when read ([`PointFields`]).
#[derive(Debug, Clone, Copy)]
pub enum PointMap<'a> {
    /// The map's array.
    Stored(ArrayView2<'a, f64>),
    /// A field of a step, derived point by point.
    Derived(PointFields<'a>, StepField),
}

impl<'a> From<ArrayView2<'a, f64>> for PointMap<'a> {
    fn from(map: ArrayView2<'a, f64>) -> Self {
        Self::Stored(map)
    }
}

impl PointMap<'_> {
    /// The grid, `(ny, nx)`.
    pub fn dim(&self) -> (usize, usize) {
        match self {
            Self::Stored(map) => map.dim(),
            Self::Derived(fields, _) => fields.dim(),
        }
    }

    /// The value at `(iy, ix)`; `None` outside the grid.
    pub fn get(&self, at: (usize, usize)) -> Option<f64> {
        match self {
            Self::Stored(map) => map.get(at).copied(),
            Self::Derived(fields, field) => fields.get(*field, at),
        }
    }

    /// The value at `(iy, ix)`, which must lie on the grid.
    ///
    /// # Panics
    /// Outside the grid, as indexing an array does.
    pub fn at(&self, at: (usize, usize)) -> f64 {
        match self {
            Self::Stored(map) => map[at],
            Self::Derived(fields, field) => fields
                .get(*field, at)
                .unwrap_or_else(|| panic!("{at:?} outside the {:?} grid", fields.dim())),
        }
    }
}

#[cfg(test)]
mod tests {
    use ndarray::Array2;

    use super::*;
    use crate::contact::{fields_from_displacement, ContactFields, FieldRequest};

    /// Every derived value equals the array [`fields_from_displacement`] writes, bit for bit,
    /// with saturated, elastic and free points and a body share other than ½.
    #[test]
    fn derived_values_equal_the_written_fields() {
        let (ny, nx) = (5, 7);
        let z = Array2::from_shape_fn((ny, nx), |(i, j)| ((i * 7 + j * 3) % 11) as f64 * 1e-7);
        let u = Array2::from_shape_fn((ny, nx), |(i, j)| ((i * 5 + j) % 6) as f64 * 2.3e-8);
        let material = ContactMaterial::from_young_poisson(210e9, 0.3, 70e9, 0.33, 2e9).unwrap();
        let p = Array2::from_shape_fn((ny, nx), |(i, j)| match (i + j) % 3 {
            0 => 0.0,
            1 => 1.2e9,
            _ => material.flow_pressure(),
        });
        let approach = 6.1e-7;
        let mut fields = ContactFields::default();
        let request = FieldRequest::ALL;
        fields_from_displacement(
            z.view(),
            p.view(),
            u.view(),
            approach,
            &material,
            request,
            &mut fields,
        )
        .unwrap();
        let point = PointFields::new(z.view(), p.view(), u.view(), approach, &material).unwrap();
        for (field, array) in [
            (StepField::Gap, &fields.gap),
            (StepField::DeformationFirst, &fields.deformation_first),
            (StepField::DeformationSecond, &fields.deformation_second),
            (StepField::PlasticPenetration, &fields.plastic_penetration),
        ] {
            let array = array.as_ref().unwrap();
            let map = PointMap::Derived(point, field);
            assert_eq!(map.dim(), (ny, nx));
            for ((iy, ix), &stored) in array.indexed_iter() {
                assert_eq!(map.at((iy, ix)).to_bits(), stored.to_bits(), "{field:?}");
            }
            assert_eq!(map.get((ny, 0)), None);
            assert_eq!(
                PointMap::from(array.view()).get((1, 2)),
                Some(array[[1, 2]])
            );
        }
        assert!(fields.plastic_penetration.unwrap().iter().any(|&v| v > 0.0));
    }

    #[test]
    fn maps_on_other_grids_are_an_error() {
        let z = Array2::zeros((3, 4));
        let other = Array2::zeros((4, 3));
        let material = ContactMaterial::against_rigid_flat(100e9, 1e9).unwrap();
        assert!(PointFields::new(z.view(), other.view(), z.view(), 0.0, &material).is_err());
        assert!(PointFields::new(z.view(), z.view(), other.view(), 0.0, &material).is_err());
    }
}
