"""The cases of issue #42: Ctrl-C at several moments (family `interrupts`), folders that cannot be
written, leftovers and two study files of one name (`folders`), the forms an angle is written in
(`angles`), and per-spot friction where spots merge, where load has no radius and where adhesion
carries the load (`per_spot`). Permission cases run the binary as the unprivileged user 65534
when the campaign runs as root (who may write anywhere)."""

import copy
import os
import shutil
import signal
import time

import mutate_yaml as my
from common import Case, check_results, classify_run, first_words, message_flags, process_outcome, rejection
from fam_cache import fresh, small_study

NOBODY = 65534


def tmp_left(cache):
    path = os.path.join(cache, "tmp")
    return sorted(os.listdir(path)) if os.path.isdir(path) else []


class InterruptFamily:
    """SIGINT once or twice at a random moment of a run of the small study on an empty cache (or,
    for the table-writing moment, on the filled reference cache), then `cache verify` at once, a
    rerun and a comparison with the reference tables."""

    name = "interrupts"

    def __init__(self, ctx, base):
        self.ctx, self.base = ctx, base
        self.rng = ctx.rng("interrupts")

    def __iter__(self):
        kinds = ["once", "twice", "while writing"]
        i = 0
        while True:
            kind = kinds[i % len(kinds)]
            i += 1
            yield self.run_case(kind, self.rng.uniform(0.02, 1.1) * self.base.seconds)

    def run_case(self, kind, delay):
        b, runner = self.base, self.ctx.runner
        cache = fresh(os.path.join(b.dir, "i-cache"))
        out = fresh(os.path.join(b.dir, "i-out"))
        if kind == "while writing":
            shutil.copytree(b.ref_cache, cache)
            case = Case("interrupts", "SIGINT when the staging folder appears (filled cache)")
        else:
            case = Case("interrupts", f"SIGINT {kind} after {delay:.2f} s")
        case.inputs["small.yaml"] = b.study_bytes
        h = runner.start(b.argv(out, cache), b.dir)
        pid = h[2]
        if kind == "while writing":
            deadline = time.monotonic() + 30
            while time.monotonic() < deadline and not any(".staging." in n for n in os.listdir(b.dir)):
                if os.waitpid(pid, os.WNOHANG)[0]:
                    break
                time.sleep(0.001)
        else:
            time.sleep(delay)
        signals = 2 if kind == "twice" else 1
        for n in range(signals):
            try:
                os.kill(pid, signal.SIGINT)
            except ProcessLookupError:
                pass
            if n + 1 < signals:
                time.sleep(0.05)
        first = runner.finish(h)
        left = tmp_left(cache)
        v1 = b.cache_cmd(cache, "verify")
        r = b.run(out, cache)
        v2 = b.cache_cmd(cache, "verify")
        case.procs += [first, v1, r, v2]
        case.flags |= message_flags([p.stderr for p in case.procs])
        case.outcome = process_outcome(first) or process_outcome(r) or "ok"
        interrupted = first.rc == 130
        case.extra["interrupted"] = interrupted
        case.extra["said interrupted"] = "interrupted" in first.stderr
        case.extra["tmp clean"] = not left
        case.extra["verify ok at once"] = v1.rc == 0
        same, why = b.same_as_ref(out)
        case.extra["rerun identical"] = r.rc == 0 and same
        if first.rc not in (0, 130) or (interrupted and not case.extra["said interrupted"]):
            case.flags.add("no_message")
            case.notes.append(f"interrupted run: exit {first.rc}: {first_words(first.stderr)}")
        if left or v1.rc != 0 or not case.extra["rerun identical"]:
            case.flags.add("lost_tables")
            case.notes += [f"left in tmp/: {n}" for n in left] + ([why] if why else [])
            if v1.rc != 0:
                case.notes.append("cache verify fails right after the interrupted run: " + first_words(v1.stdout + v1.stderr))
        return case


def as_nobody():
    if os.geteuid() == 0:
        os.setgroups([])
        os.setgid(NOBODY)
        os.setuid(NOBODY)


