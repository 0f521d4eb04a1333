//! Study and data files that are not regular files (a FIFO, a device, a directory) or are far
//! too large are refused at once, with the path and what it is; nothing blocks or reads forever.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("asperity-special-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `asperity args…`, killing it after 20 s (a blocked read would never end): exit success
/// and stderr.
fn run_bounded(args: &[&Path]) -> (bool, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(20) {
            child.kill().unwrap();
            panic!("asperity {args:?} still running after 20 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(status.success(), "mkfifo {}", path.display());
}

#[cfg(unix)]
#[test]
fn special_study_files_are_refused_naming_what_they_are() {
    let dir = scratch("study");
    let fifo = dir.join("study.yaml");
    mkfifo(&fifo);
    let big = dir.join("big.yaml");
    std::fs::write(&big, vec![b'#'; (16 << 20) + 1]).unwrap();
    let zero = PathBuf::from("/dev/zero");
    let cases = [
        (&fifo, "a FIFO"),
        (&zero, "a device"),
        (&dir, "a directory"),
        (&big, "more than a study file may hold"),
    ];
    for (path, what) in cases {
        let (ok, stderr) = run_bounded(&[Path::new("validate"), path]);
        assert!(!ok, "{stderr}");
        assert!(
            stderr.contains(&path.display().to_string()) && stderr.contains(what),
            "{}: {stderr}",
            path.display()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn inspect_refuses_special_files_naming_what_they_are() {
    let dir = scratch("inspect");
    let fifo = dir.join("map.x3p");
    mkfifo(&fifo);
    let zero = PathBuf::from("/dev/zero");
    for (path, what) in [
        (&fifo, "a FIFO"),
        (&zero, "a device"),
        (&dir, "a directory"),
    ] {
        let (ok, stderr) = run_bounded(&[Path::new("inspect"), path]);
        assert!(!ok, "{stderr}");
        assert!(
            stderr.contains(&path.display().to_string()) && stderr.contains(what),
            "{}: {stderr}",
            path.display()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A FIFO named as a study's topography file fails validation with the field and what it is.
#[cfg(unix)]
#[test]
fn special_data_files_in_a_study_are_refused_at_validate() {
    let dir = scratch("data");
    let fifo = dir.join("map.x3p");
    mkfifo(&fifo);
    let study = dir.join("s.yaml");
    std::fs::write(
        &study,
        "study: s\nnodes:\n  lower:\n    surface:\n      file:\n        path: map.x3p\n",
    )
    .unwrap();
    let (ok, stderr) = run_bounded(&[Path::new("validate"), &study]);
    assert!(!ok, "{stderr}");
    assert!(
        stderr.contains("map.x3p") && stderr.contains("a FIFO"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
