//! `surface: {file: {...}}`: a measured topography and its preprocessing into the "S-F" (or
//! "S-L") surface of ISO 25178.
//!
//! The lateral scale comes first: the file's calibration, or `pixel_size`/`size` for a file
//! without one (see [`super::lateral_scale`]; nothing is guessed).
//!
//! Steps, in this order, each optional: crop (pixel window) → decimate (keep every n-th point) →
//! form removal (least-squares polynomial of the given degree; 1 = plane) → S-filter (Gaussian
//! low-pass, removes wavelengths shorter than λs) → L-filter (Gaussian high-pass, removes
//! wavelengths longer than λc) → filling of missing points (harmonic inpainting). The file enters
//! the node key by its content hash, never by its path or modification time.

use std::path::PathBuf;

use serde::Deserialize;

use crate::engine::node::NodeError;
use crate::engine::study::{Param, ResolveContext, SpecError};
use crate::engine::value::Field;
use crate::surface::io::{read_topography, ScaleSource, TopographyData};
use crate::surface::{
    crop, decimate, fill_missing, gaussian_high_pass, gaussian_low_pass, remove_polynomial_form,
    FillOptions, HeightMap, MAX_FORM_DEGREE,
};
use crate::units::{Dimension, Length, Quantity};

use super::lateral_scale::{
    apply_lateral_calibration, calibration_fields, LateralCalibration, LateralLengths,
};
use super::synthetic::positive_length;
use super::{SurfaceSource, SurfaceTask};

/// `surface: {file: {...}}`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FileSpec {
    /// Topography file (x3p, sdf, sur, plu, dat, opd, di, gsf, gwy, al3d, zon, txt/csv, npy);
    /// relative paths are relative to the study file.
    pub path: Param<String>,
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

/// A resolved measured surface.
#[derive(Debug, Clone)]
pub(crate) struct MeasuredSource {
    path: PathBuf,
    /// blake3 of the file's bytes: the file enters the key by content, not by path.
    content_hash: String,
    file_bytes: u64,
    lateral: Option<LateralCalibration>,
    override_file_spacing: bool,
    crop: Option<[usize; 4]>,
    decimate: Option<[usize; 2]>,
    form_degree: Option<usize>,
    s_filter: Option<f64>,
    l_filter: Option<f64>,
    fill: bool,
}

impl FileSpec {
    pub(super) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<SurfaceTask, SpecError> {
        let err = |field: &str, message: String| SpecError {
            location: self.path.location(),
            field: field.to_string(),
            message,
        };
        let written: String = ctx.resolve(&self.path, "file.path")?;
        let path = ctx.study_dir().join(&written);
        let hash = ctx.file_content_hash(&path).map_err(|m| {
            err(
                "file.path",
                format!("{m}; paths are relative to the study file"),
            )
        })?;
        let file_bytes = std::fs::metadata(&path).map_or(0, |m| m.len());
        let (lateral, override_file_spacing) = self.lateral_calibration(ctx)?;
        let crop = match &self.crop {
            Some(c) => {
                let mut v = [0usize; 4];
                for (i, p) in c.iter().enumerate() {
                    v[i] = ctx.resolve(p, &format!("file.crop[{i}]"))?;
                }
                Some(v)
            }
            None => None,
        };
        let decimate = match &self.decimate {
            Some(d) => {
                let step = |n: &usize| {
                    if *n >= 1 {
                        Ok(())
                    } else {
                        Err(String::from("is out of range: the step must be ≥ 1"))
                    }
                };
                let sx = ctx.resolve_checked(&d[0], "file.decimate[0]", step)?;
                let sy = ctx.resolve_checked(&d[1], "file.decimate[1]", step)?;
                Some([sx, sy])
            }
            None => None,
        };
        let form_degree = match &self.form_degree {
            Some(p) => {
                let d = ctx.resolve_checked(p, "file.form_degree", |d: &usize| {
                    if *d <= MAX_FORM_DEGREE {
                        Ok(())
                    } else {
                        Err(format!("is out of range: at most {MAX_FORM_DEGREE}"))
                    }
                })?;
                Some(d)
            }
            None => None,
        };
        let length = |p: &Option<Param<Quantity<Length>>>, field: &str| {
            p.as_ref()
                .map(|p| Ok(ctx.resolve_checked(p, field, positive_length)?.si()))
                .transpose()
        };
        let s_filter = length(&self.s_filter, "file.s_filter")?;
        let l_filter = length(&self.l_filter, "file.l_filter")?;
        if let (Some(s), Some(l)) = (s_filter, l_filter) {
            if s >= l {
                return Err(err(
                    "file.s_filter",
                    format!("λs = {s} m must be shorter than λc = {l} m"),
                ));
            }
        }
        let fill = match &self.fill_missing {
            Some(p) => ctx.resolve(p, "file.fill_missing")?,
            None => false,
        };
        Ok(SurfaceTask {
            source: SurfaceSource::Measured(MeasuredSource {
                path,
                content_hash: hash,
                file_bytes,
                lateral,
                override_file_spacing,
                crop,
                decimate,
                form_degree,
                s_filter,
                l_filter,
                fill,
            }),
        })
    }
}

