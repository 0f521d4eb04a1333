//! Whether a run can store what it computes: checked once, before anything is computed, so a
//! read-only cache is one warning naming the folder and its fix, not one per node.

use std::fs;
use std::time::{SystemTime, UNIX_EPOCH};

use crate::cache::{hostname, Cache};

/// Creates and deletes a folder in the cache's `tmp/`, where every entry is written first. Its
/// name follows the writers' pattern (`probe.<host>.<pid>.<nanos>`), so one left by a process
/// killed in between is stale for the next run.
pub(super) fn probe(cache: &Cache) -> std::io::Result<()> {
    let nanos = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let dir = cache.root().join("tmp").join(format!(
        "probe.{}.{}.{nanos}",
        hostname(),
        std::process::id()
    ));
    fs::create_dir(&dir)?;
    fs::remove_dir(&dir)
}

/// The warning for a cache this run cannot write into.
pub(super) fn read_only_warning(cache: &Cache, error: &std::io::Error) -> String {
    let root = cache.root().display();
    format!(
        "the cache at {root} cannot be written into ({error}): results already in it are \
         used, the others are computed but not stored; make it writable for this user \
         (`chmod -R u+w {root}` by its owner) or use another cache (--cache DIR)"
    )
}
