"""The documentation runs: every Python code block of README.md's Python section and of
docs/python.md is executed (the blocks of one file in order, in one namespace, from a folder
that holds the repository's `studies/` and `tests/data/`), and type-checks under
`mypy --strict`, as the package itself does. The friction docstrings name exactly the laws of
the registry that support their method, and every public name is documented."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import asperity

REPO = Path(__file__).resolve().parents[2]
SOURCES = {"README.md": "## Python", "docs/python.md": None}


def python_blocks(name):
    """The ```python blocks of a file (of README.md: of its Python section only)."""
    text = (REPO / name).read_text()
    section = SOURCES[name]
    if section is not None:
        start = text.index(f"\n{section}\n")
        end = text.find("\n## ", start + 1)
        text = text[start : end if end > 0 else len(text)]
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


@pytest.fixture()
def docs_folder(tmp_path, monkeypatch):
    """A folder like the repository's root for the examples' relative paths (their outputs go
    here, not into the checkout)."""
    for part in ("studies", "tests"):
        (tmp_path / part).symlink_to(REPO / part)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    return tmp_path


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_every_code_block_runs(name, docs_folder):
    blocks = python_blocks(name)
    assert blocks, f"{name}: no python code block"
    namespace = {"__name__": "__docs__"}
    for i, block in enumerate(blocks):
        try:
            exec(compile(block, f"{name}[block {i}]", "exec"), namespace)
        except Exception as e:  # noqa: BLE001 - the failing block is the message
            pytest.fail(f"{name}, block {i} raised {type(e).__name__}: {e}\n{block}")


def mypy_strict(*targets, cwd):
    return subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-error-summary", "--cache-dir", str(cwd / ".mypy_cache"), *targets],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=900,
    )


def test_the_package_type_checks_strictly(tmp_path):
    done = mypy_strict("-p", "asperity", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_documentation_examples_type_check_strictly(tmp_path):
    files = []
    for name in sorted(SOURCES):
        path = tmp_path / (Path(name).stem.lower().replace("-", "_") + "_examples.py")
        path.write_text("\n".join(python_blocks(name)))
        files.append(path.name)
    done = mypy_strict(*files, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.mark.parametrize(
    "function, method",
    [("static_friction", "statistical"), ("per_summit_friction", "per_summit"), ("per_spot_friction", "per_spot")],
)
def test_friction_docstrings_name_the_registry_laws(function, method):
    doc = getattr(asperity, function).__doc__
    named = set(re.findall(r'``"([a-z_]+)"``', doc))
    laws = asperity.friction_laws()
    registry = {law["name"] for law in laws}
    supported = {law["name"] for law in laws if method in law["methods"]}
    parameters = [p for law in laws for p in law["parameters"]]
    vocabulary = registry | {p["name"] for p in parameters} | {o for p in parameters for o in p["options"]}
    unknown = sorted(named - vocabulary)
    assert not unknown, f"{function}: names unregistered law(s) {unknown}"
    missing = sorted(supported - named)
    assert not missing, f"{function}: does not name the registered law(s) {missing} (method {method})"
    wrong = sorted((named & registry) - supported)
    assert not wrong, f"{function}: names law(s) {wrong}, which do not support {method}"


def test_every_public_name_is_documented():
    help_text = subprocess.run(
        [sys.executable, "-c", "import asperity; help(asperity)"], capture_output=True, text=True, env={**os.environ, "PAGER": "cat"}
    ).stdout
    python_md = (REPO / "docs" / "python.md").read_text()
    for name in asperity.__all__:
        assert name in asperity.__doc__, f"{name}: not in the module docstring"
        assert name in help_text, f"{name}: not in help(asperity)"
        assert re.search(rf"`[^`\n]*\b{name}\b[^`\n]*`", python_md), f"{name}: not in docs/python.md"
