"""The campaign's report: one JSON line per case, a folder per anomalous case, Markdown tables."""

import json
import os
import re
from collections import Counter, defaultdict

from common import OUTCOMES, first_words

COMMON_COLUMNS = [
    ("cases", lambda cs: len(cs)),
    *[(o.replace("_", " "), lambda cs, o=o: sum(c.outcome == o for c in cs)) for o in OUTCOMES],
]
FLAG_COLUMNS = {
    "baselines": ["impossible_ok", "nonfinite_printed", "debug_text", "repeated_clause", "lost_tables"],
    "studies": ["impossible_ok", "debug_text", "repeated_clause", "late_failure", "no_message", "lost_tables"],
    "files": ["impossible_ok", "nonfinite_printed", "accepted_corrupt", "debug_text", "repeated_clause",
              "no_message", "lost_tables"],
    "folders": ["debug_text", "repeated_clause", "late_failure", "lost_tables"],
    "angles": ["impossible_ok", "debug_text", "repeated_clause", "late_failure", "no_message", "lost_tables"],
    "per_spot": ["impossible_ok", "debug_text", "repeated_clause", "late_failure", "no_message", "lost_tables"],
}
EXTRA_COLUMNS = {
    "cache": [("detected by verify", "detected"), ("rerun identical", "rerun_identical"),
              ("verify ok after rerun", "verify_after_run"), ("verify ok after gc", "verify_after_gc")],

    "kills": [("killed mid-run", "killed"), ("rerun identical", "rerun_identical"),
              ("verify ok after rerun", "verify_after_run"), ("temp files left", "leftovers")],
    "concurrency": [("complete folder", "complete"), ("identical to reference", "identical")],
    "interrupts": [("exit 130", "interrupted"), ("said interrupted", "said interrupted"),
                   ("tmp clean", "tmp clean"), ("verify ok at once", "verify ok at once"),
                   ("rerun identical", "rerun identical")],
    "memory": [("completed within budget", "within_budget"), ("refused naming --memory-mib", "refused")],
}
NAMED_TITLES = {
    "folders": "Folder cases of issue #42 (small study; unprivileged user when run as root)",
    "angles": "Angle forms of issue #42 (shrunk ground-validation study)",
    "per_spot": "Per-spot cases of issue #42 (shrunk quickstart)",
    "memory": "Memory budgets of issue #42 (quickstart at 512², `--memory-mib`)",
}


