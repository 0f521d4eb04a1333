//! The table of friction models and their parameters in `docs/study-format.md`, written from the
//! registry (a test checks the documentation holds it as written here).

use crate::friction::laws::{ParameterKind, Unit, LAWS};

/// One row per law and parameter: model, basis, methods (default first), the largest μ_s a row
/// reports as `ok`, parameter, default, range, column, meaning.
pub fn friction_models_markdown() -> String {
    let mut out = String::from(
        "| model | `model_basis` | methods (default first) | `ok` μ_s ≤ | parameter | default | range | column | meaning |\n\
         |-------|---------------|-------------------------|------------|-----------|---------|-------|--------|---------|\n",
    );
    for law in LAWS {
        let methods: Vec<String> = law
            .methods
            .iter()
            .map(|m| format!("`{}`", m.name()))
            .collect();
        let head = format!(
            "| `{}` | `{}` | {} | {} ",
            law.name,
            law.basis.name(),
            methods.join(", "),
            law.mu_s_max
        );
        if law.parameters.is_empty() {
            out.push_str(&format!("{head}| – | | | | {} |\n", law.summary));
        }
        for p in law.parameters {
            let (default, range) = match p.kind {
                ParameterKind::Number {
                    default,
                    range,
                    unit,
                } => {
                    let unit = match unit {
                        Unit::Dimensionless => "",
                        Unit::Pressure => " Pa",
                        Unit::Angle => " rad",
                    };
                    (format!("{default}{unit}"), range.describe())
                }
                ParameterKind::Choice { options, default } => {
                    (format!("`{default}`"), options.join(" / "))
                }
            };
            out.push_str(&format!(
                "{head}| `{}` | {default} | {range} | `{}` | {} |\n",
                p.name, p.column, p.description
            ));
        }
    }
    out
}
