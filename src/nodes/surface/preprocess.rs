//! The preprocessing of a measured topography into the "S-F" (or "S-L") surface of ISO 25178,
//! shared by `surface: {file: ...}` and the measured files of `surface: {twin: ...}`: one spec
//! ([`PreprocessSpec`]), one resolution with its checks, one resolved form ([`Preprocessing`])
//! with its key fields, and one application ([`Preprocessing::apply`]).
//!
//! The height unit comes first (the file's, or `height_unit` for a file without one, see
//! [`super::height_unit`]), then the lateral scale: the file's calibration, or `pixel_size`/`size` for a file
//! without one (see [`super::lateral_scale`]; nothing is guessed). Then, in this order, each
//! optional: crop (pixel window) → decimate (keep every n-th point) → form removal
//! (least-squares polynomial of the given degree; 1 = plane) → S-filter (Gaussian low-pass,
//! removes wavelengths shorter than λs) → L-filter (Gaussian high-pass, removes wavelengths
//! longer than λc) → filling of missing points (harmonic inpainting).

use std::path::Path;

use serde::Deserialize;

use crate::engine::node::NodeError;
use crate::engine::study::{Param, ResolveContext, SourceLocation, SpecError};
use crate::engine::value::Field;
use crate::surface::io::ScaleSource;
use crate::surface::{
    crop, decimate, fill_missing, gaussian_high_pass, gaussian_low_pass, remove_polynomial_form,
    FillOptions, HeightMap, MAX_FORM_DEGREE,
};
use crate::units::{Dimension, Length, Quantity};
use crate::vocabulary::surface_parameters::{
    CROP, DECIMATE_X, DECIMATE_Y, FILL_MISSING, FORM_DEGREE, HEIGHT_UNIT, L_FILTER,
    OVERRIDE_FILE_SPACING, S_FILTER,
};

use super::height_unit::{apply_height_unit, HeightUnit, HeightUnitSource};
use super::lateral_scale::{
    apply_lateral_calibration, calibration_fields, LateralCalibration, LateralLengths,
};
use super::synthetic::positive_length;

/// Declares a spec struct: its own leading fields, then the preprocessing fields that
/// `surface: {file: ...}` and `twin.preprocess` share — declared once, here — and
/// `preprocess_fields()`, the borrowed view every resolution goes through. (A `#[serde(flatten)]`
/// field would share them too, but flattening buffers the YAML and loses the line and column of
/// every error inside it.)
macro_rules! with_preprocessing_fields {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $($(#[$field_meta:meta])* pub $field:ident: $ty:ty,)*
        }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $($(#[$field_meta])* pub $field: $ty,)*
        /// Pixel size: one length (square pixels) or `[dx, dy]`. Required for a file without a
        /// lateral calibration (npy, a bare text/CSV matrix, a GSF without `XReal`/`YReal`); for a
        /// calibrated file it must agree with the file to 1e-6 (or set `override_file_spacing`).
        #[serde(default)]
        pub pixel_size: Option<Box<Param<LateralLengths>>>,
        /// Instead of `pixel_size`: the size of the whole map as read, one length (square) or
        /// `[Lx, Ly]`; dx = Lx/nx, dy = Ly/ny.
        #[serde(default)]
        pub size: Option<Box<Param<LateralLengths>>>,
        /// Use `pixel_size`/`size` although the file's own calibration differs. Default: false.
        #[serde(default)]
        pub override_file_spacing: Option<Box<Param<bool>>>,
        /// Height unit of a file that stores none (npy, a bare text/CSV matrix): a length unit
        /// (`um`, `nm`, `m`) or the length one stored value stands for (`0.1 nm`). Without it
        /// such a file is read as metres and its row is flagged; a file that states its unit
        /// refuses it.
        #[serde(default)]
        pub height_unit: Option<Box<Param<super::height_unit::HeightUnit>>>,
        /// Pixel window `[ix0, iy0, nx, ny]`.
        #[serde(default)]
        pub crop: Option<[Param<usize>; 4]>,
        /// Keep every `[sx, sy]`-th point (integer decimation, no smoothing: combine with `s_filter`).
        #[serde(default)]
        pub decimate: Option<[Param<usize>; 2]>,
        /// Degree of the least-squares polynomial form removed (0: mean, 1: plane/tilt, 2: curvature).
        #[serde(default)]
        pub form_degree: Option<Param<usize>>,
        /// S-filter nesting index λs (length): Gaussian low-pass removing short-scale noise.
        #[serde(default)]
        pub s_filter: Option<Param<Quantity<Length>>>,
        /// L-filter nesting index λc (length): Gaussian high-pass removing waviness and form.
        #[serde(default)]
        pub l_filter: Option<Param<Quantity<Length>>>,
        /// Fill missing points by harmonic inpainting (needed before contact). Default: false.
        #[serde(default)]
        pub fill_missing: Option<Param<bool>>,
        }

        impl $name {
            /// The preprocessing fields, borrowed.
            pub(crate) fn preprocess_fields(&self) -> super::preprocess::PreprocessFields<'_> {
                super::preprocess::PreprocessFields {
                    pixel_size: &self.pixel_size,
                    size: &self.size,
                    override_file_spacing: &self.override_file_spacing,
                    height_unit: &self.height_unit,
                    crop: &self.crop,
                    decimate: &self.decimate,
                    form_degree: &self.form_degree,
                    s_filter: &self.s_filter,
                    l_filter: &self.l_filter,
                    fill_missing: &self.fill_missing,
                }
            }
        }
    };
}
pub(crate) use with_preprocessing_fields;

