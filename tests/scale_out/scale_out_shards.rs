//! Shards (`run --shard I/N`) and the cache commands (`cache ls|du|verify|gc`) end to end.

use crate::scale_out_common;
use std::collections::HashSet;

use asperity::engine::plan::Plan;
use asperity::engine::shard::ShardPlan;
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;
use scale_out_common::*;

#[test]
fn shard_split_covers_the_study_is_upstream_closed_and_balanced() {
    let dir = tempdir("shard-split");
    let study = Study::<TribologyNode>::load(&write_study(&dir, "split", 7)).unwrap();
    let plan = Plan::build(&study).unwrap();
    let needed = plan.needed_for(&study.outputs);
    let cost = |i: usize| plan.nodes[i].task.memory_estimate().max(1);
    for count in 1..=9 {
        let split = ShardPlan::split(&plan, &needed, count);
        assert_eq!(
            split,
            ShardPlan::split(&plan, &needed, count),
            "deterministic"
        );
        assert_eq!((split.shards.len(), split.units), (count, 7));
        let covered: HashSet<usize> = split.shards.iter().flatten().copied().collect();
        assert_eq!(covered, needed.iter().copied().collect::<HashSet<_>>());
        for shard in &split.shards {
            let set: HashSet<usize> = shard.iter().copied().collect();
            for &i in shard {
                for (_, u) in &plan.nodes[i].upstream {
                    assert!(set.contains(u), "shard misses an upstream node");
                }
            }
        }
        // Each unit goes where the resulting load is least, so no shard exceeds the lightest by
        // more than the largest unit (sink plus its upstream closure).
        let largest_unit = needed
            .iter()
            .filter(|&&i| plan.nodes[i].task.kind() == "contact")
            .map(|&i| {
                cost(i)
                    + plan.nodes[i]
                        .upstream
                        .iter()
                        .map(|(_, u)| cost(*u))
                        .sum::<u64>()
            })
            .max()
            .unwrap();
        let (min, max) = (
            split.loads.iter().min().unwrap(),
            split.loads.iter().max().unwrap(),
        );
        assert!(max - min <= largest_unit, "loads {:?}", split.loads);
        if count <= 7 {
            assert!(split.shards.iter().all(|s| !s.is_empty()), "{count} shards");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn shards_then_a_plain_run_assembles_the_tables_without_computing() {
    let dir = tempdir("shard-run");
    let study = write_study(&dir, "sharded", 5);
    let cache = dir.join("cache");
    for i in 0..3 {
        let shard = format!("{i}/3");
        let stdout = ok(&run(&study, &cache, &dir.join("out"), &["--shard", &shard]));
        assert!(stdout.contains("no tables written"), "{stdout}");
    }
    assert!(!dir.join("out").exists(), "a shard wrote tables");
    // 5 lower surfaces, 1 upper, 5 contacts.
    assert_eq!(assert_cache_verifies(&cache), 11);
    let stdout = ok(&run(&study, &cache, &dir.join("out"), &[]));
    assert!(stdout.contains(": 0 computed, 11 reused"), "{stdout}");
    ok(&run(
        &study,
        &dir.join("cache-single"),
        &dir.join("out-single"),
        &[],
    ));
    assert_same_tables(&dir.join("out"), &dir.join("out-single"));
    // A rerun of a shard finds everything cached.
    let stdout = ok(&run(&study, &cache, &dir.join("out"), &["--shard", "1/3"]));
    assert!(stdout.contains("0 computed"), "{stdout}");
    let bad = run(&study, &cache, &dir.join("out"), &["--shard", "3/3"]);
    assert!(!bad.status.success());
    let _ = std::fs::remove_dir_all(&dir);
}

fn cache_cmd(args: &[&str], cache: &std::path::Path) -> std::process::Output {
    asperity(&["cache"])
        .args(args)
        .arg("--cache")
        .arg(cache)
        .output()
        .unwrap()
}

#[test]
fn cache_commands_list_size_verify_and_collect_garbage() {
    let dir = tempdir("cache-cmd");
    let big = write_study(&dir, "big", 3);
    let small = write_study(&dir, "small", 1);
    let cache = dir.join("cache");
    ok(&run(&big, &cache, &dir.join("out"), &[]));
    let ls = ok(&cache_cmd(&["ls"], &cache));
    assert!(
        ls.contains("7 entries") && ls.contains("contact") && ls.contains("seed=2"),
        "{ls}"
    );
    let du = ok(&cache_cmd(&["du"], &cache));
    assert!(
        du.lines()
            .any(|l| l.starts_with("total") && l.split_whitespace().nth(1) == Some("7")),
        "{du}"
    );
    assert!(ok(&cache_cmd(&["verify"], &cache)).contains("7 entries verified, 0 corrupt"));

    // Flip one byte of one array: verify names the entry and fails; --delete removes it.
    let npy = walk(&cache.join("entries/surface"))
        .into_iter()
        .find(|p| p.extension().is_some_and(|e| e == "zst"))
        .unwrap();
    let mut bytes = std::fs::read(&npy).unwrap();
    let last = bytes.len() - 1;
    bytes[last] ^= 1;
    std::fs::write(&npy, bytes).unwrap();
    let verify = cache_cmd(&["verify"], &cache);
    assert_eq!(verify.status.code(), Some(1));
    let text = String::from_utf8_lossy(&verify.stdout).to_string();
    assert!(
        text.contains("CORRUPT surface") && text.contains("1 corrupt"),
        "{text}"
    );
    ok(&cache_cmd(&["verify", "--delete"], &cache));
    assert!(ok(&cache_cmd(&["verify"], &cache)).contains("6 entries verified, 0 corrupt"));
    let rerun = ok(&run(&big, &cache, &dir.join("out"), &[]));
    assert!(rerun.contains(": 1 computed"), "{rerun}");

    // gc: without criteria only repairs (nothing to repair here); keeps everything a study
    // reaches; a dry run deletes nothing.
    let bare = ok(&cache_cmd(&["gc"], &cache));
    assert!(
        bare.contains("deleted 0 entries") && bare.contains("0 structural damage(s)"),
        "{bare}"
    );
    let big_s = big.to_str().unwrap();
    let small_s = small.to_str().unwrap();
    assert!(ok(&cache_cmd(&["gc", big_s], &cache)).contains("deleted 0 entries"));
    let dry = ok(&cache_cmd(&["gc", "--dry-run", small_s], &cache));
    assert!(dry.contains("would delete"), "{dry}");
    assert!(ok(&cache_cmd(&["ls"], &cache)).contains("7 entries"));
    // Old-and-unreachable: nothing is a day old yet.
    let aged = ok(&cache_cmd(&["gc", "--older-than", "1d", small_s], &cache));
    assert!(aged.contains("deleted 0 entries"), "{aged}");
    // The small study reaches seed 1's lower surface, the upper surface and their contact.
    let gc = ok(&cache_cmd(&["gc", small_s], &cache));
    assert!(gc.contains("kept 3"), "{gc}");
    assert!(ok(&cache_cmd(&["ls"], &cache)).contains("3 entries"));
    let stdout = ok(&run(&small, &cache, &dir.join("out-small"), &[]));
    assert!(stdout.contains(": 0 computed"), "{stdout}");
    let _ = std::fs::remove_dir_all(&dir);
}

fn walk(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p);
        }
    }
    out.sort();
    out
}

