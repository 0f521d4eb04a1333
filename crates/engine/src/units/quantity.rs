//! `Quantity<D>`: a study field of a dimension known at compile time, read from a plain number
//! ([`super::plain_number_as`]) or a string with its unit.

use std::fmt;
use std::marker::PhantomData;

use super::{format_si, parse_quantity_as, plain_number_as, Dimension};

/// A marker for a dimension known at compile time, used by [`Quantity`].
pub trait DimensionMarker: Send + Sync + 'static {
    const DIMENSION: Dimension;
}

macro_rules! dimension_marker {
    ($name:ident, $dim:expr) => {
        #[doc = concat!("Marker type for the dimension `", stringify!($dim), "`.")]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub struct $name;
        impl DimensionMarker for $name {
            const DIMENSION: Dimension = $dim;
        }
    };
}

dimension_marker!(Length, Dimension::Length);
dimension_marker!(Area, Dimension::Area);
dimension_marker!(Pressure, Dimension::Pressure);
dimension_marker!(Force, Dimension::Force);
dimension_marker!(SurfaceEnergy, Dimension::SurfaceEnergy);
dimension_marker!(Angle, Dimension::Angle);

/// An SI value of the dimension `D`, parsed from a plain number (SI) or a string with units.
pub struct Quantity<D> {
    si: f64,
    _dimension: PhantomData<D>,
}

impl<D: DimensionMarker> Quantity<D> {
    /// A quantity from an SI value.
    pub fn from_si(si: f64) -> Self {
        Self {
            si,
            _dimension: PhantomData,
        }
    }

    /// The value in SI units.
    pub fn si(&self) -> f64 {
        self.si
    }
}

impl<D> Clone for Quantity<D> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<D> Copy for Quantity<D> {}

impl<D> PartialEq for Quantity<D> {
    fn eq(&self, other: &Self) -> bool {
        self.si == other.si
    }
}

impl<D: DimensionMarker> fmt::Debug for Quantity<D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&format_si(self.si, D::DIMENSION))
    }
}

impl<'de, D: DimensionMarker> serde::Deserialize<'de> for Quantity<D> {
    fn deserialize<De: serde::Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
        struct QuantityVisitor<D>(PhantomData<D>);
        impl<D: DimensionMarker> serde::de::Visitor<'_> for QuantityVisitor<D> {
            type Value = Quantity<D>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(&plain_number_rule(D::DIMENSION))
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Self::Value, E> {
                if v.is_finite() {
                    plain_number_as(v, D::DIMENSION)
                        .map(Quantity::from_si)
                        .map_err(E::custom)
                } else {
                    Err(E::custom(format!(
                        "{v} is not a finite {}",
                        D::DIMENSION.name()
                    )))
                }
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Self::Value, E> {
                self.visit_f64(v as f64)
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Self::Value, E> {
                self.visit_f64(v as f64)
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Self::Value, E> {
                parse_quantity_as(v, D::DIMENSION)
                    .map(Quantity::from_si)
                    .map_err(E::custom)
            }
        }
        deserializer.deserialize_any(QuantityVisitor(PhantomData))
    }
}

impl<D: DimensionMarker> schemars::JsonSchema for Quantity<D> {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        format!("{:?}Quantity", D::DIMENSION).into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let mut description = plain_number_rule(D::DIMENSION);
        if let Some(first) = description.get_mut(..1) {
            first.make_ascii_uppercase();
        }
        description = format!("{description} (units: {}).", D::DIMENSION.accepted_units());
        let plain = if D::DIMENSION == Dimension::Angle {
            schemars::json_schema!({"const": 0})
        } else {
            schemars::json_schema!({"type": "number"})
        };
        schemars::json_schema!({
            "description": description,
            "anyOf": [
                plain,
                {"type": "string", "pattern": r"^\s*[-+]?[0-9.]+([eE][-+]?[0-9]+)?\s*\S*\s*$"}
            ]
        })
    }
}

/// How a quantity of `dimension` is written, for messages and the schema: "a length as a plain
/// number in SI (m) or a string with units such as '1.19 um'"; for an angle, the unit is required
/// ([`plain_number_as`]).
pub fn plain_number_rule(dimension: Dimension) -> String {
    let name = dimension.name();
    let article = if name.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    };
    if dimension == Dimension::Angle {
        format!(
            "{article} {name} with its unit such as '{}'; a plain number other than 0 is refused",
            dimension.example()
        )
    } else {
        format!(
            "{article} {name} as a plain number in SI ({}) or a string with units such as '{}'",
            dimension.si_symbol(),
            dimension.example()
        )
    }
}
