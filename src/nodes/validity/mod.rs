//! Validity of the values a node writes: the one place that says which numbers are physically
//! possible (a value outside fails the node) and which are possible but outside a model's or
//! method's assumptions (the row is flagged with a sentence and keeps its numbers).
//!
//! * [`RULES`]: per kind, a range per column. Applied by [`check_artifact`] to every computed
//!   artifact right after its computation, to the row's metrics and to long-table columns of
//!   the same name; every float must also be finite (no column is documented as NaN: undefined
//!   statistics are left out, a null cell).
//! * [`cross`]: the checks that need two inputs (a pressure against a flow pressure, a spot
//!   against the grid, heights against the field of view, a slope against the half-space
//!   theory), each a function called by the node kind that has both values.
//!
//! `docs/study-format.md` ("Validity of values") holds [`rules_markdown`] verbatim, and a test
//! checks it, so the documentation is written from this list.

pub mod cross;

use crate::engine::artifact::{Artifact, ColumnData};
use crate::engine::node::NodeError;
use crate::engine::value::{column_name, Field, Value};
use crate::units::{format_number, Dimension};
use crate::vocabulary::{contact_metrics as c, metrics as m, surface_metrics as s};

/// What happens when a value is outside a rule's range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// Impossible: the node fails with the rule's sentence.
    Fail,
    /// Possible, outside an assumption: the row is flagged with the sentence.
    Flag,
}

/// The range a column's values must lie in (bounds included, each up to a relative rounding of
/// 1e-12).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Range {
    /// > 0.
    Positive,
    /// ≥ the value.
    AtLeast(f64),
    /// ≤ the value.
    AtMost(f64),
    /// In [lower, upper].
    Between(f64, f64),
}

/// Relative rounding allowed at a bound: a share summed over many points may exceed 1 by a few
/// units in the last place.
const ROUNDING: f64 = 1e-12;

impl Range {
    /// `true` when `v` lies in the range.
    pub fn contains(self, v: f64) -> bool {
        let slack = |bound: f64| ROUNDING * bound.abs();
        match self {
            Range::Positive => v > 0.0,
            Range::AtLeast(lo) => v >= lo - slack(lo),
            Range::AtMost(hi) => v <= hi + slack(hi),
            Range::Between(lo, hi) => v >= lo - slack(lo) && v <= hi + slack(hi),
        }
    }

    /// The range as text, in the column's SI unit.
    pub fn describe(self, unit: &str) -> String {
        let u = |v: f64| match unit {
            "" => format_number(v),
            unit => format!("{} {unit}", format_number(v)),
        };
        match self {
            Range::Positive => String::from("> 0"),
            Range::AtLeast(lo) => format!("≥ {}", u(lo)),
            Range::AtMost(hi) => format!("≤ {}", u(hi)),
            Range::Between(lo, hi) => format!("[{}, {}]", u(lo), u(hi)),
        }
    }
}

/// A rule on one or more columns of a kind's table.
#[derive(Debug, Clone, Copy)]
pub struct ColumnRule {
    /// The node kind (`surface`, `contact`, `friction`).
    pub kind: &'static str,
    /// Metric names (without unit) the rule applies to.
    pub columns: &'static [&'static str],
    pub range: Range,
    pub severity: Severity,
    /// Why a value outside is impossible (or must be read with care), its likely cause and a fix.
    /// A flag's sentence is the value and this text, so a flag rule's text states its bound in
    /// words ("more than half the load ...").
    pub why: &'static str,
}

/// The kind names the rules are keyed by.
pub use crate::vocabulary::kinds::{CONTACT, FRICTION, SURFACE};

/// Smallest Sq taken as a surface (m): a picometre, a hundredth of an atom's size; below it no
/// roughness is measurable and the spectral moments derived from it underflow.
pub const MIN_SQ: f64 = 1e-12;

/// Largest grid spacing (m): topography is sampled at nanometres to millimetres; a spacing of
/// metres is a damaged or mis-scaled file.
pub const MAX_SPACING: f64 = 1.0;

/// Largest height statistic (m): instruments measure heights of nanometres to millimetres, the
/// largest shipped example (a synthetic ISO 5436 sample) spans 1.9 m; a kilometre is a damaged
/// file (bytes of another format read as floats) or a wrong height unit.
pub const MAX_HEIGHT: f64 = 1e3;

