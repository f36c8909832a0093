"""Check ``dymsum.omplapp`` on OMPL.app's 3-D problems with FCL, as OMPL.app checks.

    pip install ./python trimesh pycollada python-fcl
    python python/benchmarks/omplapp_check.py [DIR ...] [--samples N] [--seed S]

For every ``*.cfg`` under each DIR (default ``/work/omplapp-3d``: OMPL.app's
``resources/3D``, which dymsum does not ship), the problem is read with
``dymsum.omplapp.load_problem`` and the robot and the environment become
``fcl.BVHModel``s (OBBRSS, as OMPL.app's FCL checker builds them: the
environment in the world frame, the robot in its own frame moved by each
state). A loader is right when every state of the solution paths OMPL.app
ships comes out free, so this checks that every state of the problem's
``.path`` (if there is one), its start and its goal are collision-free under
``fcl.collide``, and then times ``fcl.collide`` on N random states (the
translation uniform in the bounds, the rotation uniform).

Prints a Markdown table, one row per problem: the mesh sizes, the path
states and how many collide (must be 0), whether start and goal are free,
whether the path runs from the start to the goal, the time to build the
environment's BVH, the median time of one ``fcl.collide`` over the random
states (the call alone, through python-fcl), and the fraction of them that
collide. A problem that cannot be read gets a row saying why. Exits 1 if
any path state, start or goal collides, else 0.
"""

from __future__ import annotations

import argparse
import math
import pathlib
import platform
import statistics
import sys
import time
from typing import List, Optional

import numpy as np

from dymsum.omplapp import Problem, load_path, load_problem

DEFAULT_DIR = "/work/omplapp-3d"


def bvh(vertices: np.ndarray, faces: np.ndarray):
    import fcl

    model = fcl.BVHModel()
    model.beginModel(len(vertices), len(faces))
    model.addSubModel(np.ascontiguousarray(vertices, dtype=float), np.ascontiguousarray(faces, dtype=np.int64))
    model.endModel()
    return model


def random_poses(rng: np.random.Generator, low: np.ndarray, high: np.ndarray, n: int) -> np.ndarray:
    """n poses: translation uniform in [low, high], rotation uniform (Shoemake)."""
    u1, u2, u3 = rng.random((3, n))
    q = np.stack(
        [
            np.sqrt(1 - u1) * np.sin(2 * math.pi * u2),
            np.sqrt(1 - u1) * np.cos(2 * math.pi * u2),
            np.sqrt(u1) * np.sin(2 * math.pi * u3),
            np.sqrt(u1) * np.cos(2 * math.pi * u3),
        ],
        axis=1,
    )  # x, y, z, w
    x, y, z, w = q.T
    poses = np.zeros((n, 4, 4))
    poses[:, 0] = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), np.zeros(n)], axis=1)
    poses[:, 1] = np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), np.zeros(n)], axis=1)
    poses[:, 2] = np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), np.zeros(n)], axis=1)
    poses[:, :3, 3] = rng.uniform(low, high, size=(n, 3))
    poses[:, 3, 3] = 1.0
    return poses


class Checker:
    """FCL's yes/no collision query for the robot of a problem."""

    def __init__(self, problem: Problem):
        import fcl

        self.fcl = fcl
        t0 = time.perf_counter_ns()
        env_model = bvh(problem.env_vertices, problem.env_faces)
        self.env_build_ns = time.perf_counter_ns() - t0
        self.env = fcl.CollisionObject(env_model, fcl.Transform())
        self.robot = fcl.CollisionObject(bvh(problem.robot_vertices, problem.robot_faces), fcl.Transform())
        self.request = fcl.CollisionRequest()

    def collides(self, pose: np.ndarray) -> bool:
        self.robot.setTransform(self.fcl.Transform(pose[:3, :3], pose[:3, 3]))
        return self.fcl.collide(self.robot, self.env, self.request, self.fcl.CollisionResult()) > 0

    def timed(self, pose: np.ndarray):
        self.robot.setTransform(self.fcl.Transform(pose[:3, :3], pose[:3, 3]))
        result = self.fcl.CollisionResult()
        t0 = time.perf_counter_ns()
        hit = self.fcl.collide(self.robot, self.env, self.request, result) > 0
        return hit, time.perf_counter_ns() - t0


def same_pose(a: np.ndarray, b: np.ndarray, tol: float) -> bool:
    # A rotation and its quaternion's negation are the same pose.
    return bool(np.abs(a[:3, 3] - b[:3, 3]).max() <= tol and np.abs(a[:3, :3] - b[:3, :3]).max() <= 1e-3)


