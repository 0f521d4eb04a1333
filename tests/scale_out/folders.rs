//! Folder trouble, found before anything is computed and said once: a results folder or cache
//! this user cannot write, staging folders left by earlier runs, and a results folder written by
//! another study file of the same `study:` name.
//!
//! Permissions are tested as a user without them: as root (who may write anywhere) the binary
//! runs as the unprivileged user 65534 (`nobody`), in folders made for it.

use crate::scale_out_common;
use std::os::unix::fs::PermissionsExt;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use scale_out_common::*;

const LOWERS: usize = 3;
/// The unprivileged user the binary runs as when the tests run as root.
const NOBODY: u32 = 65534;

fn is_root() -> bool {
    rustix::process::geteuid().is_root()
}

fn chmod(path: &Path, mode: u32) {
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode)).unwrap();
}

/// A folder this test and the binary may both write in.
fn shared_dir(tag: &str) -> PathBuf {
    let dir = tempdir(tag);
    chmod(&dir, 0o777);
    dir
}

/// Makes `path` (a folder) read-only for the binary: as root it stays root's, mode 755, and the
/// binary runs as [`NOBODY`]; otherwise mode 555.
fn read_only(path: &Path) {
    chmod(path, if is_root() { 0o755 } else { 0o555 });
}

/// `asperity run` as the user the permissions apply to, in `dir`.
fn run_as_user(dir: &Path, args: &[&str]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_asperity"));
    command.current_dir(dir).arg("run").arg("-q").args(args);
    if is_root() {
        command.uid(NOBODY).gid(NOBODY);
    }
    command.output().unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).to_string()
}

fn warnings(output: &Output) -> Vec<String> {
    stderr(output)
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .map(str::to_string)
        .collect()
}

