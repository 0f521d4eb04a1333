//! Concurrency, measured: four processes run the same study on one fresh cache at once. All
//! succeed (publishing second is success), their tables are identical, every entry verifies and
//! no temporary folder is left. Results folders are published whole: four runs into one folder
//! all succeed and leave one complete set, and a run that fails to write (a full disk) leaves the
//! previous set untouched and no staging folder.

use crate::scale_out_common;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use scale_out_common::*;

#[test]
fn four_processes_on_one_cache_agree() {
    let dir = tempdir("concurrency");
    let study = write_study(&dir, "concurrent", 6);
    let cache = dir.join("cache");
    let children: Vec<_> = (0..4)
        .map(|p| {
            asperity(&["run", "-q", "--jobs", "1", "--cache"])
                .arg(&cache)
                .arg("--out")
                .arg(dir.join(format!("out-{p}")))
                .arg(&study)
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    let mut computed_total = 0;
    for child in children {
        let output = child.wait_with_output().unwrap();
        let stdout = ok(&output);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!stderr.contains("warning"), "{stderr}");
        computed_total += stdout
            .split(": ")
            .nth(1)
            .and_then(|s| s.split(' ').next())
            .and_then(|n| n.parse::<usize>().ok())
            .unwrap();
    }
    // 6 lower surfaces, 1 upper, 6 contacts; each computed by at least one process.
    assert_eq!(assert_cache_verifies(&cache), 13);
    assert!(
        computed_total >= 13,
        "{computed_total} computations for 13 nodes"
    );
    assert!(
        tmp_contents(&cache).is_empty(),
        "{:?}",
        tmp_contents(&cache)
    );
    for p in 1..4 {
        assert_same_tables(&dir.join("out-0"), &dir.join(format!("out-{p}")));
    }
    ok(&run(
        &study,
        &dir.join("cache-single"),
        &dir.join("out-single"),
        &[],
    ));
    assert_same_tables(&dir.join("out-0"), &dir.join("out-single"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Four runs of different seeds into one results folder, three rounds (the first into an absent
/// folder, the others replacing one): every run exits 0, and the folder holds the complete set of
/// one of them (its scenarios, kind tables and timings join) with no staging folder left.
#[test]
fn four_runs_into_one_folder_each_publish_a_complete_set() {
    let dir = tempdir("one-folder");
    let study = write_study(&dir, "shared", 3);
    let (cache, out) = (dir.join("cache"), dir.join("results"));
    let seeds = |p: i64| (10 * p + 1..=10 * p + 3).collect::<Vec<i64>>();
    for _round in 0..3 {
        let children: Vec<_> = (0..4)
            .map(|p| {
                asperity(&["run", "-q", "--jobs", "1", "--set"])
                    .arg(format!("seed={{range: [{}, {}]}}", 10 * p + 1, 10 * p + 3))
                    .arg("--cache")
                    .arg(&cache)
                    .arg("--out")
                    .arg(&out)
                    .arg(&study)
                    .stdout(Stdio::piped())
                    .stderr(Stdio::piped())
                    .spawn()
                    .unwrap()
            })
            .collect();
        for child in children {
            ok(&child.wait_with_output().unwrap());
        }
        assert_joinable(&out, &["surfaces", "contacts"]);
        let published = int_column(&out.join("scenarios.parquet"), "seed");
        assert!(
            (0..4).any(|p| published == seeds(p)),
            "seeds {published:?} are not one run's"
        );
        assert!(
            staging_leftovers(&dir).is_empty(),
            "{:?}",
            staging_leftovers(&dir)
        );
        assert!(
            staging_leftovers(&out).is_empty(),
            "{:?}",
            staging_leftovers(&out)
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A folder that is not a results folder (it holds the study and the cache) is refused before
/// anything is computed, and left as it was.
#[test]
fn a_folder_that_is_not_a_results_folder_is_not_replaced() {
    let dir = tempdir("not-results");
    let study = write_study(&dir, "refused", 1);
    std::fs::create_dir_all(dir.join("notes")).unwrap();
    let output = run(&study, &dir.join("cache"), &dir, &[]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    assert!(
        stderr.contains("replaces its results folder whole")
            && stderr.contains("which a results folder never does"),
        "{stderr}"
    );
    assert!(study.exists() && dir.join("notes").is_dir());
    let entries = std::fs::read_dir(dir.join("cache/entries"))
        .unwrap()
        .count();
    assert_eq!(entries, 0, "a refused run computed");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A full disk during a rerun with other seeds: the run fails naming the file and the cause, the
/// previous set is untouched (same bytes) and nothing staged is left. The disk is a 4 MiB tmpfs
/// (mounting needs root; without it the test is skipped with a message, unless `CI` is set).
#[test]
fn a_full_disk_leaves_the_previous_set_untouched() {
    let dir = tempdir("full-disk");
    let study = write_study(&dir, "full", 2);
    let cache = dir.join("cache");
    let Some(disk) = Tmpfs::mount(&dir.join("disk"), "4m") else {
        let _ = std::fs::remove_dir_all(&dir);
        return;
    };
    let out = disk.0.join("results");
    ok(&run(&study, &cache, &out, &[]));
    let before = folder_bytes(&out);
    let total: usize = before.values().map(Vec::len).sum();
    assert!(total > 16 << 10, "only {total} bytes of tables");

    // Fill the disk, then free half a set: the rerun's first tables fit, the rest does not.
    let filler = disk.0.join("filler");
    fill(&filler);
    let len = std::fs::metadata(&filler).unwrap().len();
    let file = std::fs::OpenOptions::new()
        .write(true)
        .open(&filler)
        .unwrap();
    file.set_len(len.saturating_sub(total as u64 / 2)).unwrap();
    drop(file);
    let rerun = run(&study, &cache, &out, &["--set", "seed={range: [11, 12]}"]);
    let stderr = String::from_utf8_lossy(&rerun.stderr);
    assert!(!rerun.status.success(), "the rerun fit: {stderr}");
    assert!(
        stderr.contains("No space left") && stderr.contains("results/"),
        "{stderr}"
    );
    assert!(folder_bytes(&out) == before, "the previous set changed");
    assert!(
        staging_leftovers(&disk.0).is_empty(),
        "{:?}",
        staging_leftovers(&disk.0)
    );
    assert!(
        staging_leftovers(&out).is_empty(),
        "{:?}",
        staging_leftovers(&out)
    );

    // With room again the rerun publishes its own set.
    std::fs::remove_file(&filler).unwrap();
    let room = run(&study, &cache, &out, &["--set", "seed={range: [11, 12]}"]);
    assert!(room.status.success(), "a set of {total} bytes: {room:?}");
    assert_eq!(int_column(&out.join("scenarios.parquet"), "seed"), [11, 12]);
    assert_joinable(&out, &["surfaces", "contacts"]);
    drop(disk);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A tmpfs mounted for one test; unmounted when dropped.
struct Tmpfs(PathBuf);

impl Tmpfs {
    /// Mounts a tmpfs of `size` at `path`; `None` (with the reason printed) where mounting is
    /// not permitted and `CI` is not set.
    fn mount(path: &Path, size: &str) -> Option<Self> {
        std::fs::create_dir_all(path).unwrap();
        let output = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(path)
            .output();
        match output {
            Ok(o) if o.status.success() => Some(Self(path.to_path_buf())),
            other => {
                let why = match other {
                    Ok(o) => String::from_utf8_lossy(&o.stderr).trim().to_string(),
                    Err(e) => e.to_string(),
                };
                assert!(
                    std::env::var_os("CI").is_none(),
                    "cannot mount a tmpfs in CI: {why}"
                );
                println!("skipped: cannot mount a tmpfs ({why}); run as root to test a full disk");
                None
            }
        }
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

/// Writes `path` until the disk is full.
fn fill(path: &Path) {
    use std::io::Write;
    let mut file = std::fs::File::create(path).unwrap();
    let block = vec![0u8; 4096];
    while file.write_all(&block).and_then(|()| file.flush()).is_ok() {}
}

/// Every file of a folder with its bytes.
fn folder_bytes(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| {
            (
                e.file_name().to_string_lossy().to_string(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect()
}
