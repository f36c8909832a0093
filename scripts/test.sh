#!/usr/bin/env bash
# All tests in one command: the Rust workspace's tests, then the Python
# package's. The package is built from source and installed with
# `pip install ./python` into a virtual environment (target/pyenv, or
# $DYMSUM_PYENV) together with the test dependencies (pytest, numpy, scipy,
# mypy for checking the type stubs against the module, OMPL's Python wheel
# for dymsum.ompl's tests, which then must run: DYMSUM_REQUIRE_OMPL=1, the
# optional extras for non-convex sums: manifold3d, coacd, vhacdx, then
# required: DYMSUM_REQUIRE_MANIFOLD=1, and dask[distributed]:
# cobstacle_map's tests on LocalClusters then must run:
# DYMSUM_REQUIRE_DASK=1), then pytest runs python/tests. Needs the Rust
# toolchain and python3 with venv and pip (PyPI and crates.io reachable on
# the first run). Where OMPL has no wheel (it publishes Linux ones),
# DYMSUM_NO_OMPL=1 leaves it out and its tests are skipped.
#
# Cost: after `cargo run --release -p dymsum-cli -- demo` (the README's first
# command), no dependency is compiled again: the CLI and dymsum-testkit name
# the features the workspace's tests turn on in shared dependencies, and the
# wheel uses the workspace's release profile (issue 29). Every test's
# temporary files go into one folder made for this run ($TMPDIR below),
# removed at exit; the run fails if a test left a dymsum-* folder in it.
set -euo pipefail
cd "$(dirname "$0")/.."

run_tmp="$(mktemp -d "${TMPDIR:-/tmp}/dymsum-test-run.XXXXXX")"
ticker=
trap 'if [ -n "$ticker" ]; then kill "$ticker" 2>/dev/null || true; fi; rm -rf "$run_tmp"' EXIT
trap 'exit 130' INT TERM
export TMPDIR="$run_tmp"

printf '\n=== cargo test --workspace --release\n'
cargo test --workspace --release

# The certified queries against their exhaustive reference on every query
# of the core's suite (the feature makes each certified answer also
# evaluate every facet and assert that both are equal). Only dymsum, the
# testkit and dymsum's tests are compiled again for it: the dependencies are
# the first pass's (the testkit names their workspace features).
printf '\n=== cargo test -p dymsum --release --features check-reference\n'
cargo test -p dymsum --release --features check-reference

# maturin builds the extension with cargo: share the workspace's target dir
# (the dependencies the two workspaces have in common are built once).
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
venv="${DYMSUM_PYENV:-target/pyenv}"
python="${PYTHON:-python3}"

# OMPL only as a wheel (its source build needs Boost and a C++ toolchain).
ompl=(--only-binary ompl 'ompl>=2.0,<3')
if [ "${DYMSUM_NO_OMPL:-0}" = 1 ]; then
    ompl=()
    export DYMSUM_REQUIRE_OMPL=0
else
    export DYMSUM_REQUIRE_OMPL=1
fi

printf '\n=== Python: pip install ./python pytest numpy scipy mypy hypothesis %s (into %s)\n' "${ompl[*]:+ompl}" "$venv"
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv" || {
        echo "creating a virtual environment failed: install python3's venv module (e.g. apt-get install python3-venv)" >&2
        exit 1
    }
fi
# The wheel's first build takes a minute or more: a line every 15 s says
# it is still going (maturin hands cargo's output to pip only at the end),
# then cargo's `Compiling` lines and pip's results are shown. The whole log
# is printed if pip fails.
pip_log="$run_tmp/pip.log"
start=$SECONDS
(trap - EXIT INT TERM; while sleep 15; do printf '    ... pip install ./python: %s s\n' "$((SECONDS - start))"; done) &
ticker=$!
status=0
PYTHONUNBUFFERED=1 "$venv/bin/python" -m pip install -v --disable-pip-version-check ./python pytest numpy scipy mypy hypothesis 'dask[distributed]' "${ompl[@]}" 2>&1 |
    tee "$pip_log" |
    awk '/^ *(Compiling|Finished|Built wheel|Successfully (built|installed))/ { print; fflush() }' || status=$?
kill "$ticker" 2>/dev/null || true
wait "$ticker" 2>/dev/null || true
if [ "$status" != 0 ]; then
    cat "$pip_log" >&2
    echo "pip install ./python failed (the log is above)" >&2
    exit 1
fi
# cobstacle_map on Dask LocalClusters (threads and processes) must run, and
# the CLI's map container (built by the cargo tests above) is loaded.
export DYMSUM_REQUIRE_DASK=1 DYMSUM_CLI="$CARGO_TARGET_DIR/release/dymsum" DYMSUM_REQUIRE_CLI=1
# The optional extras of non-convex sums (dymsum.minkowski_sum on unions and
# non-convex meshes): Manifold merges the piece sums; CoACD and V-HACD
# decompose. The package never imports them unless used; here they are
# installed and required, so the non-convex tests and doc examples run
# rather than skip.
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check manifold3d coacd vhacdx
export DYMSUM_REQUIRE_MANIFOLD=1
# Real scenes (issue 28): trimesh and pycollada load meshes as planning
# suites ship them (dymsum.omplapp), python-fcl is the peer the scene tests
# compare every state with; installed and required here.
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check trimesh pycollada python-fcl
export DYMSUM_REQUIRE_SCENES=1
# Robots (issue 37): pinocchio + coal, the anchor the robot checks are
# compared with, and example-robot-data's robots (URDFs, SRDFs, STL and
# Collada meshes; python/tests/test_robot.py, test_robot_zoo.py);
# installed and required here.
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check pin example-robot-data
export DYMSUM_REQUIRE_PINOCCHIO=1

printf '\n=== Python: stubtest (the type stubs match the module)\n'
(cd "$venv" && bin/python -m mypy.stubtest dymsum._dymsum)

printf '\n=== Python: pytest python/tests\n'
"$venv/bin/python" -m pytest -q python/tests -p no:cacheprovider

# Every test cleans up after itself: the Rust scratch folders
# (dymsum_testkit::files::temp_dir, removed at exit) and the Python tests'.
left="$(cd "$run_tmp" && find . -maxdepth 1 -name 'dymsum-*' | sort)"
if [ -n "$left" ]; then
    printf 'the tests left these temporary folders behind (in %s):\n%s\n' "$run_tmp" "$left" >&2
    exit 1
fi
