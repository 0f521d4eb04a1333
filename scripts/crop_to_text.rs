//! Writes a pixel window of a topography file as a Gwyddion-style text matrix (calibrated: the
//! header gives the width, height and value unit), the format of the measured-pairs example data
//! in `studies/data/measured-pairs/` (see its README for the exact calls).
//!
//! Run: `cargo run --example crop_to_text -- IN IX0 IY0 NX NY OUT`

use std::fmt::Write as _;
use std::process::ExitCode;

use asperity::surface::crop;
use asperity::surface::io::{read_topography, ScaleSource, TopographyData};

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("crop_to_text: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, ix0, iy0, nx, ny, out] = args.as_slice() else {
        return Err(String::from("usage: crop_to_text IN IX0 IY0 NX NY OUT"));
    };
    let index = |s: &String| s.parse::<usize>().map_err(|e| format!("'{s}': {e}"));
    let topography = read_topography(input.as_ref()).map_err(|e| e.to_string())?;
    if topography.spacing != ScaleSource::File || topography.height_unit != ScaleSource::File {
        return Err(format!(
            "{input} is not calibrated; the example needs a calibrated file"
        ));
    }
    let TopographyData::Areal(map) = topography.data else {
        return Err(format!("{input} is a line scan"));
    };
    let window =
        crop(&map, index(ix0)?, index(iy0)?, index(nx)?, index(ny)?).map_err(|e| e.to_string())?;
    let (width, height) = window.size();
    let mut text = format!(
        "# Channel: Height\n# Width: {:.9e} m\n# Height: {:.9e} m\n# Value units: m\n",
        width, height
    );
    for row in window.heights().rows() {
        let cells: Vec<String> = row.iter().map(|z| format!("{z:.6e}")).collect();
        let _ = writeln!(text, "{}", cells.join("\t"));
    }
    std::fs::write(out, text).map_err(|e| format!("cannot write {out}: {e}"))
}
