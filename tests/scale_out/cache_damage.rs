//! Structural damage of a cache, as the fault campaign of issue #31 made it: `cache verify`
//! names every damaged path and fails, `cache gc` repairs it and says what it did, a run that
//! meets a file where a kind folder belongs says so once (naming the path and the repair), and
//! after the repair everything verifies and the removed results are recomputed.

use crate::scale_out_common;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use scale_out_common::*;

fn cache_cmd(args: &[&str], cache: &Path) -> std::process::Output {
    asperity(&["cache"])
        .args(args)
        .arg("--cache")
        .arg(cache)
        .output()
        .unwrap()
}

/// The entry folders of kind `kind`, sorted.
fn entries_of(cache: &Path, kind: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(cache.join("entries").join(kind))
        .unwrap()
        .flatten()
        .flat_map(|prefix| std::fs::read_dir(prefix.path()).unwrap().flatten())
        .map(|e| e.path())
        .collect();
    v.sort();
    v
}

/// A file or folder `hours` old.
fn age(path: &Path, hours: u64) {
    let then = SystemTime::now() - Duration::from_secs(hours * 3600);
    std::fs::File::open(path)
        .unwrap()
        .set_modified(then)
        .unwrap();
}

fn hostname() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().to_string())
        .unwrap_or_else(|_| String::from("localhost"))
}

