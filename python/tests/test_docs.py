"""The docstring examples are run: every one must pass."""

import doctest
import os
import pathlib
import re
import subprocess
import sys

import pytest

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


ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
DOCS = [ROOT / "README.md", ROOT / "python" / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

# What a block may import without naming it in a "# needs:" line: the
# standard library, dymsum and its one required dependency.
BASE = ["dymsum", "numpy"]

# Needs that scripts/test.sh installs and then requires: without them a block
# is skipped unless the variable is 1. Any other need must be installed.
OPTIONAL = {
    "ompl": "DYMSUM_REQUIRE_OMPL",
    "dask": "DYMSUM_REQUIRE_DASK",
    "distributed": "DYMSUM_REQUIRE_DASK",
    "manifold3d": "DYMSUM_REQUIRE_MANIFOLD",
    "coacd": "DYMSUM_REQUIRE_MANIFOLD",
    "vhacdx": "DYMSUM_REQUIRE_MANIFOLD",
    "trimesh": "DYMSUM_REQUIRE_SCENES",
    "collada": "DYMSUM_REQUIRE_SCENES",
    "fcl": "DYMSUM_REQUIRE_SCENES",
}

# Installed in each block's interpreter (and in every process it starts:
# Dask workers, process pools) through PYTHONPATH: a sys.meta_path finder
# that refuses the top-level modules of the installed distributions the
# block did not declare, as if they were not installed.
GUARD = """\
import importlib.util
import os
import sys

_REFUSED = frozenset(filter(None, os.environ.get("DYMSUM_DOCS_REFUSED", "").split(",")))
_NEEDS = os.environ.get("DYMSUM_DOCS_NEEDS", "")


class _Undeclared:
    @staticmethod
    def find_spec(fullname, path=None, target=None):
        if fullname in _REFUSED:
            raise ModuleNotFoundError(
                f"No module named {fullname!r}: the block does not declare it "
                f"(its '# needs:' line names {_NEEDS or 'nothing'}; dymsum, numpy "
                f"and the standard library need no line)",
                name=fullname,
            )
        return None


sys.meta_path.insert(0, _Undeclared)
_find_spec = importlib.util.find_spec


def _guarded_find_spec(name, package=None):
    if name.partition(".")[0] in _REFUSED:
        return None  # what a missing package answers
    return _find_spec(name, package)


importlib.util.find_spec = _guarded_find_spec
"""


def _blocks():
    """(doc, line, code) of every ``python`` block of the documentation."""
    out = []
    for doc in DOCS:
        text = doc.read_text()
        for m in re.finditer(r"```python\n(.*?)```", text, re.S):
            line = text.count("\n", 0, m.start()) + 1
            out.append((doc, line, m.group(1)))
    return out


BLOCKS = _blocks()


def _needs(code):
    """The requirements a block names in its "# needs: A, B[extra]" line."""
    m = re.search(r"^\s*# needs: (.*)$", code, re.M)
    return [n for n in re.split(r"[,\s]+", m.group(1)) if n] if m else []


def _requirement(text):
    try:
        from packaging.requirements import Requirement
    except ImportError:  # pip vendors it
        from pip._vendor.packaging.requirements import Requirement
    return Requirement(text)


def _canonical(name):
    return re.sub(r"[-_.]+", "-", name).lower()


def _closure(requirements):
    """The installed distributions that `requirements` (strings, extras
    included) pull in, with their dependencies, by canonical name."""
    import importlib.metadata

    seen, stack = set(), [_requirement(r) for r in requirements]
    while stack:
        req = stack.pop()
        key = (_canonical(req.name), frozenset(req.extras))
        if key in seen:
            continue
        seen.add(key)
        try:
            dist = importlib.metadata.distribution(req.name)
        except importlib.metadata.PackageNotFoundError:
            continue
        for dep in dist.requires or []:
            d = _requirement(dep)
            envs = [{"extra": e} for e in req.extras] or [{"extra": ""}]
            if d.marker is None or any(d.marker.evaluate(env) for env in envs):
                stack.append(d)
    return {name for name, _ in seen}


def _top_level_modules():
    """{top-level module name: canonical names of the installed
    distributions that provide it}, from each distribution's files."""
    import importlib.metadata
    import inspect

    out = {}
    for dist in importlib.metadata.distributions():
        names = set((dist.read_text("top_level.txt") or "").split())
        for f in dist.files or []:
            first = f.parts[0]
            if first in ("..", "__pycache__") or first.endswith((".dist-info", ".egg-info", ".data")):
                continue
            if len(f.parts) > 1:
                names.add(first)
            elif inspect.getmodulename(first) and not first.endswith(".pth"):
                names.add(inspect.getmodulename(first))
        for n in names:
            if n.isidentifier():
                out.setdefault(n, set()).add(_canonical(dist.metadata["Name"]))
    return out


def _refused(needs):
    """The third-party top-level modules a block with `needs` may not import."""
    allowed = _closure(BASE + needs)
    stdlib = set(sys.stdlib_module_names) | set(sys.builtin_module_names)
    return sorted(n for n, dists in _top_level_modules().items() if n not in stdlib and not dists & allowed)


def _installed(requirement):
    import importlib.metadata

    try:
        importlib.metadata.distribution(_requirement(requirement).name)
    except importlib.metadata.PackageNotFoundError:
        return False
    return True


@pytest.mark.parametrize(
    "doc, line, code", BLOCKS, ids=[f"{d.relative_to(ROOT)}:{n}" for d, n, _ in BLOCKS]
)
def test_documentation_python_block_runs_as_a_script(doc, line, code, tmp_path):
    """Every ``python`` block of the README, the package README and the
    guides in docs/ runs as pasted into a script file and run with
    ``python FILE`` (in a subprocess: process pools and Dask's process
    workers re-import it), where only dymsum, numpy, the standard library
    and what its "# needs:" line names can be imported, and writes nothing
    into its working directory. A block whose needs are not installed is
    skipped where the matching DYMSUM_REQUIRE_* variable is not 1
    (scripts/test.sh installs them and sets it)."""
    needs = _needs(code)
    missing = [n for n in needs if not _installed(n)]
    for n in missing:
        var = OPTIONAL.get(_canonical(_requirement(n).name))
        if var is None or os.environ.get(var) == "1":
            pytest.fail(f"{doc.name}:{line} needs {n}, which is not installed")
    if missing:
        pytest.skip(f"needs {', '.join(missing)}")
    guard, script, cwd = tmp_path / "guard", tmp_path / "script", tmp_path / "cwd"
    for d in (guard, script, cwd):
        d.mkdir()
    (guard / "sitecustomize.py").write_text(GUARD)
    path = script / f"{doc.stem}_{line}.py"
    path.write_text(code)
    env = dict(os.environ)
    env["PYTHONPATH"] = str(guard)
    env["DYMSUM_DOCS_REFUSED"] = ",".join(_refused(needs))
    env["DYMSUM_DOCS_NEEDS"] = ", ".join(needs)
    done = subprocess.run(
        [sys.executable, str(path)], cwd=cwd, env=env, capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, f"{doc.name}:{line} failed as a script:\n{done.stdout}\n{done.stderr}"
    assert list(cwd.iterdir()) == [], f"{doc.name}:{line} wrote into its working directory"


def test_documentation_python_blocks_are_found():
    """The blocks above exist, OMPL's among them, and every block that
    imports a third-party package names it in its "# needs:" line (checked
    when run; here for the blocks skipped for want of their needs)."""
    assert len(BLOCKS) >= 10
    assert sum("ompl" in _needs(code) for _, _, code in BLOCKS) >= 2
    for doc, line, code in BLOCKS:
        needs = {_canonical(_requirement(n).name) for n in _needs(code)}
        for m in re.finditer(r"^\s*(?:from|import) (\w+)", code, re.M):
            name = m.group(1)
            if name in OPTIONAL or name == "scipy":
                assert name in needs or (name == "distributed" and "dask" in needs), (
                    f"{doc.name}:{line} imports {name} without naming it in '# needs:'"
                )


def test_the_first_python_example_installs_what_it_needs():
    """The README's first Python example is preceded by the install line
    that gives it everything it imports."""
    text = (ROOT / "README.md").read_text()
    first = re.search(r"```python\n(.*?)```", text, re.S)
    before = text[: first.start()].rstrip().rsplit("\n\n", 1)[-1]
    install = re.search(r"`pip install ([^`]*)`", before)
    assert install, f"no `pip install` line above the first example: {before!r}"
    given = install.group(1).split()
    assert "./python" in given
    for n in _needs(first.group(1)):
        assert n in given, f"the first example needs {n}; the line above installs {given}"


def test_the_api_table_lists_every_public_name():
    """docs/PYTHON.md's API table has a row for every name of
    ``dymsum.__all__``, and names nothing else (the first cell of each row:
    the names its code spans start with)."""
    text = (ROOT / "docs" / "PYTHON.md").read_text()
    api = text.split("\n## API\n", 1)[1].split("\n## ", 1)[0]
    listed = set()
    for row in api.splitlines():
        if row.startswith("| `"):
            first = row.split(" | ")[0]
            listed |= {m.group(1) for s in re.findall(r"`([^`]*)`", first) for m in [re.match(r"([A-Za-z_]\w*)", s)] if m}
    public = set(dymsum.__all__)
    assert not public - listed, f"in dymsum.__all__ but not in PYTHON.md's API table: {sorted(public - listed)}"
    assert not listed - public, f"in PYTHON.md's API table but not in dymsum.__all__: {sorted(listed - public)}"
