"""Families 3-5 on one small study (quickstart at its own 256² grid, 2 Sq × 2 seeds: a run of a
few seconds): cache faults, kills and concurrent runs, each compared with a reference run's table
bytes (timings.parquet aside)."""

import os
import shutil
import signal
import time

import mutate_yaml as my
from common import Case, check_results, first_words, kill_group, message_flags, process_outcome


def small_study(repo):
    with open(os.path.join(repo, "studies", "quickstart.yaml")) as f:
        doc = my.load(f.read())
    doc["parameters"]["product"] = {"sq": ["0.03 um", "0.05 um"], "seed": {"range": [1, 2]}}
    return my.dump(doc).encode()


def table_bytes(out):
    """{name: bytes} of a results folder's tables, timings.parquet aside."""
    if not os.path.isdir(out):
        return {}
    res = {}
    for n in sorted(os.listdir(out)):
        if n.endswith(".parquet") and n != "timings.parquet":
            with open(os.path.join(out, n), "rb") as f:
                res[n] = f.read()
    return res


def leftovers(folder):
    """Hidden or temporary files in a results folder, and anything in a cache's tmp/."""
    found = []
    if os.path.isdir(folder):
        found += [n for n in os.listdir(folder) if n.startswith(".") or "tmp" in n]
    return found


class Base:
    """The small study, its reference run (cache and tables) and helpers."""

    def __init__(self, ctx):
        self.ctx = ctx
        self.dir = os.path.join(ctx.scratch, "small")
        os.makedirs(self.dir, exist_ok=True)
        self.study = os.path.join(self.dir, "small.yaml")
        self.study_bytes = small_study(ctx.repo)
        with open(self.study, "wb") as f:
            f.write(self.study_bytes)
        self.ref_cache = os.path.join(self.dir, "ref-cache")
        self.ref_out = os.path.join(self.dir, "ref-out")
        p = self.run(self.ref_out, self.ref_cache)
        if p.rc != 0:
            raise SystemExit("the reference run of the small study failed:\n" + p.tail())
        self.seconds = p.seconds
        self.ref = table_bytes(self.ref_out)

    def argv(self, out, cache):
        return [self.ctx.bin, "run", self.study, "--out", out, "--cache", cache, "-q"]

    def run(self, out, cache, timeout=None):
        return self.ctx.runner.run(self.argv(out, cache), self.dir, timeout)

    def cache_cmd(self, cache, *args):
        return self.ctx.runner.run([self.ctx.bin, "cache", *args, "--cache", cache], self.dir)

    def same_as_ref(self, out):
        got = table_bytes(out)
        if got == self.ref:
            return True, ""
        diff = sorted(set(got) ^ set(self.ref)) + [n for n in got if n in self.ref and got[n] != self.ref[n]]
        return False, "tables differ from the reference: " + ", ".join(diff)


def entries(cache):
    """(kind, entry path) of every cache entry."""
    out = []
    root = os.path.join(cache, "entries")
    for kind in sorted(os.listdir(root)):
        for shard in sorted(os.listdir(os.path.join(root, kind))):
            for key in sorted(os.listdir(os.path.join(root, kind, shard))):
                out.append((kind, os.path.join(root, kind, shard, key)))
    return out


def flip_byte(path, rng):
    with open(path, "r+b") as f:
        data = f.read()
        if not data:
            return
        i = rng.randrange(len(data))
        f.seek(i)
        f.write(bytes([data[i] ^ 0xFF]))


def replace_by_file(path):
    shutil.rmtree(path)
    with open(path, "w") as f:
        f.write("not a folder\n")


FAULTS = [
    "flip a payload byte", "flip a manifest byte", "delete manifest.json", "delete manifest.blake3",
    "delete a payload", "truncate a payload", "empty an entry folder", "entry folder -> file",
    "kind folder -> file", "stray file in tmp/", "stray folder in tmp/",
    "entry -> symlink to a copy outside", "entry -> symlink to a damaged copy outside",
]


