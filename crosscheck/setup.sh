#!/usr/bin/env bash
# Creates crosscheck/.venv with pydrake (about 42 MB; under a minute). Idempotent.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
python="${PYTHON:-python3}"
if [ ! -x "$here/.venv/bin/python" ]; then
    "$python" -m venv "$here/.venv"
fi
"$here/.venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$here/requirements.txt"
"$here/.venv/bin/python" -c "import pydrake; print('pydrake ready:', pydrake.__file__)"
