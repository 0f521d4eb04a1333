//! How a study names a body's material: a built-in name (`s235jr`), a built-in name with
//! overrides (`{name: s235jr, youngs_modulus: 205 GPa}`) or explicit constants
//! (`{youngs_modulus: 210 GPa, poisson_ratio: 0.3, hardness: 2 GPa}`). Built-in values come from
//! [`crate::materials`]; names are case-insensitive and accept aliases (`1.0037`).
//!
//! The result is a checked [`BodyMaterial`]: bounds and default rules (Y = H/2.8, k = Y/√3,
//! p_lim = H) are those of [`crate::materials`].

use std::fmt;

use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

use crate::engine::study::FromParamValue;
use crate::engine::value::ParamValue;

use crate::engine::study::{
    did_you_mean, Located, Param, ResolveContext, SourceLocation, SpecError,
};
use crate::materials::{
    all_names, bounds, find_material, BodyConstants, BodyMaterial, MaterialError, UnknownMaterial,
};
use crate::units::{format_number, Pressure, Quantity};

/// A body's material: `s235jr`, `{name: s235jr, hardness: 2.2 GPa}` or
/// `{youngs_modulus: 210 GPa, poisson_ratio: 0.3}`.
#[derive(Debug)]
pub struct MaterialSpec {
    location: SourceLocation,
    source: MaterialSource,
}

#[derive(Debug)]
enum MaterialSource {
    Named(NameSource),
    Mapping(Box<MaterialMapping>),
}

/// The mapping form of a material: a built-in `name` with overrides, or explicit constants.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialMapping {
    /// Built-in material (case-insensitive name or alias) whose values the other fields override.
    #[serde(default)]
    pub name: Option<NameSpec>,
    /// Young's modulus (or indentation modulus E_IT), pressure > 0; required without `name`.
    #[serde(default)]
    pub youngs_modulus: Option<Param<Quantity<Pressure>>>,
    /// Poisson's ratio in [0, 0.5]; required without `name`.
    #[serde(default)]
    pub poisson_ratio: Option<Param<f64>>,
    /// Hardness H (pressure > 0, below E), e.g. ultra-micro-hardness of the near-surface material.
    #[serde(default)]
    pub hardness: Option<Param<Quantity<Pressure>>>,
    /// Plastic flow pressure p_lim (pressure > 0, below E); omitted: p_lim = H.
    #[serde(default)]
    pub flow_pressure: Option<Param<Quantity<Pressure>>>,
    /// Yield strength Y (pressure > 0, at most H) used by the full-stick and Jackson–Green laws;
    /// omitted: Tabor's rule Y = H/2.8.
    #[serde(default)]
    pub yield_strength: Option<Param<Quantity<Pressure>>>,
    /// Shear strength k (pressure > 0, at most Y) of the material, the junction-shear strength of
    /// a clean interface; omitted: von Mises k = Y/√3.
    #[serde(default)]
    pub shear_strength: Option<Param<Quantity<Pressure>>>,
}

impl<'de> Deserialize<'de> for MaterialSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let located = Located::<MaterialSource>::deserialize(deserializer)?;
        Ok(Self {
            location: located.location,
            source: located.value,
        })
    }
}

struct MaterialVisitor;

impl<'de> Visitor<'de> for MaterialVisitor {
    type Value = MaterialSource;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a material name such as 's235jr' or a mapping {name, youngs_modulus, poisson_ratio, hardness, flow_pressure, yield_strength, shear_strength}")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
        NameVisitor.visit_str(v).map(MaterialSource::Named)
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
        NameVisitor.visit_f64(v).map(MaterialSource::Named)
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
        NameVisitor.visit_i64(v).map(MaterialSource::Named)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
        NameVisitor.visit_u64(v).map(MaterialSource::Named)
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
        MaterialMapping::deserialize(de::value::MapAccessDeserializer::new(map))
            .map(|m| MaterialSource::Mapping(Box::new(m)))
    }
}

/// A material name: written literally (`s235jr`, `17-4ph`, `1.0037`) or a `${param}` reference.
#[derive(Debug)]
pub struct NameSpec {
    location: SourceLocation,
    source: NameSource,
}

