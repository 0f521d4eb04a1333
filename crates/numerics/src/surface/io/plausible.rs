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
//! * Not every height the same: a measured surface is never exactly flat, while a zeroed height
//!   scale or blank data make it so.
//!
//! A reader that assumes a scale the file does not state ([`ScaleSource::Assumed`]) is not
//! checked for it: the caller replaces the placeholder.

use super::{ParseError, ScaleSource, Topography, TopographyData};

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
