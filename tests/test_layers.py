"""The layers of docs/architecture.md hold: each top-level package imports only the layers it may.

Data flows one way (study_config → server → store → analysis; the planner below them all). An import that runs
back up, or a tie between two top-level packages in both directions, fails here with the file and line. In the
browser's modules, static/js/game/ (the top-down game) imports nothing of static/js/firstperson/ (the 3D view,
which draws with the game's palette and stations); static/js/views.js chooses between the two.

Inside the analysis, the rooms of its pipeline (analysis/__init__.py) are layers too: a room imports only the rooms
before it in :data:`ANALYSIS_ROOMS`, every module lives in a room, and no module of the analysis shares its name with
another module or package of the repository.
"""

from __future__ import annotations

import ast
import posixpath
import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
PACKAGES = ("planner", "study_config", "store", "server", "analysis", "pilot")

# What each package may import of the others (docs/architecture.md, "The data flow").
ALLOWED: dict[str, frozenset[str]] = {
    "planner": frozenset(),
    "study_config": frozenset({"planner"}),
    "store": frozenset({"planner", "study_config"}),
    "server": frozenset({"planner", "study_config", "store"}),
    "analysis": frozenset({"planner", "study_config", "store"}),
    "pilot": frozenset({"planner", "study_config"}),
}
# The command line and the admin's export download are the server's entry points to the analysis and the pilot.
ENTRY_POINTS = ("server/cli.py", "server/commands/", "server/routes/admin_exports.py")


def imported_packages(path: Path) -> list[tuple[int, str]]:
    """(line, top-level package) of every import of one of this repository's packages in ``path``."""
    found: list[tuple[int, str]] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names = [node.module]
        else:
            continue
        found.extend((node.lineno, name.split(".")[0]) for name in names if name.split(".")[0] in PACKAGES)
    return found


def package_imports(package: str) -> list[tuple[str, int, str]]:
    """(file, line, imported package) of every import of another of this repository's packages in ``package``."""
    return [(path.relative_to(REPO).as_posix(), line, target)
            for path in sorted((REPO / package).rglob("*.py"))
            for line, target in imported_packages(path) if target != package]


def violations(package: str) -> list[str]:
    bad = []
    for rel, line, target in package_imports(package):
        allowed = ALLOWED[package]
        if rel.startswith(ENTRY_POINTS):
            allowed = allowed | {"analysis", "pilot"}
        if target not in allowed:
            bad.append(f"{rel}:{line} imports {target}")
    return bad


@pytest.mark.parametrize("package", PACKAGES)
def test_each_package_imports_only_the_layers_below_it(package: str) -> None:
    assert violations(package) == []


def test_the_rule_catches_an_import_that_runs_back_up(tmp_path: Path) -> None:
    source = tmp_path / "module.py"
    source.write_text("from server.app import create_app\nimport planner.fov\n", encoding="utf-8")
    assert imported_packages(source) == [(1, "server"), (2, "planner")]
    assert "server" not in ALLOWED["analysis"] and "server" not in ALLOWED["store"]


def test_no_two_top_level_packages_import_each_other() -> None:
    edges = {(package, target) for package in PACKAGES for _, _, target in package_imports(package)}
    assert sorted((a, b) for a, b in edges if (b, a) in edges) == []


@pytest.mark.parametrize("package", ["analysis", "pilot"])
def test_the_analysis_and_the_pilot_import_nothing_of_the_server(package: str) -> None:
    assert [f"{rel}:{line}" for rel, line, target in package_imports(package) if target == "server"] == []


# The analysis's rooms in pipeline order: each may import only the rooms before it (and itself).
ANALYSIS_ROOMS = ("source", "measures", "exports", "preparation", "statistics", "followups", "power_analysis",
                  "reporting", "pipeline")


def analysis_rooms_imported(path: Path, room: str) -> list[tuple[int, str]]:
    """(line, room) of every import of an analysis room in ``path``, a module of ``room``: absolute
    (``import analysis.x.y``, ``from analysis.x import y``, ``from analysis import x``) and relative."""
    found: list[tuple[int, str]] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            dotted = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:  # relative to analysis.<room>: one dot is the room itself, two the analysis package
                base = ".".join(["analysis", room][:max(0, 3 - node.level)] + ([base] if base else []))
            dotted = [f"{base}.{alias.name}" for alias in node.names]
        else:
            continue
        for name in dotted:
            parts = name.split(".")
            if parts[0] == "analysis" and len(parts) > 1 and parts[1] != "__future__":
                found.append((node.lineno, parts[1]))
    return found


