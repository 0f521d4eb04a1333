//! HDF5 reader for the subset topography files use: the root group's 2-D numeric datasets, each
//! a channel, stored contiguously (or compact) and uncompressed. No C library is linked.
//!
//! Structures read (The HDF Group, "HDF5 File Format Specification Version 3.0"): a version-0 or
//! version-1 superblock with 8-byte offsets and lengths, whose root symbol-table entry gives the
//! root group's object header; the group's symbol-table message (0x0011) gives its version-1
//! B-tree (`TREE`, group nodes) and local heap (`HEAP`, the link names); the B-tree's leaves are
//! symbol-table nodes (`SNOD`) listing each member's object header. A dataset's version-1 object
//! header holds the dataspace (0x0001: the dimensions), the datatype (0x0003: IEEE float or
//! integer, its size and byte order) and the layout (0x0008: compact or contiguous; chunked
//! data, and so any compression, is refused). Header continuation messages (0x0010) are
//! followed. Superblock versions 2 and 3 (the "latest format" of recent h5py) are refused.
//!
//! Dataset `(d0, d1)` in C order is read as `nx = d0` points along x and `ny = d1` along y (the
//! convention of SurfaceTopography's HDF5 and netCDF readers), so it is transposed into
//! `[[iy, ix]]`. The file stores no spacing and no unit: 1 m per pixel and metres are assumed
//! ([`ScaleSource::Assumed`]); the caller must supply the real values.
//!
//! Every address is checked against the file; B-tree depth, members, messages and header
//! continuations are bounded, so a damaged or hostile file fails without a large allocation.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{decode_samples, ByteCursor, Endian, SampleType};
use super::limits::check_points;
use super::reader::{pick_channel, Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"\x89HDF\r\n\x1a\n";
const LE: Endian = Endian::Little;
const MAX_DEPTH: usize = 16;
/// Most B-tree nodes visited (a node listed twice, or a loop, must not multiply the work).
const MAX_NODES: usize = 4096;
const MAX_MEMBERS: usize = 4096;
const MAX_MESSAGES: usize = 4096;
const MAX_CONTINUATIONS: usize = 64;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "hdf5",
    description: "HDF5 `.h5` (contiguous 2-D datasets, one channel each; no unit or spacing)",
    extensions: &["h5", "hdf5", "hdf"],
    magic: Some(matches_magic),
    parser: Parser::Channels(parse_channel),
};

/// `true` when `head` starts with the HDF5 signature (at offset 0; user blocks are not read).
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// A header message: type and body.
struct Message<'a> {
    kind: u16,
    body: &'a [u8],
}

/// A 2-D numeric dataset of the root group.
struct Dataset<'a> {
    name: String,
    dims: (usize, usize),
    sample: SampleType,
    endian: Endian,
    data: &'a [u8],
}

fn at<'a>(bytes: &'a [u8], addr: u64, what: &str) -> Result<ByteCursor<'a>, ParseError> {
    let mut c = ByteCursor::new(bytes);
    c.seek(usize::try_from(addr).unwrap_or(usize::MAX), what)?;
    Ok(c)
}

fn addr(c: &mut ByteCursor, what: &str) -> Result<u64, ParseError> {
    let lo = u64::from(c.u32(LE, what)?);
    Ok(lo | (u64::from(c.u32(LE, what)?) << 32))
}

