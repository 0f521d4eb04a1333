//! `surface: {file: {...}}`: a measured topography and its preprocessing
//! ([`super::preprocess`]) into the "S-F" (or "S-L") surface of ISO 25178. The file enters the
//! node key by its content hash, never by its path or modification time.

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use serde::Deserialize;

use crate::engine::node::NodeError;
use crate::engine::study::{Param, ResolveContext, SpecError};
use crate::engine::value::Field;
use crate::surface::io::{
    declared_points, read_topography_channel, supported_formats, TopographyData,
};
use crate::surface::HeightMap;

use super::lateral_scale::LateralLengths;
use super::preprocess::{
    with_preprocessing_fields, PreprocessDefaults, Preprocessed, Preprocessing,
};
use super::{SurfaceSource, SurfaceTask};
use crate::units::{Length, Quantity};
use crate::vocabulary::surface_parameters::{CHANNEL, FILE_BLAKE3, SOURCE};

with_preprocessing_fields! {
    /// `surface: {file: {...}}`.
    #[derive(Debug, Deserialize, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    pub struct FileSpec {
        /// Topography file in any format `asperity inspect` reads; relative paths are relative
        /// to the study file. The schema's text lists the formats of the reader registry
        /// ([`path_description`]).
        #[schemars(description = path_description())]
        pub path: Param<String>,
        /// The channel to read from a file holding several (height, amplitude, phase, …), by
        /// name as `asperity inspect` lists it (ASCII case ignored). Default: the file's height
        /// channel. A name the file does not hold is an error listing its channels.
        #[serde(default)]
        pub channel: Option<Param<String>>,
    }
}

/// The schema text of `file.path`, built from the reader registry (`READERS`): every format
/// with its extensions, so the schema never lists formats the readers do not have.
fn path_description() -> String {
    format!(
        "Topography file in any format `asperity inspect` reads: {} (docs/study-format.md, \
         \"Topography formats\"); relative paths are relative to the study file.",
        supported_formats()
    )
}

/// A measured file, found and hashed.
#[derive(Debug, Clone)]
pub(crate) struct MeasuredFile {
    path: PathBuf,
    /// blake3 of the file's bytes: the file enters the key by content, not by path.
    content_hash: String,
    /// The channel asked for; `None` reads the height channel.
    channel: Option<String>,
    /// For the memory estimate.
    file_bytes: u64,
    /// The point count the file's header declares (X3P), read when the estimate is first
    /// asked for, i.e. once per instance the scheduler sees, not once per scenario.
    declared_points: Arc<OnceLock<Option<u64>>>,
}

/// A resolved measured surface: a file and its preprocessing.
#[derive(Debug, Clone)]
pub(crate) struct MeasuredSource {
    file: MeasuredFile,
    preprocessing: Preprocessing,
}

impl FileSpec {
    pub(super) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<SurfaceTask, SpecError> {
        let mut file = MeasuredFile::resolve(ctx, &self.path, "file.path")?;
        if let Some(channel) = &self.channel {
            file.channel = Some(ctx.resolve(channel, "file.channel")?);
        }
        let preprocessing = self.preprocess_fields().resolve(
            ctx,
            self.path.location(),
            "file",
            PreprocessDefaults::FILE,
        )?;
        Ok(SurfaceTask {
            source: SurfaceSource::Measured(MeasuredSource {
                file,
                preprocessing,
            }),
        })
    }
}

impl MeasuredFile {
    /// The file named by `path` (relative to the study file), hashed.
    pub(super) fn resolve(
        ctx: &ResolveContext<'_>,
        path: &Param<String>,
        field: &str,
    ) -> Result<Self, SpecError> {
        let written: String = ctx.resolve(path, field)?;
        let path_buf = ctx.study_dir().join(&written);
        let content_hash = ctx.file_content_hash(&path_buf).map_err(|m| SpecError {
            location: path.location(),
            field: field.to_string(),
            message: format!("{m}; paths are relative to the study file"),
        })?;
        Ok(Self {
            file_bytes: std::fs::metadata(&path_buf).map_or(0, |m| m.len()),
            path: path_buf,
            content_hash,
            channel: None,
            declared_points: Arc::default(),
        })
    }

