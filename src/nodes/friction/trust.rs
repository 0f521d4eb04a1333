//! How far a friction row can be trusted beyond the column rules of
//! [`crate::nodes::validity`]: what its inputs' flags mean for it, and the range of μ_s its law
//! can describe. Each is one function; the validity rules flag the load shares (beyond the fit,
//! without a radius, on merged spots, beyond the ploughing regime) and the adhesion share.

use crate::engine::artifact::Artifact;
use crate::engine::value::Value;
use crate::friction::LawDescriptor;
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

/// μ_s above the law's [`LawDescriptor::mu_s_max`] is flagged: the law is outside what it can
/// describe (too small a load for its range, or spots whose radius means nothing).
pub(super) fn flag_mu_s_beyond_law(law: &LawDescriptor, artifact: &mut Artifact) {
    let Some(&Value::Float(mu)) = artifact.metric(names::MU_S).map(|f| &f.value) else {
        return;
    };
    if mu > law.mu_s_max {
        artifact.flags.push(format!(
            "`mu_s` = {} is above {}, the largest static friction coefficient `model: {}` \
             describes (docs/study-format.md, friction models): read the load shares of this row \
             (beyond the fit, without a radius, on merged spots) before using it",
            format_number(mu),
            format_number(law.mu_s_max),
            law.name
        ));
    }
}
