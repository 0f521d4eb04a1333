//! The cache's `tmp/` folder: who made what is in it, and when it is stale.
//!
//! A writer names its temporary folders after itself (`<key>.<host>.<pid>.<nanos>`, or
//! `discarded.<key>.<host>.<pid>` for an entry being removed), so whether it still runs can be
//! told on its own host; for another host's only the age tells. No writer makes other names, so
//! anything else in `tmp/` is stray at once.

use std::fs;
use std::path::Path;
use std::time::Duration;

/// How old a temporary directory of another host must be before it is considered abandoned.
pub(crate) const FOREIGN_TMP_MAX_AGE: Duration = Duration::from_secs(24 * 3600);

/// Why `entry` of `tmp/` is stale (left by a writer that died), or `None` while it may still be
/// in use: a folder of this host's writer whose process no longer runs; another host's older than
/// a day ([`FOREIGN_TMP_MAX_AGE`]); anything under a name no writer makes.
pub(crate) fn stale_tmp(entry: &fs::DirEntry) -> Option<String> {
    let name = entry.file_name().to_string_lossy().to_string();
    let age = entry
        .metadata()
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| t.elapsed().ok())
        .unwrap_or_default();
    let hours = |d: Duration| d.as_secs() / 3600;
    match parse_owner(&name) {
        Some((host, pid)) if host == hostname() => (!process_alive(pid))
            .then(|| format!("left by process {pid} of this host, which no longer runs")),
        Some((host, _)) => (age > FOREIGN_TMP_MAX_AGE)
            .then(|| format!("left by a writer on host '{host}' {} h ago", hours(age))),
        None => Some(format!(
            "not a temporary folder of asperity (no writer's host and process in its name), {} min old",
            age.as_secs() / 60
        )),
    }
}

/// Removes a folder with its contents, or a file or link.
pub(crate) fn remove_any(path: &Path) -> std::io::Result<()> {
    match fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => fs::remove_dir_all(path),
        Ok(_) => fs::remove_file(path),
        Err(e) => Err(e),
    }
}

/// `(host, pid)` from a temporary directory name `<key>.<host>.<pid>.<nanos>` or
/// `discarded.<key>.<host>.<pid>`.
fn parse_owner(name: &str) -> Option<(String, u32)> {
    let parts: Vec<&str> = name.split('.').collect();
    if parts.first() == Some(&"discarded") && parts.len() >= 4 {
        let pid = parts[parts.len() - 1].parse().ok()?;
        return Some((parts[2..parts.len() - 1].join("."), pid));
    }
    if parts.len() >= 4 {
        let pid = parts[parts.len() - 2].parse().ok()?;
        return Some((parts[1..parts.len() - 2].join("."), pid));
    }
    None
}

pub(crate) fn process_alive(pid: u32) -> bool {
    pid == std::process::id() || Path::new(&format!("/proc/{pid}")).exists()
}

pub(crate) fn hostname() -> String {
    fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().to_string())
        .ok()
        .filter(|h| !h.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| String::from("localhost"))
}
