//! The names the node kinds write and the report reads: node kinds (the cache folders), tables,
//! cached arrays, metric columns and upstream roles. Defined once here, in a module that imports
//! neither side, so the report reads results without importing the node kinds
//! (`tests/engine/architecture.rs`) and a renamed column cannot leave the report behind.

pub mod all;

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
    /// A surface's own table of its radially averaged autocorrelation (`surfaces_acf`).
    pub const ACF: &str = "acf";
    /// A surface's own table of its radially averaged power spectral density (`surfaces_psd`).
    pub const PSD: &str = "psd";
    /// A friction node's own table of its contact spots (`friction_spots`).
    pub const SPOTS: &str = "spots";
    /// A friction node's own table of its summits (`friction_summits`); a surface's own table of
    /// its identified summits (`surfaces_summits`).
    pub const SUMMITS: &str = "summits";
    /// A friction node's own table of its load steps (`friction_curve`): one row per load of a
    /// statistical node, per load step of the contact a per-summit or per-spot node reads.
    pub const CURVE: &str = "curve";
    /// One row per scenario, with its parameters and the `<node>_key` of each node.
    pub const SCENARIOS: &str = "scenarios";
}

/// Arrays a node stores in its cache entry.
pub mod arrays {
    /// Surface heights z (m, `[[iy, ix]]`).
    pub const HEIGHTS: &str = "heights";
    /// Contact pressure p (Pa) of the final step.
    pub const PRESSURE: &str = "pressure";
    /// Gap g (m) after deformation (a step's map as the Python API returns it; a study's
    /// consumers derive it point by point).
    pub const GAP: &str = "gap";
    /// Elastic deformation of the lower body (m; a step's map, as [`GAP`]).
    pub const DEFORMATION_LOWER: &str = "deformation_lower";
    /// Elastic deformation of the upper body (m; a step's map, as [`GAP`]).
    pub const DEFORMATION_UPPER: &str = "deformation_upper";
    /// Plastic penetration (m) where the pressure is saturated (a step's map, as [`GAP`]).
    pub const PLASTIC_PENETRATION: &str = "plastic_penetration";
    /// The composite height z₁ + z₂ (m) the contact was solved on.
    pub const COMPOSITE_HEIGHT: &str = "composite_height";
    /// Prefix of the contact pressure of a load step before the final one (`pressure_step_0`,
    /// …): its contact points only, row 0 their flat indices iy·nx + ix, row 1 p (Pa).
    pub const PRESSURE_STEP_PREFIX: &str = "pressure_step_";
    /// The upper body's heights z₂ (m, outward towards the lower body) the contact was solved
    /// with; only with an upper surface.
    pub const HEIGHT_UPPER: &str = "height_upper";
    /// The composite elastic displacement u = u₁ + u₂ = K p (m) of the final load step: kept
    /// for a contact's consumers, which derive its gap, deformations and plastic penetration
    /// from it point by point; derived from the pressure when a contact is read from the cache,
    /// never stored there.
    pub const DISPLACEMENT: &str = "displacement";
    /// The composite elastic displacement u = u₁ + u₂ (m) of every load step before the final
    /// one, `[[step, iy, ix]]`: derived from the steps' pressure when a contact is computed or
    /// read for its consumers, never stored in the cache.
    pub const STEP_DISPLACEMENTS: &str = "step_displacements";
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

