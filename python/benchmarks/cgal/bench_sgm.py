"""DYMSUM against CGAL's spherical Gaussian maps (issue 36's protocol).

    cargo build --release -p dymsum-bench --example sgm_protocol
    g++ -O2 -std=c++17 -DNDEBUG python/benchmarks/cgal/cgal_sgm.cpp -o target/cgal_sgm -lgmp -lmpfr
    python python/benchmarks/cgal/bench_sgm.py [--steps 100] [--pairs gs4,gs4 ellipse,ellipse]

Protocol, per pair ``P, Q`` (Q fixed at the identity, P turning under the
paper's motion at 500 steps per turn, seed 1, from its first pose):

* ``dymsum``: each DYMSUM update (``DynamicSum::set_pose_p``) along the
  ``--steps`` rotations, timed one by one, each keeping its fastest of
  ``--repeats`` runs (a fresh sum per run, built untimed at the first
  pose); the figure is the median over the steps
  (``crates/dymsum-bench/examples/sgm_protocol.rs``).
* ``cgal``: at the same rotations (the same doubles, written by the Rust
  side), CGAL 5.5's Fogel-Halperin ``Arr_polyhedral_sgm`` with the exact
  EPECK kernel recomputes the sum from scratch: P's vertices turned exactly
  (every product exact), P's map built from the turned polyhedron, then
  overlaid with Q's map (prepared once) by ``minkowski_sum``. Each step
  keeps its fastest of ``--cgal-repeats`` runs; the figure is the median
  over the steps (``cgal_sgm.cpp``).
* The ratio is ``cgal / dymsum``. Both tools must agree on the facet count
  at the last step (the map's vertices of degree three or more), or the
  row is marked as a mismatch.

The two programs run one after the other on the same machine; on a shared
machine run the script twice and compare.
"""

import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[3]


def run_json(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--repeats", type=int, default=5, help="DYMSUM runs per step")
    ap.add_argument("--cgal-repeats", type=int, default=1, help="CGAL runs per step")
    ap.add_argument("--pairs", nargs="+", default=["gs4,gs4", "ellipse,ellipse"])
    ap.add_argument("--protocol", default=str(ROOT / "target/release/examples/sgm_protocol"))
    ap.add_argument("--cgal", default=str(ROOT / "target/cgal_sgm"))
    args = ap.parse_args()
    rows = []
    for pair in args.pairs:
        p, q = pair.split(",")
        with tempfile.TemporaryDirectory() as d:
            ours = run_json([args.protocol, p, q, str(args.steps), d, str(args.repeats)])
            theirs = run_json(
                [args.cgal, f"{d}/p.off", f"{d}/q.off", f"{d}/rotations.txt", str(args.cgal_repeats)]
            )
        cgal_us = theirs["median_seconds"] * 1e6
        agree = ours["facets"] == theirs["overlay_vertices"]
        rows.append((pair, ours["median_us"], cgal_us, cgal_us / ours["median_us"], agree, ours["facets"]))
    print(f"{args.steps} steps of the paper's motion (500 per turn), medians per step")
    print("| P ⊕ Q | facets | DYMSUM update µs | CGAL SGM recompute µs | CGAL ÷ DYMSUM | facets agree |")
    print("|---|---:|---:|---:|---:|---|")
    for pair, d, c, ratio, agree, facets in rows:
        print(f"| {pair.replace(',', ' ⊕ ')} | {facets} | {d:.2f} | {c:.0f} | {ratio:,.0f}× | {'yes' if agree else 'NO'} |")
    return 0 if all(r[4] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
