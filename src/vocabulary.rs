//! The names the node kinds write and the report reads: node kinds (the cache folders), tables,
//! cached arrays, metric columns and upstream roles. Defined once here, in a module that imports
//! neither side, so the report reads results without importing the node kinds
//! (`tests/engine/architecture.rs`) and a renamed column cannot leave the report behind.

/// Node kinds: the `kind` of a task, the cache folder of its entries.
pub mod kinds {
    /// The `surface` node kind.
    pub const SURFACE: &str = "surface";
    /// The `contact` node kind.
    pub const CONTACT: &str = "contact";
    /// The `friction` node kind.
    pub const FRICTION: &str = "friction";
}

/// Result tables (`<name>.parquet`).
pub mod tables {
    /// One row per surface node instance.
    pub const SURFACES: &str = "surfaces";
    /// One row per contact node instance (its final load step).
    pub const CONTACTS: &str = "contacts";
    /// One row per friction node instance.
    pub const FRICTION: &str = "friction";
    /// A contact's own table of load steps; the engine writes it as `contacts_load_curve`
    /// ([`CONTACTS_LOAD_CURVE`]).
    pub const LOAD_CURVE: &str = "load_curve";
    /// The engine's `<table>_<own table>` for [`LOAD_CURVE`] of [`CONTACTS`].
    pub const CONTACTS_LOAD_CURVE: &str = "contacts_load_curve";
    /// A surface's own table of its material ratio curve; the engine writes it as
    /// `surfaces_material_ratio` ([`SURFACES_MATERIAL_RATIO`]).
    pub const MATERIAL_RATIO: &str = "material_ratio";
    /// The engine's `<table>_<own table>` for [`MATERIAL_RATIO`] of [`SURFACES`].
    pub const SURFACES_MATERIAL_RATIO: &str = "surfaces_material_ratio";
    /// One row per scenario, with its parameters and the `<node>_key` of each node.
    pub const SCENARIOS: &str = "scenarios";
}

/// Arrays a node stores in its cache entry.
pub mod arrays {
    /// Surface heights z (m, `[[iy, ix]]`).
    pub const HEIGHTS: &str = "heights";
    /// Contact pressure p (Pa) of the final step.
    pub const PRESSURE: &str = "pressure";
    /// Gap g (m) after deformation.
    pub const GAP: &str = "gap";
    /// Elastic deformation of the lower body (m).
    pub const DEFORMATION_LOWER: &str = "deformation_lower";
    /// Elastic deformation of the upper body (m).
    pub const DEFORMATION_UPPER: &str = "deformation_upper";
    /// Plastic penetration (m) where the pressure is saturated.
    pub const PLASTIC_PENETRATION: &str = "plastic_penetration";
    /// The composite height z₁ + z₂ (m) the contact was solved on.
    pub const COMPOSITE_HEIGHT: &str = "composite_height";
    /// Prefix of the contact pressure of a load step before the final one (`pressure_step_0`,
    /// …): its contact points only, row 0 their flat indices iy·nx + ix, row 1 p (Pa).
    pub const PRESSURE_STEP_PREFIX: &str = "pressure_step_";
}

/// Metric columns (SI; the tables append the unit: `nominal_pressure_Pa`).
pub mod metrics {
    /// Grid spacing along x (m).
    pub const DX: &str = "dx";
    /// Grid spacing along y (m).
    pub const DY: &str = "dy";
    /// Grid points along x.
    pub const GRID_NX: &str = "grid_nx";
    /// Grid points along y.
    pub const GRID_NY: &str = "grid_ny";
    /// Root-mean-square height Sq (m).
    pub const SQ: &str = "sq";
    /// Hurst exponent.
    pub const HURST: &str = "hurst";
    /// Mean summit radius (m).
    pub const SUMMIT_MEAN_RADIUS: &str = "summit_mean_radius";
    /// Nominal pressure (Pa).
    pub const NOMINAL_PRESSURE: &str = "nominal_pressure";
    /// Mean pressure over the true contact area (Pa).
    pub const MEAN_CONTACT_PRESSURE: &str = "mean_contact_pressure";
    /// True contact area fraction A_t,rel.
    pub const AREA_FRACTION: &str = "area_fraction";
    /// Stress ratio θ.
    pub const STRESS_RATIO: &str = "stress_ratio";
    /// Static friction coefficient μ_s.
    pub const MU_S: &str = "mu_s";
    /// Rigid-body approach δ of a contact's load step (m).
    pub const APPROACH: &str = "approach";
}

/// Upstream roles: the input a node names (`lower: surface_node`).
pub mod roles {
    /// The lower body's surface.
    pub const LOWER: &str = "lower";
    /// The upper body's surface.
    pub const UPPER: &str = "upper";
    /// The contact solution a friction node reads.
    pub const CONTACT: &str = "contact";
}

#[cfg(test)]
mod tests {
    use super::tables::*;

    #[test]
    fn own_tables_are_the_engines_table_of_their_kind() {
        assert_eq!(CONTACTS_LOAD_CURVE, format!("{CONTACTS}_{LOAD_CURVE}"));
        assert_eq!(
            SURFACES_MATERIAL_RATIO,
            format!("{SURFACES}_{MATERIAL_RATIO}")
        );
    }
}