/// The largest share of a friction row's load (or the adhesion share of its contact load) on
/// what its law does not describe before the row is flagged: more than half, and μ_s is mostly
/// about what the law does not describe.
pub const MAX_UNTRUSTED_LOAD_SHARE: f64 = 0.5;

/// The column rules of every kind.
pub const RULES: &[ColumnRule] = &[
    ColumnRule {
        kind: SURFACE,
        columns: &[m::DX, m::DY],
        range: Range::Positive,
        severity: Severity::Fail,
        why: "a grid spacing is a positive length; a file whose spacing is 0 or negative is \
              damaged: give `pixel_size` with `override_file_spacing: true`",
    },
    ColumnRule {
        kind: SURFACE,
        columns: &[m::DX, m::DY],
        range: Range::AtMost(MAX_SPACING),
        severity: Severity::Fail,
        why: "no topography is sampled coarser than a metre: the file's spacing (e.g. an x3p \
              `Increment`) is damaged or in the wrong unit; give `pixel_size` with \
              `override_file_spacing: true`",
    },
    ColumnRule {
        kind: SURFACE,
        columns: &[m::SQ],
        range: Range::AtLeast(MIN_SQ),
        severity: Severity::Fail,
        why: "an Sq below a picometre (an atom is about 1e-10 m) is no measurable roughness and \
              its spectral moments underflow: check the height unit or `sq`",
    },
    ColumnRule {
        kind: SURFACE,
        columns: &[m::SQ, s::SA, s::SP, s::SV, s::SZ],
        range: Range::AtMost(MAX_HEIGHT),
        severity: Severity::Fail,
        why: "no surface topography spans a kilometre in height: the file is damaged (e.g. \
              another format's bytes read as heights) or its height unit is wrong",
    },
    ColumnRule {
        kind: SURFACE,
        columns: &[s::SA, s::SP, s::SV, s::SZ, s::SDQ, s::SDR_PERCENT, s::SAL],
        range: Range::AtLeast(0.0),
        severity: Severity::Fail,
        why: "an amplitude, slope or length is never negative",
    },
    ColumnRule {
        kind: SURFACE,
        columns: &[
            s::SK,
            s::SPK,
            s::SVK,
            s::SXP,
            s::VMP,
            s::VMC,
            s::VVC,
            s::VVV,
        ],
        range: Range::AtLeast(0.0),
        severity: Severity::Fail,
        why: "heights and volumes of the material ratio curve, which never rises, are never \
              negative",
    },
    ColumnRule {
        kind: SURFACE,
        columns: &[s::SMR1_PERCENT, s::SMR2_PERCENT],
        range: Range::Between(0.0, 100.0),
        severity: Severity::Fail,
        why: "a material ratio is a share of the valid points",
    },
    ColumnRule {
        kind: SURFACE,
        columns: &[s::STR, s::HURST_FIT_R_SQUARED],
        range: Range::Between(0.0, 1.0),
        severity: Severity::Fail,
        why: "a ratio of lengths or a coefficient of determination lies in [0, 1]",
    },
    ColumnRule {
        kind: CONTACT,
        columns: &[m::AREA_FRACTION],
        range: Range::Between(0.0, 1.0),
        severity: Severity::Fail,
        why: "the real contact area is a part of the nominal area",
    },
    ColumnRule {
        kind: CONTACT,
        columns: &[m::STRESS_RATIO],
        range: Range::Between(0.0, 1.0),
        severity: Severity::Fail,
        why: "the mean contact pressure cannot exceed the flow pressure that caps every local \
              pressure",
    },
    ColumnRule {
        kind: CONTACT,
        columns: &[c::PLASTIC_AREA_SHARE],
        range: Range::Between(0.0, 1.0),
        severity: Severity::Fail,
        why: "the plastic area is a part of the contact area",
    },
    ColumnRule {
        kind: CONTACT,
        columns: &[m::COMPOSITE_MODULUS, m::NOMINAL_PRESSURE, m::DX, m::DY],
        range: Range::Positive,
        severity: Severity::Fail,
        why: "a modulus, a compressive load and a grid spacing are positive",
    },
    ColumnRule {
        kind: CONTACT,
        columns: &[
            m::MEAN_CONTACT_PRESSURE,
            c::MAX_ELASTIC_DEFORMATION,
            m::RESIDUAL,
        ],
        range: Range::AtLeast(0.0),
        severity: Severity::Fail,
        why: "contact pressures are compressive, a deformation magnitude and a residual are never \
              negative",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[
            m::MU_S,
            m::LOCAL_MU_P10,
            m::LOCAL_MU_MEDIAN,
            m::LOCAL_MU_P90,
        ],
        range: Range::AtLeast(0.0),
        severity: Severity::Fail,
        why: "a static friction coefficient is never negative (a negative model value is kept in \
              `mu_s_computed`)",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[m::AREA_FRACTION],
        range: Range::Between(0.0, 1.0),
        severity: Severity::Fail,
        why: "the real contact area cannot exceed the nominal area; statistically, the \
              Greenwood–Williamson sum over independent summits counts more area than there is \
              when the surface is very rough for its size or heavily loaded: the model does not \
              apply there (solve a `contact` node and use `method: per_spot`), or check the \
              units of `sq` and the load",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[
            m::LOAD_SHARE_BEYOND_FIT,
            m::LOAD_SHARE_ONE_PIXEL,
            m::LOAD_SHARE_WITHOUT_RADIUS,
            m::LOAD_SHARE_MERGED,
            m::LOAD_SHARE_OUTSIDE_REGIME,
        ],
        range: Range::Between(0.0, 1.0),
        severity: Severity::Fail,
        why: "a share of the load lies in [0, 1]",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[m::LOAD_SHARE_WITHOUT_RADIUS],
        range: Range::AtMost(MAX_UNTRUSTED_LOAD_SHARE),
        severity: Severity::Flag,
        why: "more than half the load sits on spots whose topography gives no convex radius, \
              which carry no tangential load under a law that needs one: μ_s is a lower bound \
              (junction shear needs no radius)",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[m::LOAD_SHARE_MERGED],
        range: Range::AtMost(MAX_UNTRUSTED_LOAD_SHARE),
        severity: Severity::Flag,
        why: "more than half the load sits on merged spots (two or more summits of the composite \
              topography in one spot), whose single-asperity radius means nothing: the \
              single-asperity law does not describe them; lower the load or use junction shear",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[m::LOAD_SHARE_OUTSIDE_REGIME],
        range: Range::AtMost(MAX_UNTRUSTED_LOAD_SHARE),
        severity: Severity::Flag,
        why: "more than half the load sits on spots whose degree of penetration is beyond the \
              ploughing regime (wedge forming or cutting after Hokkirigawa & Kato): the additive \
              ploughing laws do not describe them",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[m::ADHESION_SHARE],
        range: Range::AtLeast(0.0),
        severity: Severity::Fail,
        why: "an attractive adhesion force over a compressive contact load is never negative",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[m::ADHESION_SHARE],
        range: Range::AtMost(MAX_UNTRUSTED_LOAD_SHARE),
        severity: Severity::Flag,
        why: "adhesion carries more than half the contact load: μ_s = Q/(F_n − F_a) is governed \
              by the small difference F_n − F_a (the external load), not by the contact; check \
              the adhesion energy and the load",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[m::LOAD_SHARE_ONE_PIXEL],
        range: Range::AtMost(0.5),
        severity: Severity::Flag,
        why: "most of the load sits on one-pixel spots, whose size and radius the grid does not \
              resolve: refine the grid (smaller pixels) before trusting μ_s",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[
            m::NORMAL_LOAD,
            m::FRICTION_FORCE,
            m::ADHESION_FORCE,
            m::REAL_AREA,
            m::CONTACTS,
            m::PLASTICITY_INDEX,
            m::SHEAR_STRENGTH,
            m::SPOT_AREA_P10,
            m::SPOT_AREA_MEDIAN,
            m::SPOT_AREA_P90,
        ],
        range: Range::AtLeast(0.0),
        severity: Severity::Fail,
        why: "a contact load, a force magnitude, an area, a count, an index or a strength is \
              never negative",
    },
    ColumnRule {
        kind: FRICTION,
        columns: &[m::APPARENT_AREA, m::SECTION_AREA],
        range: Range::Positive,
        severity: Severity::Fail,
        why: "a nominal area is positive",
    },
];

