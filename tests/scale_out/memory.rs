//! `--memory-mib` bounds the process, measured as the kernel counts it (Linux: the child's
//! `ru_maxrss` from `wait4`, its peak resident set): four contacts at 512² run four at a time
//! peak near 165 MiB; under a 110 MiB budget they wait their turn, the run completes with the
//! same tables and its peak stays within the budget. A budget too small for one contact fails
//! that node, naming it, its estimate and the flag to raise.

use crate::scale_out_common;
use std::fs::File;
use std::path::{Path, PathBuf};

use scale_out_common::*;

/// The budget under test, MiB.
const BUDGET_MIB: u64 = 110;

/// What the budget does not count, MiB: the Parquet writer's buffers once the run is over
/// (≤ 2 MiB at this size) and the rounding of the estimates, which are upper bounds per node but
/// measured on other surfaces (docs/robustness.md, "Memory"). 7 % of the budget.
const ALLOWANCE_MIB: u64 = 8;

/// Four seeds of a 512² surface in contact with a flat, with fields, and a per-spot friction
/// node on each contact: 12 instances; a contact's estimate is 50 MiB with four threads.
fn study(dir: &Path) -> PathBuf {
    let path = dir.join("memory.yaml");
    std::fs::write(
        &path,
        r#"
study: memory-budget
parameters:
  product:
    seed: [1, 2, 3, 4]
nodes:
  lower:
    surface:
      synthetic: {grid: [512, 512], size: [0.5 mm, 0.5 mm], sq: 0.05 um, hurst: 0.8,
                  correlation_length: 40 um, seed: "${seed}"}
  contact:
    contact:
      lower: lower
      lower_material: s235jr
      nominal_pressures: [5 MPa, 20 MPa]
      fields: true
  junction_shear:
    friction:
      model: junction_shear
      contact: contact
      lower_material: s235jr
"#,
    )
    .unwrap();
    path
}

/// A finished run: exit code, stdout, stderr and the peak resident set in MiB.
struct Measured {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    peak_mib: u64,
}

/// Runs `asperity run STUDY -q --jobs 4 --cache <fresh> --out <fresh> [extra]` and measures the
/// child's peak resident set (`ru_maxrss`, KiB on Linux) from `wait4`.
fn run_measured(dir: &Path, study: &Path, tag: &str, extra: &[&str]) -> Measured {
    let (stdout, stderr) = (
        dir.join(format!("{tag}.out")),
        dir.join(format!("{tag}.err")),
    );
    // Reaped by `wait4` below, which also gives its resource usage.
    #[allow(clippy::zombie_processes)]
    let child = asperity(&["run", "-q", "--jobs", "4"])
        .arg(study)
        .arg("--cache")
        .arg(dir.join(format!("{tag}-cache")))
        .arg("--out")
        .arg(dir.join(tag))
        .args(extra)
        .stdout(File::create(&stdout).unwrap())
        .stderr(File::create(&stderr).unwrap())
        .spawn()
        .unwrap();
    let pid = libc::pid_t::try_from(child.id()).unwrap();
    let mut status: libc::c_int = 0;
    // SAFETY: `rusage` is plain data, valid when zeroed; `wait4` waits for our own child and
    // writes only into the two locals it is given.
    let (waited, usage) = unsafe {
        let mut usage: libc::rusage = std::mem::zeroed();
        (libc::wait4(pid, &mut status, 0, &mut usage), usage)
    };
    assert_eq!(waited, pid, "wait4 failed");
    Measured {
        code: libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status)),
        stdout: std::fs::read_to_string(stdout).unwrap(),
        stderr: std::fs::read_to_string(stderr).unwrap(),
        peak_mib: u64::try_from(usage.ru_maxrss).unwrap() / 1024,
    }
}

#[test]
fn the_memory_budget_bounds_the_peak_of_the_process_and_the_run_completes() {
    let dir = tempdir("memory-budget");
    let study = study(&dir);
    let free = run_measured(&dir, &study, "free", &[]);
    assert_eq!(free.code, Some(0), "stderr: {}", free.stderr);
    assert!(
        free.peak_mib > BUDGET_MIB + ALLOWANCE_MIB,
        "without a budget the study peaks at {} MiB: too small to test a {BUDGET_MIB} MiB budget",
        free.peak_mib
    );
    let budget = BUDGET_MIB.to_string();
    let bounded = run_measured(&dir, &study, "bounded", &["--memory-mib", &budget]);
    assert_eq!(bounded.code, Some(0), "stderr: {}", bounded.stderr);
    assert!(
        bounded.peak_mib <= BUDGET_MIB + ALLOWANCE_MIB,
        "peak {} MiB under --memory-mib {BUDGET_MIB} (unbounded: {} MiB)",
        bounded.peak_mib,
        free.peak_mib
    );
    assert!(
        bounded
            .stdout
            .contains(&format!("MiB of a {BUDGET_MIB} MiB budget")),
        "stdout: {}",
        bounded.stdout
    );
    assert_same_tables(&dir.join("bounded"), &dir.join("free"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_node_that_cannot_fit_the_budget_fails_naming_itself_its_estimate_and_the_flag() {
    let dir = tempdir("memory-too-small");
    let study = study(&dir);
    let small = run_measured(&dir, &study, "small", &["--memory-mib", "85"]);
    assert_eq!(small.code, Some(2), "stderr: {}", small.stderr);
    for needed in [
        "failed: contact node 'contact'",
        "needs about 48 MiB of memory",
        "exceeds the run's budget of 85 MiB: raise `--memory-mib` to at least",
    ] {
        assert!(small.stderr.contains(needed), "stderr: {}", small.stderr);
    }
    assert!(
        small.peak_mib <= 85 + ALLOWANCE_MIB,
        "peak {} MiB",
        small.peak_mib
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A budget that holds the nodes but not the writing of the results (a statistical friction
/// node of 1 MiB): the nodes fail naming the MiB the process needs to write them.
#[test]
fn a_budget_too_small_to_write_the_results_is_refused_naming_the_flag() {
    let dir = tempdir("memory-results");
    let study = dir.join("results.yaml");
    std::fs::write(
        &study,
        r#"
study: memory-results
nodes:
  friction:
    friction:
      lower_material: s235jr
      roughness: {sigma: 0.1 um, radius: 100 um, density: 4e9}
      nominal_area: 1 mm^2
      nominal_pressures: [5 MPa]
"#,
    )
    .unwrap();
    let small = run_measured(&dir, &study, "small", &["--memory-mib", "45"]);
    assert_eq!(small.code, Some(2), "stderr: {}", small.stderr);
    for needed in [
        "failed: friction node 'friction'",
        "the run's budget of 45 MiB is below the",
        "MiB the process needs to write the results: raise `--memory-mib` to at least",
    ] {
        assert!(small.stderr.contains(needed), "stderr: {}", small.stderr);
    }
    let enough = run_measured(&dir, &study, "enough", &["--memory-mib", "80"]);
    assert_eq!(enough.code, Some(0), "stderr: {}", enough.stderr);
    assert!(
        enough.peak_mib <= 80 + ALLOWANCE_MIB,
        "peak {} MiB",
        enough.peak_mib
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