with_preprocessing_fields! {
    /// The preprocessing fields of a measured topography (`twin.preprocess`).
    #[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    pub struct PreprocessSpec {}
}

/// The preprocessing fields of a spec, borrowed ([`with_preprocessing_fields`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PreprocessFields<'a> {
    pub(super) pixel_size: &'a Option<Box<Param<LateralLengths>>>,
    pub(super) size: &'a Option<Box<Param<LateralLengths>>>,
    pub(super) override_file_spacing: &'a Option<Box<Param<bool>>>,
    pub(super) height_unit: &'a Option<Box<Param<HeightUnit>>>,
    pub(super) crop: &'a Option<[Param<usize>; 4]>,
    pub(super) decimate: &'a Option<[Param<usize>; 2]>,
    pub(super) form_degree: &'a Option<Param<usize>>,
    pub(super) s_filter: &'a Option<Param<Quantity<Length>>>,
    pub(super) l_filter: &'a Option<Param<Quantity<Length>>>,
    pub(super) fill_missing: &'a Option<Param<bool>>,
}

/// Resolved preprocessing, in SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Preprocessing {
    pub lateral: Option<LateralCalibration>,
    pub override_file_spacing: bool,
    /// m per stored height value, for a file without a height unit.
    pub height_unit: Option<f64>,
    pub crop: Option<[usize; 4]>,
    pub decimate: Option<[usize; 2]>,
    pub form_degree: Option<usize>,
    pub s_filter: Option<f64>,
    pub l_filter: Option<f64>,
    pub fill: bool,
}

/// What a preprocessing step does when its field is absent.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PreprocessDefaults {
    pub form_degree: Option<usize>,
    pub fill_missing: bool,
}

impl PreprocessDefaults {
    /// `surface: {file: ...}`: every step off.
    pub(crate) const FILE: Self = Self {
        form_degree: None,
        fill_missing: false,
    };
    /// The files of a twin: levelled by a plane and filled (the texture is measured on complete
    /// maps).
    pub(crate) const TWIN: Self = Self {
        form_degree: Some(1),
        fill_missing: true,
    };
}

