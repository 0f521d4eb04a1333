//! Every reader against damaged copies of every file it reads (the shared folder and the
//! fixtures): truncated at many lengths and with bytes flipped in the header, the body and the
//! tail. Each copy gives an error naming the file or a consistent result, never a panic; what a
//! format makes detectable (its [`Rule`]: how much of a file it needs, which bytes it checks)
//! must fail. Headers that lie about sizes are in `lying_headers`, header values that do not
//! agree in `header_checks`.

use std::path::{Path, PathBuf};

use asperity_numerics::surface::io::{detect_format, parse_topography, read_topography, READERS};
use rayon::prelude::*;

use crate::common;
use crate::damage::{check_outcome, check_refused, positions, shared_files};
use crate::readers_a_common::fixture;

/// What damage a format lets its reader detect.
struct Rule {
    /// The reader ([`asperity_numerics::surface::io::Reader::name`]).
    reader: &'static str,
    /// Bytes a file needs: every shorter cut must fail.
    needs: fn(&[u8]) -> usize,
    /// Positions whose flipped byte (`^ 0xFF`) must fail.
    checked: fn(&[u8]) -> Vec<usize>,
}

const fn rule(
    reader: &'static str,
    needs: fn(&[u8]) -> usize,
    checked: fn(&[u8]) -> Vec<usize>,
) -> Rule {
    Rule {
        reader,
        needs,
        checked,
    }
}

/// A cut anywhere: the format ends with a directory (zip) or its data fill the file.
fn whole(b: &[u8]) -> usize {
    b.len()
}

/// The heights (of the channel read) reach past the middle of the file: a cut before it fails.
fn half(b: &[u8]) -> usize {
    b.len() / 2
}

fn none(_: &[u8]) -> Vec<usize> {
    Vec::new()
}

/// Nanoscope: up to the end of the data of the channel read (`ZSensor`, else `Height`, else
/// the first image), which the header's image list places.
fn nanoscope_needs(b: &[u8]) -> usize {
    let text = String::from_utf8_lossy(&b[..b.len().min(1 << 16)]);
    let images: Vec<&str> = text.split("\\*Ciao image list").skip(1).collect();
    let image = ["[ZSensor]", "[Height]"]
        .iter()
        .find_map(|name| images.iter().find(|s| s.contains(name)))
        .or(images.first())
        .expect("a Nanoscope image list");
    let field = |key: &str| -> usize {
        let at = image.find(key).expect(key) + key.len();
        let digits: String = image[at..]
            .chars()
            .take_while(char::is_ascii_digit)
            .collect();
        digits.parse().expect(key)
    };
    field("\\Data offset: ")
        + field("\\Samps/line: ") * field("\\Number of lines: ") * field("\\Bytes/pixel: ")
}

/// X3P: inside the compressed data of the main members (CRC-32 and inflate errors); in the
/// 1 kB fixture `len / 2` is a local header, whose name field zip readers ignore.
fn x3p_checked(b: &[u8]) -> Vec<usize> {
    let n = b.len();
    if n > 4000 {
        vec![n / 4, n / 2]
    } else {
        vec![n / 4]
    }
}

/// SUR: the signature, `xres` and `yres` (checked against the point count).
fn sur_checked(_: &[u8]) -> Vec<usize> {
    vec![0, 108, 112]
}

/// PLU: a 500-byte header, rows and columns (u32), then float32 heights.
fn plu_needs(b: &[u8]) -> usize {
    let word = |o: usize| u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]) as usize;
    508 + 4 * word(500) * word(504)
}

fn plu_checked(_: &[u8]) -> Vec<usize> {
    vec![500, 504]
}

/// SDF: ASCII up to the `*` line that closes the data; binary: every byte.
fn sdf_needs(b: &[u8]) -> usize {
    if !b.starts_with(b"aISO") {
        return b.len();
    }
    let text = String::from_utf8_lossy(b);
    let mut stars = text.match_indices('*').filter(|(i, _)| {
        let before = text[..*i].chars().next_back();
        before.is_none_or(|c| c == '\n')
    });
    stars.nth(1).map_or(b.len(), |(i, _)| i)
}

/// SDF: ASCII the magic and a data value; binary the magic, NumPoints and DataType.
fn sdf_checked(b: &[u8]) -> Vec<usize> {
    if b.starts_with(b"aISO") {
        vec![0, sdf_needs(b) - 3]
    } else {
        vec![0, 42, 79]
    }
}

