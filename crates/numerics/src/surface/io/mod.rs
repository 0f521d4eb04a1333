//! Topography file readers: our own parsers, one file per format.
//!
//! Every reader turns bytes into a [`Topography`] in SI units (metres), with missing points as
//! `NaN` (never zero). [`read_topography`] detects the format from magic bytes, then from the
//! file extension, and wraps every failure in a [`ReadError`] that names the file.

pub mod al3d;
pub mod bcrf;
mod byte_cursor;
mod error;
pub mod gsf;
pub mod gwy;
pub mod hdf5;
pub mod hfm;
pub mod ibw;
mod limits;
pub mod metropro;
pub mod nanoscope;
pub mod netcdf;
mod npy;
pub mod opd;
mod plu;
pub mod ps_tiff;
mod sdf;
mod sur;
mod text;
mod text_header;
mod text_units;
pub mod tmd;
mod topography;
pub mod wsxm;
mod x3p;
mod x3p_checksum;
mod x3p_xml;
mod xyz;
pub mod zon;

pub use error::{ParseError, ReadError};
pub use limits::MAX_POINTS;
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
    /// TrueMap `.tmd` (float32, millimetres).
    Tmd,
    /// Image Metrology SPIP BCR-STM / BCRF (`.bcr`, `.bcrf`).
    Bcrf,
    /// Igor Pro binary wave `.ibw` (Asylum Research); one channel per layer.
    Ibw,
    /// Park Systems TIFF (data in the private tags 50432–50435).
    ParkTiff,
    /// Nanotec WSxM image (`.top`, `.stp`, …).
    Wsxm,
    /// `X;Y;valid` profile text `.hfm` (a line scan).
    Hfm,
    /// netCDF classic / 64-bit offset with a `heights(x, y)` variable (SurfaceTopography layout).
    NetCdf,
    /// HDF5 (superblock 0/1, contiguous datasets): each 2-D dataset of the root group is a
    /// channel; no spacing or unit in the file ([`ScaleSource::Assumed`]).
    Hdf5,
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
        Format::Tmd,
        Format::Bcrf,
        Format::Ibw,
        Format::ParkTiff,
        Format::Wsxm,
        Format::Hfm,
        Format::NetCdf,
        Format::Hdf5,
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
            Format::Tmd => "tmd",
            Format::Bcrf => "bcrf",
            Format::Ibw => "ibw",
            Format::ParkTiff => "park-tiff",
            Format::Wsxm => "wsxm",
            Format::Hfm => "hfm",
            Format::NetCdf => "netcdf",
            Format::Hdf5 => "hdf5",
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
            Format::Tmd => tmd::matches_magic(head),
            Format::Bcrf => bcrf::matches_magic(head),
            Format::Ibw => ibw::matches_magic(head),
            Format::ParkTiff => ps_tiff::matches_magic(head),
            Format::Wsxm => wsxm::matches_magic(head),
            Format::Hfm => hfm::matches_magic(head),
            Format::NetCdf => netcdf::matches_magic(head),
            Format::Hdf5 => hdf5::matches_magic(head),
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
            Format::Tmd => ext == "tmd",
            Format::Bcrf => matches!(ext, "bcr" | "bcrf"),
            Format::Ibw => ext == "ibw",
            Format::ParkTiff => matches!(ext, "tif" | "tiff"),
            Format::Wsxm => matches!(ext, "top" | "stp"),
            Format::Hfm => ext == "hfm",
            Format::NetCdf => ext == "nc",
            Format::Hdf5 => matches!(ext, "h5" | "hdf5" | "hdf"),
            Format::Text => text::EXTENSIONS.contains(&ext),
        }
    }

    /// The format named `name` (as [`Format::name`] spells it).
    pub fn from_name(name: &str) -> Option<Format> {
        Format::ALL.iter().copied().find(|f| f.name() == name)
    }

    /// Parses the whole file content with this format's reader, whatever its magic bytes say
    /// (the fuzz targets reach each reader this way; files go through [`parse_topography`]).
    pub fn parse(self, bytes: &[u8]) -> Result<Topography, ParseError> {
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
            Format::Tmd => tmd::parse(bytes),
            Format::Bcrf => bcrf::parse(bytes),
            Format::Ibw => ibw::parse(bytes),
            Format::ParkTiff => ps_tiff::parse(bytes),
            Format::Wsxm => wsxm::parse(bytes),
            Format::Hfm => hfm::parse(bytes),
            Format::NetCdf => netcdf::parse(bytes),
            Format::Hdf5 => hdf5::parse(bytes),
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

/// Reads a topography file from disk in any supported format ([`read_topography_bytes`], then
/// [`parse_topography`]).
pub fn read_topography(path: &Path) -> Result<Topography, ReadError> {
    let bytes = read_topography_bytes(path)?;
    parse_topography(path, &bytes)
}

/// Largest topography file read, bytes: [`MAX_POINTS`] in the most verbose format (text, up to
/// ~30 bytes per height) with room for headers. A larger file could not be decoded anyway.
pub const MAX_FILE_BYTES: u64 = 4 << 30;

/// The bytes of the topography file `path`: a regular file of at most [`MAX_FILE_BYTES`]. A
/// FIFO would block, a device (`/dev/zero`) be read until memory runs out: both are refused, by
/// their file type, before the path is opened.
pub fn read_topography_bytes(path: &Path) -> Result<Vec<u8>, ReadError> {
    let io_error = |cause| ReadError::Io {
        path: path.to_path_buf(),
        cause,
    };
    let meta = std::fs::metadata(path).map_err(io_error)?;
    if let Some(kind) = non_regular_kind(&meta.file_type()) {
        return Err(ReadError::NotRegular {
            path: path.to_path_buf(),
            kind,
        });
    }
    let file = std::fs::File::open(path).map_err(io_error)?;
    let too_large = |size: u64| ReadError::TooLarge {
        path: path.to_path_buf(),
        size,
    };
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
    std::io::Read::read_to_end(
        &mut std::io::Read::take(file, MAX_FILE_BYTES + 1),
        &mut bytes,
    )
    .map_err(io_error)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// What a file type is when it is not a regular file, `None` for a regular file.
fn non_regular_kind(kind: &std::fs::FileType) -> Option<&'static str> {
    if kind.is_file() {
        return None;
    }
    if kind.is_dir() {
        return Some("a directory");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if kind.is_char_device() || kind.is_block_device() {
            return Some("a device");
        }
    }
    Some("a special file")
}

/// The number of points the header of the file `path` declares, read without decoding the
/// data, for the format whose file size says little about it (X3P, deflated: a 2 MB file may
/// hold 2 GiB of heights); `None` for other formats, whose points take a fixed share of the
/// file (only their first 4 KiB are read, to detect the format), and for a header that cannot
/// be read. Memory estimates use it before a file is decoded.
pub fn declared_points(path: &Path) -> Option<usize> {
    // Opening a FIFO would block: the file type is checked first.
    if !std::fs::metadata(path).ok()?.is_file() {
        return None;
    }
    let mut head = Vec::with_capacity(4096);
    let file = std::fs::File::open(path).ok()?;
    std::io::Read::read_to_end(&mut std::io::Read::take(file, 4096), &mut head).ok()?;
    match detect_format(path, &head)? {
        Format::X3p => x3p::declared_points(&read_topography_bytes(path).ok()?),
        _ => None,
    }
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