#[test]
fn slurm_writes_a_throttled_array_of_shards_and_a_collect_job() {
    let dir = tempdir("slurm-scripts");
    let study = write_study(&dir, "arrayed", 5);
    let jobs = dir.join("jobs");
    let output = asperity(&["slurm", "--array-size", "8", "--throttle", "2"])
        .arg(&study)
        .arg("--cache")
        .arg(dir.join("cache"))
        .arg("--dir")
        .arg(&jobs)
        .args([
            "--partition",
            "short",
            "--time",
            "00:30:00",
            "--cpus-per-task",
            "2",
        ])
        .output()
        .unwrap();
    let stdout = ok(&output);
    // 8 tasks requested, 5 units of work: 5 tasks, indices 0..=4.
    assert!(stdout.contains("5 shards over 5 units"), "{stdout}");
    assert!(stdout.contains("--dependency=afterok:"), "{stdout}");
    let array = std::fs::read_to_string(jobs.join("shards.sbatch")).unwrap();
    for line in [
        "#SBATCH --array=0-4%2",
        "#SBATCH --partition=short",
        "#SBATCH --time=00:30:00",
        "#SBATCH --cpus-per-task=2",
        "--shard \"${SLURM_ARRAY_TASK_ID}/5\"",
        "--jobs 2",
    ] {
        assert!(array.contains(line), "{line} missing in\n{array}");
    }
    let collect = std::fs::read_to_string(jobs.join("collect.sbatch")).unwrap();
    assert!(
        collect.contains(" --out ") && !collect.contains("--shard"),
        "{collect}"
    );
    assert!(jobs.join("logs").is_dir());
    let _ = std::fs::remove_dir_all(&dir);
}
