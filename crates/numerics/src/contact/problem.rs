//! The contact problem: what the solver (`solver`) solves and the multilevel start
//! (`multilevel`) coarsens.

use ndarray::ArrayView2;

use super::error::ContactError;
use super::gap::CompositeGap;
use super::influence::Boundary;
use super::material::ContactMaterial;

/// A normal contact problem: initial gap, material pair and lateral boundary condition.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactProblem {
    gap: CompositeGap,
    material: ContactMaterial,
    boundary: Boundary,
}

impl ContactProblem {
    /// Builds the problem from a composite gap.
    pub fn new(gap: CompositeGap, material: ContactMaterial, boundary: Boundary) -> Self {
        Self {
            gap,
            material,
            boundary,
        }
    }

    /// Builds the problem from a gap array in m (`[[iy, ix]]`) and pixel spacings in m.
    pub fn from_gap_array(
        gap: ArrayView2<f64>,
        dx: f64,
        dy: f64,
        material: ContactMaterial,
        boundary: Boundary,
    ) -> Result<Self, ContactError> {
        Ok(Self::new(
            CompositeGap::from_gap_array(gap, dx, dy)?,
            material,
            boundary,
        ))
    }

    /// The initial gap.
    pub fn gap(&self) -> &CompositeGap {
        &self.gap
    }

    /// The material pair.
    pub fn material(&self) -> &ContactMaterial {
        &self.material
    }

    /// The boundary condition.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }
}