def check(cfg: pathlib.Path, samples: int, seed: int) -> dict:
    row: dict = {"cfg": cfg.name}
    try:
        problem = load_problem(cfg)
    except (OSError, ValueError) as e:
        row["error"] = f"{type(e).__name__}: {e}"
        return row
    row["problem"] = problem
    checker = Checker(problem)
    row["env_build_ms"] = checker.env_build_ns / 1e6
    row["start_free"] = not checker.collides(problem.start)
    row["goal_free"] = not checker.collides(problem.goal)
    if problem.path_file is not None:
        path = load_path(problem.path_file)
        hits = [i for i, pose in enumerate(path) if checker.collides(pose)]
        row["path_states"] = len(path)
        row["path_hits"] = hits
        low, high = problem.bounds
        row["path_out_of_bounds"] = int(((path[:, :3, 3] < low) | (path[:, :3, 3] > high)).any(axis=1).sum())
        # The .path files print positions with 3 decimals or so.
        tol = 2e-3 * max(1.0, float(np.abs(path[:, :3, 3]).max()))
        row["path_ends"] = same_pose(path[0], problem.start, tol) and same_pose(path[-1], problem.goal, tol)
    rng = np.random.default_rng(seed)
    times: List[int] = []
    hits_random = 0
    for pose in random_poses(rng, problem.bounds[0], problem.bounds[1], samples):
        hit, ns = checker.timed(pose)
        times.append(ns)
        hits_random += hit
    row["collide_us"] = statistics.median(times) / 1e3
    row["random_hit_fraction"] = hits_random / samples
    return row


def yes_no(v: Optional[bool]) -> str:
    return "—" if v is None else ("yes" if v else "**no**")


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dirs", nargs="*", default=[DEFAULT_DIR], help=f"folders searched for *.cfg (default {DEFAULT_DIR})")
    parser.add_argument("--samples", type=int, default=1000, help="random states timed per problem (default 1000)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the random states (default 1)")
    args = parser.parse_args(argv)
    try:
        import fcl
    except ImportError:
        parser.error("needs python-fcl: pip install python-fcl")

    cfgs = sorted({p for d in args.dirs for p in pathlib.Path(d).rglob("*.cfg")})
    if not cfgs:
        parser.error(f"no *.cfg under {' '.join(args.dirs)}")
    rows = [check(cfg, args.samples, args.seed) for cfg in cfgs]

    print(
        f"OMPL.app problems read with dymsum.omplapp, checked with python-fcl {getattr(fcl, '__version__', '')}"
        f" (Python {platform.python_version()}, {platform.machine()}); {args.samples} random states per problem, seed {args.seed}.\n"
    )
    print(
        "| problem | robot triangles | robot vertices | env triangles | env vertices | path states | colliding states"
        " | start, goal free | path start→goal | env BVH build (ms) | median `collide` (µs) | random states colliding |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---|---|---:|---:|---:|")
    failed = False
    for row in rows:
        if "error" in row:
            print(f"| {row['cfg']} | — | — | — | — | — | — | — | — | — | — | not read: {row['error']} |")
            continue
        p: Problem = row["problem"]
        states = row.get("path_states")
        hits = row.get("path_hits")
        bad = (hits is not None and len(hits) > 0) or not row["start_free"] or not row["goal_free"]
        failed |= bad
        hit_text = "—" if hits is None else (str(len(hits)) if not hits else f"**{len(hits)}** (states {', '.join(map(str, hits[:8]))}{', …' if len(hits) > 8 else ''})")
        if row.get("path_out_of_bounds"):
            hit_text += f"; {row['path_out_of_bounds']} out of bounds"
        ends = yes_no(row.get("path_ends")) if states is not None else "—"
        print(
            f"| {row['cfg'][:-4]} | {len(p.robot_faces)} | {len(p.robot_vertices)} | {len(p.env_faces)} | {len(p.env_vertices)}"
            f" | {states if states is not None else '—'} | {hit_text} | {yes_no(row['start_free'])}, {yes_no(row['goal_free'])}"
            f" | {ends} | {row['env_build_ms']:.1f} | {row['collide_us']:.1f} | {row['random_hit_fraction']:.3f} |"
        )
    notes = []
    for row in rows:
        if "error" in row:
            continue
        name = row["cfg"][:-4]
        if row.get("path_hits"):
            notes.append(f"{name}: path states {row['path_hits']} collide")
        for which in ("start", "goal"):
            if not row[f"{which}_free"]:
                notes.append(f"{name}: the .cfg's {which} collides")
        if row.get("path_ends") is False:
            notes.append(f"{name}: the .path does not run from the .cfg's start to its goal")
    if notes:
        print("\n" + "\n".join(f"- {n}" for n in notes))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
