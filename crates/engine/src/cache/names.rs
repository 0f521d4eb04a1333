//! The metric and column names read from cache summaries, shared instead of allocated per read.
//!
//! A rerun reads the same few dozen names from every entry of a kind. A name is looked up by its
//! XXH3 hash in a per-thread table of the names seen so far, then in one table shared by the
//! threads, and compared byte for byte; only a name seen for the first time is allocated, once
//! for the process (shared names are `'static` and never freed, like the names a node kind
//! writes). So that a cache of unusual entries cannot grow this without bound, at most
//! [`MAX_NAMES`] names of at most [`MAX_LEN`] bytes are shared; any other name (or one whose hash
//! a shared name already has) is an owned string.

use std::borrow::Cow;
use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;
use std::str::Utf8Error;
use std::sync::{Mutex, OnceLock, PoisonError};

use xxhash_rust::xxh3::xxh3_64;

use crate::hash::KeyHasher;

/// Most names shared by a process.
const MAX_NAMES: usize = 4096;

/// Longest name shared, bytes.
const MAX_LEN: usize = 64;

/// Shared names by the XXH3 hash of their bytes (which the map takes as its hash as it is).
type Names = HashMap<u64, &'static str, BuildHasherDefault<KeyHasher>>;

thread_local! {
    static LOCAL: RefCell<Names> = RefCell::new(Names::default());
}

fn shared() -> &'static Mutex<Names> {
    static SHARED: OnceLock<Mutex<Names>> = OnceLock::new();
    SHARED.get_or_init(Mutex::default)
}

/// The name whose UTF-8 bytes are `bytes`: a shared one when it can be.
pub(super) fn name(bytes: &[u8]) -> Result<Cow<'static, str>, Utf8Error> {
    let hash = xxh3_64(bytes);
    let known = LOCAL.with_borrow(|local| local.get(&hash).copied());
    if let Some(name) = known.filter(|name| name.as_bytes() == bytes) {
        return Ok(Cow::Borrowed(name));
    }
    let text = std::str::from_utf8(bytes)?;
    Ok(share(text, hash).map_or_else(|| Cow::Owned(text.to_string()), Cow::Borrowed))
}

/// `text` (of XXH3 hash `hash`) from the shared table, added when new and there is room;
/// remembered by this thread.
fn share(text: &str, hash: u64) -> Option<&'static str> {
    if text.len() > MAX_LEN {
        return None;
    }
    let mut names = shared().lock().unwrap_or_else(PoisonError::into_inner);
    let name = match names.get(&hash) {
        Some(&name) if name == text => name,
        Some(_) => return None,
        None if names.len() < MAX_NAMES => {
            let name: &'static str = Box::leak(Box::from(text));
            names.insert(hash, name);
            name
        }
        None => return None,
    };
    drop(names);
    LOCAL.with_borrow_mut(|local| local.insert(hash, name));
    Some(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_shared_and_long_or_invalid_ones_are_not() {
        let a = name(b"mean_contact_pressure").unwrap();
        let b = name(b"mean_contact_pressure").unwrap();
        assert!(
            matches!((&a, &b), (Cow::Borrowed(x), Cow::Borrowed(y)) if x.as_ptr() == y.as_ptr())
        );
        let long = "x".repeat(MAX_LEN + 1);
        assert!(matches!(name(long.as_bytes()).unwrap(), Cow::Owned(s) if s == long));
        assert!(name(&[0xff, 0xfe]).is_err());
    }
}