#[derive(Debug)]
enum NameSource {
    /// As written; never parsed as a quantity (`17-4ph` is not 17 with a unit).
    Literal(String),
    /// A study parameter holding the name.
    Reference(Param<MaterialName>),
}

struct NameVisitor;

impl<'de> Visitor<'de> for NameVisitor {
    type Value = NameSource;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a material name such as 's235jr'")
    }

    /// A name holding a `${param}` reference (whole, or inside: `s${grade}jr`) becomes a
    /// `Param<MaterialName>` by reading it back as a YAML scalar (a JSON string is valid YAML);
    /// anything else is the literal name.
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
        if v.contains("${") {
            let scalar = serde_json::to_string(v).map_err(E::custom)?;
            serde_saphyr::from_str::<Param<MaterialName>>(&scalar)
                .map(NameSource::Reference)
                .map_err(E::custom)
        } else {
            Ok(NameSource::Literal(v.to_string()))
        }
    }

    /// A material number written unquoted (`1.0037`), as its shortest decimal text.
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
        Ok(NameSource::Literal(v.to_string()))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
        Ok(NameSource::Literal(v.to_string()))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
        Ok(NameSource::Literal(v.to_string()))
    }
}

impl<'de> Deserialize<'de> for NameSource {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(NameVisitor)
    }
}

impl<'de> Deserialize<'de> for NameSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let located = Located::<NameSource>::deserialize(deserializer)?;
        Ok(Self {
            location: located.location,
            source: located.value,
        })
    }
}

impl schemars::JsonSchema for NameSpec {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "MaterialName".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let names = all_names().collect::<Vec<_>>().join(", ");
        schemars::json_schema!({
            "type": ["string", "number"],
            "description": format!("A built-in material (case-insensitive): {names}; or a reference '${{param}}'.")
        })
    }
}

/// The value of a material-name parameter: text, or a number such as `1.0037` read as its
/// shortest decimal text (so numbers ending in 0 must be quoted). In parameter axes a value
/// starting with a digit and followed by letters (`17-4ph`) is read as a quantity: use a
/// letter-first alias there (`aisi630`).
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialName(pub String);

impl FromParamValue for MaterialName {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::Text(s) => Ok(Self(s.clone())),
            ParamValue::Number(x) => Ok(Self(x.to_string())),
            ParamValue::Int(i) => Ok(Self(i.to_string())),
            other => Err(format!(
                "expected a material name, got {other} ({})",
                other.type_name()
            )),
        }
    }
}

impl<'de> Deserialize<'de> for MaterialSource {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(MaterialVisitor)
    }
}

impl schemars::JsonSchema for MaterialSpec {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "MaterialSpec".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let mapping = generator.subschema_for::<MaterialMapping>();
        let name = generator.subschema_for::<NameSpec>();
        schemars::json_schema!({
            "description": "A body's material: a built-in name, a built-in name with overrides, or explicit constants.",
            "anyOf": [name, mapping]
        })
    }
}

/// A study check from a material bound ([`bounds`]).
fn within(
    bound: impl Fn(f64) -> Result<f64, MaterialError>,
) -> impl Fn(&f64) -> Result<(), String> {
    move |v| bound(*v).map(|_| ()).map_err(|e| e.range_message())
}

/// A pressure check from a material bound.
fn pressure_within(
    bound: impl Fn(f64) -> Result<f64, MaterialError>,
) -> impl Fn(&Quantity<Pressure>) -> Result<(), String> {
    move |q| bound(q.si()).map(|_| ()).map_err(|e| e.range_message())
}

impl MaterialSpec {
    /// Where the material is written.
    pub fn location(&self) -> SourceLocation {
        self.location
    }