def apply_fault(fault, cache, outside, rng):
    """Damages `cache`; returns a sentence saying where."""
    ents = entries(cache)
    kind, entry = rng.choice(ents)
    payloads = sorted(n for n in os.listdir(entry) if n not in ("manifest.json", "manifest.blake3"))
    payload = os.path.join(entry, rng.choice(payloads)) if payloads else os.path.join(entry, "manifest.json")
    where = os.path.relpath(entry, cache)
    if fault == "flip a payload byte":
        flip_byte(payload, rng)
        where = os.path.relpath(payload, cache)
    elif fault == "flip a manifest byte":
        flip_byte(os.path.join(entry, "manifest.json"), rng)
    elif fault == "delete manifest.json":
        os.remove(os.path.join(entry, "manifest.json"))
    elif fault == "delete manifest.blake3":
        os.remove(os.path.join(entry, "manifest.blake3"))
    elif fault == "delete a payload":
        os.remove(payload)
        where = os.path.relpath(payload, cache)
    elif fault == "truncate a payload":
        os.truncate(payload, os.path.getsize(payload) // 2)
        where = os.path.relpath(payload, cache)
    elif fault == "empty an entry folder":
        shutil.rmtree(entry)
        os.mkdir(entry)
    elif fault == "entry folder -> file":
        replace_by_file(entry)
    elif fault == "kind folder -> file":
        k = os.path.join(cache, "entries", kind)
        replace_by_file(k)
        where = os.path.relpath(k, cache)
    elif fault == "stray file in tmp/":
        with open(os.path.join(cache, "tmp", "stray.partial"), "w") as f:
            f.write("left by a crash\n")
        where = "tmp/stray.partial"
    elif fault == "stray folder in tmp/":
        shutil.copytree(entry, os.path.join(cache, "tmp", "half-written-entry"))
        where = "tmp/half-written-entry"
    else:
        copy = os.path.join(outside, os.path.basename(entry))
        shutil.rmtree(copy, ignore_errors=True)
        shutil.move(entry, copy)
        if "damaged" in fault:
            ps = sorted(n for n in os.listdir(copy) if n not in ("manifest.json", "manifest.blake3"))
            flip_byte(os.path.join(copy, rng.choice(ps) if ps else "manifest.json"), rng)
        os.symlink(copy, entry)
    return f"{fault} at {where}"


def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    return path


class CacheFamily:
    """Family 3: fault, `cache verify` (detected?), rerun (same bytes?), verify, the repairs
    (`cache verify --delete`, `cache gc`), verify."""

    name = "cache"

    def __init__(self, ctx, base):
        self.ctx, self.base = ctx, base
        self.rng = ctx.rng("cache")

    def __iter__(self):
        i = 0
        while True:
            fault = FAULTS[i % len(FAULTS)]
            i += 1
            yield self.run_case(fault)

    def run_case(self, fault):
        b = self.base
        cache = fresh(os.path.join(b.dir, "c-cache"))
        out = fresh(os.path.join(b.dir, "c-out"))
        outside = fresh(os.path.join(b.dir, "c-outside"))
        os.makedirs(outside)
        shutil.copytree(b.ref_cache, cache, symlinks=True)
        where = apply_fault(fault, cache, outside, self.rng)
        case = Case("cache", where)
        case.inputs["small.yaml"] = b.study_bytes
        v1 = b.cache_cmd(cache, "verify")
        r = b.run(out, cache)
        v2 = b.cache_cmd(cache, "verify")
        # The documented repairs: `verify --delete` removes corrupt entries, `gc` repairs the
        # folder structure (docs/scale-out.md).
        delete = b.cache_cmd(cache, "verify", "--delete")
        gc = b.cache_cmd(cache, "gc", b.study)
        v3 = b.cache_cmd(cache, "verify")
        procs = [v1, r, v2, delete, gc, v3]
        case.procs += procs
        case.flags |= message_flags([p.stderr for p in procs])
        specials = [process_outcome(p) for p in procs]
        case.outcome = next((s for s in specials if s), "ok")
        case.extra["detected"] = v1.rc != 0
        same, why = b.same_as_ref(out)
        case.extra["rerun_identical"] = r.rc == 0 and same
        case.extra["verify_after_run"] = v2.rc == 0
        case.extra["verify_after_gc"] = v3.rc == 0
        status, impossible, problems, _ = check_results(out)
        if r.rc != 0 or problems or not same:
            case.flags.add("lost_tables")
            case.notes += problems + ([why] if why else []) + ([f"rerun exit {r.rc}"] if r.rc else [])
        if not case.extra["detected"]:
            case.flags.add("undetected")
            case.notes.append("cache verify passed the damaged cache")
        if not case.extra["verify_after_gc"]:
            case.flags.add("still_corrupt")
            case.notes.append("cache verify fails after the rerun, `cache verify --delete` and `cache gc`: " + first_words(v3.stderr + v3.stdout))
        return case


class KillFamily:
    """Family 4: SIGKILL a run of the small study at a random time, rerun, compare, verify."""

    name = "kills"

    def __init__(self, ctx, base):
        self.ctx, self.base = ctx, base
        self.rng = ctx.rng("kills")

    def __iter__(self):
        while True:
            yield self.run_case(self.rng.uniform(0.02, 1.1) * self.base.seconds)

    def run_case(self, delay):
        b, runner = self.base, self.ctx.runner
        cache = fresh(os.path.join(b.dir, "k-cache"))
        out = fresh(os.path.join(b.dir, "k-out"))
        case = Case("kills", f"SIGKILL after {delay:.2f} s")
        case.inputs["small.yaml"] = b.study_bytes
        h = runner.start(b.argv(out, cache), b.dir)
        time.sleep(delay)
        kill_group(h[2])
        first = runner.finish(h)
        case.extra["killed"] = first.rc == -signal.SIGKILL
        r = b.run(out, cache)
        v = b.cache_cmd(cache, "verify")
        case.procs += [first, r, v]
        case.flags |= message_flags([r.stderr, v.stderr])
        case.outcome = process_outcome(r) or process_outcome(v) or "ok"
        same, why = b.same_as_ref(out)
        case.extra["rerun_identical"] = r.rc == 0 and same
        case.extra["verify_after_run"] = v.rc == 0
        left = leftovers(out) + [os.path.join("tmp", n) for n in os.listdir(os.path.join(cache, "tmp"))]
        case.extra["leftovers"] = bool(left)
        if not case.extra["rerun_identical"] or left or v.rc != 0:
            case.flags.add("lost_tables")
            case.notes += ([why] if why else []) + [f"left: {x}" for x in left]
            if v.rc != 0:
                case.notes.append("cache verify fails after the rerun")
        return case


class ConcurrencyFamily:
    """Family 5: 4 simultaneous runs into one folder with one cache (explicit paths, or the
    defaults ./cache and results/<study> from one working folder, alternately)."""

    name = "concurrency"
    runs = 4

    def __init__(self, ctx, base):
        self.ctx, self.base = ctx, base

    def __iter__(self):
        i = 0
        while True:
            yield self.run_case(defaults=i % 2 == 1)
            i += 1

    def run_case(self, defaults):
        b, runner = self.base, self.ctx.runner
        work = fresh(os.path.join(b.dir, "cc"))
        os.makedirs(work)
        if defaults:
            argv = [self.ctx.bin, "run", b.study, "-q"]
            name = my.load(b.study_bytes.decode())["study"]
            out = os.path.join(work, "results", name)
        else:
            out = os.path.join(work, "out")
            argv = b.argv(out, os.path.join(work, "cache"))
        case = Case("concurrency", f"{self.runs} runs at once, " + ("default cache and out" if defaults else "--out and --cache"))
        case.inputs["small.yaml"] = b.study_bytes
        handles = [runner.start(argv, work) for _ in range(self.runs)]
        procs = [runner.finish(h) for h in handles]
        case.procs += procs
        case.flags |= message_flags([p.stderr for p in procs])
        case.outcome = next((s for s in map(process_outcome, procs) if s), "ok")
        case.extra = {"runs": len(procs), "failed": sum(p.rc != 0 for p in procs)}
        status, impossible, problems, _ = check_results(out)
        same, why = b.same_as_ref(out)
        case.extra["complete"] = not problems
        case.extra["identical"] = same
        if case.extra["failed"] or problems or not same:
            case.flags.add("lost_tables")
            case.notes += [f"{case.extra['failed']} of {len(procs)} runs failed"] + problems
            case.notes += [why] if why else []
            case.notes += sorted({p.stderr.strip().splitlines()[-1] for p in procs if p.rc and p.stderr.strip()})
        return case