/// Removes a folder tree whatever modes the test gave it.
fn remove(dir: &Path) {
    let _ = Command::new("chmod")
        .arg("-R")
        .arg("u+rwx")
        .arg(dir)
        .status();
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_results_folder_that_cannot_be_written_is_refused_before_computing() {
    let dir = shared_dir("folders-results");
    let study = write_study(&dir, "unwritable", LOWERS);
    let results = dir.join("results");
    std::fs::create_dir(&results).unwrap();
    read_only(&results);
    let output = run_as_user(&dir, &[study.to_str().unwrap(), "--cache", "cache"]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("cannot write results/unwritable")
            && message.contains("the folder results it is made in is not writable")
            && message.contains("chmod u+w results")
            && message.contains("nothing was computed"),
        "{message}"
    );
    assert_eq!(assert_cache_verifies(&dir.join("cache")), 0, "it computed");

    // An earlier, complete results folder made read-only: refused, and left as it was.
    chmod(&results, 0o777);
    let out = results.join("unwritable");
    ok(&run(&study, &dir.join("cache"), &out, &[]));
    read_only(&out);
    let before = tables(&out);
    let output = run_as_user(&dir, &[study.to_str().unwrap(), "--cache", "cache2"]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("the folder is read-only for this user")
            && message.contains("chmod -R u+w results/unwritable"),
        "{message}"
    );
    assert_eq!(tables(&out), before);
    let leftovers: Vec<_> = std::fs::read_dir(&results)
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(leftovers, ["unwritable"]);
    remove(&dir);
}

#[test]
fn a_read_only_cache_is_one_warning_and_its_entries_are_used() {
    let dir = shared_dir("folders-cache");
    let study = write_study(&dir, "readonly", LOWERS);
    let (cache, reference) = (dir.join("cache"), dir.join("out-ref"));
    ok(&run(&study, &dir.join("cache-ref"), &reference, &[]));
    // The cache holds the first lower surface's nodes only.
    ok(&run(
        &study,
        &cache,
        &dir.join("part"),
        &["--set", "seed=[1]"],
    ));
    let stored = assert_cache_verifies(&cache);
    let output = Command::new("chmod")
        .arg("-R")
        .arg(if is_root() { "go-w" } else { "a-w" })
        .arg(&cache)
        .output()
        .unwrap();
    assert!(output.status.success());
    let output = run_as_user(
        &dir,
        &[study.to_str().unwrap(), "--cache", "cache", "--out", "out"],
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", stderr(&output));
    let said = warnings(&output);
    assert_eq!(said.len(), 1, "{said:?}");
    assert!(
        said[0].contains("the cache at cache cannot be written into")
            && said[0].contains("chmod -R u+w cache"),
        "{}",
        said[0]
    );
    let computed = 2 * LOWERS + 1 - stored;
    assert!(
        stdout.contains(&format!("{stored} reused from cache"))
            && stdout.contains(&format!("({computed} not stored in the cache)")),
        "{stdout}"
    );
    assert_same_tables(&dir.join("out"), &reference);
    remove(&dir);
}

#[test]
fn staging_folders_left_by_dead_runs_are_removed_or_named_once() {
    let dir = shared_dir("folders-staging");
    let study = write_study(&dir, "leftovers", LOWERS);
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    let dead = |pid: u32| dir.join(format!(".leftovers.staging.{}.{pid}.1-0", host.trim()));
    // Made read-only by the user (as the set a run swapped out would be): removed.
    let removable = dead(4_294_000);
    std::fs::create_dir_all(removable.join("sub")).unwrap();
    std::fs::write(removable.join("sub").join("timings.parquet"), "x").unwrap();
    // Owned by root when the binary runs unprivileged (or read-only): named, not removed.
    let stuck = dead(4_294_001);
    std::fs::create_dir_all(stuck.join("sub")).unwrap();
    std::fs::write(stuck.join("sub").join("timings.parquet"), "x").unwrap();
    read_only(&stuck.join("sub"));
    if is_root() {
        Command::new("chown")
            .arg("-R")
            .arg(format!("{NOBODY}:{NOBODY}"))
            .arg(&removable)
            .status()
            .unwrap();
        chmod(&stuck, 0o777);
    }
    chmod(&removable.join("sub"), 0o555);
    chmod(&removable, 0o555);
    let args = [
        study.to_str().unwrap(),
        "--cache",
        "cache",
        "--out",
        "leftovers",
    ];
    let output = run_as_user(&dir, &args);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(!removable.exists(), "a removable leftover stayed");
    let said = warnings(&output);
    if !is_root() {
        // Without another user, every leftover is this user's own, so it is removed.
        assert!(!stuck.exists());
        assert_eq!(said, Vec::<String>::new());
        remove(&dir);
        return;
    }
    assert!(stuck.exists());
    assert_eq!(said.len(), 1, "{said:?}");
    assert!(
        said[0].contains("cannot delete a folder left by earlier runs into ./leftovers")
            && said[0].contains(&format!(
                "rm -rf ./{}",
                stuck.file_name().unwrap().to_string_lossy()
            )),
        "{}",
        said[0]
    );
    remove(&dir);
}

#[test]
fn results_of_another_study_file_are_replaced_only_with_force() {
    let dir = tempdir("folders-origin");
    let first = write_study(&dir, "same", LOWERS);
    let other_dir = dir.join("copy");
    std::fs::create_dir(&other_dir).unwrap();
    let second = other_dir.join("same.yaml");
    std::fs::write(
        &second,
        study_text("same", LOWERS).replace("0.5 um", "0.6 um"),
    )
    .unwrap();
    let (cache, out) = (dir.join("cache"), dir.join("results"));
    ok(&run(&first, &cache, &out, &[]));
    let before = tables(&out)
        .iter()
        .map(|t| std::fs::read(t).unwrap())
        .collect::<Vec<_>>();

    let refused = run(&second, &cache, &out, &[]);
    let message = stderr(&refused);
    assert_eq!(refused.status.code(), Some(1), "{message}");
    let (a, b) = (
        std::fs::canonicalize(&first).unwrap(),
        std::fs::canonicalize(&second).unwrap(),
    );
    assert!(
        message.contains("holds the results of another study file")
            && message.contains(&a.display().to_string())
            && message.contains(&b.display().to_string())
            && message.contains("--force"),
        "{message}"
    );
    let after: Vec<_> = tables(&out)
        .iter()
        .map(|t| std::fs::read(t).unwrap())
        .collect();
    assert_eq!(before, after, "the refused run changed the folder");

    let forced = run(&second, &cache, &out, &["--force"]);
    ok(&forced);
    let said = warnings(&forced);
    assert_eq!(said.len(), 1, "{said:?}");
    assert!(
        said[0].contains(&a.display().to_string()) && said[0].contains(&b.display().to_string()),
        "{}",
        said[0]
    );

    // The same file, edited: its results are replaced without a word.
    std::fs::write(
        &second,
        study_text("same", LOWERS).replace("0.5 um", "0.7 um"),
    )
    .unwrap();
    let edited = run(&second, &cache, &out, &[]);
    ok(&edited);
    assert_eq!(warnings(&edited), Vec::<String>::new());
    let _ = std::fs::remove_dir_all(&dir);
}
