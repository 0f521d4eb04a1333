"""Running asperity under limits and classifying what it did.

Every command runs in its own session (so a timeout kills the whole process group) with an
address-space limit (RLIMIT_AS) and no core dumps; its stdout and stderr go to files, and its
peak RSS is its sampled VmHWM. A case's outcome is one of OUTCOMES; on top of it a case collects
flags (FLAGS): things that must never happen whatever the outcome.
"""

import math
import os
import re
import resource
import signal
import time
from dataclasses import dataclass, field

import pyarrow.parquet as pq

OUTCOMES = [
    "rejected_loc",  # exit != 0 with a message naming file:line:col
    "rejected",  # exit != 0 with another message
    "ok",
    "flagged",  # a status/validity column says `flagged`
    "failed_rows",  # exit 0, some rows failed with a message
    "panic",
    "hang",  # killed at the per-case timeout
    "oom",  # killed by the memory limit (allocation failure or SIGKILL)
]
FLAGS = [
    "impossible_ok",  # a row with status ok holds a physically impossible value
    "debug_text",  # a message shows Debug shapes of internal types
    "repeated_clause",  # a message repeats a clause
    "lost_tables",  # a half-written folder, tables that do not join, or temp files left
    "nonfinite_printed",  # inspect printed inf/NaN and exited 0
    "late_failure",  # validate said ok, run failed as a whole
    "no_message",  # exit != 0 with nothing on stderr
    "accepted_corrupt",  # damage that must be detected was not (checksums)
    "still_corrupt",  # the cache does not verify after a rerun and `cache gc`
    "undetected",  # `cache verify` passed a damaged cache
]

LOCATION = re.compile(r"[^\s:]+:\d+:\d+")
SOURCE_ECHO = re.compile(r"^\s*(\d+\s*)?\|")
DEBUG_SHAPES = [
    re.compile(r"\b[A-Z][A-Za-z0-9]* \{ [a-z_]+: "),  # Struct { field: .. }
    re.compile(r"\b(Some|Ok|Err)\("),
    re.compile(r"\b[A-Za-z_]\w*::[A-Za-z_]\w*"),  # paths such as io::ErrorKind
    re.compile(r"\bkind: [A-Z]\w+\b"),  # io::Error's Debug
]
NONFINITE_WORD = re.compile(r"(?<![A-Za-z])(-?inf|NaN|nan|infinity)(?![A-Za-z])", re.I)


@dataclass
class Proc:
    """One finished (or killed) command."""

    argv: list
    cwd: str
    rc: int  # exit code, or -signal
    stdout: str
    stderr: str
    seconds: float
    maxrss_mib: float
    timed_out: bool

    def text(self):
        return self.stdout + self.stderr

    def tail(self, n=3000):
        out = f"$ (cd {self.cwd} && {' '.join(quote(a) for a in self.argv)})\n"
        out += f"exit {self.rc}, {self.seconds:.1f} s, peak RSS (sampled) {self.maxrss_mib:.0f} MiB"
        out += " (timed out)\n" if self.timed_out else "\n"
        out += "--- stdout (tail) ---\n" + self.stdout[-n:] + "\n"
        out += "--- stderr (tail) ---\n" + self.stderr[-n:] + "\n"
        return out


def quote(arg):
    arg = str(arg)
    if arg and re.fullmatch(r"[\w@%+=:,./-]+", arg):
        return arg
    return "'" + arg.replace("'", "'\\''") + "'"


