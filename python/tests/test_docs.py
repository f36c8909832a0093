"""The docstring examples are run: every one must pass."""

import doctest

import dymsum
import dymsum._dymsum as ext


def run(obj, name):
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    tests = finder.find(obj, name, module=False, globs={})
    for t in tests:
        runner.run(t)
    return runner.summarize(verbose=False)


def test_function_docstrings():
    r = doctest.testmod(ext, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert r.failed == 0 and r.attempted >= 25


def test_class_and_package_docstrings():
    attempted = 0
    for obj in (dymsum, dymsum.Polytope, dymsum.DynamicSum, dymsum.ContactTracker, dymsum.ConvexUnion, dymsum.MotionChecker, dymsum.Slab):
        r = run(obj, getattr(obj, "__name__", "dymsum"))
        assert r.failed == 0, obj
        attempted += r.attempted
    assert attempted >= 15


def test_example_tour_runs(tmp_path):
    import importlib.util
    import pathlib
    import subprocess
    import sys

    script = pathlib.Path(__file__).parent.parent / "examples" / "tour.py"
    done = subprocess.run([sys.executable, str(script), str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "C-obstacle slices" in done.stdout
    saved = dymsum.load(tmp_path / "sum.off")
    assert saved.volume > dymsum.load("ellipse").volume
    has_matplotlib = importlib.util.find_spec("matplotlib") is not None
    assert (tmp_path / "depth.png").exists() == has_matplotlib


def test_documentation_python_blocks_run(tmp_path, monkeypatch):
    """Every ``python`` block of the README, the package README and the
    guides in docs/ runs, and writes nothing into the working directory
    (examples write into a temporary or named folder). Blocks that import
    OMPL are skipped where it is not installed, unless DYMSUM_REQUIRE_OMPL=1;
    blocks whose first line is "# needs: PKG ..." where those packages are
    missing, unless DYMSUM_REQUIRE_MANIFOLD=1; blocks that import Dask
    where it is missing, unless DYMSUM_REQUIRE_DASK=1 (scripts/test.sh
    installs all three and sets the variables)."""
    import importlib
    import importlib.util
    import os
    import pathlib
    import re

    def importable(name):
        try:
            importlib.import_module(name)
        except ImportError:
            return False
        return True

    root = pathlib.Path(__file__).resolve().parent.parent.parent
    monkeypatch.chdir(tmp_path)
    files = [root / "README.md", root / "python" / "README.md", *sorted((root / "docs").glob("*.md"))]
    have_ompl = os.environ.get("DYMSUM_REQUIRE_OMPL") == "1" or importlib.util.find_spec("ompl") is not None
    have_dask = os.environ.get("DYMSUM_REQUIRE_DASK") == "1" or importlib.util.find_spec("distributed") is not None
    ran = ompl_blocks = 0
    for doc in files:
        for block in re.findall(r"```python\n(.*?)```", doc.read_text(), re.S):
            if re.search(r"^\s*(from|import) ompl\b", block, re.M):
                ompl_blocks += 1
                if not have_ompl:
                    continue
            # A block whose first line is "# needs: PKG ..." uses optional
            # packages: skipped without them, unless DYMSUM_REQUIRE_MANIFOLD=1
            # (scripts/test.sh installs them and sets it).
            needs = re.match(r"# needs: (.*)\n", block)
            if needs and os.environ.get("DYMSUM_REQUIRE_MANIFOLD") != "1":
                if not all(importable(m) for m in needs.group(1).split()):
                    continue
            if re.search(r"^\s*(from|import) (dask|distributed)\b", block, re.M) and not have_dask:
                continue
            exec(compile(block, str(doc), "exec"), {})
            ran += 1
    assert ran >= 3 and ompl_blocks >= 2
    assert list(tmp_path.iterdir()) == []