    /// The file read.
    pub(super) fn path(&self) -> &std::path::Path {
        &self.path
    }

    /// blake3 of the file's bytes.
    pub(super) fn content_hash(&self) -> &str {
        &self.content_hash
    }

    /// The points the file holds, as far as can be told before reading it: the larger of the
    /// point count its header declares and its size at 4 bytes per stored point. A compressed
    /// X3P or MNT may declare far more points than its size suggests; the estimate then makes
    /// the scheduler run it alone rather than beside other large nodes (and the reader refuses
    /// more than [`crate::surface::io::MAX_POINTS`]).
    pub(super) fn points(&self) -> u64 {
        let declared = self
            .declared_points
            .get_or_init(|| declared_points(&self.path).map(|n| n as u64));
        declared.unwrap_or(0).max(self.file_bytes / 4)
    }

    /// The peak memory of reading, preprocessing and describing the file, bytes:
    /// [`MEASURED_BYTES_PER_POINT`] and the worker threads' scratch per point ([`Self::points`]).
    pub(super) fn memory_estimate(&self) -> u64 {
        let per_point = MEASURED_BYTES_PER_POINT + crate::nodes::thread_scratch_bytes_per_point();
        self.points().saturating_mul(per_point)
    }
}

/// Peak bytes per point of a measured surface node: the file's values as read, the map, its
/// validity mask, the preprocessing's copies (form removal, filters, filling missing points) and
/// the statistics' spectra and work arrays, beside the worker threads' scratch and the fixed part
/// of every surface node; an upper bound of the process's peak less its base (figures:
/// docs/robustness.md, "Memory").
const MEASURED_BYTES_PER_POINT: u64 = 16 * 8;

impl MeasuredSource {
    pub(super) fn new(file: MeasuredFile, preprocessing: Preprocessing) -> Self {
        Self {
            file,
            preprocessing,
        }
    }

    /// The key fields of a measured surface: the file by content, the channel when one is named
    /// (a surface without `channel:` keeps the key it had before channels existed), and its
    /// preprocessing, in SI. The path (the same bytes may move) and the file size (a memory
    /// estimate) are not part of it.
    pub(super) fn key_fields(&self) -> Vec<Field> {
        let Self {
            file:
                MeasuredFile {
                    path: _,
                    content_hash,
                    channel,
                    file_bytes: _,
                    declared_points: _,
                },
            preprocessing,
        } = self;
        let mut fields = vec![
            Field::text(SOURCE, "file"),
            Field::text(FILE_BLAKE3, content_hash.clone()),
        ];
        if let Some(channel) = channel {
            fields.push(Field::text(CHANNEL, channel.clone()));
        }
        fields.extend(preprocessing.key_fields());
        fields
    }

    /// Reads and preprocesses the surface, saying where its height unit came from (the lateral
    /// scale's check needs the surface statistics: [`super::lateral_scale::lateral_scale_warning`]).
    pub(super) fn load(&self) -> Result<Preprocessed, NodeError> {
        let topography = read_topography_channel(&self.file.path, self.file.channel.as_deref())
            .map_err(|e| NodeError::new(format!("reading: {e}")))?;
        let scale = [topography.spacing, topography.height_unit];
        let map = match topography.data {
            TopographyData::Areal(map) => map,
            TopographyData::Line(_) => {
                return Err(NodeError::new(format!(
                    "{} is a line scan; a surface node needs an areal topography",
                    self.file.path.display()
                )))
            }
        };
        let preprocessed = self.preprocessing.apply(map, scale, &self.file.path)?;
        check_not_degenerate(&preprocessed.map, &self.file.path)?;
        Ok(preprocessed)
    }

    pub(super) fn memory_estimate(&self) -> u64 {
        self.file.memory_estimate()
    }

    /// The points of the file ([`MeasuredFile::points`]).
    pub(super) fn points(&self) -> u64 {
        self.file.points()
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
