"""Family `memory` (issue #42.8): the shipped quickstart at a larger grid run under `--memory-mib`
budgets from generous to too small. A run that completes must peak at most the budget plus the
allowance of tests/scale_out/memory.rs (8 MiB: the results' Parquet writing after the run and the
estimates' calibration); one that cannot fit must fail its nodes naming `--memory-mib`, never be
killed by the address-space limit or exceed the budget silently."""

import copy
import os
import shutil

import mutate_yaml as my
from common import Case, classify_run, first_words

#: MiB a completed run may peak above its budget (as in tests/scale_out/memory.rs).
ALLOWANCE_MIB = 8
#: The grid the quickstart is run at, and the budgets tried (MiB).
GRID = 512
BUDGETS = (400, 160, 120, 100, 60, 40)


def memory_cases(shrunk):
    """(name, study bytes, budget MiB): the quickstart at GRID², one case per budget."""
    d = copy.deepcopy(shrunk["quickstart"])
    d["nodes"]["lower"]["surface"]["synthetic"]["grid"] = [GRID, GRID]
    payload = my.dump(d).encode()
    return [(f"quickstart {GRID}², --memory-mib {b}", payload, b) for b in BUDGETS]


class MemoryFamily:
    name = "memory"

    def __init__(self, ctx, cases):
        self.ctx, self.cases = ctx, cases
        self.dir = os.path.join(ctx.scratch, self.name)
        os.makedirs(self.dir, exist_ok=True)
        self.results = []

    def __iter__(self):
        for name, payload, budget in self.cases:
            case = self.run_case(name, payload, budget)
            self.results.append(case)
            yield case

    def run_case(self, name, payload, budget):
        case = Case(self.name, name)
        path = os.path.join(self.dir, "case.yaml")
        with open(path, "wb") as f:
            f.write(payload)
        case.inputs["case.yaml"] = payload
        out = os.path.join(self.dir, "out")
        shutil.rmtree(out, ignore_errors=True)
        shutil.rmtree(os.path.join(self.dir, "cache"), ignore_errors=True)
        argv = [self.ctx.bin, "run", "case.yaml", "--cache", "cache", "--out", "out", "-q", "--memory-mib", str(budget)]
        r = self.ctx.runner.run(argv, self.dir)
        classify_run(case, r, out, validated=False)
        case.extra["peak_mib"] = round(r.maxrss_mib, 1)
        case.extra["budget_mib"] = budget
        case.extra["within_budget"] = r.rc == 0 and r.maxrss_mib <= budget + ALLOWANCE_MIB
        case.extra["refused"] = r.rc != 0 and "memory-mib" in r.stderr
        if r.rc == 0 and r.maxrss_mib > budget + ALLOWANCE_MIB:
            case.flags.add("over_budget")
            case.notes.append(f"peak {r.maxrss_mib:.0f} MiB above the budget {budget} MiB + {ALLOWANCE_MIB}")
        elif r.rc != 0 and "--memory-mib" not in r.stderr and "memory-mib" not in r.stderr:
            case.flags.add("no_message")
            case.notes.append("failed without naming --memory-mib: " + first_words(r.stderr))
        else:
            case.notes.append(f"rc {r.rc}, peak {r.maxrss_mib:.0f} MiB of {budget} MiB")
        return case