#[test]
fn verify_finds_structural_damage_and_gc_repairs_it() {
    let dir = tempdir("cache-damage");
    let study = write_study(&dir, "damaged", 2);
    let cache = dir.join("cache");
    ok(&run(&study, &cache, &dir.join("out"), &[]));
    let clean = ok(&cache_cmd(&["verify"], &cache));
    assert!(
        clean.contains("5 entries verified, 0 corrupt, 0 structural"),
        "{clean}"
    );

    let surfaces = entries_of(&cache, "surface");
    assert_eq!(surfaces.len(), 3);
    // An entry folder replaced by a file.
    let as_file = &surfaces[0];
    std::fs::remove_dir_all(as_file).unwrap();
    std::fs::write(as_file, b"not an entry").unwrap();
    // An entry replaced by a link to a copy outside the cache.
    let outside = dir.join("outside");
    std::fs::create_dir_all(&outside).unwrap();
    let linked = &surfaces[1];
    let copy = outside.join(linked.file_name().unwrap());
    std::fs::rename(linked, &copy).unwrap();
    std::os::unix::fs::symlink(&copy, linked).unwrap();
    // A payload of an entry replaced by a link to a file outside.
    let payload_entry = &surfaces[2];
    let payload = payload_entry.join("manifest.blake3");
    let foreign = outside.join("manifest.blake3");
    std::fs::rename(&payload, &foreign).unwrap();
    std::os::unix::fs::symlink(&foreign, &payload).unwrap();
    // Unknown things in a kind folder.
    let kind = cache.join("entries/surface");
    std::fs::write(kind.join("notes.txt"), b"x").unwrap();
    std::fs::create_dir(kind.join("zz")).unwrap();
    // Stray temporaries: unknown files (old or fresh: no writer makes such names), a folder of a
    // writer that no longer runs; a folder of a writer that still runs (this test) is left alone.
    let tmp = cache.join("tmp");
    std::fs::write(tmp.join("stray.txt"), b"x").unwrap();
    age(&tmp.join("stray.txt"), 2);
    let dead = tmp.join(format!("{}.{}.4294967.1", "ab".repeat(32), hostname()));
    std::fs::create_dir(&dead).unwrap();
    std::fs::write(tmp.join("fresh.txt"), b"x").unwrap();
    let live = tmp.join(format!(
        "{}.{}.{}.1",
        "cd".repeat(32),
        hostname(),
        std::process::id()
    ));
    std::fs::create_dir(&live).unwrap();

    let verify = cache_cmd(&["verify"], &cache);
    let text = String::from_utf8_lossy(&verify.stdout).to_string();
    assert_eq!(verify.status.code(), Some(1), "{text}");
    for (path, problem) in [
        (as_file.clone(), "is a file where an entry belongs"),
        (linked.clone(), "outside the cache where an entry belongs"),
        (payload.clone(), "outside the cache in an entry"),
        (
            kind.join("notes.txt"),
            "is a file where a prefix folder belongs",
        ),
        (kind.join("zz"), "is not a prefix folder"),
        (tmp.join("stray.txt"), "stray temporary"),
        (tmp.join("fresh.txt"), "stray temporary"),
        (dead.clone(), "which no longer runs"),
    ] {
        let line = format!("DAMAGED {} ", path.display());
        assert!(
            text.lines()
                .any(|l| l.starts_with(&line) && l.contains(problem)),
            "missing '{line}… {problem}' in\n{text}"
        );
    }
    assert!(!text.contains(&live.display().to_string()), "{text}");
    assert!(text.contains("8 structural damage(s)"), "{text}");

    let dry = ok(&cache_cmd(&["gc", "--dry-run"], &cache));
    assert!(dry.contains("8 repairable"), "{dry}");
    assert!(as_file.is_file(), "a dry run repaired");
    let gc = ok(&cache_cmd(&["gc"], &cache));
    assert!(gc.contains("8 structural damage(s), 8 repaired"), "{gc}");
    assert!(
        gc.contains(&format!("damaged: {} is a link", payload.display()))
            && gc.contains(&format!("removed the entry {}", payload_entry.display())),
        "{gc}"
    );
    // Removing links never touched what they point to.
    assert!(copy.join("manifest.json").is_file() && foreign.is_file());
    assert!(live.is_dir() && !tmp.join("fresh.txt").exists());
    let after = ok(&cache_cmd(&["verify"], &cache));
    assert!(
        after.contains("2 entries verified, 0 corrupt, 0 structural"),
        "{after}"
    );

    let rerun = ok(&run(&study, &cache, &dir.join("out"), &[]));
    assert!(rerun.contains(": 3 computed"), "{rerun}");
    assert_eq!(assert_cache_verifies(&cache), 5);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A file where a kind folder belongs: every result of the kind is computed but cannot be cached.
/// The run says so once, naming the path and the repair; verify reports it; gc removes the file,
/// and the next run caches the kind again.
#[test]
fn a_file_squatting_a_kind_folder_is_reported_by_runs_and_repaired_by_gc() {
    let dir = tempdir("kind-file");
    let study = write_study(&dir, "squatted", 2);
    let cache = dir.join("cache");
    ok(&run(&study, &cache, &dir.join("out"), &[]));
    let kind = cache.join("entries/contact");
    std::fs::remove_dir_all(&kind).unwrap();
    std::fs::write(&kind, b"squatter").unwrap();

    for _ in 0..2 {
        let output = run(&study, &cache, &dir.join("out"), &[]);
        let stdout = ok(&output);
        assert!(stdout.contains(": 2 computed"), "{stdout}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        let warning = format!("{} is a file where a folder belongs", kind.display());
        assert_eq!(stderr.matches(&warning).count(), 1, "{stderr}");
        assert!(
            stderr.contains("`asperity cache gc` repairs it"),
            "{stderr}"
        );
    }
    let verify = cache_cmd(&["verify"], &cache);
    let text = String::from_utf8_lossy(&verify.stdout).to_string();
    assert_eq!(verify.status.code(), Some(1), "{text}");
    assert!(
        text.contains(&format!(
            "DAMAGED {} is a file where a kind folder belongs",
            kind.display()
        )),
        "{text}"
    );
    let gc = ok(&cache_cmd(&["gc"], &cache));
    assert!(gc.contains("1 repaired"), "{gc}");
    let stdout = ok(&run(&study, &cache, &dir.join("out"), &[]));
    assert!(stdout.contains(": 2 computed"), "{stdout}");
    let stdout = ok(&run(&study, &cache, &dir.join("out"), &[]));
    assert!(stdout.contains(": 0 computed"), "{stdout}");
    assert!(ok(&cache_cmd(&["verify"], &cache)).contains("0 structural"));
    let _ = std::fs::remove_dir_all(&dir);
}
