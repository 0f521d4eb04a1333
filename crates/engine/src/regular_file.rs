//! Reading files a user names (study files, data files) only when they are regular files, with
//! a size cap: a FIFO would block forever, a device such as `/dev/zero` would be read until
//! memory runs out, and a directory cannot be read at all. Errors say what is wrong without
//! the path, which the caller's message names once.

use std::io::Read;
use std::path::Path;

/// What a path is when it is not a regular file ("a FIFO", "a directory", …), `None` for a
/// regular file. Follows symbolic links, as opening the path would.
pub fn non_regular_kind(meta: &std::fs::Metadata) -> Option<&'static str> {
    let kind = meta.file_type();
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
        if kind.is_socket() {
            return Some("a socket");
        }
    }
    Some("a special file")
}

/// Opens `path` after checking that it is a regular file; the error says what it is instead.
pub fn open_regular(path: &Path) -> Result<std::fs::File, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if let Some(kind) = non_regular_kind(&meta) {
        return Err(format!("it is {kind}, not a regular file"));
    }
    std::fs::File::open(path).map_err(|e| e.to_string())
}

/// The bytes of the regular file `path`, refused when it holds more than `max_bytes` (checked
/// on the declared size before reading, and again while reading, since a file may grow).
pub fn read_regular(path: &Path, max_bytes: u64, what: &str) -> Result<Vec<u8>, String> {
    let file = open_regular(path)?;
    let too_large =
        |size: u64| format!("{size} bytes is more than a {what} may hold ({max_bytes} bytes)");
    let declared = file.metadata().map_or(0, |m| m.len());
    if declared > max_bytes {
        return Err(too_large(declared));
    }
    let mut bytes = Vec::with_capacity(usize::try_from(declared).unwrap_or(0));
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// blake3 hex digest of the regular file `path`, streamed (memory independent of its size).
pub fn hash_regular(path: &Path) -> Result<String, String> {
    let file = open_regular(path)?;
    let mut hasher = blake3::Hasher::new();
    hasher.update_reader(file).map_err(|e| e.to_string())?;
    Ok(hasher.finalize().to_hex().to_string())
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn devices_and_directories_are_named_and_refused() {
        for (path, kind) in [("/dev/zero", "a device"), ("/tmp", "a directory")] {
            let err = read_regular(Path::new(path), 1 << 20, "study file").unwrap_err();
            assert!(err.contains(kind), "{err}");
        }
    }

    #[test]
    fn files_above_the_cap_are_refused() {
        let dir = std::env::temp_dir().join(format!("asperity-regular-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("big.yaml");
        std::fs::write(&file, vec![b'#'; 2048]).unwrap();
        let err = read_regular(&file, 1024, "study file").unwrap_err();
        assert!(err.contains("2048 bytes") && err.contains("1024"), "{err}");
        assert_eq!(read_regular(&file, 4096, "study file").unwrap().len(), 2048);
        assert_eq!(hash_regular(&file).unwrap().len(), 64);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