    // The friction row (`friction` table): method, model and trust.
    /// Friction method (`statistical`, `per_summit`, `per_spot`).
    pub const METHOD: &str = "method";
    /// Friction law, by its registry name.
    pub const MODEL: &str = "model";
    /// How far the law's constants are confirmed.
    pub const MODEL_BASIS: &str = "model_basis";
    /// μ_s as the model computed it (may be negative).
    pub const MU_S_COMPUTED: &str = "mu_s_computed";
    /// Whether a negative computed μ_s is reported as 0.
    pub const MU_S_FLOORED: &str = "mu_s_floored";
    /// Share of the normal load outside the law's validated range.
    pub const LOAD_SHARE_BEYOND_FIT: &str = "load_share_beyond_fit";
    // The friction row: forces, areas and the solve.
    /// External normal load F = P − F_a (N).
    pub const EXTERNAL_LOAD: &str = "external_load";
    /// Contact (normal) load P (N).
    pub const NORMAL_LOAD: &str = "normal_load";
    /// Adhesion force F_a (N).
    pub const ADHESION_FORCE: &str = "adhesion_force";
    /// Static friction force Q (N).
    pub const FRICTION_FORCE: &str = "friction_force";
    /// The contact node's own load at its nominal pressure (N).
    pub const CONTACT_NORMAL_LOAD: &str = "contact_normal_load";
    /// True contact area (m²).
    pub const REAL_AREA: &str = "real_area";
    /// Apparent (nominal) area (m²).
    pub const APPARENT_AREA: &str = "apparent_area";
    /// Area of the computed section (m²).
    pub const SECTION_AREA: &str = "section_area";
    /// Separation of the mean planes (m).
    pub const SEPARATION: &str = "separation";
    /// Dimensionless separation d*.
    pub const D_STAR: &str = "d_star";
    /// Plasticity index ψ.
    pub const PLASTICITY_INDEX: &str = "plasticity_index";
    /// Number of contacting summits.
    pub const CONTACTS: &str = "contacts";
    /// GW σ of the sum surface (m).
    pub const GW_SIGMA: &str = "gw_sigma";
    /// GW σ_s of the summit heights (m).
    pub const GW_SIGMA_S: &str = "gw_sigma_s";
    /// GW mean summit radius (m).
    pub const GW_SUMMIT_RADIUS: &str = "gw_summit_radius";
    /// GW summit density (1/m²).
    pub const GW_SUMMIT_DENSITY: &str = "gw_summit_density";
    /// GW roughness parameter β = ηRσ.
    pub const GW_BETA: &str = "gw_beta";
    /// Roots of the separation solve found.
    pub const ROOTS_FOUND: &str = "roots_found";
    /// Iterations of a solve.
    pub const ITERATIONS: &str = "iterations";
    /// Relative residual of a solve.
    pub const RESIDUAL: &str = "residual";
    /// Largest relative error of the statistical integrals.
    pub const INTEGRAL_ERROR: &str = "integral_error";
    // The friction row: summits and spots.
    /// Number of summits.
    pub const SUMMIT_COUNT: &str = "summit_count";
    /// Summits in the elastic state.
    pub const ELASTIC_SUMMITS: &str = "elastic_summits";
    /// Summits in the elastic–plastic state.
    pub const ELASTIC_PLASTIC_SUMMITS: &str = "elastic_plastic_summits";
    /// Summits in the fully plastic state.
    pub const FULLY_PLASTIC_SUMMITS: &str = "fully_plastic_summits";
    /// 10 % quantile of the local μ.
    pub const LOCAL_MU_P10: &str = "local_mu_p10";
    /// Median of the local μ.
    pub const LOCAL_MU_MEDIAN: &str = "local_mu_median";
    /// 90 % quantile of the local μ.
    pub const LOCAL_MU_P90: &str = "local_mu_p90";
    /// 10 % quantile of the spot areas (m²).
    pub const SPOT_AREA_P10: &str = "spot_area_p10";
    /// Median of the spot areas (m²).
    pub const SPOT_AREA_MEDIAN: &str = "spot_area_median";
    /// 90 % quantile of the spot areas (m²).
    pub const SPOT_AREA_P90: &str = "spot_area_p90";
    /// Number of contact spots.
    pub const SPOT_COUNT: &str = "spot_count";
    /// Number of one-pixel spots.
    pub const ONE_PIXEL_SPOTS: &str = "one_pixel_spots";
    /// Share of the normal load on one-pixel spots.
    pub const LOAD_SHARE_ONE_PIXEL: &str = "load_share_one_pixel";
    /// Number of spots without a convex radius.
    pub const SPOTS_WITHOUT_RADIUS: &str = "spots_without_radius";
    /// Share of the normal load on spots without a convex radius.
    pub const LOAD_SHARE_WITHOUT_RADIUS: &str = "load_share_without_radius";
    /// Adhesion part of μ_s.
    pub const MU_ADHESION: &str = "mu_adhesion";
    /// Deformation part of μ_s.
    pub const MU_DEFORMATION: &str = "mu_deformation";
    /// (2/π) × the rms slope along ψ of the ploughing body's surface: the deformation part a
    /// topography statistic alone would give.
    pub const MU_DEFORMATION_SLOPE_BASELINE: &str = "mu_deformation_slope_baseline";
    /// Which body ploughs (`lower`, `upper`, `both`).
    pub const PLOUGHING_BODY: &str = "ploughing_body";
    /// Share of the normal load on spots beyond the ploughing regime.
    pub const LOAD_SHARE_OUTSIDE_REGIME: &str = "load_share_outside_regime";
    /// Load-weighted mean attack slope of the spots' loaded fronts.
    pub const SPOT_ATTACK_SLOPE_MEAN: &str = "spot_attack_slope_mean";
    /// Load-weighted mean groove ratio of the spots' loaded fronts.
    pub const SPOT_GROOVE_RATIO_MEAN: &str = "spot_groove_ratio_mean";
    /// Load-weighted mean degree of penetration of the spots' loaded fronts.
    pub const SPOT_PENETRATION_MEAN: &str = "spot_penetration_mean";
    /// Number of spots with two or more summits (merged asperities).
    pub const MERGED_SPOTS: &str = "merged_spots";
    /// Share of the normal load on merged spots whose friction rests on one radius.
    pub const LOAD_SHARE_MERGED: &str = "load_share_merged";
    /// Adhesion force over the contact's normal load, F_a/F_n.
    pub const ADHESION_SHARE: &str = "adhesion_share";
    // The friction row: its resolved parameters (key fields).
    /// Composite modulus E* (Pa).
    pub const COMPOSITE_MODULUS: &str = "composite_modulus";
    /// Hardness H of the softer body (Pa).
    pub const HARDNESS: &str = "hardness";
    /// Poisson ratio of the softer body.
    pub const POISSON_RATIO: &str = "poisson_ratio";
    /// Yield strength Y of the softer body (Pa), as the stick laws report it (the numerics'
    /// law registry spells it too: it knows no application vocabulary).
    pub const YIELD_STRENGTH: &str = "yield_strength";
    /// Shear strength k of the softer body (Pa), as junction shear reports it (spelt in the
    /// numerics' law registry too).
    pub const SHEAR_STRENGTH: &str = "shear_strength";
    /// Adhesion energy Δγ (N/m).
    pub const ADHESION_ENERGY: &str = "adhesion_energy";
    /// Lennard-Jones equilibrium distance ε (m).
    pub const EQUILIBRIUM_DISTANCE: &str = "equilibrium_distance";
    /// Nominal area A_n (m²).
    pub const NOMINAL_AREA: &str = "nominal_area";
    /// Explicit σ (m).
    pub const SIGMA: &str = "sigma";
    /// Explicit summit radius (m).
    pub const SUMMIT_RADIUS: &str = "summit_radius";
    /// Explicit summit density (1/m²).
    pub const SUMMIT_DENSITY: &str = "summit_density";
    /// The nominal pressures of a contact's load steps or of a statistical node (Pa), a list
    /// (`nominal_pressures_Pa`, `List(Float64)`).
    pub const NOMINAL_PRESSURES: &str = "nominal_pressures";
    /// The external normal loads of a statistical node (N), a list (`loads_N`,
    /// `List(Float64)`).
    pub const LOADS: &str = "loads";
    /// Whether the per-summit table is written.
    pub const SUMMITS_TABLE: &str = "summits_table";
    /// Spot connectivity, 4 or 8.
    pub const SPOT_CONNECTIVITY: &str = "spot_connectivity";
    /// Whether the per-spot table is written.
    pub const SPOTS_TABLE: &str = "spots_table";
}

