//! X3P integrity checks (ISO 5436-2): the MD5 sums an X3P carries of its own members.
//!
//! * `md5checksum.hex` (named by `Record4/ChecksumFile`, else at the default name beside
//!   `main.xml`) holds the MD5 of `main.xml`, as `<32 hex digits>`, optionally followed by
//!   ` *main.xml` (the `md5sum` output format); both forms are found in real files.
//! * `Record3/DataLink/MD5ChecksumPointData` and `MD5ChecksumValidPoints` hold the MD5 of the
//!   point-data and validity-mask members.
//!
//! An absent or empty checksum is not checked (older writers omit them); a present one that
//! differs from the content is an error naming the member and both sums, since a file whose
//! heights no longer match what its writer recorded is damaged, and its numbers must not reach a
//! table as valid. Hex digits compare case-insensitively (writers differ).

use md5::{Digest, Md5};

use super::ParseError;

/// Lowercase hex MD5 of `bytes`.
fn md5_hex(bytes: &[u8]) -> String {
    Md5::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Checks `content` of the member `name` against the `recorded` sum (`where_recorded` names the
/// element or file that holds it); an empty `recorded` is not checked.
pub(crate) fn verify(
    name: &str,
    content: &[u8],
    recorded: &str,
    where_recorded: &str,
) -> Result<(), ParseError> {
    let recorded = recorded.trim();
    if recorded.is_empty() {
        return Ok(());
    }
    if recorded.len() != 32 || !recorded.bytes().all(|b| b.is_ascii_hexdigit()) {
        return Err(ParseError::malformed(format!(
            "x3p: {where_recorded} holds {recorded:?}, not an MD5 sum (32 hex digits)"
        )));
    }
    let actual = md5_hex(content);
    if actual.eq_ignore_ascii_case(recorded) {
        Ok(())
    } else {
        Err(ParseError::malformed(format!(
            "x3p: checksum mismatch for {name}: {where_recorded} records MD5 {}, the content \
             has MD5 {actual}; the file is damaged or was edited after it was written",
            recorded.to_ascii_lowercase()
        )))
    }
}

/// The sum recorded in a `md5checksum.hex` member: its first word (`<hex> *main.xml`).
pub(crate) fn checksum_file_sum(content: &[u8]) -> String {
    String::from_utf8_lossy(content)
        .split_whitespace()
        .next()
        .unwrap_or("")
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_sum_and_mismatch() {
        assert_eq!(md5_hex(b""), "d41d8cd98f00b204e9800998ecf8427e");
        verify("m", b"", "D41D8CD98F00B204E9800998ECF8427E", "x").unwrap();
        verify("m", b"anything", "", "x").unwrap();
        let err = verify(
            "bindata/data.bin",
            b"a",
            "d41d8cd98f00b204e9800998ecf8427e",
            "X",
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("bindata/data.bin")
                && err.contains("d41d8cd98f00b204e9800998ecf8427e")
                && err.contains("0cc175b9c0f1b6a831c399e269772661"),
            "{err}"
        );
        assert!(verify("m", b"", "zz", "x").is_err());
        assert_eq!(checksum_file_sum(b"ABC *main.xml\n"), "ABC");
    }
}
