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
    for obj in (dymsum, dymsum.Polytope, dymsum.DynamicSum, dymsum.ContactTracker):
        r = run(obj, getattr(obj, "__name__", "dymsum"))
        assert r.failed == 0, obj
        attempted += r.attempted
    assert attempted >= 15
