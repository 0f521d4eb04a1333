//! `model:` of a friction node: a law's name (`model: full_stick`, or `${param}`) or the law with
//! its own parameter block (`model: {full_stick: {a: 0.3, b: 0.35}}`). Names, parameters,
//! defaults, ranges and the methods a law supports all come from the registry
//! [`crate::friction::LAWS`]; this file only reads the study's words against it, and is the one
//! place that decides whether a method and a model go together.

use std::fmt;
use std::sync::Arc;

use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

use crate::engine::study::{
    did_you_mean, FromParamValue, Located, Param, ResolveContext, SourceLocation, SpecError,
};
use crate::engine::value::ParamValue;
use crate::friction::laws::{
    default_law, find_law, law_names, LawDescriptor, LawInputs, Method, ParameterKind,
    ParameterSpec, ParameterValue, Unit,
};
use crate::friction::FrictionLaw;
use crate::units::{angle_without_unit, plain_number_as, Dimension, UnitError};

use super::spec_fields::spec_error;

/// `model: <name>` or `model: {<name>: {<parameter>: <value>, ...}}`.
#[derive(Debug)]
pub struct ModelSpec {
    location: SourceLocation,
    source: ModelSource,
}

#[derive(Debug)]
enum ModelSource {
    /// A name, literal or `${param}` (re-read as a parameter field; see [`ModelSpec::name`]).
    Name(Param<String>),
    /// `{<name>: {...}}`: a literal name and its parameters as written.
    Block {
        name: Located<String>,
        parameters: Vec<(Located<String>, Param<LawValue>)>,
    },
}

/// A parameter value in a law's block: a number, a quantity with its unit or a name.
#[derive(Debug, Clone, PartialEq)]
pub enum LawValue {
    /// A plain number.
    Number(f64),
    /// A quantity: its SI value and dimension (`90 deg`).
    Quantity(f64, Dimension),
    /// Text (a choice).
    Text(String),
}

impl FromParamValue for LawValue {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::Int(i) => Ok(Self::Number(*i as f64)),
            ParamValue::Number(x) => Ok(Self::Number(*x)),
            ParamValue::Quantity(q) => Ok(Self::Quantity(q.si, q.dimension)),
            ParamValue::Text(t) => Ok(Self::Text(t.clone())),
            other => Err(format!(
                "expected a number or a name, got {other} ({})",
                other.type_name()
            )),
        }
    }
}

impl ModelSpec {
    /// Where the model is written.
    pub fn location(&self) -> SourceLocation {
        self.location
    }
}

/// The law and method a node uses: the law named by `model` (default: the registry's first),
/// with its parameters, built for `inputs`' material; the method given, else the law's default,
/// refused when the law does not support it.
pub(super) fn resolve_law(
    model: Option<&ModelSpec>,
    method: Option<&MethodSpec>,
    ctx: &ResolveContext<'_>,
    material: LawInputs,
    location: SourceLocation,
) -> Result<(Arc<dyn FrictionLaw>, Method), SpecError> {
    let (law, at) = match model {
        Some(m) => (m.law(ctx)?, m.location),
        None => (default_law(), location),
    };
    let method = match method.map(|m| &m.0) {
        Some(m) if !law.supports(m.value) => {
            return Err(unsupported_method(law, m.value, m.location))
        }
        Some(m) => m.value,
        None => law.default_method(),
    };
    let mut inputs = material;
    inputs.parameters = match model {
        Some(m) => m.parameters(law, ctx)?,
        None => law.default_parameters(),
    };
    let built = (law.build)(&inputs).map_err(|e| {
        spec_error(
            at,
            "model",
            format!(
                "`model: {}` cannot be used with this material pair: {e} (change the material or choose another model)",
                law.name
            ),
        )
    })?;
    Ok((Arc::from(built), method))
}

fn unsupported_method(law: &LawDescriptor, method: Method, at: SourceLocation) -> SpecError {
    let supported: Vec<String> = law
        .methods
        .iter()
        .map(|m| format!("`method: {}`", m.name()))
        .collect();
    spec_error(
        at,
        "method",
        format!(
            "`{}` does not apply to `model: {}` ({}): use {} (the first is the model's default){}",
            method.name(),
            law.name,
            law.summary,
            supported.join(" or "),
            if law.supports(Method::PerSpot) && !law.supports(Method::Statistical) {
                ", which reads a `contact` node run with `fields: true`"
            } else {
                ""
            }
        ),
    )
}

