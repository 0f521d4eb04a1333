//! Whether a table column or a key of a Python result speaks the one vocabulary (#41): its name
//! without the unit suffix is a name of `src/vocabulary.rs` ([`crate::vocabulary::all`]), of
//! the engine's own columns or a friction law's parameter column, or one of those composed the
//! documented ways (a body's side before it, an axis after it, a list prefix, a role's key).

use std::collections::BTreeSet;

use crate::engine::columns;
use crate::engine::value::column_name;
use crate::friction::laws::LAWS;
use crate::units::Dimension;
use crate::vocabulary::surface_metrics::{X_SUFFIX, Y_SUFFIX};
use crate::vocabulary::surface_parameters::twin_of_blake3;
use crate::vocabulary::twin_metrics::{twin_fit_r2, twin_fit_rms};
use crate::vocabulary::{all, list_columns, roles, spot_columns, summit_columns};

/// The engine's own columns.
const ENGINE: [&str; 12] = [
    columns::SCENARIO,
    columns::SCENARIOS,
    columns::KEY,
    columns::NODES,
    columns::NODE,
    columns::KIND,
    columns::KIND_VERSION,
    columns::STATUS,
    columns::MESSAGE,
    columns::STEP,
    columns::FROM_CACHE,
    columns::COMPUTE_SECONDS,
];

/// Most files a twin is made from that the check recognises (`twin_of_<i>_blake3`).
const MAX_TWIN_FILES: usize = 256;

/// The names a column is built from: the vocabulary's, the engine's and the laws' parameters'.
fn bases() -> BTreeSet<&'static str> {
    let laws = LAWS
        .iter()
        .flat_map(|l| l.parameters.iter().map(|p| p.column));
    all::names().into_iter().chain(ENGINE).chain(laws).collect()
}

/// Whether `column` is a name of the vocabulary with its unit suffix (`real_area_m2`), or one
/// composed from them: `lower_youngs_modulus_Pa`, `m0_x_m2`, `spot_area_m2`, `contact_key`,
/// `twin_of_0_blake3`, `twin_fit_r2_hurst`.
pub fn is_known_column(column: &str) -> bool {
    let bases = bases();
    let known = |name: &str| bases.contains(name);
    let unit_free = Dimension::ALL
        .iter()
        .filter_map(|d| column.strip_suffix(d.column_suffix())?.strip_suffix('_'))
        .chain([column]);
    unit_free.into_iter().any(|name| {
        let sided = [roles::LOWER, roles::UPPER]
            .iter()
            .filter_map(|side| name.strip_prefix(side)?.strip_prefix('_'));
        let listed = [spot_columns::LIST_PREFIX, summit_columns::LIST_PREFIX]
            .iter()
            .filter_map(|prefix| name.strip_prefix(prefix));
        let axis = [X_SUFFIX, Y_SUFFIX]
            .iter()
            .filter_map(|suffix| name.strip_suffix(suffix));
        let fitted = bases
            .iter()
            .any(|q| twin_fit_rms(q) == name || twin_fit_r2(q) == name);
        known(name)
            || sided.chain(listed).chain(axis).any(known)
            || name.strip_suffix(columns::KEY_SUFFIX).is_some_and(known)
            || fitted
            || (0..MAX_TWIN_FILES).any(|i| twin_of_blake3(i) == name)
    })
}

/// What a list column holds ([`crate::vocabulary::list_columns`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ListItems {
    /// Numbers in SI units (`List(Float64)`).
    Floats,
    /// Texts (`List(String)`).
    Texts,
}

impl ListItems {
    /// `"float"` or `"text"`.
    pub fn name(self) -> &'static str {
        match self {
            ListItems::Floats => "float",
            ListItems::Texts => "text",
        }
    }
}

/// What `column` (a table column or a Python result's key, with its unit suffix) holds when the
/// vocabulary declares it a list column: `nominal_pressures_Pa` floats, `twin_warnings` texts;
/// `None` for a column of one value per row.
pub fn list_column(column: &str) -> Option<ListItems> {
    let floats = list_columns::FLOATS.iter().any(|name| {
        Dimension::ALL
            .iter()
            .any(|d| column_name(name, *d) == column)
    });
    if floats {
        Some(ListItems::Floats)
    } else if list_columns::TEXTS.contains(&column) {
        Some(ListItems::Texts)
    } else {
        None
    }
}

/// Whether `column` holds sentences for a reader ([`crate::vocabulary::list_columns::PROSE`]),
/// which may hold commas and semicolons without being a list.
pub fn is_prose_column(column: &str) -> bool {
    list_columns::PROSE.contains(&column)
}

#[cfg(test)]
mod tests {
    use super::{is_known_column, list_column, ListItems};

    #[test]
    fn list_columns_are_known_with_their_items() {
        assert_eq!(list_column("nominal_pressures_Pa"), Some(ListItems::Floats));
        assert_eq!(list_column("loads_N"), Some(ListItems::Floats));
        assert_eq!(list_column("twin_warnings"), Some(ListItems::Texts));
        assert_eq!(list_column("nodes"), Some(ListItems::Texts));
        for scalar in ["nominal_pressure_Pa", "mu_s", "message"] {
            assert_eq!(list_column(scalar), None, "{scalar}");
        }
    }

    #[test]
    fn vocabulary_names_with_their_unit_pass_and_others_fail() {
        for known in [
            "mu_s",
            "real_area_m2",
            "gw_summit_density_per_m2",
            "adhesion_energy_N_per_m",
            "lower_youngs_modulus_Pa",
            "m4_x_per_m2",
            "spot_area_m2",
            "summit_friction_force_N",
            "contact_key",
            "twin_of_1_blake3",
            "twin_fit_r2_hurst",
            "shear_strength_Pa",
            "compute_seconds",
        ] {
            assert!(is_known_column(known), "{known}");
        }
        for unknown in [
            "real_area_m^2",
            "adhesion_energy_N/m",
            "total_friction_force_N",
            "load_beyond_fit_N",
            "mu_s_m2x",
        ] {
            assert!(!is_known_column(unknown), "{unknown}");
        }
    }
}
