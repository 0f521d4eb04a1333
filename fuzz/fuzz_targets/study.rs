//! Fuzzes the study parser: arbitrary bytes must give a study or a `StudyError` (never a panic),
//! and a study that parses (with at most 10 000 scenarios) must plan to a `Plan` or a
//! `StudyError`.
#![no_main]

use std::path::Path;

use asperity::engine::plan::Plan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(study) = Study::<TribologyNode>::from_source(Path::new("fuzz.yaml"), text.to_string())
    {
        // Mutated axes may expand to millions of scenarios (legitimate, capped by MAX_SCENARIOS,
        // but slow): plan only spaces of a realistic size.
        if study
            .file
            .parameters
            .expand(study.dir())
            .is_ok_and(|s| s.rows.len() <= 10_000)
        {
            let _ = Plan::build(&study);
        }
    }
});
