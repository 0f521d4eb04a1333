//! Sentences for the YAML parser's resource limits (its "budget"): the parser refuses documents
//! whose size, nesting or aliasing would make reading them costly (a billion-laughs alias bomb
//! or a deeply nested document), and the study error says which limit, the count reached and a
//! fix instead of the parser's internal description.

use serde_saphyr::budget::BudgetBreach;
use serde_saphyr::Budget;

/// The breached parser limit behind `error`, through the parser's wrappers (the snippet, and
/// the alias whose expansion breached it).
pub(super) fn breach(mut error: &serde_saphyr::Error) -> Option<&BudgetBreach> {
    loop {
        match error {
            serde_saphyr::Error::WithSnippet { error: inner, .. }
            | serde_saphyr::Error::AliasError { error: inner, .. } => error = inner,
            serde_saphyr::Error::Budget { breach, .. } => return Some(breach),
            _ => return None,
        }
    }
}

/// The message for a breached parser limit.
pub(super) fn budget_message(breach: &BudgetBreach) -> String {
    let limits = Budget::default();
    let (what, reached, limit) = match breach {
        BudgetBreach::Events { events } => ("parser events", *events, limits.max_events),
        BudgetBreach::Aliases { aliases } => ("aliases (*name)", *aliases, limits.max_aliases),
        BudgetBreach::Anchors { anchors } => ("anchors (&name)", *anchors, limits.max_anchors),
        BudgetBreach::Depth { depth } => ("nesting levels", *depth, limits.max_depth),
        BudgetBreach::Documents { documents } => {
            ("YAML documents", *documents, limits.max_documents)
        }
        BudgetBreach::Nodes { nodes } => (
            "values (lists, mappings and scalars)",
            *nodes,
            limits.max_nodes,
        ),
        BudgetBreach::ScalarBytes { total_scalar_bytes } => (
            "bytes of scalar text",
            *total_scalar_bytes,
            limits.max_total_scalar_bytes,
        ),
        BudgetBreach::MergeKeys { merge_keys } => {
            ("merge keys (<<)", *merge_keys, limits.max_merge_keys)
        }
        BudgetBreach::AliasAnchorRatio { aliases, anchors } => {
            return format!(
                "the study uses {aliases} aliases for {anchors} anchors, more than {} per anchor: \
                 repeated aliases expand the document like an alias bomb; write the repeated \
                 values out or use parameters",
                limits.alias_anchor_ratio_multiplier
            )
        }
        BudgetBreach::InputBytes { input_bytes } => (
            "bytes",
            *input_bytes,
            limits.max_reader_input_bytes.unwrap_or(usize::MAX),
        ),
        BudgetBreach::RecordedAnchorEvents {
            recorded_anchor_events,
        } => (
            "copies of anchored values",
            *recorded_anchor_events,
            limits.max_recorded_anchor_events,
        ),
        BudgetBreach::RecordedAnchorBytes {
            recorded_anchor_bytes,
        } => (
            "bytes of anchored values",
            *recorded_anchor_bytes,
            limits.max_recorded_anchor_bytes,
        ),
        _ => {
            return String::from(
                "the study is too large or too deeply nested for the YAML parser's limits; \
                 a study is a few hundred lines: use parameter axes instead of repeating nodes",
            )
        }
    };
    format!(
        "the study has more than {limit} {what} (the parser stopped at {reached}), the limit \
         that keeps reading a study cheap; a study is a few hundred lines: use parameter axes \
         instead of repeating nodes or values"
    )
}
