//! Topography file readers: our own parsers, one file per format.
//!
//! Every reader turns bytes into a [`Topography`] in SI units (metres), with missing points as
//! `NaN` (never zero). [`read_topography`] detects the format from magic bytes, then from the
//! file extension, and wraps every failure in a [`ReadError`] that names the file. The formats
//! are an open set: each reader file exports a [`Reader`] and [`READERS`] lists them.

mod byte_cursor;
mod cfb;
mod error;
mod limits;
mod mnt_tlv;
mod opdx_items;
mod plausible;
mod reader;
mod text_header;
mod text_units;
mod topography;
mod x3p_checksum;
mod x3p_xml;
mod xyz;

pub use error::{ParseError, ReadError};
pub use limits::MAX_POINTS;
pub use reader::{ChannelParseFn, ParseFn, Parser, Reader, HEIGHT_CHANNEL};
pub use topography::{
    LineScan, ScaleSource, Topography, TopographyData, METADATA_INSTRUMENT, METADATA_VENDOR,
};

use std::path::Path;

/// Declares each reader's (private) module and lists its `READER` in [`READERS`], in the order
/// given: adding a format is its file and one name here.
macro_rules! readers {
    ($($format:ident),* $(,)?) => {
        $(mod $format;)*

        /// Every reader, in detection order: the first whose magic bytes match a file reads it,
        /// else the first whose extensions hold the file's. Text and PLU come last: they have
        /// no magic. Each is its own file, exporting a [`Reader`] as `READER`.
        pub const READERS: &[Reader] = &[$($format::READER),*];
    };
}

readers![
    metropro, opd, nanoscope, gsf, gwy, al3d, zon, x3p, sdf, sur, npy, tmd, bcrf, ibw, ps_tiff,
    wsxm, hfm, netcdf, hdf5, nid, mi, frt, opdx, plu, nms, mnt, text,
];

/// The reader named `name` (as [`Reader::name`] spells it).
pub fn reader_named(name: &str) -> Option<&'static Reader> {
    READERS.iter().find(|r| r.name == name)
}

/// The supported formats for an error message: "metropro (.dat), opd (.opd), …".
pub fn supported_formats() -> String {
    READERS
        .iter()
        .map(|r| format!("{} (.{})", r.name, r.extensions.join(", .")))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Detects the reader of `bytes` (magic bytes first, then the extension of `path`).
pub fn detect_format(path: &Path, bytes: &[u8]) -> Option<&'static Reader> {
    let head = &bytes[..bytes.len().min(4096)];
    if let Some(r) = READERS.iter().find(|r| r.matches_magic(head)) {
        return Some(r);
    }
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    READERS.iter().find(|r| r.matches_extension(&ext))
}

/// Reads a topography file from disk in any supported format ([`read_topography_bytes`], then
/// [`parse_topography`]).
pub fn read_topography(path: &Path) -> Result<Topography, ReadError> {
    read_topography_channel(path, None)
}

/// Reads the channel named `channel` (`None`: the height channel) of a topography file
/// ([`parse_topography_channel`]).
pub fn read_topography_channel(
    path: &Path,
    channel: Option<&str>,
) -> Result<Topography, ReadError> {
    let bytes = read_topography_bytes(path)?;
    parse_topography_channel(path, &bytes, channel)
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
/// data, for the formats whose file size says little about it (X3P and MNT, deflated: a 2 MB
/// file may hold 2 GiB of heights); `None` for other formats, whose points take a fixed share of the
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
    let name = detect_format(path, &head)?.name;
    if name == x3p::READER.name {
        x3p::declared_points(&read_topography_bytes(path).ok()?)
    } else if name == mnt::READER.name {
        mnt::declared_points(&read_topography_bytes(path).ok()?)
    } else {
        None
    }
}

/// Parses file content already in memory (the height channel); `path` is used for format
/// detection and errors only.
pub fn parse_topography(path: &Path, bytes: &[u8]) -> Result<Topography, ReadError> {
    parse_topography_channel(path, bytes, None)
}

/// Parses file content already in memory, reading the channel named `channel` (`None`: the
/// height channel); an unknown name is an error listing the file's channels.
pub fn parse_topography_channel(
    path: &Path,
    bytes: &[u8],
    channel: Option<&str>,
) -> Result<Topography, ReadError> {
    let reader = detect_format(path, bytes).ok_or_else(|| ReadError::UnknownFormat {
        path: path.to_path_buf(),
    })?;
    reader
        .parse(bytes, channel)
        .map_err(|cause| ReadError::Parse {
            path: path.to_path_buf(),
            format: reader.name,
            cause,
        })
}