/// The root group's B-tree and local heap addresses.
fn superblock(bytes: &[u8]) -> Result<(u64, u64), ParseError> {
    if !bytes.starts_with(MAGIC) {
        return Err(ParseError::malformed("missing HDF5 signature"));
    }
    let mut c = at(bytes, 8, "HDF5 superblock")?;
    let version = c.u8("HDF5 superblock version")?;
    if version > 1 {
        return Err(ParseError::unsupported(format!(
            "HDF5 superblock version {version} (versions 0 and 1 are read; save with \
             h5py's default `libver`)"
        )));
    }
    c.seek(13, "HDF5 offset sizes")?;
    let (offsets, lengths) = (c.u8("HDF5 size of offsets")?, c.u8("HDF5 size of lengths")?);
    if (offsets, lengths) != (8, 8) {
        return Err(ParseError::unsupported(format!(
            "HDF5 with {offsets}-byte offsets and {lengths}-byte lengths (8 are read)"
        )));
    }
    // Version 1 adds 4 bytes (indexed-storage K and reserved) before the addresses.
    let root_entry = 24 + 4 * usize::from(version) + 32;
    let mut c = at(bytes, root_entry as u64 + 8, "HDF5 root group entry")?;
    let header = addr(&mut c, "HDF5 root object header")?;
    let symbol_table = messages(bytes, header)?
        .into_iter()
        .find(|m| m.kind == 0x0011)
        .ok_or_else(|| {
            ParseError::unsupported("HDF5 root group without a symbol table (new-style groups)")
        })?;
    let mut s = ByteCursor::new(symbol_table.body);
    Ok((
        addr(&mut s, "HDF5 B-tree address")?,
        addr(&mut s, "HDF5 heap address")?,
    ))
}

/// The messages of the version-1 object header at `address`, continuations followed.
fn messages(bytes: &[u8], address: u64) -> Result<Vec<Message<'_>>, ParseError> {
    let mut c = at(bytes, address, "HDF5 object header")?;
    let version = c.u8("HDF5 object header version")?;
    if version != 1 {
        return Err(ParseError::unsupported(format!(
            "HDF5 object header version {version} (version 1 is read)"
        )));
    }
    c.take(3, "HDF5 object header")?;
    c.u32(LE, "HDF5 reference count")?;
    let size = c.u32(LE, "HDF5 object header size")? as usize;
    c.take(4, "HDF5 object header padding")?;
    let mut blocks = vec![c.take(size, "HDF5 object header messages")?];
    let mut out = Vec::new();
    while let Some(block) = blocks.pop() {
        let mut m = ByteCursor::new(block);
        while m.remaining() >= 8 {
            let kind = m.u16(LE, "HDF5 message type")?;
            let len = usize::from(m.u16(LE, "HDF5 message size")?);
            m.take(4, "HDF5 message flags")?;
            let body = m.take(len, "HDF5 message body")?;
            if kind == 0x0010 {
                if blocks.len() + out.len() > MAX_CONTINUATIONS + MAX_MESSAGES {
                    return Err(ParseError::malformed("HDF5: too many header continuations"));
                }
                let mut b = ByteCursor::new(body);
                let (start, length) = (
                    addr(&mut b, "HDF5 continuation")?,
                    addr(&mut b, "HDF5 continuation")?,
                );
                let length = usize::try_from(length).unwrap_or(usize::MAX);
                blocks.push(
                    at(bytes, start, "HDF5 continuation block")?
                        .take(length, "HDF5 continuation block")?,
                );
            }
            out.push(Message { kind, body });
            if out.len() > MAX_MESSAGES {
                return Err(ParseError::malformed(
                    "HDF5: more than 4096 header messages",
                ));
            }
        }
    }
    Ok(out)
}

/// `(name heap offset, object header address)` of every member, from the B-tree at `node`;
/// `visited` counts the nodes read so far.
fn members(
    bytes: &[u8],
    node: u64,
    depth: usize,
    visited: &mut usize,
    out: &mut Vec<(u64, u64)>,
) -> Result<(), ParseError> {
    *visited += 1;
    if depth > MAX_DEPTH || *visited > MAX_NODES {
        return Err(ParseError::malformed(format!(
            "HDF5 group B-tree deeper than {MAX_DEPTH} levels or of more than {MAX_NODES} nodes"
        )));
    }
    let mut c = at(bytes, node, "HDF5 B-tree node")?;
    if c.take(4, "HDF5 B-tree signature")? != b"TREE" || c.u8("HDF5 B-tree type")? != 0 {
        return Err(ParseError::malformed(format!(
            "HDF5: no group B-tree node at byte {node}"
        )));
    }
    let level = c.u8("HDF5 B-tree level")?;
    let entries = usize::from(c.u16(LE, "HDF5 B-tree entries")?);
    c.take(16, "HDF5 B-tree siblings")?;
    for _ in 0..entries {
        addr(&mut c, "HDF5 B-tree key")?;
        let child = addr(&mut c, "HDF5 B-tree child")?;
        if level > 0 {
            members(bytes, child, depth + 1, visited, out)?;
            continue;
        }
        *visited += 1;
        if *visited > MAX_NODES {
            return Err(ParseError::malformed(format!(
                "HDF5 group of more than {MAX_NODES} B-tree and symbol table nodes"
            )));
        }
        let mut s = at(bytes, child, "HDF5 symbol table node")?;
        if s.take(4, "HDF5 SNOD signature")? != b"SNOD" {
            return Err(ParseError::malformed(format!(
                "HDF5: no symbol table node at byte {child}"
            )));
        }
        s.take(2, "HDF5 SNOD version")?;
        for _ in 0..s.u16(LE, "HDF5 SNOD symbols")? {
            let name = addr(&mut s, "HDF5 link name offset")?;
            let header = addr(&mut s, "HDF5 member object header")?;
            s.take(24, "HDF5 symbol table entry")?;
            out.push((name, header));
            if out.len() > MAX_MEMBERS {
                return Err(ParseError::malformed(
                    "HDF5 group with more than 4096 members",
                ));
            }
        }
    }
    Ok(())
}

