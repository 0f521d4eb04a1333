//! `asperity cache ls|du|verify|gc`: inspect and maintain a cache folder.

use std::collections::{BTreeMap, HashSet};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};

use asperity::engine::cache::Cache;
use asperity::engine::cache_admin::{
    check_structure, collect_garbage, list_entries, parse_age, payload_usage, remove_entry,
    verify_entry, GcCriteria, PayloadClass, Repair,
};

use super::CacheArg;

/// Arguments of `asperity cache`.
#[derive(Debug, clap::Args)]
pub struct CacheArgs {
    #[command(subcommand)]
    action: CacheAction,
}

#[derive(Debug, clap::Subcommand)]
enum CacheAction {
    /// List entries: kind, key, size, creation time, node parameters.
    Ls {
        #[command(flatten)]
        cache: CacheArg,
    },
    /// Sizes per kind and in total (arrays, long tables, summaries, manifests), then per kind and
    /// payload (each array and table by name, the summary): what each kind holds.
    Du {
        #[command(flatten)]
        cache: CacheArg,
    },
    /// Verify every entry's checksums and the cache's folder structure (files or links where
    /// folders belong, unknown files in kind folders, links, stray temporary files); exit code 1
    /// when anything is corrupt or damaged.
    Verify {
        #[command(flatten)]
        cache: CacheArg,
        /// Delete the corrupt entries (they are recomputed when next needed).
        #[arg(long)]
        delete: bool,
    },
    /// Repair the cache's folder structure (what `verify` reports as damaged) and delete entries
    /// no given study can reach and/or older than an age. Criteria combine: only entries matching
    /// all given criteria are deleted; with none, only the structure is repaired.
    Gc {
        #[command(flatten)]
        cache: CacheArg,
        /// Studies whose node instances are kept (all of them, whatever their outputs).
        studies: Vec<PathBuf>,
        /// Delete only entries created longer ago than this (30d, 12h, 90m, 45s, 2w).
        #[arg(long, value_name = "AGE", value_parser = parse_age)]
        older_than: Option<std::time::Duration>,
        /// Only show what would be deleted.
        #[arg(long)]
        dry_run: bool,
    },
}

pub fn cache(args: CacheArgs) -> Result<ExitCode> {
    match args.action {
        CacheAction::Ls { cache } => list(&cache.open()?),
        CacheAction::Du { cache } => usage(&cache.open()?),
        CacheAction::Verify { cache, delete } => verify(&cache.open()?, delete),
        CacheAction::Gc {
            cache,
            studies,
            older_than,
            dry_run,
        } => gc(&cache.open()?, &studies, older_than, dry_run),
    }
}

/// `cache ls`: one line per entry.
fn list(cache: &Cache) -> Result<ExitCode> {
    let entries = list_entries(cache)?;
    println!(
        "{:<10} {:<64} {:>12} {:>12}  params",
        "kind", "key", "bytes", "created"
    );
    for e in &entries {
        let params = e.manifest.as_ref().map_or_else(
            || String::from("(unreadable manifest)"),
            |m| {
                m.params
                    .iter()
                    .map(|f| format!("{}={}", f.column_name(), f.value))
                    .collect::<Vec<_>>()
                    .join(" ")
            },
        );
        println!(
            "{:<10} {:<64} {:>12} {:>12}  {params}",
            e.kind, e.key, e.bytes, e.created_unix
        );
    }
    println!("{} entries", entries.len());
    Ok(ExitCode::SUCCESS)
}

/// Bytes of one kind (or of all) in `cache du`: entries, then arrays, tables, summaries, the
/// rest (manifests) and the total.
#[derive(Default)]
struct Usage {
    entries: usize,
    classes: BTreeMap<PayloadClass, u64>,
    total: u64,
}

impl Usage {
    fn add(&mut self, other: &Usage) {
        self.entries += other.entries;
        for (class, bytes) in &other.classes {
            *self.classes.entry(*class).or_default() += bytes;
        }
        self.total += other.total;
    }

    fn row(&self, label: &str) -> String {
        let class = |c| human(self.classes.get(&c).copied().unwrap_or(0));
        let listed: u64 = self.classes.values().sum();
        format!(
            "{label:<10} {:>8} {:>12} {:>12} {:>12} {:>12} {:>12}",
            self.entries,
            class(PayloadClass::Array),
            class(PayloadClass::Table),
            class(PayloadClass::Summary),
            human(self.total.saturating_sub(listed)),
            human(self.total)
        )
    }
}

