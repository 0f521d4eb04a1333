"""Studies from Python: `run`, `plan`, `validate` and `RunResult`."""

from __future__ import annotations

import sys
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union, cast

from . import _args, _native
from ._results import StudyCounts

if TYPE_CHECKING:
    import os

    import polars as pl

PathLike = Union[str, "os.PathLike[str]"]
Progress = Callable[[str, Any, str], None]
Overrides = Union[None, Mapping[str, Any], Sequence[str]]


def overrides(set: Overrides) -> List[str]:
    """Overrides as the command line's ``--set NAME=VALUE`` strings."""
    if set is None:
        return []
    if isinstance(set, Mapping):
        if not all(isinstance(k, str) for k in set):
            raise TypeError(f"set: expected parameter names (str) as keys, got {_args.show(list(set))}")
        return [f"{k}={_override_value(v)}" for k, v in set.items()]
    if isinstance(set, str):
        return [set]
    if isinstance(set, Sequence) and all(isinstance(s, str) for s in set):
        return list(set)
    raise TypeError(f"set: expected a mapping {{name: value}} or a list of 'name=value' strings, got {_args.show(set)}")


def _override_value(v: Any) -> str:
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(str(x) for x in v) + "]"
    return str(v)


@dataclass
class RunResult:
    """The tables a run wrote (polars DataFrames by table name: ``result["friction"]``), its
    folder, its counts of instances, and one ``(kind, nodes, message)`` per failure and flag."""

    folder: Path
    tables: Dict[str, "pl.DataFrame"]
    computed: int
    cached: int
    failed: int
    skipped: int
    flagged: int
    wall_seconds: float
    failures: List[Tuple[str, str, str]] = field(default_factory=list)
    flags: List[Tuple[str, str, str]] = field(default_factory=list)

    def __getitem__(self, table: str) -> "pl.DataFrame":
        return self.tables[table]

    def __repr__(self) -> str:
        shapes = ", ".join(f"{name} {t.height}×{t.width}" for name, t in sorted(self.tables.items()))
        return (
            f"RunResult(folder={str(self.folder)!r}, tables=[{shapes}], computed={self.computed}, "
            f"cached={self.cached}, failed={self.failed}, skipped={self.skipped}, "
            f"flagged={self.flagged}, wall_seconds={self.wall_seconds:.3g})"
        )


def _text_progress() -> Progress:
    state = {"total": 0, "done": 0}

    def show(event: str, a: Any, b: str) -> None:
        if event == "start":
            state["total"] = int(a)
        elif event == "node":
            state["done"] += 1
            end = "\n" if state["done"] == state["total"] else ""
            sys.stderr.write(f"\r{state['done']}/{state['total']} nodes  {a:<9} {b[:60]:<60}{end}")
            sys.stderr.flush()
        elif event == "warning":
            warnings.warn(str(a), stacklevel=2)

    return show


def run(
    study: PathLike,
    set: Overrides = None,
    out: Optional[PathLike] = None,
    cache: Optional[PathLike] = None,
    jobs: Optional[int] = None,
    *,
    memory_mib: Optional[int] = None,
    progress: Union[bool, Progress, None] = None,
    force: bool = False,
) -> RunResult:
    """Run a study as ``asperity run`` does and return its tables as polars DataFrames.

    ``set`` overrides parameter axes (``{"sq": ["0.4 um", "1 um"]}`` or ``["n=64"]``); ``out``
    is the results folder (default ``results/<study>``), ``cache`` the cache folder (default
    ``$ASPERITY_CACHE`` or ``./cache``), ``jobs`` the worker threads (default all cores),
    ``memory_mib`` the memory budget of the nodes computed at once (MiB). A results folder
    that holds the results of another study file (same ``study:`` name) is refused unless
    ``force=True`` (then a warning names both files), as ``asperity run --force`` does.
    ``progress=True`` shows a progress line on stderr; a callable receives
    ``(event, value, text)`` with events ``"start"`` (total), ``"node"`` (status, node) and
    ``"warning"`` (message). Ctrl-C stops the run after the nodes being computed (the cache
    stays valid, no tables are written) and raises ``KeyboardInterrupt``.
    """
    import polars as pl

    if progress is True:
        callback: Optional[Progress] = _text_progress()
    elif progress is None or progress is False:
        callback = None
    elif callable(progress):
        callback = progress
    else:
        raise TypeError(f"progress: expected True, False, None or a callable(event, value, text), got {_args.show(progress)}")
    folder, files, report = _native.run_study(
        _args.path("study", study),
        overrides(set),
        _args.optional_path("out", out),
        _args.optional_path("cache", cache),
        None if jobs is None else _args.integer("jobs", jobs, 1, "a number of worker threads"),
        None if memory_mib is None else _args.integer("memory_mib", memory_mib, 1, "a memory budget in MiB"),
        callback,
        _args.boolean("force", force),
    )
    tables = {Path(f).stem: pl.read_parquet(f) for f in files if str(f).endswith(".parquet")}
    return RunResult(
        folder=Path(folder),
        tables=tables,
        computed=report["computed"],
        cached=report["cached"],
        failed=report["failed"],
        skipped=report["skipped"],
        flagged=report["flagged"],
        wall_seconds=report["wall_seconds"],
        failures=list(report["failures"]),
        flags=list(report["flags"]),
    )


def plan(study: PathLike, set: Overrides = None, cache: Optional[PathLike] = None) -> "pl.DataFrame":
    """The instances a run would load or compute, as a polars DataFrame
    (``key``, ``kind``, ``version``, ``nodes``, ``cached``)."""
    import polars as pl

    rows = _native.plan_study(_args.path("study", study), overrides(set), _args.optional_path("cache", cache))
    schema: Dict[str, Any] = {"key": pl.Utf8, "kind": pl.Utf8, "version": pl.UInt32, "nodes": pl.List(pl.Utf8), "cached": pl.Boolean}
    return pl.DataFrame(rows, schema=schema)


def validate(study: PathLike, set: Overrides = None) -> StudyCounts:
    """Check a study without running it: its name and counts of scenarios, nodes and instances,
    and the parameters no node uses. A broken study raises :class:`StudyError`."""
    return cast(StudyCounts, dict(_native.validate_study(_args.path("study", study), overrides(set))))
