#!/usr/bin/env bash
# Creates the Python environment of the robustness campaign (scripts/campaign/campaign.py):
# a virtual environment in scripts/campaign/.venv (git-ignored; reused when its packages are
# already installed) with PyYAML (to mutate study files) and pyarrow (to read the result tables)
# from PyPI, at the versions pinned below. Needs Python >= 3.11 (PYTHON, default python3).
#
# Usage: scripts/campaign/setup.sh          then  scripts/campaign/.venv/bin/python \
#        scripts/campaign/campaign.py --help
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
venv=${CAMPAIGN_VENV:-$here/.venv}
python=${PYTHON:-python3}

PINS=(
  "PyYAML==6.0.2"
  "pyarrow==18.1.0"
)

if [[ ! -x $venv/bin/python ]]; then
  "$python" -m venv "$venv"
fi
if ! "$venv/bin/python" -c 'import yaml, pyarrow' 2>/dev/null; then
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${PINS[@]}"
fi
"$venv/bin/python" -c 'import yaml, pyarrow; print("campaign venv ready:", yaml.__version__, pyarrow.__version__)'
