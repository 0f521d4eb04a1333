//! Physical quantities at the boundary: "1.19 um", "20 MPa", "0.5 N/m", "210 GPa" → SI numbers.
//!
//! Everything inside asperity is SI. Study files may write a quantity either as a plain number
//! (taken as SI) or as a string `"<number> <unit>"`; the unit's dimension is checked against what
//! the field expects, so a pressure where a length is expected is an error, not a silent number.
//! Angles are the one exception to plain numbers being SI ([`plain_number_as`]): an angle needs
//! its unit, except 0.

mod quantity;

pub use quantity::{
    plain_number_rule, Angle, Area, DimensionMarker, Force, Length, Pressure, Quantity,
    SurfaceEnergy,
};

/// The physical dimension of a quantity.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "snake_case")]
pub enum Dimension {
    Dimensionless,
    Length,
    Area,
    Pressure,
    Force,
    SurfaceEnergy,
    Angle,
    /// Per unit area (m⁻²): summit densities, fourth spectral moments.
    InverseArea,
}

impl Dimension {
    /// Lower-case name used in messages ("a length"), node keys and cache summaries.
    pub fn name(self) -> &'static str {
        match self {
            Dimension::Dimensionless => "dimensionless number",
            Dimension::Length => "length",
            Dimension::Area => "area",
            Dimension::Pressure => "pressure",
            Dimension::Force => "force",
            Dimension::SurfaceEnergy => "surface energy",
            Dimension::Angle => "angle",
            Dimension::InverseArea => "inverse area",
        }
    }

    /// Every dimension.
    pub const ALL: [Dimension; 8] = [
        Dimension::Dimensionless,
        Dimension::Length,
        Dimension::Area,
        Dimension::Pressure,
        Dimension::Force,
        Dimension::SurfaceEnergy,
        Dimension::Angle,
        Dimension::InverseArea,
    ];

    /// The dimension whose name (as [`Dimension::name`] writes it) has the bytes `name`.
    pub fn from_name(name: &[u8]) -> Option<Self> {
        Self::ALL.into_iter().find(|d| d.name().as_bytes() == name)
    }

    /// The SI unit symbol written in messages and in the tables' unit metadata ("m", "m^2",
    /// "N/m", …); empty when dimensionless. Column names use [`Dimension::column_suffix`].
    pub fn si_symbol(self) -> &'static str {
        match self {
            Dimension::Dimensionless => "",
            Dimension::Length => "m",
            Dimension::Area => "m^2",
            Dimension::Pressure => "Pa",
            Dimension::Force => "N",
            Dimension::SurfaceEnergy => "N/m",
            Dimension::Angle => "rad",
            Dimension::InverseArea => "m^-2",
        }
    }

    /// The unit as a column name ends: `<name>_<suffix>` (`sq_m`, `real_area_m2`,
    /// `summit_density_per_m2`, `adhesion_energy_N_per_m`); empty when dimensionless. Letters,
    /// digits and `_` only, so every column is a Python identifier (pandas `.query`, attribute
    /// access) and the unit is still read off the name: `per_` divides, a digit is a power.
    pub fn column_suffix(self) -> &'static str {
        match self {
            Dimension::Dimensionless => "",
            Dimension::Length => "m",
            Dimension::Area => "m2",
            Dimension::Pressure => "Pa",
            Dimension::Force => "N",
            Dimension::SurfaceEnergy => "N_per_m",
            Dimension::Angle => "rad",
            Dimension::InverseArea => "per_m2",
        }
    }

    /// An example value for messages.
    pub fn example(self) -> &'static str {
        match self {
            Dimension::Dimensionless => "0.8",
            Dimension::Length => "1.19 um",
            Dimension::Area => "1 mm^2",
            Dimension::Pressure => "20 MPa",
            Dimension::Force => "10 N",
            Dimension::SurfaceEnergy => "0.5 N/m",
            Dimension::Angle => "30 deg",
            Dimension::InverseArea => "1e9 1/m^2",
        }
    }

    /// Units accepted for this dimension, for messages.
    pub fn accepted_units(self) -> String {
        UNITS
            .iter()
            .filter(|u| u.dimension == self)
            .map(|u| u.symbol)
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// A unit: SI value = number × 10^pow10 × factor. Decimal prefixes are applied to the decimal
/// exponent before the text is converted to binary, so "1.19 um", "1190 nm" and "1.19e-6" give
/// bit-identical SI values (and therefore identical node keys).
struct Unit {
    symbol: &'static str,
    dimension: Dimension,
    pow10: i32,
    factor: f64,
}

const fn unit(symbol: &'static str, dimension: Dimension, pow10: i32) -> Unit {
    Unit {
        symbol,
        dimension,
        pow10,
        factor: 1.0,
    }
}

const DEG: Unit = Unit {
    symbol: "deg",
    dimension: Dimension::Angle,
    pow10: 0,
    factor: std::f64::consts::PI / 180.0,
};
const DEG_SIGN: Unit = Unit {
    symbol: "°", ..DEG
};

/// Recognised unit symbols and their factor to SI. `u`, `µ` (micro sign) and `μ` (Greek mu) are
/// all accepted for micro.
const UNITS: &[Unit] = &[
    unit("m", Dimension::Length, 0),
    unit("cm", Dimension::Length, -2),
    unit("mm", Dimension::Length, -3),
    unit("um", Dimension::Length, -6),
    unit("µm", Dimension::Length, -6),
    unit("μm", Dimension::Length, -6),
    unit("nm", Dimension::Length, -9),
    unit("pm", Dimension::Length, -12),
    unit("m^2", Dimension::Area, 0),
    unit("m2", Dimension::Area, 0),
    unit("mm^2", Dimension::Area, -6),
    unit("mm2", Dimension::Area, -6),
    unit("um^2", Dimension::Area, -12),
    unit("um2", Dimension::Area, -12),
    unit("µm^2", Dimension::Area, -12),
    unit("Pa", Dimension::Pressure, 0),
    unit("kPa", Dimension::Pressure, 3),
    unit("MPa", Dimension::Pressure, 6),
    unit("GPa", Dimension::Pressure, 9),
    unit("N/mm^2", Dimension::Pressure, 6),
    unit("N/mm2", Dimension::Pressure, 6),
    unit("N/m^2", Dimension::Pressure, 0),
    unit("N", Dimension::Force, 0),
    unit("kN", Dimension::Force, 3),
    unit("mN", Dimension::Force, -3),
    unit("uN", Dimension::Force, -6),
    unit("µN", Dimension::Force, -6),
    unit("N/m", Dimension::SurfaceEnergy, 0),
    unit("mN/m", Dimension::SurfaceEnergy, -3),
    unit("J/m^2", Dimension::SurfaceEnergy, 0),
    unit("J/m2", Dimension::SurfaceEnergy, 0),
    unit("mJ/m^2", Dimension::SurfaceEnergy, -3),
    unit("mJ/m2", Dimension::SurfaceEnergy, -3),
    unit("rad", Dimension::Angle, 0),
    DEG,
    DEG_SIGN,
    unit("1/m^2", Dimension::InverseArea, 0),
    unit("1/mm^2", Dimension::InverseArea, 6),
    unit("1/um^2", Dimension::InverseArea, 12),
];

/// A value in SI units with its dimension.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DimensionedValue {
    pub si: f64,
    pub dimension: Dimension,
}

