//! Every file of the shared topography folder is read, or refused for a reason written here:
//! a new file dropped into the folder without a reader (or a reader that starts refusing a file)
//! fails this test instead of going unnoticed. Where the folder's `reference_values.json` gives
//! SurfaceTopography's Sq for the channel read, ours must agree to 1e-6 relative.

use asperity_numerics::surface::io::{read_topography, Topography, TopographyData};
use asperity_numerics::surface::{amplitude_statistics, Boundary};

use crate::common::data_dir;
use crate::damage::shared_files;

/// Files the readers refuse on purpose, with why (relative to the shared folder).
const REFUSED: &[(&str, &str)] = &[(
    "di/di_corrupted.di",
    "a damaged Nanoscope file (the trap of the folder)",
)];

/// Metres per unit of `reference_values.json` (`None`: a unit this test does not compare).
fn unit_factor(unit: &str) -> Option<f64> {
    Some(match unit {
        "m" => 1.0,
        "mm" => 1e-3,
        "um" | "µm" => 1e-6,
        "nm" => 1e-9,
        "A" | "Å" => 1e-10,
        _ => return None,
    })
}

/// The comparison of the file's Sq with SurfaceTopography's (same channel, a known unit, an
/// areal map): `None` when there is nothing to compare, `Err` beyond 1e-6 relative.
fn sq_check(
    name: &str,
    topo: &Topography,
    reference: &serde_json::Value,
) -> Option<Result<(), String>> {
    let st = reference.get(name)?.get("SurfaceTopography_1.27.1")?;
    let sq_ref = st.get("Sq")?.as_f64()?;
    let factor = unit_factor(st.get("unit")?.as_str()?)?;
    // A single-channel file is compared whatever the channel is called; of several, the one
    // SurfaceTopography read.
    let channel = st.get("channel").and_then(|c| c.as_str());
    let single = st.get("n_channels").and_then(|n| n.as_u64()) == Some(1);
    if !single && channel.is_some() && topo.channel.as_deref() != channel {
        return None;
    }
    let TopographyData::Areal(map) = &topo.data else {
        return None;
    };
    let ours = amplitude_statistics(map, Boundary::Open).ok()?.sq;
    let expected = sq_ref * factor;
    Some(if (ours - expected).abs() <= 1e-6 * expected.abs() {
        Ok(())
    } else {
        Err(format!(
            "{name}: Sq {ours:e} m, SurfaceTopography {expected:e} m"
        ))
    })
}

#[test]
fn every_shared_file_is_read_or_refused_for_a_stated_reason() {
    let Some(root) = data_dir() else { return };
    let text = std::fs::read_to_string(root.join("reference_values.json"))
        .unwrap_or_else(|e| panic!("reference_values.json: {e}"));
    let reference: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("reference_values.json: {e}"));
    let all = shared_files(&root);
    let mut problems = Vec::new();
    let mut read = 0;
    let mut compared = Vec::new();
    for path in &all {
        let relative = path.strip_prefix(&root).unwrap_or(path);
        let name = relative.to_string_lossy().replace('\\', "/");
        let refused = REFUSED.iter().find(|(f, _)| *f == name);
        match (read_topography(path), refused) {
            (Ok(topo), None) => {
                read += 1;
                match sq_check(&name, &topo, &reference) {
                    Some(Ok(())) => compared.push(name),
                    Some(Err(message)) => problems.push(message),
                    None => {}
                }
            }
            (Err(_), Some(_)) => {}
            (Ok(_), Some((_, why))) => {
                problems.push(format!("{name}: read, but listed as refused ({why})"))
            }
            (Err(e), None) => problems.push(format!("{name}: {e}")),
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert!(read >= 40, "only {read} files read");
    // The files whose channel, unit and kind let Sq be compared (34 when written).
    assert!(
        compared.len() >= 34,
        "Sq compared for {} files only: {compared:?}",
        compared.len()
    );
}
