#!/usr/bin/env bash
# Creates crosscheck/.venv with pydrake (about 42 MB; under a minute) and MuJoCo (peers.py's third
# peer; about 100 MB installed), and crosscheck/.records (real ground-motion records, 1 MB).
# Idempotent.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
python="${PYTHON:-python3}"
if [ ! -x "$here/.venv/bin/python" ]; then
    "$python" -m venv "$here/.venv"
fi
"$here/.venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$here/requirements.txt"
"$here/.venv/bin/python" -c "import pydrake; print('pydrake ready:', pydrake.__file__)"
"$here/.venv/bin/python" -c "import mujoco; print('mujoco ready:', mujoco.__version__)"
# Real strong-motion records for `cargo test real_records -- --ignored`: the eighteen SLAMMER's
# Python port ships (pyslammer 0.2.2 from PyPI, GPL-3.0; its sample_ground_motions folder),
# taken from its wheel as they come, into crosscheck/.records (not kept in the repository).
if [ ! -f "$here/.records/Kobe_1995_TAK-090.csv" ]; then
    "$here/.venv/bin/python" - "$here" <<'PY'
import glob, os, subprocess, sys, tempfile, zipfile
here = sys.argv[1]
with tempfile.TemporaryDirectory() as tmp:
    subprocess.run([sys.executable, "-m", "pip", "download", "--quiet", "--no-deps",
                    "--disable-pip-version-check", "pyslammer==0.2.2", "-d", tmp], check=True)
    (wheel,) = glob.glob(os.path.join(tmp, "pyslammer-*.whl"))
    part = os.path.join(here, ".records.part")
    os.makedirs(part, exist_ok=True)
    with zipfile.ZipFile(wheel) as z:
        for name in z.namelist():
            if "/sample_ground_motions/" in name and name.endswith(".csv"):
                with open(os.path.join(part, os.path.basename(name)), "wb") as f:
                    f.write(z.read(name))
    os.replace(part, os.path.join(here, ".records"))
print("real records ready:", len(os.listdir(os.path.join(here, ".records"))))
PY
fi
