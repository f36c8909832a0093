"""Build time and memory per mesh: dymsum against python-fcl (issue 35).

    pip install ./python trimesh python-fcl
    python python/benchmarks/bench_builds.py DIR [DIR ...] [--repeats N]
        [--memory] [--min-faces F] [--soup N[,N...]]

Every ``*.stl`` under the folders given (e.g. git checkouts of
``ros-industrial/universal_robot`` and ``ros-industrial/abb``), read by
trimesh as it is (``process=False``: unwelded, as robots ship them).
``--soup`` adds synthetic soups of N triangles each (the issue's
extremes): seeded random triangles, each with its own three vertices
(nothing welded), sides up to 1 at random orientations, centres uniform
in a cube of side ``10 N^(1/3)`` (so they rarely meet).

Time: per mesh, what a planner builds before its first query, both
tools timed alternately in one process, the median of ``--repeats``
rounds: ``dymsum.MotionChecker((v, f), [(v, f)])`` (the mesh as the moving
body and as the obstacle: two bodies, cleaned exactly, and the checker
ready for its first query) against two fcl ``BVHModel`` (OBBRSS) and
their ``CollisionObject``.

Memory (``--memory``): each mesh in fresh processes, one per tool
(``build_memory.py``): the peak resident memory during the build (VmHWM,
reset just before it) less the resident memory before it.

Prints one Markdown row per mesh and the geometric mean and worst of the
ratios dymsum / fcl (below 1: dymsum is faster or smaller).
"""

import argparse
import glob
import os
import sys
import time

import numpy as np

from build_memory import build_memory


def load(path):
    import trimesh

    m = trimesh.load(path, process=False, force="mesh")
    return np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)


def build_fcl(fcl, v, f):
    objects = []
    for _ in range(2):
        b = fcl.BVHModel()
        b.beginModel(len(v), len(f))
        b.addSubModel(v, f)
        b.endModel()
        objects.append(fcl.CollisionObject(b))
    return objects


def build_dymsum(dymsum, v, f):
    return dymsum.MotionChecker((v, f), [(v, f)])


def soup(n, seed=1):
    """A seeded soup of ``n`` unwelded triangles (module docs)."""
    rng = np.random.default_rng(seed)
    centres = rng.uniform(0.0, 10.0 * n ** (1.0 / 3.0), size=(n, 1, 3))
    v = (centres + rng.uniform(-0.5, 0.5, size=(n, 3, 3))).reshape(-1, 3)
    return v, np.arange(3 * n, dtype=np.int64).reshape(n, 3)


def times(mesh, repeats):
    import fcl

    import dymsum

    v, f = mesh
    td, tf = [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        built = build_dymsum(dymsum, v, f)
        td.append(time.perf_counter() - t0)
        del built
        t0 = time.perf_counter()
        built = build_fcl(fcl, v, f)
        tf.append(time.perf_counter() - t0)
        del built
    return len(f), float(np.median(td)), float(np.median(tf))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="*")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--memory", action="store_true")
    ap.add_argument("--min-faces", type=int, default=0)
    ap.add_argument("--soup", default="", help="comma-separated triangle counts of synthetic soups")
    a = ap.parse_args()
    files = sorted(
        {f for d in a.dirs for pattern in ("*.stl", "*.STL") for f in glob.glob(os.path.join(d, "**", pattern), recursive=True)}
    )
    meshes = [(os.path.basename(p)[:-4], lambda p=p: load(p)) for p in files]
    meshes += [(f"soup of {int(n)} triangles", lambda n=int(n): soup(n)) for n in a.soup.split(",") if n.strip()]
    header = "| mesh | triangles | build ms dymsum / fcl (ratio) |"
    rule = "|---|---|---|"
    if a.memory:
        header += " added peak memory KiB dymsum / fcl (ratio) |"
        rule += "---|"
    print(header)
    print(rule)
    ratios, mem_ratios = [], []
    for name, read in meshes:
        try:
            mesh = read()
            n, td, tf = times(mesh, a.repeats)
        except Exception as e:  # noqa: BLE001 - a file trimesh cannot read is reported and skipped
            print(f"skipped {name}: {e}", file=sys.stderr)
            continue
        if n < max(1, a.min_faces):
            continue
        ratios.append(td / tf)
        row = f"| {name} | {n} | {td * 1e3:.2f} / {tf * 1e3:.2f} ({td / tf:.2f}) |"
        if a.memory:
            v, f = mesh
            m = build_memory(v, f, v, f)
            md, mf = m["dymsum"].get("peak_kb"), m["fcl"].get("peak_kb")
            if md is None or mf is None:
                row += f" {m} |"
            else:
                mem_ratios.append(max(md, 1) / max(mf, 1))
                row += f" {md} / {mf} ({mem_ratios[-1]:.2f}) |"
        print(row, flush=True)
    gm = lambda v: float(np.exp(np.mean(np.log(v)))) if v else float("nan")  # noqa: E731
    print()
    print(
        f"Build time dymsum / fcl over {len(ratios)} meshes: geometric mean {gm(ratios):.2f}, "
        f"worst {max(ratios or [0]):.2f}, {sum(r > 1 for r in ratios)} above 1"
    )
    if a.memory:
        print(
            f"Added peak memory dymsum / fcl: geometric mean {gm(mem_ratios):.2f}, "
            f"worst {max(mem_ratios or [0]):.2f}, {sum(r > 1 for r in mem_ratios)} above 1"
        )


if __name__ == "__main__":
    main()
