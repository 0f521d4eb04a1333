//! Crash safety, measured: `asperity run` is SIGKILLed at random (seeded) moments, again and
//! again; a rerun then completes, every cache entry verifies, no stale temporary folder is left,
//! no corrupt entry was ever read back, and the tables equal those of an uninterrupted run; a run
//! into the killed runs' results folder removes the staging folders they left.
//!
//! CI runs 20 kills. For more (e.g. 200, another seed):
//! `ASPERITY_CRASH_KILLS=200 ASPERITY_CRASH_SEED=7 cargo test --test crash_safety -- --nocapture`

use crate::scale_out_common;
use std::process::Stdio;
use std::time::{Duration, Instant};

use scale_out_common::*;

/// SplitMix64: a tiny seeded generator for the kill moments (reproducible per seed).
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// Lower surfaces of the study: `2 × LOWERS + 1` entries.
const LOWERS: usize = 12;
const ENTRIES: usize = 2 * LOWERS + 1;

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn sigkill_at_random_moments_never_corrupts_the_cache() {
    let kills = env_number("ASPERITY_CRASH_KILLS", 20);
    let mut rng = SplitMix(env_number("ASPERITY_CRASH_SEED", 2026));
    let dir = tempdir("crash");
    let study = write_study(&dir, "crash", LOWERS);

    // The uninterrupted reference run, timed with the same thread count as the killed runs.
    let start = Instant::now();
    ok(&run(
        &study,
        &dir.join("cache-ref"),
        &dir.join("out-ref"),
        &["--jobs", "2"],
    ));
    let full_ms = (start.elapsed().as_millis() as u64).max(20);

    // Kills come in rounds of 5 on a fresh cache, so most of them hit a run with work left.
    let (mut landed, mut rounds) = (0u64, 0u64);
    let mut done = 0;
    while done < kills {
        rounds += 1;
        let cache = dir.join(format!("cache-{rounds}"));
        for _ in 0..5.min(kills - done) {
            done += 1;
            // A moment anywhere in the expected remaining run time (the time a full run takes,
            // scaled by the fraction of entries still missing, plus process start-up).
            let present = if cache.exists() {
                assert_cache_verifies(&cache)
            } else {
                0
            };
            let window = (full_ms * (ENTRIES - present) as u64 / ENTRIES as u64).max(20);
            let delay = rng.next() % window;
            let mut child = asperity(&["run", "-q", "--jobs", "2", "--cache"])
                .arg(&cache)
                .arg("--out")
                .arg(dir.join("out-killed"))
                .arg(&study)
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .unwrap();
            std::thread::sleep(Duration::from_millis(delay));
            if child.try_wait().unwrap().is_none() {
                landed += 1;
            }
            child.kill().unwrap();
            child.wait().unwrap();
            // Whatever was published before the kill is complete and verifies.
            if cache.exists() {
                assert_cache_verifies(&cache);
            }
        }
        let out = dir.join(format!("out-{rounds}"));
        let resumed = run(&study, &cache, &out, &[]);
        let stdout = ok(&resumed);
        let stderr = String::from_utf8_lossy(&resumed.stderr);
        assert!(
            !stdout.contains("corrupt") && !stderr.contains("corrupt"),
            "a corrupt entry was read back:\n{stdout}\n{stderr}"
        );
        assert_eq!(assert_cache_verifies(&cache), ENTRIES);
        assert!(
            tmp_contents(&cache).is_empty(),
            "stale temporary folders after a run: {:?}",
            tmp_contents(&cache)
        );
        assert_same_tables(&out, &dir.join("out-ref"));
        let _ = std::fs::remove_dir_all(&cache);
    }
    // Staging folders of killed runs are stale: the next run into that folder removes them.
    ok(&run(
        &study,
        &dir.join("cache-ref"),
        &dir.join("out-killed"),
        &[],
    ));
    assert!(
        staging_leftovers(&dir).is_empty(),
        "{:?}",
        staging_leftovers(&dir)
    );
    assert_same_tables(&dir.join("out-killed"), &dir.join("out-ref"));
    println!(
        "{kills} kills in {rounds} rounds, {landed} landed in a running process \
         (uninterrupted run: {full_ms} ms)"
    );
    // The moments are spread over the run; most must interrupt it for the test to mean anything.
    assert!(
        landed * 2 >= kills,
        "only {landed} of {kills} kills hit a running process"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
