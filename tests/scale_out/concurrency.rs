//! Concurrency, measured: four processes run the same study on one fresh cache at once. All
//! succeed (publishing second is success), their tables are identical, every entry verifies and
//! no temporary folder is left.

use crate::scale_out_common;
use std::process::Stdio;

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