impl FileSpec {
    /// `pixel_size` or `size` (not both), and `override_file_spacing` (only with one of them).
    fn lateral_calibration(
        &self,
        ctx: &ResolveContext<'_>,
    ) -> Result<(Option<LateralCalibration>, bool), SpecError> {
        let pixel = self
            .pixel_size
            .as_ref()
            .map(|p| ctx.resolve(p, "file.pixel_size"))
            .transpose()?;
        let size = self
            .size
            .as_ref()
            .map(|p| ctx.resolve(p, "file.size"))
            .transpose()?;
        let override_file = self
            .override_file_spacing
            .as_ref()
            .map(|p| ctx.resolve(p, "file.override_file_spacing"))
            .transpose()?;
        let location =
            |p: &Option<Box<Param<_>>>| p.as_ref().map_or(self.path.location(), |p| p.location());
        let lateral = match (pixel, size) {
            (Some(_), Some(_)) => {
                return Err(SpecError {
                    location: location(&self.size),
                    field: String::from("file.size"),
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
                    .map_or(self.path.location(), |p| p.location()),
                field: String::from("file.override_file_spacing"),
                message: String::from(
                    "overrides the file's spacing with `pixel_size` or `size`, and neither is \
                     given",
                ),
            });
        }
        Ok((lateral, override_file.unwrap_or(false)))
    }
}

impl MeasuredSource {
    /// A file levelled by a polynomial of `form_degree` with its missing points filled.
    pub(super) fn levelled_and_filled(
        path: PathBuf,
        content_hash: String,
        form_degree: usize,
    ) -> Self {
        let file_bytes = std::fs::metadata(&path).map_or(0, |m| m.len());
        Self {
            path,
            content_hash,
            file_bytes,
            lateral: None,
            override_file_spacing: false,
            crop: None,
            decimate: None,
            form_degree: Some(form_degree),
            s_filter: None,
            l_filter: None,
            fill: true,
        }
    }

    /// The file read.
    pub(super) fn path(&self) -> &std::path::Path {
        &self.path
    }

    /// blake3 of the file's bytes.
    pub(super) fn content_hash(&self) -> &str {
        &self.content_hash
    }

    /// The key fields of a measured surface: the file by content and every preprocessing step,
    /// in SI. The path (the same bytes may move) and the file size (a memory estimate) are not
    /// part of it.
    pub(super) fn key_fields(&self) -> Vec<Field> {
        let Self {
            path: _,
            content_hash,
            file_bytes: _,
            lateral,
            override_file_spacing,
            crop,
            decimate,
            form_degree,
            s_filter,
            l_filter,
            fill,
        } = self;
        let mut fields = vec![
            Field::text("source", "file"),
            Field::text("file_blake3", content_hash.clone()),
        ];
        if let Some(given) = lateral {
            fields.extend(calibration_fields(*given));
            fields.push(Field::bool("override_file_spacing", *override_file_spacing));
        }
        if let Some(c) = crop {
            for (name, x) in ["crop_ix0", "crop_iy0", "crop_nx", "crop_ny"].iter().zip(c) {
                fields.push(Field::int(*name, *x as i64));
            }
        }
        if let Some([sx, sy]) = decimate {
            fields.push(Field::int("decimate_x", *sx as i64));
            fields.push(Field::int("decimate_y", *sy as i64));
        }
        if let Some(d) = form_degree {
            fields.push(Field::int("form_degree", *d as i64));
        }
        for (name, v) in [("s_filter", s_filter), ("l_filter", l_filter)] {
            if let Some(v) = v {
                fields.push(Field::float(name, *v, Dimension::Length));
            }
        }
        fields.push(Field::bool("fill_missing", *fill));
        fields
    }

    /// Reads and preprocesses the surface.
    pub(super) fn load(&self) -> Result<HeightMap, NodeError> {
        self.load_with_scale_report().map(|(map, _)| map)
    }

    /// Reads and preprocesses the surface; also returns `height_unit_from_file` (the lateral
    /// scale's check needs the surface statistics: [`super::lateral_scale::lateral_scale_warning`]).
    pub(super) fn load_with_scale_report(&self) -> Result<(HeightMap, Vec<Field>), NodeError> {
        let fail = |step: &str, e: &dyn std::fmt::Display| NodeError::new(format!("{step}: {e}"));
        let topography = read_topography(&self.path).map_err(|e| fail("reading", &e))?;
        let height_unit_from_file = topography.height_unit == ScaleSource::File;
        let map = match topography.data {
            TopographyData::Areal(map) => map,
            TopographyData::Line(_) => {
                return Err(NodeError::new(format!(
                    "{} is a line scan; a surface node needs an areal topography",
                    self.path.display()
                )))
            }
        };
        let mut map = apply_lateral_calibration(
            map,
            topography.spacing,
            self.lateral,
            self.override_file_spacing,
            &self.path,
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
        check_not_degenerate(&map, &self.path)?;
        Ok((
            map,
            vec![Field::bool("height_unit_from_file", height_unit_from_file)],
        ))
    }

    /// File size plus working arrays (≈ 8 f64 per point, 4 bytes per stored point assumed).
    pub(super) fn memory_estimate(&self) -> u64 {
        self.file_bytes.saturating_mul(16)
    }
}

/// A map with no valid point, or whose valid heights are all equal, is a broken export (or a
/// wrongly chosen channel), not a surface: the node fails and says so.
fn check_not_degenerate(map: &HeightMap, path: &std::path::Path) -> Result<(), NodeError> {
    let (low, high) = map
        .heights()
        .iter()
        .filter(|z| !z.is_nan())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &z| {
            (lo.min(z), hi.max(z))
        });
    if low > high {
        return Err(NodeError::new(format!(
            "{}: the map has no valid (measured) point after preprocessing; check the file, the \
             channel and the crop",
            path.display()
        )));
    }
    if low == high {
        return Err(NodeError::new(format!(
            "{}: the map is perfectly flat (every valid height is {low:e} m after \
             preprocessing): there is no roughness to measure; for a smooth rigid counter-body \
             leave `upper` out of the contact node",
            path.display()
        )));
    }
    Ok(())
}