impl PreprocessFields<'_> {
    /// Resolves and checks the fields; errors name `<prefix>.<field>` and point at `at` when the
    /// field itself has no location.
    pub(crate) fn resolve(
        self,
        ctx: &ResolveContext<'_>,
        at: SourceLocation,
        prefix: &str,
        defaults: PreprocessDefaults,
    ) -> Result<Preprocessing, SpecError> {
        let (lateral, override_file_spacing) = self.lateral_calibration(ctx, at, prefix)?;
        let height_unit = self
            .height_unit
            .as_ref()
            .map(|p| ctx.resolve(p, &format!("{prefix}.height_unit")))
            .transpose()?
            .map(|HeightUnit(u)| u);
        let crop = self.crop_window(ctx, prefix)?;
        let decimate = self.decimation(ctx, prefix)?;
        let form_degree = match self.form_degree {
            Some(p) => {
                Some(
                    ctx.resolve_checked(p, &format!("{prefix}.form_degree"), |d: &usize| {
                        if *d <= MAX_FORM_DEGREE {
                            Ok(())
                        } else {
                            Err(format!("is out of range: at most {MAX_FORM_DEGREE}"))
                        }
                    })?,
                )
            }
            None => defaults.form_degree,
        };
        let (s_filter, l_filter) = self.filters(ctx, at, prefix)?;
        let fill = match self.fill_missing {
            Some(p) => ctx.resolve(p, &format!("{prefix}.fill_missing"))?,
            None => defaults.fill_missing,
        };
        Ok(Preprocessing {
            lateral,
            override_file_spacing,
            height_unit,
            crop,
            decimate,
            form_degree,
            s_filter,
            l_filter,
            fill,
        })
    }

    fn crop_window(
        self,
        ctx: &ResolveContext<'_>,
        prefix: &str,
    ) -> Result<Option<[usize; 4]>, SpecError> {
        let Some(c) = self.crop else {
            return Ok(None);
        };
        let mut v = [0usize; 4];
        for (i, p) in c.iter().enumerate() {
            v[i] = ctx.resolve(p, &format!("{prefix}.crop[{i}]"))?;
        }
        Ok(Some(v))
    }

    fn decimation(
        self,
        ctx: &ResolveContext<'_>,
        prefix: &str,
    ) -> Result<Option<[usize; 2]>, SpecError> {
        let Some(d) = self.decimate else {
            return Ok(None);
        };
        let step = |n: &usize| {
            if *n >= 1 {
                Ok(())
            } else {
                Err(String::from("is out of range: the step must be ≥ 1"))
            }
        };
        let sx = ctx.resolve_checked(&d[0], &format!("{prefix}.decimate[0]"), step)?;
        let sy = ctx.resolve_checked(&d[1], &format!("{prefix}.decimate[1]"), step)?;
        Ok(Some([sx, sy]))
    }

    /// λs and λc (m), λs < λc when both are given.
    fn filters(
        self,
        ctx: &ResolveContext<'_>,
        at: SourceLocation,
        prefix: &str,
    ) -> Result<(Option<f64>, Option<f64>), SpecError> {
        let length = |p: &Option<Param<Quantity<Length>>>, field: &str| {
            p.as_ref()
                .map(|p| {
                    Ok(ctx
                        .resolve_checked(p, &format!("{prefix}.{field}"), positive_length)?
                        .si())
                })
                .transpose()
        };
        let s_filter = length(self.s_filter, "s_filter")?;
        let l_filter = length(self.l_filter, "l_filter")?;
        if let (Some(s), Some(l)) = (s_filter, l_filter) {
            if s >= l {
                return Err(SpecError {
                    location: self.s_filter.as_ref().map_or(at, |p| p.location()),
                    field: format!("{prefix}.s_filter"),
                    message: format!("λs = {s} m must be shorter than λc = {l} m"),
                });
            }
        }
        Ok((s_filter, l_filter))
    }

    /// `pixel_size` or `size` (not both), and `override_file_spacing` (only with one of them).
    fn lateral_calibration(
        self,
        ctx: &ResolveContext<'_>,
        at: SourceLocation,
        prefix: &str,
    ) -> Result<(Option<LateralCalibration>, bool), SpecError> {
        let pixel = self
            .pixel_size
            .as_ref()
            .map(|p| ctx.resolve(p, &format!("{prefix}.pixel_size")))
            .transpose()?;
        let size = self
            .size
            .as_ref()
            .map(|p| ctx.resolve(p, &format!("{prefix}.size")))
            .transpose()?;
        let override_file = self
            .override_file_spacing
            .as_ref()
            .map(|p| ctx.resolve(p, &format!("{prefix}.override_file_spacing")))
            .transpose()?;
        let location = |p: &Option<Box<Param<_>>>| p.as_ref().map_or(at, |p| p.location());
        let lateral = match (pixel, size) {
            (Some(_), Some(_)) => {
                return Err(SpecError {
                    location: location(self.size),
                    field: String::from(&format!("{prefix}.size")),
                    message: String::from(
                        "give the pixel size or the map size, not both (remove `size` or \
                         `pixel_size`)",
                    ),
                })
            }
            (Some(LateralLengths(d)), None) => Some(LateralCalibration::PixelSize(d)),
            (None, Some(LateralLengths(l))) => Some(LateralCalibration::Size(l)),
            (None, None) => None,
        };
        if lateral.is_none() && override_file.is_some() {
            return Err(SpecError {
                location: self
                    .override_file_spacing
                    .as_ref()
                    .map_or(at, |p| p.location()),
                field: String::from(&format!("{prefix}.override_file_spacing")),
                message: String::from(
                    "overrides the file's spacing with `pixel_size` or `size`, and neither is \
                     given",
                ),
            });
        }
        Ok((lateral, override_file.unwrap_or(false)))
    }
}