/// Why a quantity string could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitError {
    #[error("'{text}' is not a quantity: expected '<number> <unit>', e.g. '1.19 um'")]
    NotAQuantity { text: String },
    #[error("unknown unit '{unit}' in '{text}'{hint}")]
    UnknownUnit {
        text: String,
        unit: String,
        hint: String,
    },
    #[error("'{text}' is not finite")]
    NotFinite { text: String },
    #[error("{text} {}", angle_without_unit(text))]
    AngleWithoutUnit { text: String },
    #[error(
        "expected a {expected} such as '{example}' (units: {units}), got '{text}', which is a {found}",
        expected = expected.name(), example = expected.example(),
        units = expected.accepted_units(), found = found.name()
    )]
    WrongDimension {
        text: String,
        expected: Dimension,
        found: Dimension,
    },
}

/// Parses `"<number> [unit]"`. A bare number is dimensionless here; callers that accept plain SI
/// numbers for a dimensioned field use [`parse_quantity_as`].
pub fn parse_quantity(text: &str) -> Result<DimensionedValue, UnitError> {
    let trimmed = text.trim();
    let split = number_prefix_len(trimmed);
    if split == 0 {
        return Err(UnitError::NotAQuantity {
            text: text.to_string(),
        });
    }
    let (num, unit_text) = trimmed.split_at(split);
    let not_a_quantity = || UnitError::NotAQuantity {
        text: text.to_string(),
    };
    let finite = |v: f64| {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(UnitError::NotFinite {
                text: text.to_string(),
            })
        }
    };
    let unit_text = unit_text.trim();
    if unit_text.is_empty() {
        return Ok(DimensionedValue {
            si: finite(num.parse().map_err(|_| not_a_quantity())?)?,
            dimension: Dimension::Dimensionless,
        });
    }
    let unit = UNITS
        .iter()
        .find(|u| u.symbol == unit_text)
        .ok_or_else(|| UnitError::UnknownUnit {
            text: text.to_string(),
            unit: unit_text.to_string(),
            hint: unit_hint(unit_text),
        })?;
    let (mantissa, exponent) = match num.find(['e', 'E']) {
        Some(i) => (
            &num[..i],
            num[i + 1..].parse::<i32>().map_err(|_| not_a_quantity())?,
        ),
        None => (num, 0),
    };
    let scaled: f64 = format!("{mantissa}e{}", exponent.saturating_add(unit.pow10))
        .parse()
        .map_err(|_| not_a_quantity())?;
    Ok(DimensionedValue {
        si: finite(scaled * unit.factor)?,
        dimension: unit.dimension,
    })
}