impl ModelSpec {
    /// The registry entry named here.
    fn law(&self, ctx: &ResolveContext<'_>) -> Result<&'static LawDescriptor, SpecError> {
        let (name, at) = match &self.source {
            ModelSource::Name(p) => (
                ctx.resolve(p, "model").map_err(|e| SpecError {
                    location: self.location,
                    ..e
                })?,
                self.location,
            ),
            ModelSource::Block { name, .. } => (name.value.clone(), name.location),
        };
        find_law(&name).ok_or_else(|| {
            spec_error(
                at,
                "model",
                format!(
                    "unknown model '{name}'{}; models: {}",
                    did_you_mean(&name, law_names().into_iter()),
                    law_names().join(", ")
                ),
            )
        })
    }

    /// The law's parameters: its defaults, overridden by the block's values.
    fn parameters(
        &self,
        law: &'static LawDescriptor,
        ctx: &ResolveContext<'_>,
    ) -> Result<crate::friction::laws::LawParameters, SpecError> {
        let mut values = law.default_parameters();
        let ModelSource::Block { parameters, .. } = &self.source else {
            return Ok(values);
        };
        for (key, param) in parameters {
            let spec = law
                .parameter(&key.value)
                .ok_or_else(|| unknown_parameter(law, key))?;
            let field = format!("model.{}.{}", law.name, spec.name);
            let value = resolve_value(ctx, spec, param, &field)?;
            values.set(spec.name, value);
        }
        Ok(values)
    }
}

/// A parameter's default as a study writes it.
pub(super) fn default_text(spec: &ParameterSpec) -> String {
    match spec.kind {
        ParameterKind::Number { default, .. } => default.to_string(),
        ParameterKind::Choice { default, .. } => default.to_string(),
    }
}

fn unknown_parameter(law: &LawDescriptor, key: &Located<String>) -> SpecError {
    let names: Vec<&str> = law.parameters.iter().map(|p| p.name).collect();
    let known = if names.is_empty() {
        String::from("it has no parameters")
    } else {
        format!("its parameters: {}", names.join(", "))
    };
    spec_error(
        key.location,
        &format!("model.{}.{}", law.name, key.value),
        format!(
            "is not a parameter of `model: {}`{}; {known}",
            law.name,
            did_you_mean(&key.value, names.into_iter())
        ),
    )
}

/// One parameter's value, checked against its declaration.
fn resolve_value(
    ctx: &ResolveContext<'_>,
    spec: &'static ParameterSpec,
    param: &Param<LawValue>,
    field: &str,
) -> Result<ParameterValue, SpecError> {
    let convert = |v: &LawValue| match (v, spec.kind) {
        (LawValue::Number(x), ParameterKind::Number { unit, .. }) => {
            // The value is already named before the message: say only what is wrong with it.
            plain_number_as(*x, dimension_of(unit))
                .map_err(|e| match e {
                    UnitError::AngleWithoutUnit { text } => angle_without_unit(&text),
                    other => other.to_string(),
                })
                .and_then(|x| spec.number(x))
        }
        (LawValue::Quantity(x, d), ParameterKind::Number { unit, .. })
            if *d == dimension_of(unit) =>
        {
            spec.number(*x)
        }
        (LawValue::Quantity(_, d), ParameterKind::Number { unit, .. }) => Err(format!(
            "is a {}, expected {}",
            d.name(),
            unit_example(unit)
        )),
        (LawValue::Quantity(..), ParameterKind::Choice { options, .. }) => {
            Err(format!("is not one of: {}", options.join(", ")))
        }
        (LawValue::Text(t), ParameterKind::Choice { .. }) => spec.choice(t),
        (LawValue::Text(_), ParameterKind::Number { range, .. }) => {
            Err(format!("expected a number {}", range.describe()))
        }
        (LawValue::Number(_), ParameterKind::Choice { options, .. }) => {
            Err(format!("is not one of: {}", options.join(", ")))
        }
    };
    let value = ctx.resolve_checked(param, field, |v| convert(v).map(|_| ()))?;
    convert(&value).map_err(|message| spec_error(param.location(), field, message))
}

/// The dimension a parameter's unit stands for.
fn dimension_of(unit: Unit) -> Dimension {
    match unit {
        Unit::Dimensionless => Dimension::Dimensionless,
        Unit::Pressure => Dimension::Pressure,
        Unit::Angle => Dimension::Angle,
    }
}

/// How a value of `unit` is written, for messages: "a quantity of dimension angle with its
/// unit, e.g. 30 deg".
fn unit_example(unit: Unit) -> String {
    let d = dimension_of(unit);
    format!(
        "a quantity of dimension {} with its unit, e.g. {}",
        d.name(),
        d.example()
    )
}

impl<'de> Deserialize<'de> for ModelSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let located = Located::<ModelSource>::deserialize(deserializer)?;
        Ok(Self {
            location: located.location,
            source: located.value,
        })
    }
}