/// Why a float must be finite: the sentence of the rule every float column obeys.
pub const FINITE_WHY: &str = "a physical quantity is a finite number; NaN or an infinity means \
    an input overflowed or underflowed double precision: a damaged file, a value in the wrong \
    unit or a parameter far out of its range";

/// Checks a computed artifact of `kind` against [`RULES`] and the finite rule: `Err` with the
/// first impossible value's sentence; flags are added to `artifact.flags`.
pub fn check_artifact(kind: &str, artifact: &mut Artifact) -> Result<(), NodeError> {
    let mut flags = Vec::new();
    for field in &artifact.metrics {
        if let Value::Float(v) = field.value {
            let label = format!("`{}`", column_name(&field.name, field.dimension));
            check_value(kind, &field.name, &label, field.dimension, v, &mut flags)?;
        }
    }
    for (table, t) in &artifact.tables {
        for c in &t.columns {
            let ColumnData::Float(values) = &c.data else {
                continue;
            };
            for (row, &v) in values.iter().enumerate() {
                let label = format!("`{}` (long table `{table}`, row {row})", c.column_name());
                check_value(kind, &c.name, &label, c.dimension, v, &mut flags)?;
            }
        }
    }
    for flag in flags {
        if !artifact.flags.contains(&flag) {
            artifact.flags.push(flag);
        }
    }
    Ok(())
}

