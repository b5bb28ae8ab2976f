"""The suite's CPU profile tool (``tests/tools/cpu_profile.py``): what it writes per test and how it sums it."""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

TOOL = Path(__file__).resolve().parent / "tools" / "cpu_profile.py"


def load() -> Any:
    spec = importlib.util.spec_from_file_location("cpu_profile", TOOL)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclass looks its module up there
    spec.loader.exec_module(module)
    return module


def test_the_summary_adds_up_by_test_module_package_and_worker(tmp_path, capsys):
    tool = load()
    rows = [tool.Spent("tests/server/test_a.py::one", "gw0", 2.0, 1.0, 10.0, 100.0),
            tool.Spent("tests/server/test_a.py::two", "gw1", 0.5, 0.0, 1.0, 101.0),
            tool.Spent("tests/planner/test_b.py::three[x]", "gw0", 4.0, 0.0, 5.0, 110.0)]
    for row in rows:
        with (tmp_path / f"{row.worker}.jsonl").open("a") as out:
            out.write(json.dumps(row.__dict__) + "\n")
    assert sorted(tool.read(tmp_path), key=lambda r: r.test) == sorted(rows, key=lambda r: r.test)
    assert tool.main([str(tmp_path), "--top", "2"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == ("3 tests: worker CPU 6.5 s, reaped children's CPU 1.0 s, wall 16.0 s (summed over "
                        "workers)")
    assert "  gw0       15.0 s" in lines and "  gw1        1.0 s" in lines
    assert "  gw0        0.0 s    15.0 s" in lines and "  gw1        1.0 s     2.0 s" in lines, "each worker's span"
    costliest = [line.split()[-1] for line in lines if line.endswith(("::one", "::two", "::three[x]"))]
    assert costliest == ["tests/planner/test_b.py::three[x]", "tests/server/test_a.py::one"], "top 2, most CPU first"
    packages = lines[lines.index(next(line for line in lines if line.endswith("package"))) + 1:][:2]
    assert [p.split() for p in packages] == [["4.0", "5.0", "1", "tests/planner"],
                                             ["3.5", "11.0", "2", "tests/server"]]


def test_a_folder_without_a_run_gets_a_usage_error(tmp_path, capsys):
    with pytest.raises(SystemExit) as exited:
        load().main([str(tmp_path)])
    assert exited.value.code == 2
    assert "no *.jsonl files of a run" in capsys.readouterr().err


def test_as_a_plugin_it_writes_one_line_per_test(tmp_path):
    (tmp_path / "test_two.py").write_text("def test_one():\n    pass\n\ndef test_two():\n    sum(range(10**5))\n")
    out = tmp_path / "profile"
    # Not an xdist worker itself, though the test may run in one (whose name it would otherwise take).
    env = {name: value for name, value in os.environ.items() if not name.startswith("PYTEST_XDIST")}
    env |= {"PYTHONPATH": str(TOOL.parent), "PYTEST_DISABLE_PLUGIN_AUTOLOAD": "1"}
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-c", os.devnull, "--rootdir", str(tmp_path),
                          "-p", "cpu_profile", f"--cpu-profile={out}", "test_two.py"],
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    rows = load().read(out)
    assert [r.test for r in rows] == ["test_two.py::test_one", "test_two.py::test_two"]
    assert all(r.worker == "main" and r.wall >= 0 and r.own >= 0 and r.children >= 0 for r in rows)
    assert 0 < rows[0].start <= rows[1].start, "when each began, in order"