/// The resolved parameters of a surface node (its key fields; columns of `surfaces`).
pub mod surface_parameters;

/// What a surface node measures on its heights (columns of `surfaces` beyond
/// [`super::metrics`]' shared ones).
pub mod surface_metrics;

/// What a twin surface reports of its model and calibration (columns of `surfaces`).
pub mod twin_metrics;

/// Columns of a surface's `psd` table (`surfaces_psd`).
pub mod psd_columns {
    /// Wavenumber q (rad/m).
    pub const Q: &str = "q_rad_per_m";
    /// Radially averaged PSD C(q) (m⁴).
    pub const C: &str = "c_m4";
}

/// Columns of a surface's `acf` table (`surfaces_acf`).
pub mod acf_columns {
    /// Lag r (m).
    pub const R: &str = "r";
    /// Radially averaged autocorrelation, normalised to 1 at r = 0.
    pub const ACF: &str = "acf";
}

/// Columns of a surface's `material_ratio` table (`surfaces_material_ratio`).
pub mod material_ratio_columns {
    /// Material ratio (%).
    pub const MATERIAL_RATIO_PERCENT: &str = "material_ratio_percent";
    /// Height at that ratio (m).
    pub const HEIGHT: &str = "height";
}

/// The resolved parameters of a contact node (its key fields; columns of `contacts`).
pub mod contact_parameters {
    /// Flow pressure of the softer body (Pa).
    pub const FLOW_PRESSURE: &str = "flow_pressure";
    /// Whether the surfaces are periodic.
    pub const PERIODIC: &str = "periodic";
    /// Relative tolerance of the solver.
    pub const TOLERANCE: &str = "tolerance";
    /// Whether the final step's fields are kept.
    pub const FIELDS: &str = "fields";
    /// Young's modulus of a body (Pa), after its side ([`lower`](super::roles::LOWER)
    /// or [`upper`](super::roles::UPPER)).
    pub const YOUNGS_MODULUS: &str = "youngs_modulus";

