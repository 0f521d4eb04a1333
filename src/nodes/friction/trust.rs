//! How far a friction row can be trusted beyond the column rules of
//! [`crate::nodes::validity`]: what its inputs' flags mean for it, the range of μ (μ_s and the
//! local μ quantiles) its law can describe, and the share of its load beyond that law's
//! validated range. Each is one function; the validity rules flag the other load shares (without
//! a radius, on merged spots, beyond the ploughing regime, on one-pixel spots) and the adhesion
//! share.

use crate::engine::artifact::Artifact;
use crate::engine::value::Value;
use crate::friction::LawDescriptor;
use crate::nodes::validity;
use crate::units::format_number;
use crate::vocabulary::metrics as names;

/// A row computed from a flagged input is flagged: each flag of each input carries over with
/// the input's role (`roles[i]` of `inputs[i]`).
pub(super) fn inherit_flags(roles: &[&str], inputs: &[&Artifact], flags: &mut Vec<String>) {
    for (role, input) in roles.iter().zip(inputs) {
        for flag in &input.flags {
            let inherited = format!("the {role} node this row is computed from is flagged: {flag}");
            if !flags.contains(&inherited) {
                flags.push(inherited);
            }
        }
    }
}

/// μ_s and the load-weighted local μ quantiles (`local_mu_p10`, `local_mu_median`,
/// `local_mu_p90`) above the law's [`LawDescriptor::mu_s_max`] flag the row, in one sentence:
/// the law is outside what it can describe (too small a load for its range, or spots whose
/// radius means nothing), and a quantile above it says that much of the load sits on such spots.
pub(super) fn flag_mu_beyond_law(law: &LawDescriptor, artifact: &mut Artifact) {
    let above: Vec<String> = MU_COLUMNS
        .iter()
        .filter_map(|&name| match artifact.metric(name).map(|f| &f.value) {
            Some(&Value::Float(mu)) if mu > law.mu_s_max => {
                Some(format!("`{name}` = {}", format_number(mu)))
            }
            _ => None,
        })
        .collect();
    let (list, verb) = match above.as_slice() {
        [] => return,
        [one] => (one.clone(), "is"),
        [rest @ .., last] => (format!("{} and {last}", rest.join(", ")), "are"),
    };
    let local = if above.iter().any(|a| a.starts_with("`local_mu")) {
        "; a local μ quantile above it means that share of the load sits on spots the law \
         extrapolates to"
    } else {
        ""
    };
    artifact.flags.push(format!(
        "{list} {verb} above {}, the largest friction coefficient `model: {}` describes \
         (docs/study-format.md, friction models{local}): read the load shares of this row \
         (beyond the fit, without a radius, on merged spots) before using it",
        format_number(law.mu_s_max),
        law.name
    ));
}

/// The μ-like columns a friction row reports: μ_s and the local μ quantiles.
const MU_COLUMNS: [&str; 4] = [
    names::MU_S,
    names::LOCAL_MU_P10,
    names::LOCAL_MU_MEDIAN,
    names::LOCAL_MU_P90,
];

/// More than half the row's load beyond the validated range of its law: a flag naming that law
/// alone ([`validity::cross::load_beyond_fit`]).
pub(super) fn flag_load_beyond_fit(law: &LawDescriptor, artifact: &mut Artifact) {
    let Some(&Value::Float(share)) = artifact
        .metric(names::LOAD_SHARE_BEYOND_FIT)
        .map(|f| &f.value)
    else {
        return;
    };
    if let Some(flag) = validity::cross::load_beyond_fit(share, law.name, law.validated_range) {
        artifact.flags.push(flag);
    }
}