class FolderFamily:
    """Each folder case once: a results folder whose parent, or which itself, cannot be written; a
    partly filled cache that cannot be written; staging folders of dead runs, one removable and
    one not; the same `study:` name from two files."""

    name = "folders"

    def __init__(self, ctx, base):
        self.ctx, self.base = ctx, base

    def __iter__(self):
        for name in ("results parent read-only", "results folder read-only", "cache read-only, partly filled",
                     "stale staging folders", "same study name from two files"):
            yield self.run_case(name)

    def setup(self):
        work = fresh(os.path.join(self.base.dir, "f"))
        os.makedirs(work)
        os.chmod(work, 0o777)
        study = os.path.join(work, "small.yaml")
        with open(study, "wb") as f:
            f.write(self.base.study_bytes)
        return work, study

    def run_user(self, argv, cwd):
        runner = self.ctx.runner
        saved = runner._preexec

        def preexec():
            saved()
            as_nobody()

        runner._preexec = preexec
        try:
            return runner.run(argv, cwd)
        finally:
            runner._preexec = saved

    def run_case(self, name):
        b, bin_ = self.base, self.ctx.bin
        work, study = self.setup()
        case = Case("folders", name)
        case.inputs["small.yaml"] = b.study_bytes
        ro = 0o755 if os.geteuid() == 0 else 0o555
        run = [bin_, "run", "small.yaml", "-q"]
        out = os.path.join(work, "results", my.load(b.study_bytes.decode())["study"])
        expect_fail = True
        if name == "results parent read-only":
            os.makedirs(os.path.join(work, "results"))
            os.chmod(os.path.join(work, "results"), ro)
            p = self.run_user(run + ["--cache", "cache"], work)
        elif name == "results folder read-only":
            os.makedirs(os.path.join(work, "results"), mode=0o777)
            os.chmod(os.path.join(work, "results"), 0o777)
            self.ctx.runner.run(run + ["--cache", "cache0"], work)
            os.chmod(out, ro)
            p = self.run_user(run + ["--cache", "cache"], work)
        elif name == "cache read-only, partly filled":
            self.ctx.runner.run(run + ["--cache", "cache", "--out", "part", "--set", "seed=[1]"], work)
            for root, dirs, files in os.walk(os.path.join(work, "cache")):
                for d in dirs:
                    os.chmod(os.path.join(root, d), ro)
            os.chmod(os.path.join(work, "cache"), ro)
            p = self.run_user(run + ["--cache", "cache"], work)
            expect_fail = False
        elif name == "stale staging folders":
            host = open("/proc/sys/kernel/hostname").read().strip()
            results = os.path.join(work, "results")
            os.makedirs(results)
            os.chmod(results, 0o777)
            base = os.path.basename(out)
            for pid, mode in ((4294000, 0o555), (4294001, 0o755)):
                d = os.path.join(results, f".{base}.staging.{host}.{pid}.1-0")
                os.makedirs(os.path.join(d, "sub"))
                open(os.path.join(d, "sub", "timings.parquet"), "w").close()
                if pid == 4294000 and os.geteuid() == 0:
                    for x in (d, os.path.join(d, "sub")):
                        os.chown(x, NOBODY, NOBODY)
                os.chmod(os.path.join(d, "sub"), mode)
                os.chmod(d, 0o777 if pid == 4294001 else mode)
            p = self.run_user(run + ["--cache", "cache"], work)
            expect_fail = False
            case.extra["leftovers"] = sorted(n for n in os.listdir(results) if n.startswith("."))
        else:
            other = os.path.join(work, "copy")
            os.makedirs(other)
            with open(os.path.join(other, "small.yaml"), "wb") as f:
                f.write(b.study_bytes.replace(b"0.03 um", b"0.04 um"))
            self.ctx.runner.run(run + ["--cache", "cache"], work)
            p = self.ctx.runner.run([bin_, "run", "copy/small.yaml", "-q", "--cache", "cache"], work)
            forced = self.ctx.runner.run([bin_, "run", "copy/small.yaml", "-q", "--cache", "cache", "--force"], work)
            case.procs.append(forced)
            case.extra["forced warns"] = forced.rc == 0 and "another study file" in forced.stderr
        case.procs.insert(0, p)
        case.flags |= message_flags([x.stderr for x in case.procs])
        special = process_outcome(p)
        warnings = [line for line in p.stderr.splitlines() if line.startswith("warning:")]
        case.extra["warning lines"] = len(warnings)
        case.extra["before computing"] = "nothing was computed" in p.stderr
        if special:
            case.outcome = special
        elif p.rc != 0:
            case.outcome = rejection(p)
        else:
            status, impossible, problems, _ = check_results(out if name != "stale staging folders" else out)
            case.outcome = "ok"
            if problems:
                case.flags.add("lost_tables")
                case.notes += problems
        if expect_fail != (p.rc != 0):
            case.flags.add("late_failure")
        case.notes.append(first_words(p.stderr) or first_words(p.stdout))
        if len(warnings) > 1:
            case.flags.add("repeated_clause")
            case.notes.append(f"{len(warnings)} warning lines")
        return case


