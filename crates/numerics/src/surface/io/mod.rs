//! Topography file readers: our own parsers, one file per format.
//!
//! Every reader turns bytes into a [`Topography`] in SI units (metres), with missing points as
//! `NaN` (never zero). [`read_topography`] detects the format from magic bytes, then from the
//! file extension, and wraps every failure in a [`ReadError`] that names the file.

pub mod al3d;
mod byte_cursor;
mod error;
pub mod gsf;
pub mod gwy;
pub mod metropro;
pub mod nanoscope;
mod npy;
pub mod opd;
mod plu;
mod sdf;
mod sur;
mod text;
mod text_header;
mod text_units;
mod topography;
mod x3p;
mod x3p_xml;
pub mod zon;

pub use error::{ParseError, ReadError};
pub use topography::{LineScan, ScaleSource, Topography, TopographyData};

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
    /// ISO 25178-72 X3P: zip with `main.xml` and `bindata/`; int16/int32/float32/float64 heights,
    /// validity bit mask, inline `DataList`; lateral offsets go to the metadata.
    X3p,
    /// ISO 25178-71 SDF: ASCII `aISO-1.0`/`aISO-2.0` (`BAD` = missing) or binary `bISO-1.0`.
    Sdf,
    /// Digital Surf `.sur` (uncompressed, int16/int32; non-measured points → NaN).
    Sur,
    /// NumPy `.npy` (f4/f8/i1/i2/i4/u1/u2/u4, either byte order): heights in metres, `NaN` =
    /// missing. A plain `.npy` has no spacing: it is read as **1 pixel = 1 m** with
    /// [`Topography::spacing`] = [`ScaleSource::Assumed`]; the caller must apply the real pixel
    /// size.
    Npy,
    /// Sensofar `.plu` (float32 µm heights; 1 000 001 µm = not measured).
    Plu,
    /// Text/CSV: a matrix grid (header styles `h= w=` / `pixel size=` /
    /// `height conversion factor (-> m)=`, or Gwyddion `# Width:` / `# Value units:`), x y z
    /// triples, or a 2-column line scan (returned as [`TopographyData::Line`]). Without a
    /// spacing or height unit in the file, 1 m is assumed and [`Topography::spacing`] /
    /// [`Topography::height_unit`] say [`ScaleSource::Assumed`].
    Text,
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
        Format::X3p,
        Format::Sdf,
        Format::Sur,
        Format::Npy,
        Format::Plu,
        Format::Text,
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
            Format::X3p => "x3p",
            Format::Sdf => "sdf",
            Format::Sur => "sur",
            Format::Npy => "npy",
            Format::Plu => "plu",
            Format::Text => "text",
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
            Format::X3p => x3p::matches_magic(head),
            Format::Sdf => sdf::matches_magic(head),
            Format::Sur => sur::matches_magic(head),
            Format::Npy => npy::matches_magic(head),
            Format::Plu => false,
            Format::Text => false,
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
            Format::X3p => ext == "x3p",
            Format::Sdf => ext == "sdf",
            Format::Sur => ext == "sur",
            Format::Npy => ext == "npy",
            Format::Plu => ext == "plu",
            Format::Text => text::EXTENSIONS.contains(&ext),
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
            Format::X3p => x3p::parse(bytes),
            Format::Sdf => sdf::parse(bytes),
            Format::Sur => sur::parse(bytes),
            Format::Npy => npy::parse(bytes),
            Format::Plu => plu::parse(bytes),
            Format::Text => text::parse(bytes),
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
    let io_error = |cause| ReadError::Io {
        path: path.to_path_buf(),
        cause,
    };
    // A device or a pipe would be read forever (`/dev/zero`) or block (a FIFO).
    if std::fs::metadata(path).is_ok_and(|meta| !meta.is_file()) {
        return Err(io_error(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file (a directory, device or pipe)",
        )));
    }
    let bytes = std::fs::read(path).map_err(io_error)?;
    parse_topography(path, &bytes)
}

/// Parses file content already in memory; `path` is used for format detection and errors only.
pub fn parse_topography(path: &Path, bytes: &[u8]) -> Result<Topography, ReadError> {
    let format = detect_format(path, bytes).ok_or_else(|| ReadError::UnknownFormat {
        path: path.to_path_buf(),
    })?;
    format.parse(bytes).map_err(|cause| ReadError::Parse {
        path: path.to_path_buf(),
        format: format.name(),
        cause,
    })
}