class Runner:
    """Runs commands with a timeout and an address-space limit, logging into `logdir`."""

    def __init__(self, timeout, mem_bytes, logdir):
        self.timeout = timeout
        self.mem_bytes = mem_bytes
        self.logdir = logdir
        self.count = 0
        os.makedirs(logdir, exist_ok=True)

    def _preexec(self):
        os.setsid()
        resource.setrlimit(resource.RLIMIT_AS, (self.mem_bytes, self.mem_bytes))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))

    def start(self, argv, cwd):
        """Starts a command; returns a handle for `finish`."""
        self.count += 1
        out = os.path.join(self.logdir, f"{self.count}.out")
        err = os.path.join(self.logdir, f"{self.count}.err")
        env = dict(os.environ, NO_COLOR="1", RUST_BACKTRACE="0")
        env.pop("ASPERITY_CACHE", None)
        with open(out, "wb") as fo, open(err, "wb") as fe, open(os.devnull, "rb") as fi:
            pid = spawn(argv, cwd, env, (fi, fo, fe), self._preexec)
        return (argv, cwd, pid, out, err, time.monotonic())

    def finish(self, handle, timeout=None):
        """Waits for a started command (killing its group at the timeout). The peak RSS is the
        child's VmHWM sampled while it runs (wait4's ru_maxrss would include the RSS of this
        Python process, which the child had at fork)."""
        argv, cwd, pid, out, err, t0 = handle
        limit = self.timeout if timeout is None else timeout
        timed_out = False
        delay = 0.005
        hwm_kib = 0
        try:
            while True:
                wpid, status = os.waitpid(pid, os.WNOHANG)
                if wpid == pid:
                    break
                hwm_kib = max(hwm_kib, vm_hwm_kib(pid))
                if time.monotonic() - t0 > limit:
                    timed_out = True
                    kill_group(pid)
                    _, status = os.waitpid(pid, 0)
                    break
                time.sleep(delay)
                delay = min(delay * 2, 0.05)
        except BaseException:  # interrupted: the child is in its own session, end it too
            kill_group(pid)
            raise
        seconds = time.monotonic() - t0
        rc = os.waitstatus_to_exitcode(status)
        return Proc(
            argv=argv,
            cwd=cwd,
            rc=rc,
            stdout=read_text(out),
            stderr=read_text(err),
            seconds=seconds,
            maxrss_mib=hwm_kib / 1024,
            timed_out=timed_out,
        )

    def run(self, argv, cwd, timeout=None):
        return self.finish(self.start(argv, cwd), timeout)


def spawn(argv, cwd, env, stdio, preexec):
    """fork + exec with stdin/stdout/stderr from `stdio` and `preexec` run in the child."""
    pid = os.fork()
    if pid == 0:
        try:
            os.chdir(cwd)
            for fd, f in enumerate(stdio):
                os.dup2(f.fileno(), fd)
            preexec()
            os.execve(argv[0], argv, env)
        finally:
            os._exit(127)
    return pid


def own_name():
    with open("/proc/self/comm") as f:
        return f.read().strip()


OWN_NAME = own_name()


