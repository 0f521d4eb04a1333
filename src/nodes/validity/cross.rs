//! The validity checks that compare two inputs or two columns, each one function, called by the
//! node kind that has both values, and listed in [`CHECKS`] for the documentation.

use super::{Range, MAX_UNTRUSTED_LOAD_SHARE};
use crate::units::format_number;
use crate::vocabulary::kinds::{CONTACT, FRICTION, SURFACE};
use crate::vocabulary::metrics as names;

/// One cross-input check, as documented.
pub struct CrossCheck {
    pub kind: &'static str,
    pub columns: &'static str,
    pub rule: &'static str,
    pub outcome: &'static str,
    pub why: &'static str,
}

/// Least points a side of a contact grid for spot and summit statistics: a spot resolved by more
/// than one pixel (2 points across) with the one-point ring its radius is fitted over spans 4
/// points, and two such spots that do not touch across the periodic edge need 8. Fewer, and no
/// section holds two resolved spots.
pub const MIN_GRID: usize = 8;

/// Largest rms slope Sdq of the composite surface the half-space contact solution is taken to
/// hold for. Linear elasticity of a half-space applies loads and displacements on the mean plane
/// and neglects terms of order s² in the slope s: a slope tilts the true normal by atan(s), so a
/// normal pressure is off by 1 − 1/√(1+s²) — 10.6 % at s = 0.5, the limit of a 10 % correction.
pub const MAX_SLOPE: f64 = 0.5;

/// Mismatch of flow pressures above which a friction node flags its contact input (1 %).
pub const FLOW_PRESSURE_FLAG: f64 = 0.01;

/// Ratio of flow pressures above which a friction node refuses its contact input: surface-layer
/// and ultra-micro hardness exceed the bulk hardness by up to about 3×, so a factor of 10 is an
/// input error, not a material property.
pub const FLOW_PRESSURE_FAIL: f64 = 10.0;

/// The cross-input checks, as the documentation lists them.
pub const CHECKS: &[CrossCheck] = &[
    CrossCheck {
        kind: SURFACE,
        columns: "`sq_m` against the map's size",
        rule: "Sq ≤ the larger side nx·dx, ny·dy",
        outcome: "flagged",
        why: "heights larger than the field of view are no surface texture: the height unit or the file is wrong (e.g. a header from another file)",
    },
    CrossCheck {
        kind: CONTACT,
        columns: "grid of the upstream surfaces",
        rule: "≥ 8 points a side",
        outcome: "flagged",
        why: "a spot of more than one pixel with its one-point ring spans 4 points, two such spots 8: a coarser grid resolves no contact spot (friction per spot or per summit fails there)",
    },
    CrossCheck {
        kind: CONTACT,
        columns: "`sdq` of the surfaces, √(Sdq₁² + Sdq₂²)",
        rule: "≤ 0.5",
        outcome: "flagged",
        why: "the half-space solution neglects terms of order s² in the slope s: the true normal is tilted by atan(s), a normal pressure off by 1 − 1/√(1+s²), 10.6 % at 0.5 (ground steel sampled at 0.5 µm has Sdq 0.5–0.8 and is flagged)",
    },
    CrossCheck {
        kind: FRICTION,
        columns: "`nominal_pressure_Pa` against H of the softer body",
        rule: "p_nom ≤ H (also at `validate` for `nominal_pressures`)",
        outcome: "fails",
        why: "equilibrium needs A/A₀ ≥ p_nom/p_lim with p_lim = H, so p_nom > H would need more real area than nominal area",
    },
    CrossCheck {
        kind: FRICTION,
        columns: "per summit, per spot: the contact's flow pressure against H of the friction materials",
        rule: "within 1 % (flag), within a factor of 10 (at `validate`)",
        outcome: "flagged / fails",
        why: "the contact solution caps pressures at its flow pressure while the friction laws use H: surface-layer hardness exceeds bulk by up to ~3×, so a factor of 10 is an input error; an elastic contact (no flow pressure) is flagged",
    },
    CrossCheck {
        kind: FRICTION,
        columns: "per summit, per spot: the contact's grid",
        rule: "≥ 8 points a side",
        outcome: "fails",
        why: "summits need the 8-neighbourhood and spots a ring around them; below 8 points no section holds two resolved spots",
    },
    CrossCheck {
        kind: FRICTION,
        columns: "grid of the surfaces (statistical method)",
        rule: "≥ 8 points a side",
        outcome: "failed",
        why: "the spectral moments m2, m4 are finite differences of the heights: a coarser grid gives summit statistics of a few differences, not of a surface",
    },
    CrossCheck {
        kind: FRICTION,
        columns: "`load_share_beyond_fit` against the row's law",
        rule: "≤ 0.5",
        outcome: "flagged",
        why: "more than half the load lies beyond the validated range of the row's law, which the sentence names with where its range ends (KE: x = 6, CEB: x = 1, full stick: ω* = 110, ploughing: each spot's loaded front; docs/friction-models.md): μ_s is mostly the law's extrapolation, not its fit",
    },
];

/// Friction: a flag when more than [`MAX_UNTRUSTED_LOAD_SHARE`] of the row's load lies beyond
/// the validated range of its law `law`, named with `range` (where that range ends,
/// [`crate::friction::LawDescriptor::validated_range`]).
pub fn load_beyond_fit(share: f64, law: &str, range: &str) -> Option<String> {
    (!Range::AtMost(MAX_UNTRUSTED_LOAD_SHARE).contains(share)).then(|| {
        format!(
            "`{}` = {}: more than half the load lies beyond the validated range of `model: \
             {law}` ({range}): μ_s is mostly the law's extrapolation, not its fit",
            names::LOAD_SHARE_BEYOND_FIT,
            format_number(share)
        )
    })
}