    fn lookup(
        &self,
        ctx: &ResolveContext<'_>,
        name: &NameSource,
        location: SourceLocation,
        field: &str,
    ) -> Result<&'static crate::materials::BuiltinMaterial, SpecError> {
        let text = match name {
            NameSource::Literal(text) => text.clone(),
            NameSource::Reference(p) => {
                ctx.resolve(p, field)
                    .map_err(|e| SpecError { location, ..e })?
                    .0
            }
        };
        find_material(&text).map_err(|UnknownMaterial { name: wanted }| SpecError {
            location,
            field: field.to_string(),
            message: format!(
                "unknown material '{wanted}'{}; built-in materials: {} (or give explicit `{{youngs_modulus, poisson_ratio, hardness}}`)",
                did_you_mean(&wanted.trim().to_lowercase(), all_names()),
                crate::materials::known_names().join(", ")
            ),
        })
    }

    /// Resolves the material under one scenario into a checked [`BodyMaterial`]: the given
    /// values over the built-in ones, each checked by its bound ([`bounds`]) where it is written,
    /// the relations between them (H below E, Y at most H, k at most Y) at the material; `field`
    /// names it in messages (`lower_material`).
    pub fn resolve(
        &self,
        ctx: &ResolveContext<'_>,
        field: &str,
    ) -> Result<BodyMaterial, SpecError> {
        let constants = match &self.source {
            MaterialSource::Named(name) => self.lookup(ctx, name, self.location, field)?.constants,
            MaterialSource::Mapping(m) => self.constants(m, ctx, field)?,
        };
        BodyMaterial::new(constants).map_err(|e| SpecError {
            location: self.location,
            field: format!("{field}.{}", e.parameter()),
            message: format!("{} {}", format_number(e.value()), e.range_message()),
        })
    }

    /// The constants of the mapping form: its values over those of its built-in `name`.
    fn constants(
        &self,
        m: &MaterialMapping,
        ctx: &ResolveContext<'_>,
        field: &str,
    ) -> Result<BodyConstants, SpecError> {
        let base = match &m.name {
            Some(name) => Some(
                self.lookup(ctx, &name.source, name.location, &format!("{field}.name"))?
                    .constants,
            ),
            None => None,
        };
        let strength = |p: &Option<Param<Quantity<Pressure>>>, sub: &'static str| {
            p.as_ref()
                .map(|p| {
                    let check = pressure_within(|v| bounds::strength(sub, v));
                    ctx.resolve_checked(p, &format!("{field}.{sub}"), check)
                        .map(|q| q.si())
                })
                .transpose()
        };
        let missing = |sub: &str| {
            SpecError {
            location: self.location,
            field: format!("{field}.{sub}"),
            message: format!(
                "is required without a built-in `name` (e.g. `{field}: {{youngs_modulus: 210 GPa, poisson_ratio: 0.3}}` or `{field}: s235jr`)"
            ),
        }
        };
        let youngs_modulus = match (&m.youngs_modulus, base) {
            (Some(p), _) => {
                let check = pressure_within(bounds::youngs_modulus);
                ctx.resolve_checked(p, &format!("{field}.youngs_modulus"), check)?
                    .si()
            }
            (None, Some(b)) => b.youngs_modulus,
            (None, None) => return Err(missing("youngs_modulus")),
        };
        let poisson_ratio = match (&m.poisson_ratio, base) {
            (Some(p), _) => {
                let check = within(bounds::poisson_ratio);
                ctx.resolve_checked(p, &format!("{field}.poisson_ratio"), check)?
            }
            (None, Some(b)) => b.poisson_ratio,
            (None, None) => return Err(missing("poisson_ratio")),
        };
        let base = |pick: fn(&BodyConstants) -> Option<f64>| base.as_ref().and_then(pick);
        Ok(BodyConstants {
            youngs_modulus,
            poisson_ratio,
            hardness: strength(&m.hardness, "hardness")?.or(base(|b| b.hardness)),
            yield_strength: strength(&m.yield_strength, "yield_strength")?
                .or(base(|b| b.yield_strength)),
            shear_strength: strength(&m.shear_strength, "shear_strength")?
                .or(base(|b| b.shear_strength)),
            flow_pressure: strength(&m.flow_pressure, "flow_pressure")?
                .or(base(|b| b.flow_pressure)),
        })
    }
}
