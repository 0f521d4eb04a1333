#!/usr/bin/env python3
"""The adversarial robustness campaign of issue #31, rerun in bounded time.

Five families of cases, each given a share of the wall-clock budget (time a family leaves unused
goes to the next): cache faults, kills and concurrent runs on a small study, then mutated studies
and damaged instrument files. Every command runs with a per-case timeout and an address-space
limit in a scratch folder. The case lists are deterministic for a seed (random choices come from
random.Random seeded per family); how far down each list a run gets depends on the budget and the
machine's speed. It prints one Markdown table per family and writes every anomalous case (input
files, commands, output tails) to the report folder. See docs/robustness.md.

Run scripts/campaign/setup.sh once, then:
    scripts/campaign/.venv/bin/python scripts/campaign/campaign.py [--budget-minutes 20] [--seed 1]
"""

import argparse
import datetime
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import report  # noqa: E402
from common import Runner  # noqa: E402
from fam_cache import Base, CacheFamily, ConcurrencyFamily, KillFamily  # noqa: E402
from fam_files import FileFamily  # noqa: E402
from fam_issue42 import FolderFamily, InterruptFamily, StudyCasesFamily, angle_cases, per_spot_cases  # noqa: E402
from fam_memory import MemoryFamily, memory_cases  # noqa: E402
from fam_studies import StudyFamily, shrunk_studies  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARES = {"cache": 0.07, "kills": 0.07, "concurrency": 0.07, "interrupts": 0.07, "folders": 0.02,
          "angles": 0.03, "per_spot": 0.04, "memory": 0.04, "studies": 0.32, "files": 0.27}
# Families whose every case is listed in the report, with what it said.
NAMED = {"folders", "angles", "per_spot", "memory"}


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bin", help="asperity binary [target/release/asperity, else target/debug/asperity]")
    p.add_argument("--budget-minutes", type=float, default=20.0, help="wall-clock budget (default 20)")
    p.add_argument("--seed", type=int, default=1, help="seed of every random choice (default 1)")
    p.add_argument("--timeout", type=float, default=45.0, help="per-command timeout, s (default 45)")
    p.add_argument("--memory-gib", type=float, default=3.0, help="address-space limit per command (default 3)")
    p.add_argument("--families", default=",".join(SHARES), help="comma-separated subset of " + ",".join(SHARES))
    p.add_argument("--data", action="append", help="instrument-file folder (repeatable) "
                   "[/work/shared/data/topography when present, and tests/data]")
    p.add_argument("--report", default=os.path.join(REPO, "scripts", "campaign", "report"),
                   help="report folder, emptied first (default scripts/campaign/report)")
    p.add_argument("--keep-scratch", action="store_true", help="keep the scratch folder")
    return p.parse_args()


class Context:
    def __init__(self, args):
        self.repo = REPO
        self.seed = args.seed
        self.bin = os.path.abspath(args.bin or default_bin())
        self.scratch = tempfile.mkdtemp(prefix="asperity-campaign-")
        self.runner = Runner(args.timeout, int(args.memory_gib * (1 << 30)), os.path.join(self.scratch, "logs"))
        dirs = args.data or [d for d in ("/work/shared/data/topography", os.path.join(REPO, "tests", "data"))
                             if os.path.isdir(d)]
        self.data_dirs = [os.path.abspath(d) for d in dirs]

    def rng(self, family):
        return random.Random(f"{self.seed}/{family}")


def default_bin():
    for profile in ("release", "debug"):
        path = os.path.join(REPO, "target", profile, "asperity")
        if os.path.exists(path):
            return path
    raise SystemExit("no asperity binary: cargo build --bin asperity, or pass --bin")


def git(*args):
    try:
        return subprocess.run(["git", "-C", REPO, *args], capture_output=True, text=True).stdout.strip()
    except OSError:
        return "?"


def main():
    args = parse_args()
    # SIGTERM ends the campaign like Ctrl-C: the running command is killed, the table printed.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    ctx = Context(args)
    chosen = [f for f in SHARES if f in args.families.split(",")]
    start = time.monotonic()
    budget = args.budget_minutes * 60
    shutil.rmtree(args.report, ignore_errors=True)
    os.makedirs(args.report)
    rep = report.Report(args.report, ctx.repo)
    header = {
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "commit": git("log", "-1", "--format=%h", "--", "src", "crates", "Cargo.toml", "Cargo.lock")
        + (" (dirty)" if git("status", "--porcelain", "--", "src", "crates") else ""),
        "binary": os.path.relpath(ctx.bin, REPO) if ctx.bin.startswith(REPO) else ctx.bin,
        "budget_minutes": args.budget_minutes,
        "seed": args.seed,
        "timeout_s": args.timeout,
        "memory_gib": args.memory_gib,
        "cpus": os.cpu_count(),
    }
    print(f"campaign: {header}", file=sys.stderr)
    try:
        base = Base(ctx) if {"cache", "kills", "concurrency", "interrupts", "folders"} & set(chosen) else None
        if base:
            print(f"campaign: reference run of the small study: {base.seconds:.1f} s", file=sys.stderr)
        families = {
            "cache": lambda: CacheFamily(ctx, base),
            "kills": lambda: KillFamily(ctx, base),
            "concurrency": lambda: ConcurrencyFamily(ctx, base),
            "interrupts": lambda: InterruptFamily(ctx, base),
            "folders": lambda: FolderFamily(ctx, base),
            "angles": lambda: StudyCasesFamily(ctx, "angles", angle_cases(shrunk_studies(ctx.repo))),
            "per_spot": lambda: StudyCasesFamily(ctx, "per_spot", per_spot_cases(shrunk_studies(ctx.repo))),
            "memory": lambda: MemoryFamily(ctx, memory_cases(shrunk_studies(ctx.repo))),
            "studies": lambda: StudyFamily(ctx),
            "files": lambda: FileFamily(ctx),
        }
        share_sum = sum(SHARES[f] for f in chosen)
        used = 0.0
        for name in chosen:
            used += SHARES[name] / share_sum
            deadline = start + budget * used
            fam = families[name]()
            t0 = time.monotonic()
            for case in fam:
                rep.add(case)
                if time.monotonic() >= deadline - args.timeout / 4:
                    break
            rep.family_time[name] = time.monotonic() - t0
            print(f"campaign: {name}: {rep.count(name)} cases in {rep.family_time[name]:.0f} s", file=sys.stderr)
            if name == "studies":
                rep.issue_cases = fam.issue_results
            if name in NAMED:
                rep.named[name] = list(rep.cases[name])
    finally:
        header["minutes"] = round((time.monotonic() - start) / 60, 1)
        text = rep.markdown(header, chosen)
        print(text)
        with open(os.path.join(args.report, "summary.md"), "w") as f:
            f.write(text)
        with open(os.path.join(args.report, "run.json"), "w") as f:
            json.dump(header, f, indent=1)
        if not args.keep_scratch:
            shutil.rmtree(ctx.scratch, ignore_errors=True)
        else:
            print(f"campaign: scratch kept in {ctx.scratch}", file=sys.stderr)


if __name__ == "__main__":
    main()