/// Parses a quantity that must have dimension `expected`; a bare number follows
/// [`plain_number_as`].
pub fn parse_quantity_as(text: &str, expected: Dimension) -> Result<f64, UnitError> {
    let v = parse_quantity(text)?;
    if v.dimension == Dimension::Dimensionless {
        plain_number_as(v.si, expected)
    } else if v.dimension == expected {
        Ok(v.si)
    } else {
        Err(UnitError::WrongDimension {
            text: text.to_string(),
            expected,
            found: v.dimension,
        })
    }
}

/// The one rule for a plain number (no unit) written where a quantity of dimension `expected`
/// belongs: it is the value in SI units, except for an angle, which needs its unit (`rad`,
/// `deg`, `°`): a plain angle other than 0 (the same in every unit) is refused. Engineers write
/// angles in degrees as often as in radians, and a guessed unit would turn `90` into a valid but
/// different direction (90 rad ≈ 116.6°) without a word.
pub fn plain_number_as(value: f64, expected: Dimension) -> Result<f64, UnitError> {
    if expected == Dimension::Angle && value != 0.0 {
        Err(UnitError::AngleWithoutUnit {
            text: format_number(value),
        })
    } else {
        Ok(value)
    }
}

/// What is said of the plain number `text` written as an angle, after the value: "is an angle
/// without its unit: write '90 deg' or '90 rad' (…)".
pub fn angle_without_unit(text: &str) -> String {
    format!(
        "is an angle without its unit: write '{text} deg' or '{text} rad' (angles are written in \
         degrees as often as in radians, so a plain number other than 0 is refused rather than \
         guessed)"
    )
}

/// Formats an SI value with its unit for messages and metadata ("1.19e-6 m").
pub fn format_si(value: f64, dimension: Dimension) -> String {
    match dimension.si_symbol() {
        "" => format_number(value),
        s => format!("{} {s}", format_number(value)),
    }
}

/// Shortest round-trip form, in scientific notation outside [1e-4, 1e6) ("2e7", "0.5", "1.19e-6").
pub fn format_number(value: f64) -> String {
    let magnitude = value.abs();
    if value != 0.0 && !(1e-4..1e6).contains(&magnitude) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

fn number_prefix_len(s: &str) -> usize {
    let bytes = s.as_bytes();
    let mut end = 0;
    let mut i = 0;
    let mut seen_digit = false;
    if i < bytes.len() && (bytes[i] == b'+' || bytes[i] == b'-') {
        i += 1;
    }
    while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
        seen_digit |= bytes[i].is_ascii_digit();
        i += 1;
        end = i;
    }
    if !seen_digit {
        return 0;
    }
    if i < bytes.len() && (bytes[i] == b'e' || bytes[i] == b'E') {
        let mut j = i + 1;
        if j < bytes.len() && (bytes[j] == b'+' || bytes[j] == b'-') {
            j += 1;
        }
        let digits_start = j;
        while j < bytes.len() && bytes[j].is_ascii_digit() {
            j += 1;
        }
        if j > digits_start {
            end = j;
        }
    }
    end
}

