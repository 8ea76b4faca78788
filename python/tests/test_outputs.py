"""A route's and a check's files from Python: the library's own writers, so the same bytes as the
command line's (the run-time figures of the manifests aside), in a folder written whole."""

from __future__ import annotations

import json
import pickle
import re
import subprocess

import pytest

import slideroute
from test_slideroute import SCENES, cli


def without_run_time(value):
    """A summary or manifest without what differs between two runs of the same route: how long
    it took and the command line that wrote it."""
    if isinstance(value, dict):
        return {
            k: without_run_time(v)
            for k, v in value.items()
            if k not in ("wall_s", "command_line", "files")
        }
    if isinstance(value, list):
        return [without_run_time(v) for v in value]
    return value


def page_without_command_line(path) -> str:
    """report.html without its manifest's command line (embedded, escaped, in a <pre>)."""
    text = path.read_text(encoding="utf-8")
    return re.sub(r"&quot;command_line&quot;: \[.*?\]", "", text, flags=re.S)


def files_in(folder) -> list[str]:
    return sorted(
        str(p.relative_to(folder))
        for p in folder.rglob("*")
        if p.is_file() and not p.name.startswith(".")
    )


def test_a_routes_files_are_the_bytes_slideroute_run_writes(tmp_path):
    scene = SCENES / "turning.toml"
    by_cli, by_python = tmp_path / "cli", tmp_path / "python"
    run = [cli(), "run", "--scene", str(scene), "--out", str(by_cli)]
    subprocess.run(run, check=True, capture_output=True)
    written = slideroute.Scene.from_file(scene).route().write(by_python)
    names = files_in(by_cli)
    assert files_in(by_python) == names
    assert [p.split("/")[-1] for p in written] == [
        "route.csv",
        "route.html",
        "route.glb",
        "plan.svg",
        "profile.svg",
        "angles.svg",
        "reactions.svg",
        "summary.json",
    ]
    for name in names:
        if name == "summary.json":
            continue
        assert (by_python / name).read_bytes() == (by_cli / name).read_bytes(), name
    ours = json.loads((by_python / "summary.json").read_text())
    theirs = json.loads((by_cli / "summary.json").read_text())
    assert without_run_time(ours) == without_run_time(theirs)
    # The manifest names the files beside it, of the same sizes.
    listed = [{f["name"]: f["bytes"] for f in s["manifest"]["files"]} for s in (ours, theirs)]
    assert listed[0] == listed[1]
    assert sorted(listed[0]) == [n for n in names if n != "summary.json"]


def test_the_plan_view_alone_is_the_command_lines_plan_svg(tmp_path):
    by_cli = tmp_path / "cli"
    subprocess.run([cli(), "run", "--out", str(by_cli)], check=True, capture_output=True)
    route = slideroute.Scene.default().route()
    route.plot_plan(tmp_path / "plan.svg")
    assert (tmp_path / "plan.svg").read_bytes() == (by_cli / "plan.svg").read_bytes()
    # Nothing is left beside it but the picture.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cli", "plan.svg"]


def test_a_route_without_pictures_or_view_writes_its_table_and_summary_only(tmp_path):
    route = slideroute.Scene.default().with_keys({"solver.t_end_s": 0.5}).route()
    route.write(tmp_path, pictures=False, view=False)
    assert files_in(tmp_path) == ["route.csv", "summary.json"]
    # Written again with its pictures into the same folder, then without: the pictures of the
    # earlier run are gone, as the command line's are.
    route.write(tmp_path)
    assert "plan.svg" in files_in(tmp_path)
    route.write(tmp_path, pictures=False, view=False)
    assert files_in(tmp_path) == ["route.csv", "summary.json"]


def test_a_checks_files_are_the_bytes_slideroute_check_writes(tmp_path):
    scene = SCENES / "dam.toml"
    by_cli, by_python = tmp_path / "cli", tmp_path / "python"
    printed = subprocess.run(
        [cli(), "check", "--scene", str(scene), "--out", str(by_cli), "--no-3d"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    check = slideroute.Scene.from_file(scene).check()
    written = check.write_report(by_python, view=False)
    names = files_in(by_cli)
    assert files_in(by_python) == names
    assert "case-3/route.csv" in names and "report.html" in names
    assert any(p.endswith("check.json") for p in written)
    for name in names:
        if name.endswith(".json") or name == "report.html":
            continue
        assert (by_python / name).read_bytes() == (by_cli / name).read_bytes(), name
    for name in ("check.json", "case-3/summary.json"):
        ours = json.loads((by_python / name).read_text())
        theirs = json.loads((by_cli / name).read_text())
        assert without_run_time(ours) == without_run_time(theirs), name
    assert page_without_command_line(by_python / "report.html") == page_without_command_line(
        by_cli / "report.html"
    )
    # The tables it prints, the files it names aside.
    assert printed.startswith(check.table())


def test_a_folder_that_cannot_be_written_is_an_output_error_naming_it(tmp_path):
    route = slideroute.Scene.default().with_keys({"solver.t_end_s": 0.2}).route()
    taken = tmp_path / "a-file"
    taken.write_text("mine")
    with pytest.raises(slideroute.OutputError) as e:
        route.write(taken)
    assert isinstance(e.value, OSError)
    assert str(taken) in str(e.value) and "is a file, not a folder" in str(e.value)
    assert taken.read_text() == "mine"


def test_an_unpickled_route_keeps_its_numbers_and_says_it_cannot_write_its_files(tmp_path):
    route = slideroute.Scene.default().with_keys({"solver.t_end_s": 0.2}).route()
    back = pickle.loads(pickle.dumps(route))
    assert back.summary == route.summary and len(back) == len(route)
    with pytest.raises(slideroute.InputError, match="compute it again"):
        back.write(tmp_path)