def angle_cases(shrunk):
    """(name, study bytes): the ploughing node of the shrunk ground-validation study and the
    anisotropy of its surface, with angles in every form."""
    out = []
    forms = ["6.2832", "6.2832 rad", "360 deg", "360°", "0", "-0.0", "90", "90 deg", "1.5707963267948966 rad",
             "1e400 rad", "-90 deg", "720 deg"]
    doc = shrunk["ground-validation"]
    plough = next(n for n, s in doc["nodes"].items()
                  if isinstance(s.get("friction", {}).get("model"), dict) and "ploughing" in s["friction"]["model"])
    surface = next(n for n, s in doc["nodes"].items()
                   if "synthetic" in s.get("surface", {}) and "anisotropy" in s["surface"]["synthetic"])
    for form in forms:
        d = copy.deepcopy(doc)
        d["nodes"][plough]["friction"]["model"]["ploughing"]["sliding_direction"] = form
        out.append((f"sliding_direction: {form}", my.dump(d).encode()))
        d = copy.deepcopy(doc)
        d["nodes"][surface]["surface"]["synthetic"]["anisotropy"]["angle"] = form
        out.append((f"anisotropy.angle: {form}", my.dump(d).encode()))
    d = copy.deepcopy(doc)
    d.setdefault("parameters", {}).setdefault("product", {})["psi"] = [1.57]
    d["nodes"][plough]["friction"]["model"]["ploughing"]["sliding_direction"] = "${psi}"
    out.append(("sliding_direction: ${psi}, psi: [1.57]", my.dump(d).encode()))
    return out


def per_spot_cases(shrunk):
    """(name, study bytes): per-spot friction on the shrunk quickstart where spots merge (a load
    near the flow pressure), where little load has a radius, and with adhesion."""
    out = []
    q = shrunk["quickstart"]
    for p in ("490 MPa", "980 MPa", "1470 MPa", "1862 MPa"):
        d = copy.deepcopy(q)
        d["nodes"]["contact"]["contact"]["nominal_pressures"] = [p]
        out.append((f"merged spots: full_stick and junction_shear per spot at {p}", my.dump(d).encode()))
    d = copy.deepcopy(q)
    d["nodes"]["lower"]["surface"]["synthetic"]["grid"] = [16, 16]
    out.append(("load without radius: 16² grid", my.dump(d).encode()))
    d = copy.deepcopy(q)
    d["nodes"]["junction_shear"]["friction"]["adhesion_energy"] = "0.5 N/m"
    d["nodes"]["contact"]["contact"]["nominal_pressures"] = ["0.2 MPa"]
    out.append(("adhesion-dominated: 0.5 N/m at 0.2 MPa", my.dump(d).encode()))
    return out


class StudyCasesFamily:
    """Named study cases, each `validate`d then `run` into its own results folder."""

    def __init__(self, ctx, name, cases):
        self.ctx, self.name, self.cases = ctx, name, cases
        self.dir = os.path.join(ctx.scratch, name)
        os.makedirs(self.dir, exist_ok=True)
        link = os.path.join(self.dir, "data")
        if not os.path.lexists(link):
            os.symlink(os.path.join(ctx.repo, "studies", "data"), link)
        self.results = []

    def __iter__(self):
        for name, payload in self.cases:
            case = self.run_case(name, payload)
            self.results.append(case)
            yield case

    def run_case(self, name, payload):
        ctx = self.ctx
        case = Case(self.name, name)
        path = os.path.join(self.dir, "case.yaml")
        with open(path, "wb") as f:
            f.write(payload)
        case.inputs["case.yaml"] = payload
        out = os.path.join(self.dir, "out")
        shutil.rmtree(out, ignore_errors=True)
        v = ctx.runner.run([ctx.bin, "validate", "case.yaml"], self.dir)
        case.procs.append(v)
        case.flags |= message_flags([v.stderr])
        special = process_outcome(v)
        if special or v.rc != 0:
            case.outcome = special or rejection(v)
            case.notes.append(first_words(v.stderr))
            return case
        r = ctx.runner.run([ctx.bin, "run", "case.yaml", "--cache", "cache", "--out", "out", "-q"], self.dir)
        classify_run(case, r, out, validated=True)
        if not case.notes:
            case.notes.append(first_words(r.stderr) or "ok")
        return case