    /// A body's material column: `<side>_<name>` (`lower_youngs_modulus`).
    pub fn of_side(side: &str, name: &str) -> String {
        format!("{side}_{name}")
    }
}

/// What a contact node reports of its final step (columns of `contacts` and
/// `contacts_load_curve` beyond [`super::metrics`]' shared ones).
pub mod contact_metrics {
    /// Share of the contact area at the flow pressure.
    pub const PLASTIC_AREA_SHARE: &str = "plastic_area_share";
    /// Mean separation of the deformed surfaces (m).
    pub const MEAN_SEPARATION: &str = "mean_separation";
    /// Largest elastic deformation (m).
    pub const MAX_ELASTIC_DEFORMATION: &str = "max_elastic_deformation";
    /// Iterations on the coarse grid.
    pub const COARSE_ITERATIONS: &str = "coarse_iterations";
    /// Iterations of the free-set (plastic) loop.
    pub const FREE_SET_ITERATIONS: &str = "free_set_iterations";
}

/// Columns of a friction node's `spots` table (`friction_spots`, one row per contact spot).
pub mod spot_columns {
    /// The prefix of a Python per-spot result's list of one of these columns (`spot_area_m2`).
    pub const LIST_PREFIX: &str = "spot_";
    /// Spot id.
    pub const SPOT: &str = "spot";
    /// Column of the highest point.
    pub const PEAK_IX: &str = "peak_ix";
    /// Row of the highest point.
    pub const PEAK_IY: &str = "peak_iy";
    /// x of the highest point (m).
    pub const PEAK_X: &str = "peak_x";
    /// y of the highest point (m).
    pub const PEAK_Y: &str = "peak_y";
    /// Grid points in the spot.
    pub const PIXELS: &str = "pixels";
    /// Spot area (m²).
    pub const AREA: &str = "area";
    /// Spot load (N).
    pub const NORMAL_FORCE: &str = "normal_force";
    /// Highest pressure (Pa).
    pub const MAX_PRESSURE: &str = "max_pressure";
    /// Paraboloid radius (m).
    pub const RADIUS: &str = "radius";
    /// `convex` or `not_convex`.
    pub const RADIUS_STATUS: &str = "radius_status";
    /// Summits of the composite height in the spot (two or more: merged).
    pub const SUMMITS: &str = "summits";
    /// The law's load measure (P*, x).
    pub const LOAD_MEASURE: &str = "load_measure";
    /// Tangential capacity Q_i (N).
    pub const FRICTION_FORCE: &str = "friction_force";
    /// Q_i/P_i.
    pub const LOCAL_MU: &str = "local_mu";
    /// `inside` or `beyond` the law's fit.
    pub const FIT: &str = "fit";
    /// Attack slope tan α of the loaded front.
    pub const ATTACK_SLOPE: &str = "attack_slope";
    /// Groove ratio A_side/A_f of the loaded front.
    pub const GROOVE_RATIO: &str = "groove_ratio";
    /// Height of the ploughing asperity's cap above its front boundary (m).
    pub const CAP_HEIGHT: &str = "cap_height";
    /// Area of the loaded front A_f (m²).
    pub const FRONT_AREA: &str = "front_area";
    /// Radius of the loaded front a_f = √(2A_f/π) (m).
    pub const FRONT_RADIUS: &str = "front_radius";
    /// Degree of penetration D_p of the loaded front.
    pub const PENETRATION: &str = "penetration";
    /// Deformation force Q_d,i (N).
    pub const DEFORMATION_FORCE: &str = "deformation_force";
    /// `ploughing` or `beyond` the ploughing regime.
    pub const REGIME: &str = "regime";
}

