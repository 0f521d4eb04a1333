//! Topography file readers: our own parsers, one file per format.
//!
//! Every reader turns bytes into a [`Topography`] in SI units (metres), with missing points as
//! `NaN` (never zero). [`read_topography`] detects the format from magic bytes, then from the
//! file extension, and wraps every failure in a [`ReadError`] that names the file.

pub mod al3d;
mod error;
pub mod gsf;
pub mod gwy;
pub mod metropro;
pub mod nanoscope;
pub mod opd;
mod topography;
pub mod zon;

pub use error::{ParseError, ReadError};
pub use topography::{LineScan, Topography, TopographyData};

use std::path::Path;

/// A supported file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// Zygo MetroPro `.dat`.
    MetroPro,
    /// Wyko/Veeco Vision `.opd`.
    Opd,
    /// Bruker Nanoscope `.di` / `.spm`.
    Nanoscope,
    /// Gwyddion Simple Field `.gsf`.
    Gsf,
    /// Gwyddion native `.gwy`.
    Gwy,
    /// Alicona `.al3d`.
    Al3d,
    /// Keyence `.zon`.
    Zon,
}

impl Format {
    /// Every supported format, in detection order.
    pub const ALL: &'static [Format] = &[
        Format::MetroPro,
        Format::Opd,
        Format::Nanoscope,
        Format::Gsf,
        Format::Gwy,
        Format::Al3d,
        Format::Zon,
    ];

    /// Short lowercase name ("x3p", "sdf", …).
    pub fn name(self) -> &'static str {
        match self {
            Format::MetroPro => "metropro",
            Format::Opd => "opd",
            Format::Nanoscope => "nanoscope",
            Format::Gsf => "gsf",
            Format::Gwy => "gwy",
            Format::Al3d => "al3d",
            Format::Zon => "zon",
        }
    }

    /// `true` when the first bytes of a file identify this format.
    fn matches_magic(self, head: &[u8]) -> bool {
        match self {
            Format::MetroPro => metropro::matches_magic(head),
            Format::Opd => opd::matches_magic(head),
            Format::Nanoscope => nanoscope::matches_magic(head),
            Format::Gsf => gsf::matches_magic(head),
            Format::Gwy => gwy::matches_magic(head),
            Format::Al3d => al3d::matches_magic(head),
            Format::Zon => zon::matches_magic(head),
        }
    }

    /// `true` when the (lowercase) file extension belongs to this format.
    fn matches_extension(self, ext: &str) -> bool {
        match self {
            Format::MetroPro => ext == "dat",
            Format::Opd => ext == "opd",
            Format::Nanoscope => matches!(ext, "di" | "spm"),
            Format::Gsf => ext == "gsf",
            Format::Gwy => ext == "gwy",
            Format::Al3d => ext == "al3d",
            Format::Zon => ext == "zon",
        }
    }

    /// Parses the whole file content.
    fn parse(self, bytes: &[u8]) -> Result<Topography, ParseError> {
        match self {
            Format::MetroPro => metropro::parse(bytes),
            Format::Opd => opd::parse(bytes),
            Format::Nanoscope => nanoscope::parse(bytes),
            Format::Gsf => gsf::parse(bytes),
            Format::Gwy => gwy::parse(bytes),
            Format::Al3d => al3d::parse(bytes),
            Format::Zon => zon::parse(bytes),
        }
    }
}

/// Detects the format of `bytes` (magic bytes first, then the extension of `path`).
pub fn detect_format(path: &Path, bytes: &[u8]) -> Option<Format> {
    let head = &bytes[..bytes.len().min(4096)];
    if let Some(f) = Format::ALL.iter().copied().find(|f| f.matches_magic(head)) {
        return Some(f);
    }
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    Format::ALL
        .iter()
        .copied()
        .find(|f| f.matches_extension(&ext))
}

/// Reads a topography file from disk in any supported format.
pub fn read_topography(path: &Path) -> Result<Topography, ReadError> {
    let bytes = std::fs::read(path).map_err(|source| ReadError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_topography(path, &bytes)
}

/// Parses file content already in memory; `path` is used for format detection and errors only.
pub fn parse_topography(path: &Path, bytes: &[u8]) -> Result<Topography, ReadError> {
    let format = detect_format(path, bytes).ok_or_else(|| ReadError::UnknownFormat {
        path: path.to_path_buf(),
    })?;
    format.parse(bytes).map_err(|source| ReadError::Parse {
        path: path.to_path_buf(),
        format: format.name(),
        source,
    })
}