/// Surface: Sq against the larger side of the map; a flag when the heights exceed the field of
/// view.
pub fn surface_size(sq: f64, lx: f64, ly: f64) -> Option<String> {
    let side = lx.max(ly);
    (sq > side).then(|| {
        format!(
            "`sq_m` = {} exceeds the map's larger side {} m: heights larger than the field of \
             view are no surface texture; check the height unit and the file (a header from \
             another file?)",
            format_number(sq),
            format_number(side)
        )
    })
}

/// Contact: a flag when the grid has fewer than [`MIN_GRID`] points a side.
pub fn contact_grid(nx: usize, ny: usize) -> Option<String> {
    (nx.min(ny) < MIN_GRID).then(|| {
        format!(
            "the {nx}×{ny} grid resolves no contact spot (at least {MIN_GRID} points a side are \
             needed for two spots of more than one pixel): use a finer grid"
        )
    })
}

/// Contact: a flag when the rms slope of the composite surface, √(Sdq₁² + Sdq₂²) for
/// uncorrelated surfaces, exceeds [`MAX_SLOPE`].
pub fn contact_slope(sdq: &[f64]) -> Option<String> {
    let s = sdq.iter().map(|s| s * s).sum::<f64>().sqrt();
    (s > MAX_SLOPE).then(|| {
        format!(
            "the composite rms slope Sdq = {} exceeds {MAX_SLOPE}, beyond the small-slope \
             assumption of the half-space contact solution: the values are the linear theory's, \
             not the surface's (check the lateral scale and the height unit)",
            format_number(round3(s))
        )
    })
}

/// `x` to three significant digits, for ratios in sentences.
fn round3(x: f64) -> f64 {
    format!("{x:.2e}").parse().unwrap_or(x)
}

/// Friction: the nominal pressure must not exceed the flow pressure H of the softer body.
pub fn pressure_within_flow(nominal_pressure: f64, hardness: f64) -> Result<(), String> {
    if nominal_pressure <= hardness {
        return Ok(());
    }
    Err(format!(
        "the nominal pressure {} Pa exceeds the flow pressure H = {} Pa of the softer body: \
         equilibrium needs a real contact area of p_nom/H = {} times the nominal area, more than \
         there is; lower the load or check its unit",
        format_number(nominal_pressure),
        format_number(hardness),
        format_number(round3(nominal_pressure / hardness))
    ))
}

/// Friction per summit or per spot: the contact's flow pressure against the friction
/// materials' H. `Err` beyond a factor of [`FLOW_PRESSURE_FAIL`], `Ok(Some(flag))` beyond
/// [`FLOW_PRESSURE_FLAG`] or for an elastic contact, `Ok(None)` when they agree.
pub fn flow_pressure_match(contact: f64, hardness: f64) -> Result<Option<String>, String> {
    let both = format!(
        "the contact node solved with a flow pressure of {} Pa, the friction laws use H = {} Pa \
         of the softer body",
        format_number(contact),
        format_number(hardness)
    );
    if !contact.is_finite() {
        return Ok(Some(format!(
            "the contact node was solved purely elastic (no flow pressure), the friction laws \
             use H = {} Pa of the softer body: local pressures may exceed H; give the contact \
             node the friction node's materials or a `flow_pressure`",
            format_number(hardness)
        )));
    }
    let ratio = contact.max(hardness) / contact.min(hardness);
    if ratio > FLOW_PRESSURE_FAIL {
        return Err(format!(
            "{both}, a factor of {} apart (more than {FLOW_PRESSURE_FAIL}: surface-layer hardness \
             exceeds bulk by up to about 3×, so this is an input error); give both nodes the \
             same material or make `flow_pressure` match its hardness",
            format_number(round3(ratio))
        ));
    }
    Ok((ratio - 1.0 > FLOW_PRESSURE_FLAG).then(|| {
        format!(
            "{both}, {} % apart: the spots' pressures and the laws' hardness disagree",
            format_number(((ratio - 1.0) * 1000.0).round() / 10.0)
        )
    }))
}

/// Friction per summit or per spot: the contact grid must have [`MIN_GRID`] points a side.
pub fn friction_grid(nx: usize, ny: usize) -> Result<(), String> {
    if nx.min(ny) >= MIN_GRID {
        return Ok(());
    }
    Err(format!(
        "the contact's {nx}×{ny} grid is too coarse to resolve a contact spot or a summit's \
         8-neighbourhood (at least {MIN_GRID} points a side): use a finer grid"
    ))
}

/// Statistical friction from surfaces: the spectral moments m2, m4 (finite differences of the
/// heights) describe summits only on a grid of at least [`MIN_GRID`] points a side.
pub fn moments_grid(nx: usize, ny: usize) -> Result<(), String> {
    if nx.min(ny) >= MIN_GRID {
        return Ok(());
    }
    Err(format!(
        "the surface's {nx}×{ny} grid is too coarse for summit statistics: its slopes and \
         curvatures (spectral moments m2, m4) come from a few differences (at least {MIN_GRID} \
         points a side): use a finer grid or give `roughness` explicitly"
    ))
}