/// Columns of a friction node's `summits` table (`friction_summits`, one row per summit) and of
/// a surface's (`surfaces_summits`: ix, iy, x, y, height, slope, radius).
pub mod summit_columns {
    /// The prefix of a Python per-summit result's list of one of these columns
    /// (`summit_radius_m`).
    pub const LIST_PREFIX: &str = "summit_";
    /// Column index.
    pub const IX: &str = "ix";
    /// Row index.
    pub const IY: &str = "iy";
    /// x (m).
    pub const X: &str = "x";
    /// y (m).
    pub const Y: &str = "y";
    /// Composite height (m).
    pub const HEIGHT: &str = "height";
    /// Summit radius (m).
    pub const RADIUS: &str = "radius";
    /// Surface slope at the summit (`surfaces_summits`).
    pub const SLOPE: &str = "slope";
    /// Interference ω (m).
    pub const INTERFERENCE: &str = "interference";
    /// x = ω/ω_c.
    pub const INTERFERENCE_RATIO: &str = "interference_ratio";
    /// Deformation state.
    pub const STATE: &str = "state";
    /// Normal force (N).
    pub const NORMAL_FORCE: &str = "normal_force";
    /// Adhesion force (N).
    pub const ADHESION_FORCE: &str = "adhesion_force";
    /// Friction force (N).
    pub const FRICTION_FORCE: &str = "friction_force";
}

/// Columns of a friction node's `curve` table (`friction_curve`, one row per load step) beyond
/// the row's metrics.
pub mod curve_columns {
    /// Index of the load step (0 for the first), the engine's step column.
    pub use crate::engine::columns::STEP;
    /// `ok` or `flagged`: the validity of the step's own values (the final step's is the row's).
    pub const STEP_STATUS: &str = "step_status";
    /// The sentences that flag the step, joined by "; " (empty when `ok`).
    pub const STEP_MESSAGE: &str = "step_message";
}

/// The columns that hold a list in every row, by name without unit; every other column holds
/// one value per row. A list is never written as text joined by commas or semicolons: these are
/// Parquet list columns, read by polars as `list[f64]`/`list[str]` and in Python as lists. An
/// empty list, not null, says "none" (`twin_warnings` of a twin without warnings); null is a row
/// the column does not apply to (a surface that is no twin).
pub mod list_columns {
    use super::twin_metrics::{
        TWIN_CORRELATION_X_METHODS, TWIN_CORRELATION_Y_METHODS, TWIN_HURST_BANDS,
        TWIN_MEASURED_BANDS, TWIN_WARNINGS,
    };

    /// Lists of numbers in SI units, the unit in the column name (`List(Float64)`:
    /// `nominal_pressures_Pa`, `loads_N`).
    pub const FLOATS: [&str; 2] = [super::metrics::NOMINAL_PRESSURES, super::metrics::LOADS];
    /// Lists of texts (`List(String)`): an instance's node names (`nodes`), a twin's warnings,
    /// per-file bands and correlation methods.
    pub const TEXTS: [&str; 6] = [
        crate::engine::columns::NODES,
        TWIN_WARNINGS,
        TWIN_HURST_BANDS,
        TWIN_MEASURED_BANDS,
        TWIN_CORRELATION_X_METHODS,
        TWIN_CORRELATION_Y_METHODS,
    ];
    /// Columns of sentences for a reader, which may hold commas and semicolons: the reason a row
    /// is flagged or failed (its sentences joined by "; ") and a step's, the lateral-scale
    /// warning. Every other text column holds a name, a key or a label.
    pub const PROSE: [&str; 3] = [
        crate::engine::columns::MESSAGE,
        super::curve_columns::STEP_MESSAGE,
        super::surface_metrics::LATERAL_SCALE_WARNING,
    ];
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
