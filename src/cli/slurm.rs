//! `asperity slurm`: write (and with `--submit`, submit) a Slurm job array whose tasks run the
//! study's shards on a shared cache, and a collect job that runs after all of them succeed.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use anyhow::{bail, Context, Result};

use asperity::engine::shard::ShardPlan;

use super::CacheArg;

/// Slurm's default `MaxArraySize` (array indices must be smaller), used when `scontrol` is absent.
const DEFAULT_MAX_ARRAY_SIZE: usize = 1001;

/// Arguments of `asperity slurm`.
#[derive(Debug, clap::Args)]
pub struct SlurmArgs {
    /// The study file (YAML).
    study: PathBuf,
    #[command(flatten)]
    set: super::SetArg,
    #[command(flatten)]
    cache: CacheArg,
    /// Output folder for the tables the collect job writes [default: results/<study>].
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Number of array tasks (shards) [default: one per unit of work, at most MaxArraySize].
    #[arg(long, value_name = "N")]
    array_size: Option<usize>,
    /// At most K array tasks run at once (the `%K` throttle of `--array`).
    #[arg(long, value_name = "K")]
    throttle: Option<usize>,
    /// Slurm partition.
    #[arg(long, short, value_name = "P")]
    partition: Option<String>,
    /// Time limit of each task (`--time`, e.g. 01:00:00).
    #[arg(long, value_name = "TIME")]
    time: Option<String>,
    /// CPUs per task (also the worker threads of each shard).
    #[arg(long, value_name = "N", default_value_t = 1)]
    cpus_per_task: usize,
    /// Memory per task (`--mem`, e.g. 8G).
    #[arg(long, value_name = "SIZE")]
    mem: Option<String>,
    /// Folder for the scripts and the Slurm logs [default: slurm/<study>].
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
    /// Submit with sbatch (the collect job with --dependency=afterok on the array).
    #[arg(long)]
    submit: bool,
}