/// The NUL-terminated name at `offset` in the local heap at `heap`.
fn heap_name(bytes: &[u8], heap: u64, offset: u64) -> Result<String, ParseError> {
    let mut c = at(bytes, heap, "HDF5 local heap")?;
    if c.take(4, "HDF5 heap signature")? != b"HEAP" {
        return Err(ParseError::malformed(format!(
            "HDF5: no local heap at byte {heap}"
        )));
    }
    c.take(4, "HDF5 heap version")?;
    let size = addr(&mut c, "HDF5 heap size")?;
    addr(&mut c, "HDF5 heap free list")?;
    let data = addr(&mut c, "HDF5 heap data")?;
    if offset >= size {
        return Err(ParseError::malformed(format!(
            "HDF5 name offset {offset} beyond the heap"
        )));
    }
    let mut d = at(bytes, data.saturating_add(offset), "HDF5 link name")?;
    let rest = d.take(d.remaining().min(1024), "HDF5 link name")?;
    let end = rest
        .iter()
        .position(|&b| b == 0)
        .ok_or_else(|| ParseError::truncated("HDF5 link name"))?;
    Ok(String::from_utf8_lossy(&rest[..end]).into_owned())
}

/// Dimensions from a dataspace message (versions 1 and 2).
fn dataspace(body: &[u8]) -> Result<Vec<usize>, ParseError> {
    let mut c = ByteCursor::new(body);
    let version = c.u8("HDF5 dataspace version")?;
    let rank = usize::from(c.u8("HDF5 dataspace rank")?);
    c.take(if version == 1 { 6 } else { 2 }, "HDF5 dataspace flags")?;
    (0..rank.min(32))
        .map(|_| addr(&mut c, "HDF5 dimension").map(|d| usize::try_from(d).unwrap_or(usize::MAX)))
        .collect()
}

/// Sample type and byte order from a datatype message.
fn datatype(body: &[u8]) -> Result<(SampleType, Endian), ParseError> {
    let mut c = ByteCursor::new(body);
    let class = c.u8("HDF5 datatype class")? & 0x0f;
    let bits = c.u8("HDF5 datatype bits")?;
    c.take(2, "HDF5 datatype bits")?;
    let size = c.u32(LE, "HDF5 datatype size")?;
    let endian = if bits & 1 == 1 { Endian::Big } else { LE };
    let signed = bits & 0x08 != 0;
    let sample = match (class, size, signed) {
        (1, 4, _) => SampleType::F32,
        (1, 8, _) => SampleType::F64,
        (0, 1, true) => SampleType::I8,
        (0, 1, false) => SampleType::U8,
        (0, 2, true) => SampleType::I16,
        (0, 2, false) => SampleType::U16,
        (0, 4, true) => SampleType::I32,
        (0, 4, false) => SampleType::U32,
        _ => {
            return Err(ParseError::unsupported(format!(
                "HDF5 datatype class {class} of {size} bytes (floats and integers up to 4 bytes \
                 are read)"
            )))
        }
    };
    Ok((sample, endian))
}

