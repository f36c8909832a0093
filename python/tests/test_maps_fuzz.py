"""Fuzzing the map reader (issue 26 §5): byte mutations of valid small
maps of both forms, and containers with random arrays in place of fields.
``dymsum.load_cobstacle_map`` either returns a map that answers every
slice or raises ValueError/OSError naming the path; nothing else. A small
budget (200 examples each) keeps CI fast."""

import os

import numpy as np
import pytest
from test_maps import small_arrays, write_zip

import dymsum

pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


FUZZ = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])


def load_or_refuse(path):
    """The reader's contract: a valid map, or ValueError/OSError naming the
    path; nothing else."""
    try:
        m = dymsum.load_cobstacle_map(path)
    except (ValueError, OSError) as e:
        assert str(path) in str(e), e
        return None
    # A map that loads answers every slice.
    for p in range(len(m.pairs)):
        r, o = (int(x) for x in m.pairs[p])
        for k in range(m.slices_per_pair):
            m[r, o, k]
    return m


_SMALL = {}


def small_map_bytes(form):
    if form not in _SMALL:
        import tempfile

        with tempfile.TemporaryDirectory() as d:
            dymsum.CObstacleMap(small_arrays(form)).save(os.path.join(d, "m.npz"))
            with open(os.path.join(d, "m.npz"), "rb") as f:
                _SMALL[form] = f.read()
    return _SMALL[form]


@FUZZ
@given(
    form=st.sampled_from(["halfspaces", "mesh"]),
    edits=st.lists(st.tuples(st.integers(min_value=0), st.integers(0, 255)), min_size=1, max_size=8),
    cut=st.one_of(st.none(), st.integers(min_value=0)),
)
def test_fuzz_mutated_map_files_load_or_raise_value_or_os_error(tmp_path, form, edits, cut):
    data = bytearray(small_map_bytes(form))
    for at, byte in edits:
        data[at % len(data)] = byte
    if cut is not None:
        data = data[: cut % (len(data) + 1)]
    path = tmp_path / "fuzz.npz"
    path.write_bytes(bytes(data))
    load_or_refuse(path)


ARRAY = st.one_of(
    st.builds(lambda n, s: np.arange(n, dtype=np.int64) * s, st.integers(0, 20), st.integers(-3, 3)),
    st.builds(lambda v, n: np.full((n, 3), v), st.floats(allow_nan=True, allow_infinity=True), st.integers(0, 12)),
    st.builds(lambda v: np.array(v), st.one_of(st.integers(-(2**63), 2**63 - 1), st.floats(), st.text(max_size=5))),
    st.builds(lambda n: np.array(["x"] * n), st.integers(0, 4)),
    st.builds(lambda n, t: np.zeros(n, dtype=t), st.integers(0, 6), st.sampled_from(["<i4", ">i8", "<f4", "|b1", "<u8", "<c16", "|S3", "<U2"])),
)


@FUZZ
@given(
    form=st.sampled_from(["halfspaces", "mesh"]),
    changes=st.dictionaries(st.sampled_from(sorted(set(dymsum._maps._KINDS))), st.one_of(st.none(), ARRAY), min_size=1, max_size=3),
)
def test_fuzz_random_arrays_in_a_map_container(tmp_path, form, changes):
    arrays = dict(small_arrays(form))
    for k, v in changes.items():
        if v is None:
            arrays.pop(k, None)
        else:
            arrays[k] = v
    load_or_refuse(write_zip(tmp_path / "fuzz.npz", list(arrays.items())))