/// `cache du`: per kind, the bytes of arrays, tables, summaries and manifests; then per kind
/// and payload (an array, a table, the summary), the files and their bytes.
fn usage(cache: &Cache) -> Result<ExitCode> {
    let mut per_kind: BTreeMap<String, Usage> = BTreeMap::new();
    // Per kind and payload: files and bytes.
    let mut per_payload: BTreeMap<(String, PayloadClass, String), (usize, u64)> = BTreeMap::new();
    for e in list_entries(cache)? {
        let kind = per_kind.entry(e.kind.clone()).or_default();
        kind.entries += 1;
        kind.total += e.bytes;
        for (class, name, bytes) in e.manifest.as_ref().map(payload_usage).unwrap_or_default() {
            *kind.classes.entry(class).or_default() += bytes;
            let slot = per_payload
                .entry((e.kind.clone(), class, name))
                .or_default();
            *slot = (slot.0 + 1, slot.1 + bytes);
        }
    }
    println!(
        "{:<10} {:>8} {:>12} {:>12} {:>12} {:>12} {:>12}",
        "kind", "entries", "arrays", "tables", "summaries", "other", "total"
    );
    let mut sum = Usage::default();
    for (kind, usage) in &per_kind {
        println!("{}", usage.row(kind));
        sum.add(usage);
    }
    println!("{}", sum.row("total"));
    println!();
    println!(
        "{:<10} {:<8} {:<28} {:>8} {:>12}",
        "kind", "payload", "name", "files", "bytes"
    );
    for ((kind, class, name), (files, bytes)) in &per_payload {
        let class = match class {
            PayloadClass::Array => "array",
            PayloadClass::Table => "table",
            PayloadClass::Summary => "summary",
        };
        println!(
            "{kind:<10} {class:<8} {name:<28} {files:>8} {:>12}",
            human(*bytes)
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// `cache verify`: every entry and the folder structure; exit code 1 on corruption or damage.
fn verify(cache: &Cache, delete: bool) -> Result<ExitCode> {
    let damage = check_structure(cache)?;
    for d in &damage {
        println!("DAMAGED {d}");
    }
    let entries = list_entries(cache)?;
    let mut corrupt = 0;
    for e in &entries {
        if let Err(reason) = verify_entry(cache, e) {
            corrupt += 1;
            println!("CORRUPT {} {}: {reason}", e.kind, e.key);
            if delete {
                remove_entry(cache, e)?;
                println!("  deleted");
            }
        }
    }
    println!(
        "{} entries verified, {corrupt} corrupt, {} structural damage(s){}",
        entries.len(),
        damage.len(),
        if damage.is_empty() {
            ""
        } else {
            " (`asperity cache gc` repairs them)"
        }
    );
    if (corrupt > 0 && !delete) || !damage.is_empty() {
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// `cache gc`: repairs the structure and deletes the entries the criteria select.
fn gc(
    cache: &Cache,
    studies: &[PathBuf],
    older_than: Option<std::time::Duration>,
    dry_run: bool,
) -> Result<ExitCode> {
    let mut keep: Option<HashSet<String>> = None;
    for path in studies {
        let (_, plan) = super::load(path, &super::SetArg::default())
            .with_context(|| format!("cannot plan {}", path.display()))?;
        keep.get_or_insert_with(HashSet::new)
            .extend(plan.nodes.iter().map(|n| n.key.to_hex()));
    }
    let report = collect_garbage(cache, &GcCriteria { keep, older_than }, dry_run)?;
    let verb = if dry_run { "would delete" } else { "deleted" };
    for d in &report.damage {
        let done = match (&d.repair, dry_run) {
            (Repair::Manual(what), _) => what.clone(),
            (repair, true) => format!("would be {repair}"),
            (repair, false) => repair.to_string(),
        };
        println!("damaged: {d}: {done}");
    }
    for e in &report.removed {
        println!("{verb} {} {} ({} bytes)", e.kind, e.key, e.bytes);
    }
    let repaired = report
        .damage
        .iter()
        .filter(|d| !matches!(d.repair, Repair::Manual(_)))
        .count();
    println!(
        "{verb} {} entries ({}), kept {}; {} structural damage(s), {repaired} {}",
        report.removed.len(),
        human(report.freed_bytes),
        report.kept,
        report.damage.len(),
        if dry_run { "repairable" } else { "repaired" }
    );
    if studies.is_empty() && older_than.is_none() {
        println!("(no studies or --older-than given: no entry is deleted)");
    }
    Ok(ExitCode::SUCCESS)
}

fn human(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} B")
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}