/// Text: a matrix with an `h= w=` header loses values or rows when cut before its last line;
/// other text files count nothing.
fn text_needs(b: &[u8]) -> usize {
    let text = String::from_utf8_lossy(b);
    if text.starts_with("h=") {
        text.trim_end().rfind('\n').unwrap_or(0)
    } else {
        0
    }
}

/// Text: a byte flipped in the data is a non-ASCII, hence non-numeric, character.
fn text_checked(b: &[u8]) -> Vec<usize> {
    vec![b.len() / 2, 3 * b.len() / 4]
}

/// HFM: the `X;Y;valid` line and the start of the unit line; a cut in the data is a shorter
/// profile.
fn hfm_needs(_: &[u8]) -> usize {
    21
}

/// One rule per reader of the registry (`every_reader_has_a_damage_rule` checks it).
const RULES: &[Rule] = &[
    rule("metropro", half, none),
    rule("opd", half, none),
    rule("nanoscope", nanoscope_needs, none),
    rule("gsf", whole, none),
    rule("gwy", half, none),
    rule("al3d", half, none),
    rule("zon", half, none),
    rule("x3p", whole, x3p_checked),
    rule("sdf", sdf_needs, sdf_checked),
    rule("sur", whole, sur_checked),
    rule("npy", whole, none),
    rule("tmd", half, none),
    rule("bcrf", half, none),
    rule("ibw", half, none),
    rule("park-tiff", half, none),
    rule("wsxm", half, none),
    rule("hfm", hfm_needs, none),
    rule("netcdf", half, none),
    rule("hdf5", half, none),
    rule("nid", half, none),
    rule("mi", half, none),
    rule("frt", half, none),
    rule("opdx", half, none),
    rule("plu", plu_needs, plu_checked),
    rule("nms", whole, none),
    rule("mnt", half, none),
    rule("text", text_needs, text_checked),
];

#[test]
fn every_reader_has_a_damage_rule() {
    let missing: Vec<&str> = READERS
        .iter()
        .map(|r| r.name)
        .filter(|name| !RULES.iter().any(|rule| rule.reader == *name))
        .collect();
    assert!(
        missing.is_empty(),
        "readers without a row in RULES (damaged_files.rs): {missing:?}"
    );
    for rule in RULES {
        assert!(
            READERS.iter().any(|r| r.name == rule.reader),
            "RULES names `{}`, which is no reader",
            rule.reader
        );
    }
}

/// Every file of the shared folder (but its documentation) and the fixtures.
fn sample_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = [
        "sdf-1.sdf",
        "mm11_iso1_ascii_int32.sdf",
        "mm11_iso2_binary_f64.sdf",
        "sdf-1_binary_int32.sdf",
        "tiny_int32_masked.x3p",
    ]
    .iter()
    .map(|f| fixture(f))
    .collect();
    if let Some(dir) = common::data_dir() {
        files.extend(shared_files(&dir));
    }
    files
}

/// The cuts tried on a file of `n` bytes that needs `needs` of them.
fn cuts(n: usize, needs: usize) -> Vec<usize> {
    let mut cuts = vec![
        0, 1, 3, 4, 7, 8, 16, 17, 40, 64, 100, 200, 300, 383, 500, 511, 600, 1000, 1400, 4096,
    ];
    cuts.extend([n / 10, n / 4, n / 2, 3 * n / 4, 9 * n / 10, n - 2, n - 1]);
    cuts.extend([needs.saturating_sub(1), needs.saturating_sub(7)]);
    cuts.retain(|&c| c < n);
    cuts.sort_unstable();
    cuts.dedup();
    cuts
}