fn unit_hint(unit: &str) -> String {
    let lower = unit.to_ascii_lowercase();
    match UNITS
        .iter()
        .find(|u| u.symbol.to_ascii_lowercase() == lower)
    {
        Some(u) => format!(" (did you mean '{}'? units are case-sensitive)", u.symbol),
        None => String::from(" (known units: m, mm, um, nm, Pa, MPa, GPa, N, N/m, deg, …)"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dimension_is_found_by_its_name() {
        for d in Dimension::ALL {
            assert_eq!(Dimension::from_name(d.name().as_bytes()), Some(d));
        }
        assert_eq!(Dimension::from_name(b"volume"), None);
    }

    #[test]
    fn parses_units_to_si() {
        let v = parse_quantity("1.19 um").unwrap();
        assert_eq!(v.dimension, Dimension::Length);
        assert!((v.si - 1.19e-6).abs() < 1e-21);
        assert_eq!(parse_quantity("20MPa").unwrap().si, 20e6);
        assert_eq!(
            parse_quantity("0.5 N/m").unwrap().dimension,
            Dimension::SurfaceEnergy
        );
        assert_eq!(parse_quantity("210 GPa").unwrap().si, 210e9);
        assert_eq!(parse_quantity("1e-3 m").unwrap().si, 1e-3);
        assert_eq!(parse_quantity("-2.5e2").unwrap().si, -250.0);
        assert_eq!(parse_quantity("3 µm").unwrap().si, 3e-6);
        assert_eq!(parse_quantity("1.2e3 nm").unwrap().si, 1.2e-6);
        assert!((parse_quantity("90 deg").unwrap().si - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn equal_values_in_different_units_are_bit_identical() {
        let si = |t: &str| parse_quantity(t).unwrap().si.to_bits();
        assert_eq!(si("1.19 um"), si("1190 nm"));
        assert_eq!(si("1.19 um"), 1.19e-6f64.to_bits());
        assert_eq!(si("0.5 mm"), si("500 um"));
        assert_eq!(si("20 MPa"), si("0.02 GPa"));
        assert_eq!(si("210 GPa"), 210e9f64.to_bits());
    }

    #[test]
    fn rejects_wrong_dimension_and_unknown_units() {
        let err = parse_quantity_as("20 MPa", Dimension::Length).unwrap_err();
        assert!(err.to_string().contains("expected a length"), "{err}");
        assert!(err.to_string().contains("which is a pressure"), "{err}");
        let err = parse_quantity("3 mpa").unwrap_err();
        assert!(err.to_string().contains("did you mean 'MPa'"), "{err}");
        assert!(matches!(
            parse_quantity("abc"),
            Err(UnitError::NotAQuantity { .. })
        ));
        assert!(matches!(
            parse_quantity("1e400 m"),
            Err(UnitError::NotFinite { .. })
        ));
    }

    #[test]
    fn bare_numbers_are_si() {
        assert_eq!(parse_quantity_as("2e-6", Dimension::Length).unwrap(), 2e-6);
    }

    #[test]
    fn a_plain_angle_needs_its_unit_unless_it_is_zero() {
        assert_eq!(plain_number_as(0.0, Dimension::Angle), Ok(0.0));
        assert_eq!(plain_number_as(-0.0, Dimension::Angle), Ok(0.0));
        assert_eq!(plain_number_as(6.5, Dimension::Length), Ok(6.5));
        let err = plain_number_as(6.5, Dimension::Angle).unwrap_err();
        assert_eq!(
            err,
            UnitError::AngleWithoutUnit {
                text: String::from("6.5")
            }
        );
        let text = err.to_string();
        assert!(
            text.contains("'6.5 deg'") && text.contains("'6.5 rad'"),
            "{text}"
        );
        assert!(parse_quantity_as("90", Dimension::Angle).is_err());
        assert_eq!(parse_quantity_as("0", Dimension::Angle), Ok(0.0));
        let turn = parse_quantity_as("6.5 rad", Dimension::Angle).unwrap();
        assert_eq!(turn, 6.5);
        let full = parse_quantity_as("360 deg", Dimension::Angle).unwrap();
        assert_eq!(full, parse_quantity_as("360 °", Dimension::Angle).unwrap());
        assert!((full - std::f64::consts::TAU).abs() < 1e-15);
    }

    #[test]
    fn a_plain_angle_is_refused_in_a_quantity_field() {
        let parse = |yaml: &str| serde_saphyr::from_str::<Quantity<Angle>>(yaml);
        assert_eq!(parse("0").unwrap().si(), 0.0);
        assert_eq!(parse("\"90 deg\"").unwrap().si(), 90f64.to_radians());
        for plain in ["6.2832", "90", "1"] {
            let message = parse(plain).unwrap_err().to_string();
            assert!(message.contains("without its unit"), "{plain}: {message}");
        }
        let length = serde_saphyr::from_str::<Quantity<Length>>("1e-6").unwrap();
        assert_eq!(length.si(), 1e-6);
    }
}
