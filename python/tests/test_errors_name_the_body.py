"""Errors come from the body they concern (issue 34): a misspelt second
operand is reported as such, not as the first mesh's need for a
decomposition; a mesh of several closed shells is named so, not "not a
topological sphere"; the decomposition error is a public type."""

import numpy as np
import pytest

import dymsum

QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]


def boxes(n, weld=False):
    v, f = [], []
    for s in range(n):
        o = len(v)
        lo, hi = [1.0 * s, 0, 0] if weld else [3.0 * s, 0, 0], [1.0 * s + 1, 1, 1] if weld else [3.0 * s + 1, 1, 1]
        v += [[hi[k] if (i >> k) & 1 else lo[k] for k in range(3)] for i in range(8)]
        f += [[o + x for x in q] for q in QUADS]
    return np.array(v, float), f


def l_shape():
    """An L of two boxes as one closed triangle mesh (not convex, one shell)."""
    import itertools

    pts = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
    v = [[x, y, z] for z in (0.0, 1.0) for x, y in pts]
    f = []
    bottom = [[0, 3, 1], [1, 3, 2], [0, 5, 3], [3, 5, 4]]
    f += bottom
    f += [[a + 6, c + 6, b + 6] for a, b, c in bottom]
    for i in range(6):
        j = (i + 1) % 6
        f += [[i, j, j + 6], [i, j + 6, i + 6]]
    del itertools
    return np.array(v, float), np.array(f)


def test_a_misspelt_second_operand_is_reported_as_such(tmp_path):
    missing = str(tmp_path / "typo.off")
    with pytest.raises((FileNotFoundError, ValueError), match=r"^b: .*typo\.off"):
        dymsum.contact(l_shape(), missing)


def test_the_decomposition_error_is_public():
    with pytest.raises(dymsum.NeedsDecompositionError, match=r"^a: .*decomposition"):
        dymsum.contact(l_shape(), "box:1,1,1")
    assert issubclass(dymsum.NeedsDecompositionError, ValueError)
    assert dymsum.nonconvex.NeedsDecompositionError is dymsum.NeedsDecompositionError


def test_a_mesh_of_several_closed_shells_is_named_so():
    with pytest.raises(ValueError, match=r"^a: a mesh of 5 closed shells") as e:
        dymsum.contact(boxes(5), "box:1,1,1")
    assert "topological sphere" not in str(e.value)
