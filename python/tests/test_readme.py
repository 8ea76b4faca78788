"""Every ```python block of README.md runs as written, from the repository's root (where its
scene paths are), and the install line it gives installs what its blocks need."""

from __future__ import annotations

import os
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text(encoding="utf-8")
BLOCKS = re.findall(r"^```python\n(.*?)^```", README, flags=re.S | re.M)


def test_the_readme_has_python_blocks():
    assert len(BLOCKS) >= 2


@pytest.mark.parametrize("k", range(len(BLOCKS)))
def test_each_python_block_of_the_readme_runs_as_written(k, monkeypatch):
    pytest.importorskip("pandas")  # the install line's extras
    monkeypatch.chdir(ROOT)
    code = compile(BLOCKS[k], f"README.md python block {k + 1}", "exec")
    exec(code, {"__name__": f"readme_{k}"})


def test_the_readmes_install_line_brings_pandas_and_says_it_takes_minutes():
    section = README[README.index("## Python\n") : README.index("## Coordinates and units")]
    assert 'pip install -v "./python[pandas,dask]"' in section
    assert "few minutes" in section