impl<'de> Deserialize<'de> for ModelSource {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ModelVisitor)
    }
}

struct ModelVisitor;

impl<'de> Visitor<'de> for ModelVisitor {
    type Value = ModelSource;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "a model name ({}) or a model with its parameters, e.g. {{full_stick: {{a: 0.27, b: 0.35}}}}",
            law_names().join(", ")
        )
    }

    /// The name as a parameter field (it may be `${model}`), read back from a YAML scalar.
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
        let scalar = serde_json::to_string(v).map_err(E::custom)?;
        serde_saphyr::from_str::<Param<String>>(&scalar)
            .map(ModelSource::Name)
            .map_err(E::custom)
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let Some(name) = map.next_key::<Located<String>>()? else {
            return Err(de::Error::custom(
                "an empty mapping: write the model's name, e.g. `model: full_stick`",
            ));
        };
        let block = map.next_value::<ParameterBlock>()?;
        if let Some(other) = map.next_key::<Located<String>>()? {
            return Err(de::Error::custom(format!(
                "one model per node: `{}` follows `{}` (give each model a node of its own)",
                other.value, name.value
            )));
        }
        Ok(ModelSource::Block {
            name,
            parameters: block.0,
        })
    }
}

/// The `{parameter: value}` block of a model (empty when written `{}` or left null).
struct ParameterBlock(Vec<(Located<String>, Param<LawValue>)>);

impl<'de> Deserialize<'de> for ParameterBlock {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(BlockVisitor)
    }
}

struct BlockVisitor;

impl<'de> Visitor<'de> for BlockVisitor {
    type Value = ParameterBlock;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("the model's parameters as a mapping, e.g. {a: 0.27, b: 0.35}")
    }

    fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
        Ok(ParameterBlock(Vec::new()))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut entries: Vec<(Located<String>, Param<LawValue>)> = Vec::new();
        while let Some(key) = map.next_key::<Located<String>>()? {
            if entries.iter().any(|(k, _)| k.value == key.value) {
                return Err(de::Error::custom(format!(
                    "parameter `{}` is given twice",
                    key.value
                )));
            }
            entries.push((key, map.next_value()?));
        }
        Ok(ParameterBlock(entries))
    }
}

impl schemars::JsonSchema for ModelSpec {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "FrictionModel".into()
    }

    /// Generated from the registry: a name, or `{name: {parameters}}` per law.
    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let blocks: Vec<serde_json::Value> = crate::friction::LAWS
            .iter()
            .map(|law| law_block_schema(law))
            .collect();
        schemars::json_schema!({
            "description": "The friction law: its name (default kogut_etsion), a reference '${param}', or the name with its parameter block.",
            "anyOf": [
                { "type": "string", "enum": law_names() },
                { "type": "string", "pattern": r"^\$\{\s*[A-Za-z_][A-Za-z0-9_]*\s*\}$" },
                { "oneOf": blocks }
            ]
        })
    }
}

fn law_block_schema(law: &LawDescriptor) -> serde_json::Value {
    let properties: serde_json::Map<String, serde_json::Value> = law
        .parameters
        .iter()
        .map(|p| {
            let value = match p.kind {
                ParameterKind::Number { default, .. } => {
                    serde_json::json!({"type": ["number", "string"], "default": default, "description": p.description})
                }
                ParameterKind::Choice { options, default } => {
                    serde_json::json!({"type": "string", "enum": options, "default": default, "description": p.description})
                }
            };
            (p.name.to_string(), value)
        })
        .collect();
    serde_json::json!({
        "type": "object",
        "description": law.summary,
        "properties": { law.name: {
            "type": ["object", "null"],
            "properties": properties,
            "additionalProperties": false
        }},
        "required": [law.name],
        "additionalProperties": false
    })
}

/// `method:` — a method's name ([`Method::name`]).
#[derive(Debug, Clone)]
pub struct MethodSpec(pub(super) Located<Method>);

impl<'de> Deserialize<'de> for MethodSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = Located::<String>::deserialize(deserializer)?;
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        match Method::ALL.iter().find(|m| m.name() == name.value) {
            Some(m) => Ok(Self(Located::new(*m, name.location))),
            None => Err(de::Error::custom(format!(
                "unknown method '{}'{}; methods: {}",
                name.value,
                did_you_mean(&name.value, names.iter().copied()),
                names.join(", ")
            ))),
        }
    }
}

impl schemars::JsonSchema for MethodSpec {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "FrictionMethod".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        schemars::json_schema!({
            "description": "statistical (GW summit statistics), per_summit (summits of a contact node's solution) or per_spot (contact spots of a contact node's solution); default: the model's first method.",
            "type": "string",
            "enum": names
        })
    }
}
