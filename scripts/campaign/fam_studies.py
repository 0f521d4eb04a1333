"""Family 1: mutated studies. Every shipped study shrunk (mutate_yaml.shrink), then mutated one
site at a time, plus the named cases of issue #31; each case is `validate`d, then `run`."""

import copy
import os
import shutil

import mutate_yaml as my
from common import Case, classify_run, message_flags, process_outcome, rejection


def issue_cases(quickstart):
    """The cases of issue #31 on the shrunk quickstart: (name, study bytes)."""
    out = []

    def edit(name, f):
        d = copy.deepcopy(quickstart)
        f(d)
        out.append((name, my.dump(d).encode()))

    nodes = lambda d: d["nodes"]  # noqa: E731
    edit("friction nominal_pressures [10 GPa]", lambda d: nodes(d)["friction"]["friction"].update(nominal_pressures=["10 GPa"]))
    edit("sq 64 um", lambda d: d["parameters"]["product"].update(sq=["64 um"]))
    edit("sq 1e-300 m", lambda d: d["parameters"]["product"].update(sq=["1e-300 m"]))
    edit("sq 1e308 um", lambda d: d["parameters"]["product"].update(sq=["1e308 um"]))
    edit("junction_shear interface_factor 1e308", lambda d: nodes(d)["junction_shear"]["friction"].update(model={"junction_shear": {"interface_factor": 1e308}}))
    edit("contact flow_pressure 21 MPa", lambda d: nodes(d)["contact"]["contact"].update(flow_pressure="21 MPa"))
    for n in (2, 3):
        edit(f"grid {n}x{n}", lambda d, n=n: nodes(d)["lower"]["surface"]["synthetic"].update(grid=[n, n]))
    for t in (1e-16, 1e-300):
        edit(f"contact tolerance {t}", lambda d, t=t: nodes(d)["contact"]["contact"].update(tolerance=t))
    edit("size [1e6 m, 0.125 mm]", lambda d: nodes(d)["lower"]["surface"]["synthetic"].update(size=["1e6 m", "0.125 mm"]))
    edit("summaries by [sq, sq]", lambda d: d["summaries"]["per_sq"].update(by=["sq", "sq"]))
    edit("256-character study name", lambda d: d.update(study="q" * 256))

    def refs(pattern, n):
        def f(d):
            d["parameters"]["product"]["n"] = [n]
            nodes(d)["lower"]["surface"]["synthetic"]["grid"] = [pattern, pattern]
        return f

    edit('grid "${n}${n}" (n = 3, expect ok)', refs("${n}${n}", 3))
    edit('grid "${n}0" (n = 3, expect ok)', refs("${n}0", 3))
    return out


SPECIAL_FILES = [("study file is a FIFO", "fifo"), ("study file is /dev/zero", "/dev/zero"),
                 ("study file is /dev/urandom", "/dev/urandom")]


def build_cases(repo, rng, shrunk):
    """The ordered case list: issue cases first, then the mutations of every study interleaved."""
    cases = [("quickstart", name, text, True) for name, text in issue_cases(shrunk["quickstart"])]
    cases += [("special", name, target, True) for name, target in SPECIAL_FILES]
    per_study = []
    for study, doc in sorted(shrunk.items()):
        muts = [(study, name, text.encode(), False) for name, text in my.tree_mutations(doc)]
        muts += [(study, name, text, False) for name, text in my.line_mutations(my.dump(doc), rng, 4)]
        rng.shuffle(muts)
        per_study.append(muts)
    while any(per_study):
        for muts in per_study:
            if muts:
                cases.append(muts.pop())
    return cases


def shrunk_studies(repo):
    out = {}
    for name in sorted(os.listdir(os.path.join(repo, "studies"))):
        if name.endswith(".yaml"):
            with open(os.path.join(repo, "studies", name)) as f:
                out[name[:-5]] = my.shrink(my.load(f.read()))
    return out


class StudyFamily:
    name = "studies"

    def __init__(self, ctx):
        self.ctx = ctx
        self.dir = os.path.join(ctx.scratch, "studies")
        os.makedirs(self.dir, exist_ok=True)
        os.symlink(os.path.join(ctx.repo, "studies", "data"), os.path.join(self.dir, "data"))
        self.cache = os.path.join(self.dir, "cache")
        self.shrunk = shrunk_studies(ctx.repo)
        self.cases = build_cases(ctx.repo, ctx.rng("studies"), self.shrunk)
        self.issue_results = []

    def baselines(self):
        """Each shrunk study unmutated: it must validate and run, or its mutations mean little."""
        for study, doc in sorted(self.shrunk.items()):
            case = self.run_case(study, "shrunk, unmutated", my.dump(doc).encode(), False)
            case.family = "baselines"
            yield case

    def __iter__(self):
        yield from self.baselines()
        for study, name, payload, is_issue in self.cases:
            case = self.run_case(study, name, payload, is_issue)
            if is_issue:
                self.issue_results.append(case)
            yield case

    def run_case(self, study, name, payload, is_issue):
        ctx = self.ctx
        case = Case(self.name, f"{study}: {name}")
        path = os.path.join(self.dir, "case.yaml")
        out = os.path.join(self.dir, "out")
        shutil.rmtree(out, ignore_errors=True)
        if os.path.lexists(path):
            os.remove(path)
        if study == "special":
            if payload == "fifo":
                os.mkfifo(path)
            else:
                os.symlink(payload, path)
            case.inputs["how.txt"] = f"case.yaml is {payload}\n".encode()
        else:
            with open(path, "wb") as f:
                f.write(payload)
            case.inputs["case.yaml"] = payload
        case.inputs["data"] = os.path.join(ctx.repo, "studies", "data")
        v = ctx.runner.run([ctx.bin, "validate", "case.yaml"], self.dir)
        case.procs.append(v)
        case.flags |= message_flags([v.stderr])
        special = process_outcome(v)
        if special:
            case.outcome = special
            return case
        if v.rc != 0:
            case.outcome = rejection(v)
            if not v.stderr.strip():
                case.flags.add("no_message")
            return case
        if study == "special":
            case.outcome = "ok"
            case.flags.add("late_failure")
            case.notes.append(f"validate accepted {payload} as a study file")
            return case
        argv = [ctx.bin, "run", "case.yaml", "--cache", "cache", "-q"]
        if is_issue:  # as a user runs it: into results/<study>
            shutil.rmtree(os.path.join(self.dir, "results"), ignore_errors=True)
            out = os.path.join(self.dir, "results", str(my.load(payload.decode()).get("study")))
        else:
            argv += ["--out", "out"]
        r = ctx.runner.run(argv, self.dir)
        classify_run(case, r, out, validated=True)
        return case