impl Preprocessing {
    /// The key fields of the preprocessing, in SI.
    pub(crate) fn key_fields(&self) -> Vec<Field> {
        let Self {
            lateral,
            override_file_spacing,
            height_unit,
            crop,
            decimate,
            form_degree,
            s_filter,
            l_filter,
            fill,
        } = *self;
        let mut fields = Vec::new();
        if let Some(given) = lateral {
            fields.extend(calibration_fields(given));
            fields.push(Field::bool(OVERRIDE_FILE_SPACING, override_file_spacing));
        }
        if let Some(unit) = height_unit {
            fields.push(Field::float(HEIGHT_UNIT, unit, Dimension::Length));
        }
        if let Some(c) = crop {
            for (name, x) in CROP.iter().zip(c) {
                fields.push(Field::int(*name, x as i64));
            }
        }
        if let Some([sx, sy]) = decimate {
            fields.push(Field::int(DECIMATE_X, sx as i64));
            fields.push(Field::int(DECIMATE_Y, sy as i64));
        }
        if let Some(d) = form_degree {
            fields.push(Field::int(FORM_DEGREE, d as i64));
        }
        for (name, v) in [(S_FILTER, s_filter), (L_FILTER, l_filter)] {
            if let Some(v) = v {
                fields.push(Field::float(name, v, Dimension::Length));
            }
        }
        fields.push(Field::bool(FILL_MISSING, fill));
        fields
    }

    /// The height unit, the lateral calibration and every step, in order, on the map read from
    /// `path` with the spacing and height unit `scale` says the file gave (`[spacing, height
    /// unit]`); also where the height unit came from and, when it was assumed, the flag.
    pub(crate) fn apply(
        &self,
        map: HeightMap,
        [spacing, height_unit]: [ScaleSource; 2],
        path: &Path,
    ) -> Result<Preprocessed, NodeError> {
        let fail = |step: &str, e: &dyn std::fmt::Display| NodeError::new(format!("{step}: {e}"));
        let (map, height_unit_source, flag) =
            apply_height_unit(map, height_unit, self.height_unit, path)?;
        let mut map = apply_lateral_calibration(
            map,
            spacing,
            self.lateral,
            self.override_file_spacing,
            path,
        )?;
        if let Some([ix0, iy0, nx, ny]) = self.crop {
            map = crop(&map, ix0, iy0, nx, ny).map_err(|e| fail("crop", &e))?;
        }
        if let Some([sx, sy]) = self.decimate {
            map = decimate(&map, sx, sy).map_err(|e| fail("decimate", &e))?;
        }
        if let Some(degree) = self.form_degree {
            map = remove_polynomial_form(&map, degree)
                .map_err(|e| fail("form removal", &e))?
                .surface;
        }
        if let Some(ls) = self.s_filter {
            map = gaussian_low_pass(&map, ls).map_err(|e| fail("S-filter", &e))?;
        }
        if let Some(lc) = self.l_filter {
            map = gaussian_high_pass(&map, lc).map_err(|e| fail("L-filter", &e))?;
        }
        if self.fill {
            map = fill_missing(&map, FillOptions::default())
                .map_err(|e| fail("filling missing points", &e))?
                .surface;
        }
        Ok(Preprocessed {
            map,
            height_unit_source,
            flag,
        })
    }
}

/// A preprocessed map and where its height unit came from.
pub(crate) struct Preprocessed {
    pub map: HeightMap,
    pub height_unit_source: HeightUnitSource,
    /// The sentence that flags the row when the height unit was assumed.
    pub flag: Option<String>,
}
