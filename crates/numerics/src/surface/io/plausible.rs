//! What a topography instrument can have measured, checked on every reader's result
//! ([`super::Reader::parse`]) where the file states the scale: a header field damaged into a
//! value no instrument produces (a spacing of 10³⁰ m, a height scale of zero) is refused with
//! the value and its cause, instead of reaching a study as a surface.
//!
//! * Lateral spacing between 1 pm and 1 m: atomic-resolution scanning probes sample at tens of
//!   picometres, wide-area profilometers at a millimetre or so.
//! * Heights within ±10 m of zero: no profilometer, interferometer, confocal or scanning-probe
//!   instrument has a vertical range of metres (absolute stage heights of centimetres occur,
//!   0.107 m in the shared `hfm-1`, and ISO 5436-2's sample X3P files hold heights near 1 m).
//! * An rms slope (Sdq from forward differences, heights over lateral steps) of at most 100, about
//!   89.4°: no stylus, optical or scanning-probe instrument measures flanks steeper than about
//!   85° (tan 85° ≈ 11), and an rms slope lies below the largest one; the steepest shared files,
//!   the synthetic ISO 5436-2 x3p samples, reach 37 (central differences). A height scale or a
//!   spacing damaged by orders of magnitude (one flipped exponent bit) gives slopes of thousands
//!   while heights and spacing each stay in their ranges; this check needs both scales from the
//!   file.
//! * Not every height the same: a measured surface is never exactly flat, while a zeroed height
//!   scale or blank data make it so.
//!
//! A reader that assumes a scale the file does not state ([`ScaleSource::Assumed`]) is not
//! checked for it: the caller replaces the placeholder.

use super::{ParseError, ScaleSource, Topography, TopographyData};

/// Largest plausible rms slope (dimensionless, module doc).
pub(crate) const SLOPE_LIMIT: f64 = 100.0;

/// Smallest and largest plausible lateral spacing, metres.
pub(crate) const SPACING_RANGE: (f64, f64) = (1e-12, 1.0);
/// Largest plausible magnitude of a height, metres.
pub(crate) const HEIGHT_LIMIT: f64 = 10.0;

/// `Ok` when the scales `topography` takes from its file are plausible (module doc).
pub(crate) fn check(topography: &Topography) -> Result<(), ParseError> {
    if topography.spacing == ScaleSource::File {
        check_spacing(&topography.data)?;
    }
    if topography.height_unit == ScaleSource::File {
        let heights: Box<dyn Iterator<Item = f64> + '_> = match &topography.data {
            TopographyData::Areal(map) => Box::new(map.heights().iter().copied()),
            TopographyData::Line(line) => Box::new(line.z.iter().copied()),
        };
        check_heights(heights)?;
    }
    if topography.spacing == ScaleSource::File && topography.height_unit == ScaleSource::File {
        check_slope(&topography.data)?;
    }
    Ok(())
}

fn check_spacing(data: &TopographyData) -> Result<(), ParseError> {
    let steps = match data {
        TopographyData::Areal(map) => vec![("dx", map.dx()), ("dy", map.dy())],
        TopographyData::Line(line) => match (line.x.first(), line.x.last()) {
            (Some(first), Some(last)) if line.x.len() > 1 => {
                vec![("mean x step", (last - first) / (line.x.len() - 1) as f64)]
            }
            _ => Vec::new(),
        },
    };
    let (lo, hi) = SPACING_RANGE;
    match steps.iter().find(|(_, d)| !(lo..=hi).contains(d)) {
        Some((name, d)) => Err(ParseError::malformed(format!(
            "the header's lateral scale gives {name} = {d:e} m, outside what an instrument \
             samples ({lo:e} to {hi:e} m): a damaged spacing or unit field"
        ))),
        None => Ok(()),
    }
}

fn check_heights(heights: impl Iterator<Item = f64>) -> Result<(), ParseError> {
    let (mut count, mut lo, mut hi) = (0usize, f64::INFINITY, f64::NEG_INFINITY);
    for z in heights.filter(|z| !z.is_nan()) {
        count += 1;
        lo = lo.min(z);
        hi = hi.max(z);
    }
    if count == 0 {
        return Ok(());
    }
    if lo < -HEIGHT_LIMIT || hi > HEIGHT_LIMIT {
        return Err(ParseError::malformed(format!(
            "the header's height scale gives heights from {lo:e} to {hi:e} m, beyond the ±{} m \
             an instrument measures: a damaged height scale, offset or unit field",
            HEIGHT_LIMIT
        )));
    }
    if count > 1 && lo == hi {
        return Err(ParseError::malformed(format!(
            "all {count} heights are {lo:e} m: a measured surface is never exactly flat, the \
             file's height scale is zero or its data are blank (a damaged header or data block)"
        )));
    }
    Ok(())
}

fn check_slope(data: &TopographyData) -> Result<(), ParseError> {
    let slope = match data {
        TopographyData::Areal(map) => {
            let z = map.heights();
            let along_x = z
                .windows((1, 2))
                .into_iter()
                .map(|w| (w[[0, 1]] - w[[0, 0]]) / map.dx());
            let along_y = z
                .windows((2, 1))
                .into_iter()
                .map(|w| (w[[1, 0]] - w[[0, 0]]) / map.dy());
            mean_square_slope(along_x) + mean_square_slope(along_y)
        }
        TopographyData::Line(line) => {
            mean_square_slope(line.x.windows(2).zip(line.z.windows(2)).map(|(x, z)| {
                if x[1] > x[0] {
                    (z[1] - z[0]) / (x[1] - x[0])
                } else {
                    f64::NAN
                }
            }))
        }
    }
    .sqrt();
    if slope > SLOPE_LIMIT {
        return Err(ParseError::malformed(format!(
            "the header's scales give an rms slope of {slope:e} (height differences over the \
             lateral steps, {:.2}°), steeper than any instrument measures (at most \
             {SLOPE_LIMIT}): a damaged height scale or spacing field, or heights and spacing in \
             other units than the header states",
            slope.atan().to_degrees()
        )));
    }
    Ok(())
}

/// Mean of the squared finite `slopes` (0 when there are none): a slope next to a missing
/// point is NaN and left out.
fn mean_square_slope(slopes: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut count) = (0.0, 0usize);
    for slope in slopes.filter(|s| s.is_finite()) {
        sum += slope * slope;
        count += 1;
    }
    if count == 0 {
        0.0
    } else {
        sum / count as f64
    }
}
