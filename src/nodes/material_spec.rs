//! How a study names a body's material: a built-in name (`s235jr`), a built-in name with
//! overrides (`{name: s235jr, youngs_modulus: 205 GPa}`) or explicit constants
//! (`{youngs_modulus: 210 GPa, poisson_ratio: 0.3, hardness: 2 GPa}`). Built-in values come from
//! [`crate::materials`]; names are case-insensitive and accept aliases (`1.0037`).
//!
//! Flow pressure rule: p_lim given explicitly wins; otherwise a built-in material's p_lim; otherwise
//! p_lim = H when a hardness is known (the rule of [`crate::materials`]); otherwise none.

use std::fmt;

use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

use crate::engine::study::FromParamValue;
use crate::engine::value::ParamValue;

use crate::engine::study::{
    did_you_mean, Located, Param, ResolveContext, SourceLocation, SpecError,
};
use crate::materials::{all_names, find_material, UnknownMaterial};
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
    /// Poisson's ratio in [0, 0.5); required without `name`.
    #[serde(default)]
    pub poisson_ratio: Option<Param<f64>>,
    /// Hardness H (pressure > 0), e.g. from ultra-micro-hardness of the near-surface material.
    #[serde(default)]
    pub hardness: Option<Param<Quantity<Pressure>>>,
    /// Plastic flow pressure p_lim (pressure > 0); omitted: the built-in value, else = hardness.
    #[serde(default)]
    pub flow_pressure: Option<Param<Quantity<Pressure>>>,
    /// Yield strength Y (pressure > 0) used by the full-stick and Jackson–Green laws; omitted:
    /// Tabor's rule Y = H/2.8.
    #[serde(default)]
    pub yield_strength: Option<Param<Quantity<Pressure>>>,
    /// Shear strength k (pressure > 0) of the material, the junction-shear strength of a clean
    /// interface; omitted: von Mises k = Y/√3.
    #[serde(default)]
    pub shear_strength: Option<Param<Quantity<Pressure>>>,
}

/// A material resolved for one scenario (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedMaterial {
    /// Canonical built-in name, if one was used.
    pub name: Option<&'static str>,
    /// Young's modulus (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Hardness (Pa), if known.
    pub hardness: Option<f64>,
    /// Plastic flow pressure (Pa), if known.
    pub flow_pressure: Option<f64>,
    /// Yield strength (Pa), if given (the friction models default to H/2.8).
    pub yield_strength: Option<f64>,
    /// Shear strength (Pa), if given (the friction models default to Y/√3).
    pub shear_strength: Option<f64>,
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

fn positive_pressure(q: &Quantity<Pressure>) -> Result<(), String> {
    if q.si() > 0.0 {
        Ok(())
    } else {
        Err(String::from("is out of range: must be > 0 Pa"))
    }
}

fn poisson(v: &f64) -> Result<(), String> {
    if (0.0..0.5).contains(v) {
        Ok(())
    } else {
        Err(String::from(
            "is out of range: Poisson's ratio must be in [0, 0.5)",
        ))
    }
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

    /// Resolves the material under one scenario; `field` names it in messages (`lower_material`).
    pub fn resolve(
        &self,
        ctx: &ResolveContext<'_>,
        field: &str,
    ) -> Result<ResolvedMaterial, SpecError> {
        let m = match &self.source {
            MaterialSource::Named(name) => {
                let b = self.lookup(ctx, name, self.location, field)?;
                return Ok(ResolvedMaterial {
                    name: Some(b.name),
                    youngs_modulus: b.youngs_modulus,
                    poisson_ratio: b.poisson_ratio,
                    hardness: Some(b.hardness),
                    flow_pressure: Some(b.flow_pressure),
                    yield_strength: None,
                    shear_strength: None,
                });
            }
            MaterialSource::Mapping(m) => m,
        };
        let base = match &m.name {
            Some(name) => {
                Some(self.lookup(ctx, &name.source, name.location, &format!("{field}.name"))?)
            }
            None => None,
        };
        let pressure = |p: &Option<Param<Quantity<Pressure>>>, sub: &str| {
            p.as_ref()
                .map(|p| {
                    ctx.resolve_checked(p, &format!("{field}.{sub}"), positive_pressure)
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
        let youngs_modulus = match (pressure(&m.youngs_modulus, "youngs_modulus")?, base) {
            (Some(e), _) => e,
            (None, Some(b)) => b.youngs_modulus,
            (None, None) => return Err(missing("youngs_modulus")),
        };
        let poisson_ratio = match (&m.poisson_ratio, base) {
            (Some(p), _) => ctx.resolve_checked(p, &format!("{field}.poisson_ratio"), poisson)?,
            (None, Some(b)) => b.poisson_ratio,
            (None, None) => return Err(missing("poisson_ratio")),
        };
        let hardness = pressure(&m.hardness, "hardness")?.or(base.map(|b| b.hardness));
        let flow_pressure = pressure(&m.flow_pressure, "flow_pressure")?
            .or(base.map(|b| b.flow_pressure))
            .or(hardness);
        if let Some(h) = hardness.filter(|h| *h >= youngs_modulus) {
            return Err(SpecError {
                location: self.location,
                field: format!("{field}.hardness"),
                message: format!(
                    "{} Pa is out of range: the hardness must be below Young's modulus {} Pa",
                    format_number(h),
                    format_number(youngs_modulus)
                ),
            });
        }
        Ok(ResolvedMaterial {
            name: base.map(|b| b.name),
            youngs_modulus,
            poisson_ratio,
            hardness,
            flow_pressure,
            yield_strength: pressure(&m.yield_strength, "yield_strength")?,
            shear_strength: pressure(&m.shear_strength, "shear_strength")?,
        })
    }
}