def room_violations(modules: list[tuple[str, Path]]) -> list[str]:
    """``file:line room imports later-room`` for every import in ``modules`` ((room, path) pairs) of a room that
    comes later in the pipeline, or of something of the analysis that is no room."""
    bad = []
    for room, path in modules:
        for line, target in analysis_rooms_imported(path, room):
            if target not in ANALYSIS_ROOMS or ANALYSIS_ROOMS.index(target) > ANALYSIS_ROOMS.index(room):
                rel = path.relative_to(REPO).as_posix() if path.is_relative_to(REPO) else path.name
                bad.append(f"{rel}:{line} ({room}) imports analysis.{target}")
    return bad


def analysis_modules() -> list[tuple[str, Path]]:
    return [(path.relative_to(REPO / "analysis").parts[0], path)
            for path in sorted((REPO / "analysis").rglob("*.py")) if path.parent != REPO / "analysis"]


def test_every_analysis_module_lives_in_a_room_and_every_room_is_in_the_order() -> None:
    assert sorted(p.name for p in (REPO / "analysis").glob("*.py")) == ["__init__.py"]
    folders = sorted(p.name for p in (REPO / "analysis").iterdir() if p.is_dir() and p.name != "__pycache__")
    assert folders == sorted(ANALYSIS_ROOMS)
    assert all((REPO / "analysis" / room / "__init__.py").is_file() for room in ANALYSIS_ROOMS)


def test_each_analysis_room_imports_only_the_rooms_before_it() -> None:
    assert room_violations(analysis_modules()) == []


def test_the_room_rule_catches_an_import_that_runs_back_up(tmp_path: Path) -> None:
    source = tmp_path / "module.py"
    source.write_text("from analysis.reporting.document import Heading\nimport analysis.source.naming\n"
                      "from analysis import pipeline\nfrom ..followups import pairwise\nfrom . import anova\n",
                      encoding="utf-8")
    assert analysis_rooms_imported(source, "statistics") == [
        (1, "reporting"), (2, "source"), (3, "pipeline"), (4, "followups"), (5, "statistics")]
    assert room_violations([("statistics", source)]) == [
        "module.py:1 (statistics) imports analysis.reporting", "module.py:3 (statistics) imports analysis.pipeline",
        "module.py:4 (statistics) imports analysis.followups"]


def test_no_analysis_module_shares_its_name_with_another_module_of_the_repository() -> None:
    others = {path.stem if path.suffix else path.name
              for package in PACKAGES if package != "analysis"
              for path in [*(REPO / package).rglob("*.py"), *(REPO / package).rglob("*/")]
              if path.name != "__init__.py" and "__pycache__" not in path.parts}
    ours = [path.stem for _, path in analysis_modules() if path.name != "__init__.py"] + list(ANALYSIS_ROOMS)
    assert sorted(name for name in set(ours) if ours.count(name) > 1) == []
    assert sorted(set(ours) & others) == []


JS = REPO / "static" / "js"
_JS_IMPORT = re.compile(r"""(?:\bfrom\s*|\bimport\s*\(?\s*)["']([^"']+)["']""")


def js_imports(source: str, folder: str) -> list[tuple[int, str]]:
    """(line, module path relative to static/js) of every static or dynamic import of a relative module in the
    ``source`` of a module in ``folder`` (relative to static/js)."""
    found: list[tuple[int, str]] = []
    for number, line in enumerate(source.splitlines(), start=1):
        if line.lstrip().startswith(("*", "//", "/*")):
            continue
        found.extend((number, posixpath.normpath(posixpath.join(folder, spec)))
                     for spec in _JS_IMPORT.findall(line) if spec.startswith("."))
    return found


def module_imports(path: Path) -> list[tuple[int, str]]:
    return js_imports(path.read_text(encoding="utf-8"), path.parent.relative_to(JS).as_posix())


def test_the_game_modules_import_nothing_of_the_first_person_view() -> None:
    bad = [f"{path.relative_to(REPO).as_posix()}:{line} imports {target}"
           for path in sorted((JS / "game").rglob("*.js"))
           for line, target in module_imports(path) if target.startswith("firstperson/")]
    assert bad == []


def test_the_js_rule_sees_static_and_dynamic_imports() -> None:
    source = ('import { A } from "../firstperson/steering.js";\n'
              'const v = import("../firstperson/view.js");\n'
              '/** see ../firstperson/ in a comment */\nimport { h } from "../dom.js";\n')
    assert js_imports(source, "game") == [(1, "firstperson/steering.js"), (2, "firstperson/view.js"), (4, "dom.js")]
    assert [t for _, t in module_imports(JS / "views.js")] == [
        "game/renderer.js", "firstperson/steering.js", "firstperson/view.js"]
