"""The memory a build adds, each tool in a fresh process (shared by
``bench_scenes.py`` and ``bench_builds.py``).

The child loads the arrays, builds a tetrahedron once with the same tool
(its code paged in and its one-time tables made: counted once per
process, not per build), resets the peak resident memory
(``/proc/self/clear_refs``), builds ``dymsum.MotionChecker((rv, rf),
[(ev, ef)])`` or python-fcl's two ``BVHModel`` (OBBRSS) and their
``CollisionObject``, and reports VmRSS after less before (what stays) and
VmHWM after less VmRSS before (what the build needed at most).
"""

import json
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

CHILD = r"""
import gc, json, sys, time
import numpy as np
def status():
    out = {}
    for line in open("/proc/self/status"):
        k, _, v = line.partition(":")
        if k in ("VmRSS", "VmHWM"):
            out[k] = int(v.split()[0])
    return out
d = dict(np.load(sys.argv[1]))
which = sys.argv[2]
if which == "dymsum":
    import dymsum
    build_of = lambda rv, rf, ev, ef: dymsum.MotionChecker((rv, rf), [(ev, ef)])
else:
    import fcl
    def bvh(v, f):
        m = fcl.BVHModel(); m.beginModel(len(v), len(f)); m.addSubModel(v, f); m.endModel(); return m
    build_of = lambda rv, rf, ev, ef: (fcl.CollisionObject(bvh(rv, rf), fcl.Transform()), fcl.CollisionObject(bvh(ev, ef), fcl.Transform()))
build = lambda: build_of(d["rv"], d["rf"], d["ev"], d["ef"])
# One build of a tetrahedron first: the tool's code is paged in (file-backed
# pages, counted once per process, not by the build) and its one-time
# tables are made, so the peak below is what this build needs.
tv = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
tf = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.int64)
warm = build_of(tv, tf, tv, tf)
del warm
gc.collect()
try:
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")  # resets VmHWM to the current VmRSS
    reset = True
except OSError:
    reset = False
before = status()
t0 = time.perf_counter()
built = build()
seconds = time.perf_counter() - t0
after = status()
print(json.dumps({"rss_kb": after["VmRSS"] - before["VmRSS"], "peak_kb": after["VmHWM"] - before["VmRSS"] if reset else None, "seconds": seconds}))
"""


def build_memory(rv, rf, ev, ef) -> dict:
    """``{"dymsum": m, "fcl": m}``, each ``m`` holding ``rss_kb``,
    ``peak_kb`` (``None`` where the peak cannot be reset) and ``seconds``,
    or ``error`` (the child's last line of stderr)."""
    out = {}
    with tempfile.TemporaryDirectory(prefix="bench-memory-") as tmp:
        arrays = pathlib.Path(tmp) / "mesh.npz"
        np.savez(
            arrays,
            rv=np.ascontiguousarray(rv, float), rf=np.ascontiguousarray(rf, np.int64),
            ev=np.ascontiguousarray(ev, float), ef=np.ascontiguousarray(ef, np.int64),
        )
        for which in ("dymsum", "fcl"):
            done = subprocess.run([sys.executable, "-c", CHILD, str(arrays), which], capture_output=True, text=True, timeout=600)
            if done.returncode != 0:
                out[which] = {"error": done.stderr.strip().splitlines()[-1:] or ["exit " + str(done.returncode)]}
                continue
            out[which] = json.loads(done.stdout.strip().splitlines()[-1])
    return out
