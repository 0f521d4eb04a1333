//! Every name of the vocabulary as one list, read from the vocabulary's own source (each
//! `pub const …: &str` and `[&str; n]` of `src/vocabulary.rs` and `src/vocabulary/`), so a name
//! added there is in the list without a second mention.

/// The vocabulary's source files.
const SOURCES: [&str; 4] = [
    include_str!("../vocabulary.rs"),
    include_str!("surface_parameters.rs"),
    include_str!("surface_metrics.rs"),
    include_str!("twin_metrics.rs"),
];

/// Every name the vocabulary defines (column, metric, table, array and role names, prefixes and
/// suffixes), sorted, without repeats.
pub fn names() -> Vec<&'static str> {
    let mut out = Vec::new();
    for source in SOURCES {
        let mut definition = false;
        for line in source.lines() {
            let line = line.trim_start();
            definition |= line.starts_with("pub const ") && line.contains("&str");
            if definition {
                out.extend(line.split('"').skip(1).step_by(2));
                definition = !line.ends_with(';');
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::names;
    use crate::vocabulary::{metrics, surface_parameters, tables};

    #[test]
    fn the_list_holds_every_kind_of_definition_and_nothing_else() {
        let all = names();
        for name in [
            metrics::MU_S,
            tables::SURFACES_MATERIAL_RATIO,
            surface_parameters::CROP[3],
            surface_parameters::HEIGHT_UNIT_SOURCE,
        ] {
            assert!(all.contains(&name), "{name}");
        }
        assert!(all.len() > 200, "{} names", all.len());
        assert!(
            all.iter().all(|n| !n.is_empty() && !n.contains(' ')),
            "{all:?}"
        );
    }
}