class Report:
    def __init__(self, folder, repo):
        self.folder = folder
        self.repo = repo
        self.cases = defaultdict(list)
        self.family_time = {}
        self.issue_cases = []
        self.named = {}
        self.anomalies = []
        self.jsonl = open(os.path.join(folder, "cases.jsonl"), "w")

    def count(self, family):
        return len(self.cases[family])

    def add(self, case):
        self.cases[case.family].append(case)
        n = len(self.cases[case.family])
        record = {
            "family": case.family, "n": n, "case": case.name, "outcome": case.outcome,
            "flags": sorted(case.flags), "extra": case.extra, "notes": case.notes[:10],
            "commands": [{"argv": p.argv[1:], "rc": p.rc, "seconds": round(p.seconds, 2),
                          "maxrss_mib": round(p.maxrss_mib), "stderr_tail": p.stderr[-400:]} for p in case.procs],
        }
        self.jsonl.write(json.dumps(record, default=str) + "\n")
        self.jsonl.flush()
        if case.anomalous():
            self.write_case(case, n)

    def write_case(self, case, n):
        slug = re.sub(r"[^\w.-]+", "-", case.name)[:60].strip("-")
        folder = os.path.join(self.folder, case.family, f"{n:04d}-{slug}")
        os.makedirs(folder, exist_ok=True)
        for name, content in case.inputs.items():
            path = os.path.join(folder, name)
            if isinstance(content, str):
                os.symlink(content, path)
            else:
                with open(path, "wb") as f:
                    f.write(content)
        with open(os.path.join(folder, "case.md"), "w") as f:
            f.write(f"# {case.family} #{n}: {case.name}\n\n")
            f.write(f"outcome: {case.outcome}; flags: {', '.join(sorted(case.flags)) or '-'}\n\n")
            for note in case.notes:
                f.write(f"* {note}\n")
            f.write("\nCommands (the input files of this folder stand for the scratch files):\n\n```\n")
            for p in case.procs:
                f.write(p.tail() + "\n")
            f.write("```\n")
        self.anomalies.append((case, os.path.relpath(folder, self.repo)))

    def markdown(self, header, families):
        h = header
        out = [f"Campaign of {h['date']} on commit {h['commit']} ({h['binary']}), budget "
               f"{h['budget_minutes']:g} min (took {h.get('minutes', '?')} min), seed {h['seed']}, "
               f"per-command timeout {h['timeout_s']:g} s, address space {h['memory_gib']:g} GiB, "
               f"{h['cpus']} CPUs.", ""]
        for fam in (["baselines"] if self.cases.get("baselines") else []) + families:
            cs = self.cases.get(fam, [])
            took = f", {self.family_time[fam]:.0f} s" if fam in self.family_time else ""
            out += [f"### {fam} ({len(cs)} cases{took})", ""]
            out += self.family_table(fam, cs) + [""]
            if fam == "cache" and cs:
                out += self.cache_breakdown(cs) + [""]
        if self.issue_cases:
            out += ["### The cases named in issue #31 (shrunk quickstart)", "",
                    "| case | outcome | flags | what it said |", "|---|---|---|---|"]
            for c in self.issue_cases:
                said = c.notes[0] if c.notes else (first_words(c.procs[-1].stderr) if c.procs else "")
                out.append(f"| {c.name.split(': ', 1)[1]} | {c.outcome} | {', '.join(sorted(c.flags)) or '-'} | "
                           f"{cell(said)} |")
            out.append("")
        for fam, cases in self.named.items():
            out += [f"### {NAMED_TITLES[fam]}", "", "| case | outcome | flags | what it said |", "|---|---|---|---|"]
            for c in cases:
                said = "; ".join(c.notes[:2]) if c.notes else ""
                out.append(f"| {cell(c.name, 60)} | {c.outcome} | {', '.join(sorted(c.flags)) or '-'} | {cell(said, 160)} |")
            out.append("")
        out += [f"Anomalous cases: {len(self.anomalies)} (each in the report folder with its input, "
                "commands and output tails)."]
        kinds = Counter()
        for c, _ in self.anomalies:
            kinds.update(c.flags | ({c.outcome} if c.outcome in ("panic", "hang", "oom") else set()))
        if kinds:
            out.append("By kind: " + ", ".join(f"{k.replace('_', ' ')} {v}" for k, v in sorted(kinds.items())) + ".")
        return "\n".join(out) + "\n"

    def family_table(self, fam, cs):
        cols = list(COMMON_COLUMNS)
        if fam in FLAG_COLUMNS:
            cols += [(f.replace("_", " "), lambda cs, f=f: sum(f in c.flags for c in cs)) for f in FLAG_COLUMNS[fam]]
        else:
            cols = [cols[0]] + [(t, lambda cs, k=k: sum(bool(c.extra.get(k)) for c in cs)) for t, k in EXTRA_COLUMNS[fam]]
            if fam == "concurrency":
                cols.insert(1, ("runs failed", lambda cs: f"{sum(c.extra['failed'] for c in cs)}/"
                                                           f"{sum(c.extra['runs'] for c in cs)}"))
            cols += [(o, lambda cs, o=o: sum(c.outcome == o for c in cs)) for o in ("panic", "hang", "oom")]
            cols += [(f.replace("_", " "), lambda cs, f=f: sum(f in c.flags for c in cs))
                     for f in ("debug_text", "repeated_clause", "lost_tables")]
            if fam == "cache":
                cols.append(("still corrupt", lambda cs: sum("still_corrupt" in c.flags for c in cs)))
                cols.insert(2, ("undetected", lambda cs: sum("undetected" in c.flags for c in cs)))
        names = [c[0] for c in cols]
        return ["| " + " | ".join(names) + " |", "|" + "---|" * len(names),
                "| " + " | ".join(str(f(cs)) for _, f in cols) + " |"]

    def cache_breakdown(self, cs):
        rows = defaultdict(list)
        for c in cs:
            rows[c.name.split(" at ")[0]].append(c)
        out = ["| fault | cases | detected by verify | rerun identical | verify ok after gc |", "|---|---|---|---|---|"]
        for fault, group in rows.items():
            n = len(group)
            out.append(f"| {fault} | {n} | " + " | ".join(
                f"{sum(bool(c.extra.get(k)) for c in group)}/{n}"
                for k in ("detected", "rerun_identical", "verify_after_gc")) + " |")
        return out


def cell(text, limit=110):
    text = " ".join(str(text).split()).replace("|", "\\|")
    return text if len(text) <= limit else text[: limit - 1] + "…"