/// The data bytes a layout message points to (compact or contiguous).
fn layout<'a>(bytes: &'a [u8], body: &'a [u8]) -> Result<&'a [u8], ParseError> {
    let mut c = ByteCursor::new(body);
    let version = c.u8("HDF5 layout version")?;
    let class = if version >= 3 {
        c.u8("HDF5 layout class")?
    } else {
        c.u8("HDF5 layout rank")?;
        let class = c.u8("HDF5 layout class")?;
        c.take(5, "HDF5 layout")?;
        class
    };
    match (version >= 3, class) {
        (true, 0) => {
            let size = usize::from(c.u16(LE, "HDF5 compact size")?);
            c.take(size, "HDF5 compact data")
        }
        (_, 1) => {
            let start = addr(&mut c, "HDF5 data address")?;
            if start == u64::MAX {
                return Err(ParseError::malformed(
                    "HDF5 dataset whose data were never written",
                ));
            }
            let mut d = at(bytes, start, "HDF5 dataset data")?;
            // Version 3 states the size: a file cut inside any dataset is truncated.
            let size = if version >= 3 {
                usize::try_from(addr(&mut c, "HDF5 data size")?).unwrap_or(usize::MAX)
            } else {
                d.remaining()
            };
            d.take(size, "HDF5 dataset data")
        }
        (_, 2) => Err(ParseError::unsupported(
            "chunked (possibly compressed) HDF5 dataset; save it contiguous (h5py: no `chunks`, \
             no `compression`)",
        )),
        (_, k) => Err(ParseError::unsupported(format!(
            "HDF5 data layout class {k}"
        ))),
    }
}

/// The root group's 2-D numeric datasets (other members are skipped).
fn datasets(bytes: &[u8]) -> Result<Vec<Dataset<'_>>, ParseError> {
    let (tree, heap) = superblock(bytes)?;
    let mut list = Vec::new();
    members(bytes, tree, 0, &mut 0, &mut list)?;
    let mut out = Vec::new();
    for (name_offset, header) in list {
        let name = heap_name(bytes, heap, name_offset)?;
        let msgs = messages(bytes, header)?;
        let find = |kind: u16| msgs.iter().find(|m| m.kind == kind).map(|m| m.body);
        let (Some(space), Some(ty), Some(lay)) = (find(0x0001), find(0x0003), find(0x0008)) else {
            continue; // a group or a named datatype
        };
        let dims = dataspace(space)?;
        let [d0, d1] = dims[..] else {
            continue;
        };
        let (sample, endian) = datatype(ty)?;
        let data = layout(bytes, lay)?;
        out.push(Dataset {
            name,
            dims: (d0, d1),
            sample,
            endian,
            data,
        });
    }
    Ok(out)
}

/// Parses the dataset named `channel` (ASCII case ignored; the first 2-D one for `None`).
fn parse_channel(bytes: &[u8], channel: Option<&str>) -> Result<Topography, ParseError> {
    let sets = datasets(bytes)?;
    let all: Vec<String> = sets.iter().map(|d| d.name.clone()).collect();
    let set = &sets[pick_channel(&all, channel, &[])?];
    let (nx, ny) = set.dims;
    let n = check_points(nx, ny, &format!("HDF5 dataset `{}`", set.name))?;
    let raw = decode_samples(set.data, n, set.sample, set.endian, "HDF5 dataset data")?;
    // C order (d0, d1), d1 fastest: (ix, iy) is raw[ix·ny + iy].
    let grid = Array2::from_shape_fn((ny, nx), |(iy, ix)| {
        let v = raw[ix * ny + iy];
        if v.is_finite() {
            v
        } else {
            f64::NAN
        }
    });
    let map =
        HeightMap::new(grid, 1.0, 1.0).map_err(|e| ParseError::malformed(format!("HDF5: {e}")))?;
    Ok(Topography {
        spacing: ScaleSource::Assumed,
        height_unit: ScaleSource::Assumed,
        data: TopographyData::Areal(map),
        channel: Some(set.name.clone()),
        channels: all,
        metadata: BTreeMap::new(),
    })
}
