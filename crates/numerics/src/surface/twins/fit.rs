//! The fit of texture statistics against Sq across measured surfaces ([`fit_twin_model`]) and
//! the prediction at a new Sq ([`TwinModel::predict`]).
//!
//! With `Sq_ref` the geometric mean of the measured Sq and `u = ln(Sq / Sq_ref)`:
//! * `ξx(Sq) = ξx_ref · (Sq/Sq_ref)^bx`, `ξy` likewise (power laws: least squares of `ln ξ`
//!   against `u`);
//! * `H(Sq) = H_ref + h · u` (linear in `ln Sq`, least squares).
//!
//! Each fit reports its quality ([`LineFit`]): the root-mean-square residual (of `ln ξ`, i.e. a
//! relative scatter, and of H) and, with three or more surfaces, the coefficient of
//! determination R². A single surface, or surfaces all at the same Sq, give constant fits
//! (exponents 0) and a [`TwinWarning::ConstantFit`].

use super::{
    LineFit, LogLinear, MeasuredTexture, PowerLaw, TwinError, TwinModel, TwinPrediction,
    TwinWarning, HURST_RANGE,
};

/// Fits the statistics of `measured` as functions of Sq (see module docs).
pub fn fit_twin_model(measured: &[MeasuredTexture]) -> Result<TwinModel, TwinError> {
    if measured.is_empty() {
        return Err(TwinError::NoSurfaces);
    }
    check_measurements(measured)?;
    let n = measured.len() as f64;
    let sq_reference = (measured.iter().map(|m| m.sq.ln()).sum::<f64>() / n).exp();
    let u: Vec<f64> = measured
        .iter()
        .map(|m| (m.sq / sq_reference).ln())
        .collect();
    let line = |value: fn(&MeasuredTexture) -> f64| {
        least_squares(&u, &measured.iter().map(value).collect::<Vec<_>>())
    };
    let (ax, bx, fit_x) = line(|m| m.correlation_length_x.ln());
    let (ay, by, fit_y) = line(|m| m.correlation_length_y.ln());
    let (h0, h1, fit_h) = line(|m| m.hurst);
    let min = measured.iter().map(|m| m.sq).fold(f64::INFINITY, f64::min);
    let max = measured.iter().map(|m| m.sq).fold(0.0, f64::max);
    let warnings = if min == max {
        vec![TwinWarning::ConstantFit {
            surfaces: measured.len(),
        }]
    } else {
        Vec::new()
    };
    Ok(TwinModel {
        sq_reference,
        sq_range: (min, max),
        correlation_length_x: PowerLaw {
            at_reference: ax.exp(),
            exponent: bx,
            fit: fit_x,
        },
        correlation_length_y: PowerLaw {
            at_reference: ay.exp(),
            exponent: by,
            fit: fit_y,
        },
        hurst: LogLinear {
            at_reference: h0,
            slope: h1,
            fit: fit_h,
        },
        surfaces: measured.len(),
        warnings,
    })
}

/// Every measured statistic must be finite and positive.
fn check_measurements(measured: &[MeasuredTexture]) -> Result<(), TwinError> {
    for (index, m) in measured.iter().enumerate() {
        for (what, value) in [
            ("sq", m.sq),
            ("correlation_length_x", m.correlation_length_x),
            ("correlation_length_y", m.correlation_length_y),
            ("hurst", m.hurst),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(TwinError::InvalidMeasurement { index, what, value });
            }
        }
    }
    Ok(())
}

/// Least-squares line `y = a + b x` and its quality; a constant (`b = 0`) when all `x` are equal.
pub(super) fn least_squares(x: &[f64], y: &[f64]) -> (f64, f64, LineFit) {
    let n = x.len() as f64;
    let mean_x = x.iter().sum::<f64>() / n;
    let mean_y = y.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|v| (v - mean_x).powi(2)).sum();
    let sxy: f64 = x
        .iter()
        .zip(y)
        .map(|(a, b)| (a - mean_x) * (b - mean_y))
        .sum();
    let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    let intercept = mean_y - slope * mean_x;
    let residual2: f64 = x
        .iter()
        .zip(y)
        .map(|(a, b)| (b - intercept - slope * a).powi(2))
        .sum();
    let total2: f64 = y.iter().map(|b| (b - mean_y).powi(2)).sum();
    let r_squared = (x.len() >= 3 && total2 > 0.0).then(|| 1.0 - residual2 / total2);
    let fit = LineFit {
        rms_residual: (residual2 / n).sqrt(),
        r_squared,
    };
    (intercept, slope, fit)
}

impl TwinModel {
    /// Predicted statistics at `sq` (m), with warnings when extrapolating or clamping.
    pub fn predict(&self, sq: f64) -> Result<TwinPrediction, TwinError> {
        if !(sq.is_finite() && sq > 0.0) {
            return Err(TwinError::InvalidSq(sq));
        }
        let ratio = sq / self.sq_reference;
        let mut warnings = self.warnings.clone();
        let (min, max) = self.sq_range;
        // The geometric mean of one Sq (`sq: measured`) may differ from it in the last bit.
        let round_off = 1e-12;
        if sq < min * (1.0 - round_off) || sq > max * (1.0 + round_off) {
            warnings.push(TwinWarning::Extrapolated { sq, min, max });
        }
        let predicted = self.hurst.at_reference + self.hurst.slope * ratio.ln();
        let hurst = predicted.clamp(HURST_RANGE.0, HURST_RANGE.1);
        if hurst != predicted {
            warnings.push(TwinWarning::HurstClamped {
                predicted,
                used: hurst,
            });
        }
        let law = |p: PowerLaw| p.at_reference * ratio.powf(p.exponent);
        Ok(TwinPrediction {
            sq,
            correlation_length_x: law(self.correlation_length_x),
            correlation_length_y: law(self.correlation_length_y),
            hurst,
            hurst_predicted: predicted,
            warnings,
        })
    }
}
