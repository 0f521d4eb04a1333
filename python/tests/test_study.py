"""Studies from Python: the same Parquet bytes as the command line, StudyError as the command
line reports it, progress events and a clean interrupt."""

import signal
import subprocess
import sys
from pathlib import Path

import polars as pl
import pytest

import asperity
from conftest import run_cli


def parquet_files(folder: Path) -> dict:
    """Every results table but the run times (the one file that differs between runs)."""
    return {
        p.name: p.read_bytes() for p in sorted(folder.glob("*.parquet")) if p.name != "timings.parquet"
    }


def test_a_study_run_from_python_writes_the_cli_bytes(asperity_bin, contact_study, tmp_path):
    cli = run_cli(asperity_bin, "run", str(contact_study), "--out", "cli", "--cache", "cache-cli", "-q", cwd=tmp_path)
    assert cli.returncode == 0, cli.stderr
    result = asperity.run(contact_study, out=tmp_path / "py", cache=tmp_path / "cache-py", jobs=2)
    assert result.failed == 0 and result.computed == 8
    ours, theirs = parquet_files(tmp_path / "py"), parquet_files(tmp_path / "cli")
    assert {"contacts.parquet", "contacts_load_curve.parquet", "surfaces.parquet"} <= set(ours)
    assert ours == theirs
    assert result.folder == tmp_path / "py"
    assert result["contacts"].equals(pl.read_parquet(tmp_path / "cli" / "contacts.parquet"))
    again = asperity.run(contact_study, out=tmp_path / "py", cache=tmp_path / "cache-py", set={"seed": [3, 4]})
    assert again.cached == 8 and again.computed == 0


def test_set_overrides_and_plan_and_validate(contact_study, tmp_path):
    counts = asperity.validate(contact_study, set=["seed=[1, 2, 3]"])
    assert counts["scenarios"] == 3 and counts["instances"] == 12
    planned = asperity.plan(contact_study, set={"seed": 7}, cache=tmp_path / "cache")
    assert sorted(planned["kind"].to_list()) == ["contact", "friction", "friction", "surface"]
    assert planned["cached"].to_list() == [False, False, False, False]
    with pytest.raises(ValueError, match="set"):
        asperity.validate(contact_study, set=["no equals sign"])


def test_a_broken_study_raises_what_the_cli_prints(asperity_bin, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(
        "study: bad\nnodes:\n  s:\n    surface:\n      synthetic: {grid: [8, 8], size: [1 mm, 1 mm],\n"
        "                  sq: 1 um, hurst: 0.8, corelation_length: 0.1 mm, seed: 1}\n"
    )
    cli = run_cli(asperity_bin, "validate", str(bad), cwd=tmp_path)
    assert cli.returncode == 1
    with pytest.raises(asperity.StudyError) as caught:
        asperity.validate(bad)
    error = caught.value
    assert cli.stderr.strip() == f"error: {error}"
    assert (error.file, error.line) == (str(bad), 6)
    assert error.column is not None and error.column > 1
    assert "corelation_length" in error.message and "did you mean" in error.message
    with pytest.raises(asperity.StudyError):
        asperity.run(bad, out=tmp_path / "out", cache=tmp_path / "cache")
    assert not (tmp_path / "out").exists()


def test_progress_reaches_the_callback(contact_study, tmp_path):
    events = []
    asperity.run(contact_study, out=tmp_path / "out", cache=tmp_path / "cache", progress=lambda *e: events.append(e))
    assert events[0] == ("start", 8, "")
    nodes = [e for e in events if e[0] == "node"]
    assert len(nodes) == 8 and {e[1] for e in nodes} == {"computed"}


def test_an_interrupt_stops_the_run_and_leaves_a_valid_cache(asperity_bin, contact_study, tmp_path):
    def interrupt(event, value, text):
        if event == "node":
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        asperity.run(contact_study, out=tmp_path / "out", cache=tmp_path / "cache", jobs=1, progress=interrupt)
    assert not (tmp_path / "out").exists()
    verify = run_cli(asperity_bin, "cache", "verify", "--cache", "cache", cwd=tmp_path)
    assert verify.returncode == 0, verify.stdout + verify.stderr
    done = asperity.run(contact_study, out=tmp_path / "out", cache=tmp_path / "cache", jobs=1)
    assert done.cached >= 1 and done.cached + done.computed == 8 and done.failed == 0


SLOW_STUDY = """\
study: slow
parameters:
  product:
    seed: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16]
nodes:
  rough:
    surface:
      synthetic: {grid: [512, 512], size: [0.5 mm, 0.5 mm], sq: 0.8 um, hurst: 0.7,
                  correlation_length: 40 um, seed: "${seed}"}
  squeeze:
    contact:
      lower: rough
      lower_material: s235jr
      nominal_pressures: [5 MPa, 20 MPa, 40 MPa]
      tolerance: 1e-10
"""

CHILD = """\
import signal, sys
import asperity
signal.signal(signal.SIGINT, signal.default_int_handler)
def progress(event, value, text):
    if event == "node":
        print("node", flush=True)
try:
    asperity.run(sys.argv[1], out="out", cache="cache", jobs=1, progress=progress)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""


def test_ctrl_c_interrupts_a_run_cleanly(asperity_bin, tmp_path):
    (tmp_path / "slow.yaml").write_text(SLOW_STUDY)
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, "slow.yaml"], cwd=tmp_path, stdout=subprocess.PIPE, text=True
    )
    assert child.stdout.readline().strip() == "node"
    child.send_signal(signal.SIGINT)
    rest = child.stdout.read().split()
    assert child.wait(timeout=120) == 0
    assert rest[-1] == "interrupted" and len(rest) < 31, rest
    assert not (tmp_path / "out").exists()
    verify = run_cli(asperity_bin, "cache", "verify", "--cache", "cache", cwd=tmp_path)
    assert verify.returncode == 0 and " 0 corrupt" in verify.stdout, verify.stdout
