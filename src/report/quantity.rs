//! How quantities are shown: SI values from the tables are scaled to readable units (µm, mm,
//! MPa, …) and columns get readable names with the tribology symbols (A_t,rel, θ, μ_s).

use crate::units::Dimension;
use crate::vocabulary::metrics;

/// A display unit: multiply an SI value by `factor` to get it in `symbol`.
#[derive(Debug, Clone, PartialEq)]
pub struct DisplayUnit {
    pub factor: f64,
    pub symbol: String,
}

impl DisplayUnit {
    fn new(factor: f64, symbol: &str) -> Self {
        Self {
            factor,
            symbol: symbol.to_string(),
        }
    }

    /// A unit-less display unit.
    pub fn none() -> Self {
        Self::new(1.0, "")
    }

    /// The readable unit for values of SI unit `si` whose largest magnitude is `max_abs`
    /// (lengths in µm below 1 mm, pressures in MPa below 1 GPa, angles in degrees, …).
    pub fn for_values(si: &str, max_abs: f64) -> Self {
        match si {
            "m" if max_abs < 1e-3 => Self::new(1e6, "µm"),
            "m" if max_abs < 1.0 => Self::new(1e3, "mm"),
            "m^2" if max_abs < 1e-6 => Self::new(1e12, "µm²"),
            "m^2" if max_abs < 1.0 => Self::new(1e6, "mm²"),
            "Pa" if max_abs >= 1e9 => Self::new(1e-9, "GPa"),
            "Pa" if max_abs >= 1e5 || max_abs == 0.0 => Self::new(1e-6, "MPa"),
            "Pa" if max_abs >= 1e2 => Self::new(1e-3, "kPa"),
            "N" if max_abs != 0.0 && max_abs < 1e-3 => Self::new(1e6, "µN"),
            "N" if max_abs != 0.0 && max_abs < 1.0 => Self::new(1e3, "mN"),
            "rad" => Self::new(180.0 / std::f64::consts::PI, "°"),
            "" => Self::none(),
            other => Self::new(1.0, other),
        }
    }

    /// The unit for a set of SI values.
    pub fn for_slice(si: &str, values: impl IntoIterator<Item = f64>) -> Self {
        let max_abs = values
            .into_iter()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        Self::for_values(si, max_abs)
    }

    /// `label (unit)`, or just `label` when dimensionless.
    pub fn axis_label(&self, label: &str) -> String {
        if self.symbol.is_empty() {
            label.to_string()
        } else {
            format!("{label} ({})", self.symbol)
        }
    }

    /// `value unit` with four significant digits.
    pub fn format(&self, si_value: f64) -> String {
        let text = super::axis::format_number(si_value * self.factor);
        match self.symbol.as_str() {
            "" => text,
            "°" => format!("{text}°"),
            s => format!("{text} {s}"),
        }
    }
}

/// The column name without its unit suffix (`sq_m` → `sq`, `nominal_pressure_Pa` →
/// `nominal_pressure`).
pub fn base_name<'a>(column: &'a str, unit: &str) -> &'a str {
    // The unit metadata holds the SI symbol (`m^2`); the name ends in its column suffix (`m2`).
    let suffix: &str = match Dimension::ALL.into_iter().find(|d| d.si_symbol() == unit) {
        Some(dimension) => dimension.column_suffix(),
        None => unit,
    };
    if suffix.is_empty() {
        return column;
    }
    let base = column.len().saturating_sub(suffix.len() + 1);
    match column.split_at_checked(base) {
        Some((name, tail)) if tail.strip_prefix('_') == Some(suffix) => name,
        _ => column,
    }
}

/// A readable name for a column base name, with the symbol used in the literature where there
/// is one.
pub fn pretty_name(base: &str) -> String {
    match base {
        metrics::AREA_FRACTION => String::from("A_t,rel (true area fraction)"),
        metrics::STRESS_RATIO => String::from("θ (stress ratio)"),
        metrics::MU_S => String::from("μ_s (static friction coefficient)"),
        metrics::SQ => String::from("Sq"),
        metrics::HURST => String::from("Hurst exponent H"),
        metrics::NOMINAL_PRESSURE => String::from("nominal pressure"),
        metrics::MEAN_CONTACT_PRESSURE => String::from("mean contact pressure"),
        other => other.replace('_', " "),
    }
}

/// A short name for series labels (`Sq`, `seed`, `θ`).
pub fn short_name(base: &str) -> String {
    match base {
        metrics::AREA_FRACTION => String::from("A_t,rel"),
        metrics::STRESS_RATIO => String::from("θ"),
        metrics::MU_S => String::from("μ_s"),
        metrics::SQ => String::from("Sq"),
        metrics::HURST => String::from("H"),
        other => other.replace('_', " "),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_and_pressures_get_readable_units() {
        let u = DisplayUnit::for_values("m", 1.5e-6);
        assert_eq!(u.format(1.19e-6), "1.19 µm");
        let u = DisplayUnit::for_values("Pa", 2e7);
        assert_eq!(u.axis_label("nominal pressure"), "nominal pressure (MPa)");
        assert_eq!(base_name("nominal_pressure_Pa", "Pa"), "nominal_pressure");
        assert_eq!(base_name("seed", ""), "seed");
        assert_eq!(base_name("real_area_m2", "m^2"), "real_area");
        assert_eq!(
            base_name("adhesion_energy_N_per_m", "N/m"),
            "adhesion_energy"
        );
    }
}
