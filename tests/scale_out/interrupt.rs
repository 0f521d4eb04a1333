//! Ctrl-C, with a real SIGINT: `asperity run` interrupted while it plans, while it computes,
//! while it writes its tables, and twice in a row says "interrupted" and exits with 130; it
//! leaves nothing in the cache's `tmp/`, a cache that `asperity cache verify` passes, no
//! staging folder and no half-written results folder; a rerun gives the tables of an
//! uninterrupted run.

use crate::scale_out_common;
use std::path::{Path, PathBuf};
use std::process::{Child, Output, Stdio};
use std::time::{Duration, Instant};

use rustix::process::{kill_process, Pid, Signal};
use scale_out_common::*;

/// Lower surfaces of the computing study: `2 × LOWERS + 1` entries, a few seconds in all.
const LOWERS: usize = 12;

/// `asperity run STUDY --cache CACHE --out OUT -q --jobs 1`, started.
fn start(study: &Path, cache: &Path, out: &Path) -> Child {
    asperity(&["run", "-q", "--jobs", "1"])
        .arg(study)
        .arg("--cache")
        .arg(cache)
        .arg("--out")
        .arg(out)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Waits until `ready()` or the child ended; `true` when `ready()`.
fn wait_for(child: &mut Child, ready: impl Fn() -> bool) -> bool {
    let deadline = Instant::now() + Duration::from_secs(120);
    while Instant::now() < deadline {
        if ready() {
            return true;
        }
        if child.try_wait().unwrap().is_some() {
            return false;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    panic!("the run neither got there nor ended in 120 s");
}

/// `true` once the process `pid` receives Ctrl-C on its own thread (named `ctrl-c`): a SIGINT
/// sent earlier ends it as the system does, which is not what is tested here.
fn handles_ctrl_c(pid: u32) -> bool {
    let tasks = format!("/proc/{pid}/task");
    std::fs::read_dir(tasks).is_ok_and(|tasks| {
        tasks.flatten().any(|t| {
            std::fs::read_to_string(t.path().join("comm")).is_ok_and(|c| c.trim() == "ctrl-c")
        })
    })
}

fn sigint(child: &Child) {
    kill_process(Pid::from_child(child), Signal::INT).unwrap();
}

/// Waits for the interrupted child and checks what it said: "interrupted", exit code 130.
fn interrupted(child: Child) -> Output {
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "stderr: {stderr}");
    assert!(stderr.contains("interrupted"), "stderr: {stderr}");
    output
}

/// Cache entries stored so far.
fn entries(cache: &Path) -> usize {
    let mut n = 0;
    let Ok(kinds) = std::fs::read_dir(cache.join("entries")) else {
        return 0;
    };
    for kind in kinds.flatten() {
        for prefix in std::fs::read_dir(kind.path())
            .into_iter()
            .flatten()
            .flatten()
        {
            n += std::fs::read_dir(prefix.path())
                .into_iter()
                .flatten()
                .count();
        }
    }
    n
}

/// Hidden folders (staging, set aside) beside `out`.
fn hidden_beside(out: &Path) -> Vec<String> {
    std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n.starts_with('.'))
        .collect()
}

/// After an interrupted run: nothing in `tmp/`, `cache verify` passes, no staging folder, no
/// results folder unless complete; then the rerun's tables equal the reference's.
fn assert_clean_and_rerun(study: &Path, cache: &Path, out: &Path, reference: &Path) {
    assert_eq!(tmp_contents(cache), Vec::<String>::new(), "cache tmp/");
    let verify = asperity(&["cache", "verify", "--cache"])
        .arg(cache)
        .output()
        .unwrap();
    ok(&verify);
    assert_eq!(hidden_beside(out), Vec::<String>::new());
    if out.exists() {
        assert_same_tables(out, reference);
    }
    ok(&run(study, cache, out, &[]));
    assert_same_tables(out, reference);
}

/// A study that is planned for a while: 200 000 scenarios of one small surface.
fn slow_to_plan(dir: &Path) -> PathBuf {
    let path = dir.join("plan.yaml");
    let text = r#"
study: plan
parameters:
  product:
    seed: {range: [1, 200000]}
nodes:
  s:
    surface:
      synthetic: {grid: [16, 16], size: [50 um, 50 um], sq: 1 um, hurst: 0.8,
                  correlation_length: 10 um, seed: "${seed}"}
"#;
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn ctrl_c_while_planning_stops_before_anything_is_written() {
    let dir = tempdir("interrupt-plan");
    let study = slow_to_plan(&dir);
    let (cache, out) = (dir.join("cache"), dir.join("out"));
    let mut child = start(&study, &cache, &out);
    let pid = child.id();
    assert!(wait_for(&mut child, || handles_ctrl_c(pid)));
    sigint(&child);
    interrupted(child);
    assert_eq!(entries(&cache), 0);
    assert!(!out.exists());
    assert_eq!(hidden_beside(&out), Vec::<String>::new());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn ctrl_c_while_computing_lets_the_running_nodes_finish_and_writes_no_tables() {
    let dir = tempdir("interrupt-compute");
    let study = write_study(&dir, "compute", LOWERS);
    let reference = dir.join("out-ref");
    ok(&run(
        &study,
        &dir.join("cache-ref"),
        &reference,
        &["--jobs", "1"],
    ));
    let (cache, out) = (dir.join("cache"), dir.join("out"));
    let mut child = start(&study, &cache, &out);
    assert!(
        wait_for(&mut child, || entries(&cache) >= 2),
        "the run ended before it was interrupted"
    );
    sigint(&child);
    let output = interrupted(child);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("no tables written"), "{stderr}");
    assert!(!out.exists(), "an interrupted run wrote tables");
    assert!(entries(&cache) < 2 * LOWERS + 1, "nothing was left to do");
    assert_clean_and_rerun(&study, &cache, &out, &reference);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A surface and a contact on it that computes for a few seconds.
fn slow_contact(dir: &Path) -> PathBuf {
    let path = dir.join("slow.yaml");
    let text = r#"
study: slow
nodes:
  lower:
    surface:
      synthetic: {grid: [512, 512], size: [0.25 mm, 0.25 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 1}
  pair:
    contact:
      lower: lower
      lower_material: {youngs_modulus: 210 GPa, poisson_ratio: 0.3}
      flow_pressure: 4 GPa
      nominal_pressures: [5 MPa, 20 MPa, 50 MPa, 100 MPa]
"#;
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_second_ctrl_c_stops_at_once_without_damaging_the_cache() {
    let dir = tempdir("interrupt-twice");
    let study = slow_contact(&dir);
    let reference = dir.join("out-ref");
    ok(&run(&study, &dir.join("cache-ref"), &reference, &[]));
    let (cache, out) = (dir.join("cache"), dir.join("out"));
    let mut child = start(&study, &cache, &out);
    // The surface is stored: the contact computes.
    assert!(wait_for(&mut child, || entries(&cache) >= 1));
    sigint(&child);
    std::thread::sleep(Duration::from_millis(50));
    sigint(&child);
    interrupted(child);
    assert_eq!(
        entries(&cache),
        1,
        "the second Ctrl-C waited for the contact"
    );
    assert!(!out.exists());
    assert_clean_and_rerun(&study, &cache, &out, &reference);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn ctrl_c_while_writing_tables_leaves_no_half_written_folder() {
    let dir = tempdir("interrupt-write");
    let study = write_study(&dir, "write", LOWERS);
    let (cache, reference) = (dir.join("cache"), dir.join("out-ref"));
    // The cache filled by the reference run leaves the interrupted run little but the tables.
    ok(&run(&study, &cache, &reference, &[]));
    let out = dir.join("out");
    let mut child = start(&study, &cache, &out);
    let staging = || hidden_beside(&out).iter().any(|n| n.contains(".staging."));
    assert!(
        wait_for(&mut child, staging),
        "the run ended before it wrote its tables"
    );
    sigint(&child);
    interrupted(child);
    assert_clean_and_rerun(&study, &cache, &out, &reference);
    let _ = std::fs::remove_dir_all(&dir);
}