/// Checks `fields` of `kind` before the rest is computed (e.g. a surface's spacing, which would
/// make its statistics meaningless or unbounded): `Err` with the first impossible value's
/// sentence; flags are left to [`check_artifact`].
pub fn check_fields(kind: &str, fields: &[Field]) -> Result<(), NodeError> {
    let mut flags = Vec::new();
    for field in fields {
        if let Value::Float(v) = field.value {
            let label = format!("`{}`", column_name(&field.name, field.dimension));
            check_value(kind, &field.name, &label, field.dimension, v, &mut flags)?;
        }
    }
    Ok(())
}

/// One value of column `name` (shown as `label`): finite, and inside every rule of the kind on
/// that column.
fn check_value(
    kind: &str,
    name: &str,
    label: &str,
    dimension: Dimension,
    v: f64,
    flags: &mut Vec<String>,
) -> Result<(), NodeError> {
    if !v.is_finite() {
        return Err(NodeError::new(format!(
            "{label} is {}: {FINITE_WHY}",
            format_number(v)
        )));
    }
    for rule in RULES
        .iter()
        .filter(|r| r.kind == kind && r.columns.contains(&name))
    {
        if rule.range.contains(v) {
            continue;
        }
        match rule.severity {
            Severity::Fail => {
                let range = rule.range.describe(dimension.si_symbol());
                return Err(NodeError::new(format!(
                    "{label} = {} is outside {range}: {}",
                    format_number(v),
                    rule.why
                )));
            }
            // A flag's sentence states its bound in words ("more than half the load"), so that
            // several flags of a row joined in its message do not repeat "is outside ≤ 0.5".
            Severity::Flag => flags.push(format!("{label} = {}: {}", format_number(v), rule.why)),
        }
    }
    Ok(())
}

/// The rules as the Markdown table of `docs/study-format.md` ("Validity of values"): kind,
/// columns, range, outcome and reason, [`RULES`] in order, then the cross-input checks.
pub fn rules_markdown() -> String {
    let mut out =
        String::from("| kind | columns | range | outside | why |\n|---|---|---|---|---|\n");
    let outcome = |s: Severity| match s {
        Severity::Fail => "fails",
        Severity::Flag => "flagged",
    };
    out.push_str(&format!(
        "| all | every float column, long tables included | finite | fails | {FINITE_WHY} |\n"
    ));
    for rule in RULES {
        let columns: Vec<String> = rule.columns.iter().map(|c| format!("`{c}`")).collect();
        let unit = match rule.columns.first() {
            Some(&("dx" | "dy" | "sq")) => "m",
            _ => "",
        };
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} |\n",
            rule.kind,
            columns.join(", "),
            rule.range.describe(unit),
            outcome(rule.severity),
            rule.why.split_whitespace().collect::<Vec<_>>().join(" ")
        ));
    }
    for check in cross::CHECKS {
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} |\n",
            check.kind, check.columns, check.rule, check.outcome, check.why
        ));
    }
    out
}
