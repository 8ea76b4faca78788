#!/usr/bin/env bash
# Creates python/.venv and installs the Python package from this checkout into it — one
# `pip install`, which builds the Rust extension with maturin (fetched from PyPI) — with what its
# tests need. Idempotent: a second run rebuilds the extension only if the sources changed.
# `python/setup.sh --requirements` makes the environment and installs the tests' requirements
# only (CI does that while Rust compiles).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
python="${PYTHON:-python3}"
if [ ! -x "$here/.venv/bin/python" ]; then
    "$python" -m venv "$here/.venv"
fi
pip=("$here/.venv/bin/python" -m pip --disable-pip-version-check)
"${pip[@]}" install --quiet -r "$here/requirements-test.txt"
if [ "${1:-}" = "--requirements" ]; then
    exit 0
fi
# The extension compiles for a few minutes the first time: said before, and shown as it goes
# (`-v`: pip passes on maturin's and cargo's lines).
echo "python/setup.sh: building the Rust extension and installing slideroute into $here/.venv; this takes a few minutes the first time (cargo's progress follows)…"
"${pip[@]}" install -v "$here"
"$here/.venv/bin/python" -c "import slideroute; print('slideroute', slideroute.__version__, 'ready:', slideroute.__file__)"