def vm_hwm_kib(pid):
    """VmHWM of a running process in KiB; 0 when it cannot be read or the child has not yet
    left this process's image (between fork and exec it has this process's memory)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            fields = dict(line.split(":", 1) for line in f if ":" in line)
        if fields["Name"].strip() == OWN_NAME:
            return 0
        return int(fields["VmHWM"].split()[0])
    except (OSError, ValueError, KeyError):
        return 0


def kill_group(pid):
    try:
        os.killpg(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def read_text(path, limit=1 << 20):
    with open(path, "rb") as f:
        data = f.read(limit)
    return data.decode("utf-8", "replace")


def process_outcome(proc):
    """The outcome of a command that did not exit 0 for a plain reason, else None."""
    text = proc.text()
    if proc.timed_out:
        return "hang"
    if proc.rc == 101 or "panicked" in text or "overflowed its stack" in text:
        return "panic"
    if "memory allocation of" in text or "out of memory" in text.lower():
        return "oom"
    if proc.rc in (-signal.SIGKILL, -signal.SIGABRT):
        return "oom"  # killed from outside (the kernel's OOM killer) or aborted on allocation
    if proc.rc < 0:
        return "panic"  # any other signal is a crash
    return None


def rejection(proc):
    """`rejected_loc` or `rejected` for a command that exited != 0."""
    return "rejected_loc" if LOCATION.search(proc.stderr) else "rejected"


def message_lines(text):
    """The lines of a message without echoed source lines."""
    return [line for line in text.splitlines() if line.strip() and not SOURCE_ECHO.match(line)]


QUOTED = re.compile(r"`[^`]*`")


def has_debug_text(text):
    """A Debug-formatted Rust value in a message; spans in backquotes are names the message
    quotes (a file's own header key such as WSxM's `Control::Y Amplitude`), not checked."""
    lines = (QUOTED.sub("``", line) for line in message_lines(text))
    return any(p.search(line) for line in lines for p in DEBUG_SHAPES)


def clauses(text):
    """The ': '-separated clauses of a message (anyhow's `Caused by:` lines included)."""
    out = []
    for line in message_lines(text):
        line = re.sub(r"^\s*(\d+: |error: |Error: |warning: )", "", line)
        if line.strip() == "Caused by:":
            continue
        out.extend(c.strip() for c in line.split(": ") if c.strip())
    return out


def has_repeated_clause(text):
    """A line of a message with a clause twice, or two clauses sharing a tail of 16+ characters
    (`missing X magic: missing X magic`, `header has no X: file has no X`)."""
    for line in message_lines(text):
        cs = clauses(line)
        for i, a in enumerate(cs):
            for b in cs[i + 1 :]:
                if len(a) >= 10 and a == b:
                    return True
                tail = common_tail(a, b)
                if len(tail) >= 16 and (tail == a or tail == b or tail[0] == " "):
                    return True
    return False


def common_tail(a, b):
    n = 0
    while n < min(len(a), len(b)) and a[-1 - n] == b[-1 - n]:
        n += 1
    return a[len(a) - n :]


def message_flags(texts):
    flags = set()
    for t in texts:
        if has_debug_text(t):
            flags.add("debug_text")
        if has_repeated_clause(t):
            flags.add("repeated_clause")
    return flags


@dataclass
class Case:
    """One case of a family: what was done and what came of it."""

    family: str
    name: str
    outcome: str = ""
    flags: set = field(default_factory=set)
    notes: list = field(default_factory=list)
    procs: list = field(default_factory=list)
    inputs: dict = field(default_factory=dict)  # file name in the report -> bytes (or a link target)
    extra: dict = field(default_factory=dict)  # family-specific findings (cache, kills, ...)

    def anomalous(self):
        return bool(self.flags) or self.outcome in ("panic", "hang", "oom")


def is_fraction_column(name):
    """Columns that hold a share of a whole: area fractions, shares, stress ratios, theta."""
    if name.endswith("_key") or name in ("anisotropy_ratio", "ratio"):
        return False
    return (
        "area_fraction" in name
        or name.endswith("_share")
        or "_share_" in name
        or name in ("stress_ratio", "theta", "contact_fraction", "plastic_fraction")
        or name.endswith("_fraction")
        or name.startswith("load_share")
    )


def is_mu_column(name):
    return name == "mu" or name.startswith("mu_") or "_mu_" in name


MU_MAX = 10.0  # no static friction coefficient measured between solids comes near this


HEIGHT_STATS = {"sq_m", "sa_m", "sz_m", "sp_m", "sv_m", "rms_height_m"}
HEIGHT_MAX = 1e3  # m: no measured or synthetic surface has heights of a kilometre


def impossible_values(table_name, rows):
    """Sentences naming impossible values in rows whose status is ok."""
    found = []
    for row in rows:
        if row.get("status") != "ok":
            continue
        for name, value in row.items():
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                continue
            where = f"{table_name}: key {str(row.get('key', '?'))[:12]}: {name} = {value!r}"
            if isinstance(value, float) and not math.isfinite(value):
                found.append(where + " (not finite)")
            elif is_fraction_column(name) and not 0.0 <= value <= 1.0:
                found.append(where + " (a fraction outside [0, 1])")
            elif is_mu_column(name) and value < 0 and not name.endswith("_computed"):
                found.append(where + " (negative friction coefficient)")
            elif is_mu_column(name) and value > MU_MAX:
                found.append(where + f" (a friction coefficient above {MU_MAX:g})")
            elif name in HEIGHT_STATS and not 0.0 <= value <= HEIGHT_MAX:
                found.append(where + f" (a height statistic outside [0, {HEIGHT_MAX:g} m])")
    return found


def read_rows(path):
    table = pq.read_table(path)
    return table.column_names, table.to_pylist()


TEMP_NAME = re.compile(r"(^\.|\.tmp|tmp\.|~$|\.partial)")


def check_results(out):
    """Reads a results folder: (status counts, impossible sentences, inconsistencies, messages)."""
    status = {"ok": 0, "failed": 0, "failed_silent": 0, "skipped": 0, "flagged": 0}
    impossible, problems, messages = [], [], []
    if not os.path.isdir(out):
        return status, impossible, ["no results folder"], messages
    names = sorted(os.listdir(out))
    for n in names:
        if TEMP_NAME.search(n):
            problems.append(f"temporary file left: {n}")
    tables = {n[: -len(".parquet")]: os.path.join(out, n) for n in names if n.endswith(".parquet")}
    for required in ("scenarios", "timings"):
        if required not in tables:
            problems.append(f"{required}.parquet missing")
    if "scenarios" not in tables:
        return status, impossible, problems, messages
    try:
        data = {t: read_rows(p) for t, p in tables.items()}
    except Exception as e:  # a table pyarrow cannot read is itself the finding
        return status, impossible, problems + [f"unreadable table: {e}"], messages
    keys_status = {}
    kind_tables = [t for t in data if t not in ("scenarios", "timings") and "_" not in t]
    for t in kind_tables:
        cols, rows = data[t]
        for row in rows:
            keys_status[row.get("key")] = row.get("status")
            st = row.get("status")
            if st in status:
                status[st] += 1
            if st == "failed" and not (row.get("message") or "").strip():
                status["failed_silent"] += 1
            if row.get("message"):
                messages.append(row["message"])
            if any(isinstance(v, str) and "flagged" in v for k, v in row.items() if k != "message"):
                status["flagged"] += 1
        impossible += impossible_values(t, rows)
    for t, (cols, rows) in data.items():
        if t in kind_tables or t in ("scenarios", "timings") or t.startswith("summary"):
            continue
        if "key" in cols:
            # A load step's row (`friction_curve`) has its own `step_status`; other long-table
            # rows take their instance's status.
            ok_rows = [dict(r, status=r.get("step_status") or keys_status.get(r.get("key")))
                       for r in rows]
            impossible += impossible_values(t, ok_rows)
    cols, rows = data["scenarios"]
    for c in cols:
        if c.endswith("_key"):
            missing = {r[c] for r in rows if r[c] is not None and r[c] not in keys_status}
            if missing:
                problems.append(f"scenarios.{c}: {len(missing)} key(s) in no kind table")
    return status, impossible, problems, messages


def classify_run(case, proc, out, validated=True):
    """Sets the outcome and flags of a case from an `asperity run` and its results folder."""
    case.procs.append(proc)
    special = process_outcome(proc)
    case.flags |= message_flags([proc.stderr])
    if special:
        case.outcome = special
        return
    if proc.rc not in (0, 2):  # 2: some nodes failed, the tables are written
        case.outcome = rejection(proc)
        if not proc.stderr.strip():
            case.flags.add("no_message")
        if validated:
            case.flags.add("late_failure")
            case.notes.append("validate said ok; run failed: " + last_line(proc.stderr))
        if os.path.isdir(out) and any(n.endswith(".parquet") or n.startswith(".") for n in os.listdir(out)):
            case.flags.add("lost_tables")
            case.notes.append("failed run left files: " + ", ".join(sorted(os.listdir(out))))
        return
    status, impossible, problems, messages = check_results(out)
    case.flags |= message_flags(messages)
    if impossible:
        case.flags.add("impossible_ok")
        case.notes += impossible[:20]
    if problems:
        case.flags.add("lost_tables")
        case.notes += problems
    if status["failed"]:
        case.outcome = "failed_rows"
        if status["failed_silent"]:
            case.flags.add("no_message")
    elif status["flagged"]:
        case.outcome = "flagged"
    else:
        case.outcome = "ok"


def first_words(text):
    """The first line of a message that is not an echoed source line or a caret."""
    for line in message_lines(text):
        if line.strip() not in ("|", "^") and not line.strip().startswith("^"):
            return line.strip()
    return ""


def last_line(text):
    lines = [line for line in text.strip().splitlines() if line.strip()]
    return lines[-1] if lines else ""