/// Every truncation and flip of one file, as a list of problems.
fn damage_one(path: &Path, seed: u64) -> Vec<String> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let n = bytes.len();
    let Some(reader) = detect_format(path, &bytes) else {
        return vec![format!("{}: no reader detects it", path.display())];
    };
    let rule = RULES
        .iter()
        .find(|r| r.reader == reader.name)
        .unwrap_or_else(|| panic!("no rule for {}", reader.name));
    let readable = parse_topography(path, &bytes).is_ok();
    let needs = (rule.needs)(&bytes);
    let mut problems = Vec::new();
    for cut in cuts(n, needs) {
        let what = format!("{} cut at {cut} of {n} bytes", path.display());
        let outcome = if readable && cut < needs {
            check_refused(path, &bytes[..cut], &what)
        } else {
            check_outcome(path, &bytes[..cut], &what)
        };
        problems.extend(outcome.err());
    }
    // Headers and directories sit at the start (all formats) and at the end (zip directories,
    // trailing blocks): probed densely there, sparsely in the body.
    let checked = if readable {
        (rule.checked)(&bytes)
    } else {
        Vec::new()
    };
    let mut spots = positions(seed, 40, n.min(4096));
    spots.extend(positions(seed + 101, 16, n));
    spots.extend(
        positions(seed + 201, 8, n.min(8192))
            .into_iter()
            .map(|p| n - 1 - p),
    );
    spots.extend(&checked);
    let mut damaged = bytes.clone();
    for spot in spots {
        damaged[spot] ^= 0xFF;
        let what = format!("{} with byte {spot} flipped", path.display());
        let outcome = if checked.contains(&spot) {
            check_refused(path, &damaged, &what)
        } else {
            check_outcome(path, &damaged, &what)
        };
        problems.extend(outcome.err());
        damaged[spot] ^= 0xFF;
    }
    problems
}

#[test]
fn damaged_copies_of_every_file_fail_naming_it_or_read_consistently() {
    let files = sample_files();
    let problems: Vec<String> = files
        .par_iter()
        .enumerate()
        .flat_map(|(k, path)| damage_one(path, k as u64 + 1))
        .collect();
    assert!(
        problems.is_empty(),
        "{} problems:\n{}",
        problems.len(),
        problems.join("\n")
    );
    if common::data_dir().is_some() {
        let without_file: Vec<&str> = READERS
            .iter()
            .map(|r| r.name)
            .filter(|name| {
                !files.iter().any(|p| {
                    let head = std::fs::read(p).unwrap_or_default();
                    detect_format(p, &head).is_some_and(|r| r.name == *name)
                })
            })
            .collect();
        // No measured file: their synthetic copies are cut below.
        assert_eq!(
            without_file,
            ["gsf", "npy"],
            "readers without a damaged file"
        );
    }
}

/// GSF and npy have no measured file: a 40 × 30 map of each built here, cut at every length
/// (as their rules say, every cut fails).
#[test]
fn synthetic_gsf_and_npy_fail_at_every_cut() {
    let heights = || (0..1200).map(|i| f64::from(i) * 1e-9);
    let dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (30, 40), }";
    let mut npy = b"\x93NUMPY\x01\x00".to_vec();
    npy.extend((dict.len() as u16).to_le_bytes());
    npy.extend(dict.as_bytes());
    npy.extend(heights().flat_map(f64::to_le_bytes));
    let mut gsf = b"Gwyddion Simple Field 1.0\nXRes = 40\nYRes = 30\nXReal = 4e-5\nYReal = 3e-5\n\
                    ZUnits = m\n"
        .to_vec();
    gsf.resize((gsf.len() / 4 + 1) * 4, 0);
    gsf.extend(heights().flat_map(|z| (z as f32).to_le_bytes()));
    for (name, bytes) in [("map.npy", npy), ("map.gsf", gsf)] {
        let path = Path::new(name);
        let reader = detect_format(path, &bytes).map(|r| r.name);
        let rule = RULES
            .iter()
            .find(|r| Some(r.reader) == reader)
            .expect("a rule");
        assert_eq!((rule.needs)(&bytes), bytes.len(), "{name}");
        assert!(parse_topography(path, &bytes).is_ok(), "{name}");
        for cut in 0..bytes.len() {
            let outcome = check_refused(path, &bytes[..cut], &format!("{name} cut at {cut}"));
            assert!(outcome.is_ok(), "{outcome:?}");
        }
    }
}

/// A device, a pipe or a directory is refused by its file type before anything is read
/// (`/dev/zero` would otherwise be read until memory runs out).
#[cfg(unix)]
#[test]
fn files_that_are_not_regular_are_refused_before_reading() {
    for path in ["/dev/zero", "/dev/null", "/tmp"] {
        let error = read_topography(Path::new(path))
            .expect_err("not a regular file")
            .to_string();
        assert!(
            error.contains(path) && error.contains("not a regular file"),
            "{path}: {error}"
        );
    }
}