pub fn slurm(args: SlurmArgs) -> Result<ExitCode> {
    let (study, plan) = super::load(&args.study, &args.set)?;
    anyhow::ensure!(
        args.cpus_per_task >= 1,
        "--cpus-per-task must be at least 1"
    );
    let study_path = absolute(&args.study)?;
    let cache = absolute(&args.cache.dir())?;
    args.cache.open()?;
    let out = absolute(
        &args
            .out
            .clone()
            .unwrap_or_else(|| PathBuf::from("results").join(study.name())),
    )?;
    let dir = absolute(
        &args
            .dir
            .clone()
            .unwrap_or_else(|| PathBuf::from("slurm").join(study.name())),
    )?;
    let exe = std::env::current_exe().context("cannot locate the asperity executable")?;
    let needed = plan.needed_for(&study.outputs);
    let units = ShardPlan::split(&plan, &needed, 1).units.max(1);
    let count = array_count(&args, units)?;
    if let Some(k) = args.throttle {
        anyhow::ensure!(k >= 1, "--throttle must be at least 1");
    }
    let split = ShardPlan::split(&plan, &needed, count);
    std::fs::create_dir_all(dir.join("logs"))
        .with_context(|| format!("cannot create {}", dir.display()))?;
    let header = |name: &str, log: &str| sbatch_header(&args, &dir, name, log);
    let run = run_command(&args, &exe, &study_path, &cache);
    let mut array = header(&format!("asperity-{}", study.name()), "shard-%A_%a.out");
    let throttle = args.throttle.map(|k| format!("%{k}")).unwrap_or_default();
    let _ = writeln!(array, "#SBATCH --array=0-{}{throttle}", count - 1);
    let _ = write!(
        array,
        "set -euo pipefail\nexec {run} --shard \"${{SLURM_ARRAY_TASK_ID}}/{count}\"\n"
    );
    let mut collect = header(
        &format!("asperity-{}-collect", study.name()),
        "collect-%j.out",
    );
    let _ = write!(
        collect,
        "set -euo pipefail\nexec {run} --out {}\n",
        quote(&out)
    );
    let array_path = dir.join("shards.sbatch");
    let collect_path = dir.join("collect.sbatch");
    for (path, text) in [(&array_path, &array), (&collect_path, &collect)] {
        std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    println!(
        "{}: {} shards over {} units of work (estimated loads {}..{}), scripts in {}",
        study.name(),
        count,
        split.units,
        split.loads.iter().min().copied().unwrap_or(0),
        split.loads.iter().max().copied().unwrap_or(0),
        dir.display()
    );
    if !args.submit {
        println!(
            "submit with:\n  jobid=$(sbatch --parsable {})\n  \
             sbatch --dependency=afterok:${{jobid%%;*}} {}",
            quote(&array_path),
            quote(&collect_path)
        );
        return Ok(ExitCode::SUCCESS);
    }
    let array_id = sbatch(&[], &array_path)?;
    let collect_id = sbatch(&[format!("--dependency=afterok:{array_id}")], &collect_path)?;
    println!("submitted array job {array_id} and collect job {collect_id}");
    println!("tables will be in {}", out.display());
    Ok(ExitCode::SUCCESS)
}

/// The number of array tasks: `--array-size` (default one per unit of work), at most the units
/// and Slurm's `MaxArraySize`; says so when it is fewer than asked.
fn array_count(args: &SlurmArgs, units: usize) -> Result<usize> {
    let max_array = max_array_size();
    let requested = args.array_size.unwrap_or(units);
    anyhow::ensure!(requested >= 1, "--array-size must be at least 1");
    let count = requested.min(units).min(max_array);
    if count < requested {
        eprintln!(
            "note: {count} array tasks instead of {requested} ({units} units of work, \
             MaxArraySize {max_array})"
        );
    }
    Ok(count)
}

/// The `#SBATCH` header of a job script named `name` logging to `dir/logs/log`.
fn sbatch_header(args: &SlurmArgs, dir: &Path, name: &str, log: &str) -> String {
    let mut s = format!(
        "#!/bin/bash\n#SBATCH --job-name={name}\n#SBATCH --output={}\n\
         #SBATCH --cpus-per-task={}\n",
        dir.join("logs").join(log).display(),
        args.cpus_per_task
    );
    for (flag, value) in [
        ("partition", &args.partition),
        ("time", &args.time),
        ("mem", &args.mem),
    ] {
        if let Some(v) = value {
            let _ = writeln!(s, "#SBATCH --{flag}={v}");
        }
    }
    s
}

/// The `asperity run` command line each job runs (without `--shard` or `--out`).
fn run_command(args: &SlurmArgs, exe: &Path, study_path: &Path, cache: &Path) -> String {
    let mut run = format!(
        "{} run {} --cache {} --quiet --jobs {}",
        quote(exe),
        quote(study_path),
        quote(cache),
        args.cpus_per_task
    );
    for o in &args.set.overrides {
        let _ = write!(
            run,
            " --set {}",
            quote_text(&format!("{}={}", o.name, o.text))
        );
    }
    run
}

/// Runs `sbatch --parsable [extra] script` and returns the job id.
fn sbatch(extra: &[String], script: &Path) -> Result<String> {
    let output = Command::new("sbatch")
        .arg("--parsable")
        .args(extra)
        .arg(script)
        .output()
        .context("cannot run sbatch (is Slurm installed and on PATH?)")?;
    if !output.status.success() {
        bail!(
            "sbatch {} failed: {}",
            script.display(),
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    // `--parsable` prints `jobid` or `jobid;cluster`.
    let text = String::from_utf8_lossy(&output.stdout);
    let id = text
        .trim()
        .split(';')
        .next()
        .unwrap_or_default()
        .to_string();
    anyhow::ensure!(
        !id.is_empty() && id.chars().all(|c| c.is_ascii_digit()),
        "unexpected sbatch output '{}'",
        text.trim()
    );
    Ok(id)
}

/// `MaxArraySize` from `scontrol show config`, or Slurm's default when it cannot be read.
fn max_array_size() -> usize {
    Command::new("scontrol")
        .args(["show", "config"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| {
            String::from_utf8_lossy(&o.stdout)
                .lines()
                .find(|l| l.trim_start().starts_with("MaxArraySize"))
                .and_then(|l| l.split('=').nth(1))
                .and_then(|v| v.trim().parse().ok())
        })
        .unwrap_or(DEFAULT_MAX_ARRAY_SIZE)
}

fn absolute(path: &Path) -> Result<PathBuf> {
    std::path::absolute(path).with_context(|| format!("cannot resolve {}", path.display()))
}

/// Single-quotes a path for bash.
fn quote(path: &Path) -> String {
    quote_text(&path.display().to_string())
}

/// `text` as one single-quoted shell word.
fn quote_text(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}
