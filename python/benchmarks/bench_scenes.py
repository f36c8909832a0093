"""dymsum against python-fcl and OMPL's DiscreteMotionValidator on OMPL.app's
3-D problems.

    pip install ./python ompl trimesh pycollada python-fcl
    python python/benchmarks/bench_scenes.py [DIR] [--problems cubicles,Home,...]
        [--runs N] [--cap S] [--record-time S] [--states N] [--near N]
        [--motions N] [--motion-budget S] [--motions-dir D] [--save FILE]
    python python/benchmarks/bench_scenes.py --report FILE

For each ``*.cfg`` in DIR (default ``/work/omplapp-3d``: OMPL.app's
``resources/3D``, which dymsum does not ship), read with
``dymsum.omplapp.load_problem``, smallest meshes first:

a. **build**: the median time (of 3) of ``dymsum.MotionChecker(robot,
   [env])`` and of python-fcl's two ``BVHModel``s (OBBRSS, robot and
   environment, as OMPL.app builds them), and the memory each takes: in a
   fresh process, VmRSS (``/proc/self/status``) before and after the build
   (what stays) and VmHWM after, the peak having been reset just before
   (``/proc/self/clear_refs``; what the build needed at most);
b. **states**, one call at a time from Python as OMPL asks them: dymsum's
   ``collides_at(pose)`` against ``setTransform`` + ``fcl.collide`` with a
   fresh request and result, on N random states (translation uniform in
   the bounds, rotation uniform) and on states near contact (for a random
   rotation, 30 bisection steps on the translation between a free and a
   colliding pose; both ends kept). Medians and 99th percentiles in µs, and every state where
   the two disagree (expected only at contact: dymsum counts touching, and
   the two ends of a bisection are a few 1e-7 of the bounds apart);
c. **motions**, those RRTConnect really asks: one RRTConnect run with fcl
   and OMPL's DiscreteMotionValidator (default resolution, 1% of the
   space's extent) records every ``checkMotion(s1, s2)`` (a random sample
   of at most N), saved to ``<motions-dir>/<problem>.npz`` (``poses0``,
   ``poses1`` (K, 4, 4); ``states0``, ``states1`` (K, 7) as ``x y z qx qy
   qz qw``; ``discrete_valid``, the answer the planner got). Then, on the
   same motions, one call at a time: the DiscreteMotionValidator's
   ``checkMotion`` (fcl state checks from Python), python-fcl's
   ``continuousCollide`` with its default ``ContinuousCollisionRequest()``
   (conservative advancement of a *translation*: FCL's ``CCDM_TRANS``
   holds the start's rotation, so a motion that turns is not the motion
   checked), dymsum's ``MotionChecker.check(pose0, pose1, 1e-6)`` and
   dymsum's OMPL validator (``CertifiedMotionValidator.checkMotion``, the
   yes/no check a planner makes). Medians in µs per motion; each method
   stops after ``--motion-budget`` seconds (the count done is shown). The
   motions the discrete validator accepts where dymsum finds a contact are
   the ones sampling steps over; also counted: the reverse (expected only
   at contact), ``MotionUndecided``, and where fcl's CCD and dymsum differ
   (on OMPL's motion and on the translation-only motion the CCD checks).
   Besides the sample, every motion the discrete validator accepted in the
   recording run (up to 20,000, within ``--motion-budget`` seconds) is
   checked by dymsum, each contact found confirmed or not by fcl's own
   ``collide`` at 1001 poses just after dymsum's ``t_contact``;
d. **planning**: ``--runs`` runs of RRTConnect (time limit: the ``.cfg``'s,
   at most ``--cap`` s) with dymsum's validators and with fcl + the
   DiscreteMotionValidator (``examples/ompl_app.py``): how many solve, the
   median planning time (unsolved runs count at their time, the limit),
   the median numbers of state and motion checks, and how many of the fcl
   paths dymsum certifies free, motion by motion.

A part that fails for a problem reports why and the others still run.
Prints Markdown tables at the end; ``--save FILE`` appends each problem's
results to FILE (JSON lines) as soon as they are done, and ``--report
FILE`` prints the tables of such a file. OMPL's RNG is not seeded.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import time
import traceback
import zlib
from typing import Any, Callable, List, Optional

import numpy as np

import dymsum
import dymsum.ompl
from dymsum.omplapp import Problem, load_problem

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from build_memory import build_memory  # noqa: E402
from omplapp_check import random_poses  # noqa: E402

DEFAULT_DIR = "/work/omplapp-3d"
DEFAULT_MOTIONS_DIR = "/work/omplapp-motions"


def _example():
    spec = importlib.util.spec_from_file_location("ompl_app", HERE.parent / "examples" / "ompl_app.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


app = _example()


def log(*args: Any) -> None:
    print(*args, file=sys.stderr, flush=True)


def median(xs) -> float:
    xs = list(xs)
    return float(statistics.median(xs)) if xs else math.nan


def mesh_args(p: Problem):
    return (p.robot_vertices, p.robot_faces), [(p.env_vertices, p.env_faces)]


def dymsum_checker(p: Problem) -> dymsum.MotionChecker:
    return dymsum.MotionChecker(*mesh_args(p))


class Fcl:
    """python-fcl's robot and environment objects of a problem."""

    def __init__(self, p: Problem):
        import fcl

        self.fcl = fcl
        self.robot = app.fcl_object(p.robot_vertices, p.robot_faces)
        self.env = app.fcl_object(p.env_vertices, p.env_faces)

    def collides(self, pose: np.ndarray) -> bool:
        fcl = self.fcl
        self.robot.setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))
        return fcl.collide(self.robot, self.env, fcl.CollisionRequest(), fcl.CollisionResult()) > 0

    def distance(self, pose: np.ndarray) -> float:
        fcl = self.fcl
        self.robot.setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))
        return float(fcl.distance(self.robot, self.env, fcl.DistanceRequest(), fcl.DistanceResult()))


def slerp_poses(a: np.ndarray, b: np.ndarray, ts: np.ndarray) -> np.ndarray:
    """OMPL's SE(3) interpolation of two poses at each t: the translation
    linear, the rotation by slerp along the shorter arc."""
    from scipy.spatial.transform import Rotation, Slerp

    ts = np.asarray(ts, float)
    out = np.tile(np.eye(4), (len(ts), 1, 1))
    out[:, :3, :3] = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([a[:3, :3], b[:3, :3]])))(ts).as_matrix()
    out[:, :3, 3] = a[:3, 3] + (b[:3, 3] - a[:3, 3]) * ts[:, None]
    return out


def fcl_confirms(f: "Fcl", a: np.ndarray, b: np.ndarray, t: float, width: float = 0.01, n: int = 1001) -> bool:
    """Whether fcl's own ``collide`` finds a collision at one of n poses of
    the motion a → b in [t, t + width] (a contact dymsum reported at t)."""
    ts = np.linspace(t, min(1.0, t + width), n)
    return any(f.collides(q) for q in slerp_poses(a, b, ts))


# ---------------------------------------------------------------- a. build




def part_build(p: Problem, repeats: int = 3) -> dict:
    out: dict = {}
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        dymsum_checker(p)
        times.append(time.perf_counter() - t0)
    out["dymsum_ms"] = median(times) * 1e3
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        Fcl(p)
        times.append(time.perf_counter() - t0)
    out["fcl_ms"] = median(times) * 1e3
    for which, m in build_memory(p.robot_vertices, p.robot_faces, p.env_vertices, p.env_faces).items():
        if "error" in m:
            out[f"{which}_memory_error"] = m["error"]
            continue
        out[f"{which}_rss_mb"] = m["rss_kb"] / 1024
        out[f"{which}_peak_mb"] = None if m["peak_kb"] is None else m["peak_kb"] / 1024
    return out


# ---------------------------------------------------------------- b. states


def near_contact_poses(checker: dymsum.MotionChecker, p: Problem, rng: np.random.Generator, n: int, steps: int = 30) -> np.ndarray:
    """n poses (n/2 bisections, both ends): for a random rotation, a free and
    a colliding translation, then ``steps`` halvings of the segment between
    them (dymsum's exact check decides). Rotations where 64 translations
    give no free or no colliding one are drawn again."""
    low, high = p.bounds
    out: List[np.ndarray] = []
    tries = 0
    while len(out) < n and tries < 50 * n:
        tries += 1
        rotation = random_poses(rng, low, high, 1)[0]
        poses = np.tile(rotation, (64, 1, 1))
        poses[:, :3, 3] = rng.uniform(low, high, size=(64, 3))
        hits = checker.collides_many(poses)
        if hits.all() or not hits.any():
            continue
        free, hit = poses[np.flatnonzero(~hits)[0]], poses[np.flatnonzero(hits)[0]]
        a, b = free[:3, 3].copy(), hit[:3, 3].copy()
        pose = rotation.copy()
        for _ in range(steps):
            pose[:3, 3] = (a + b) / 2
            if checker.collides_at(pose):
                b = pose[:3, 3].copy()
            else:
                a = pose[:3, 3].copy()
        for t in (a, b):
            q = rotation.copy()
            q[:3, 3] = t
            out.append(q)
    return np.array(out[:n])


def time_states(checker: dymsum.MotionChecker, f: Fcl, poses: np.ndarray) -> dict:
    """Each pose once with each checker, alternating, one call at a time."""
    fcl = f.fcl
    robot, env = f.robot, f.env
    collides_at = checker.collides_at
    clock = time.perf_counter_ns
    d_ns, f_ns, d_hit, f_hit = [], [], [], []
    for pose in poses:
        t0 = clock()
        hd = collides_at(pose)
        t1 = clock()
        robot.setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))
        hf = fcl.collide(robot, env, fcl.CollisionRequest(), fcl.CollisionResult()) > 0
        t2 = clock()
        d_ns.append(t1 - t0)
        f_ns.append(t2 - t1)
        d_hit.append(hd)
        f_hit.append(hf)
    d_hit_a, f_hit_a = np.array(d_hit), np.array(f_hit)
    only_d = np.flatnonzero(d_hit_a & ~f_hit_a)
    only_f = np.flatnonzero(f_hit_a & ~d_hit_a)
    out = {
        "n": len(poses),
        "colliding": int(d_hit_a.sum()),
        "dymsum_us": median(d_ns) / 1e3,
        "fcl_us": median(f_ns) / 1e3,
        "dymsum_p99_us": float(np.percentile(d_ns, 99)) / 1e3,
        "fcl_p99_us": float(np.percentile(f_ns, 99)) / 1e3,
        "dymsum_only": [int(i) for i in only_d],
        "fcl_only": [int(i) for i in only_f],
    }
    # How far apart the bodies are where only dymsum says they meet (fcl's distance).
    out["dymsum_only_fcl_distance"] = [f.distance(poses[i]) for i in only_d[:20]]
    return out


def part_states(p: Problem, checker: dymsum.MotionChecker, f: Fcl, n_random: int, n_near: int, seed: int) -> dict:
    rng = np.random.default_rng([seed, zlib.crc32(p.name.encode())])
    out: dict = {}
    low, high = p.bounds
    out["random"] = time_states(checker, f, random_poses(rng, low, high, n_random))
    near = near_contact_poses(checker, p, rng, n_near)
    out["near"] = time_states(checker, f, near)
    if len(near) >= 2:
        out["near"]["bisection_gap"] = float(np.median(np.linalg.norm(near[0::2, :3, 3] - near[1::2, :3, 3], axis=1)))
    return out


# ---------------------------------------------------------------- c. motions


def _values(s) -> tuple:
    q = s.rotation()
    return (s.getX(), s.getY(), s.getZ(), q.x, q.y, q.z, q.w)


def _set(s, v) -> None:
    s.setXYZ(float(v[0]), float(v[1]), float(v[2]))
    r = s.rotation()
    r.x, r.y, r.z, r.w = (float(c) for c in v[3:])


def record_motions(p: Problem, seconds: float, cap: int, seed: int) -> dict:
    """One RRTConnect run with fcl + the DiscreteMotionValidator, recording
    every motion asked (a uniform sample of at most ``cap``)."""
    from ompl import base as ob

    ss, _ = app.simple_setup(p, "fcl")
    si = ss.getSpaceInformation()
    inner = si.getMotionValidator()  # OMPL's DiscreteMotionValidator
    rng = np.random.default_rng([seed, zlib.crc32(p.name.encode()), 7])

    class Recorder(ob.MotionValidator):
        def __init__(self, si_):
            super().__init__(si_)
            self.asked = 0
            self.kept: List[tuple] = []
            self.accepted: List[tuple] = []  # every motion found valid (up to 20000)

        def checkMotion(self, s1, s2, last_valid=None):  # noqa: N802
            valid = inner.checkMotion(s1, s2)
            self.asked += 1
            row = (_values(s1), _values(s2), valid)
            if valid and len(self.accepted) < 20000:
                self.accepted.append(row)
            if len(self.kept) < cap:
                self.kept.append(row)
            else:
                j = int(rng.integers(self.asked))
                if j < cap:
                    self.kept[j] = row
            return valid

    recorder = Recorder(si)
    si.setMotionValidator(recorder)
    ss.setup()
    solved = bool(ss.solve(seconds)) and ss.haveExactSolutionPath()
    kept = recorder.kept
    out = {
        "solved": solved,
        "time": ss.getLastPlanComputationTime(),
        "asked": recorder.asked,
        "states0": np.array([k[0] for k in kept], float).reshape(-1, 7),
        "states1": np.array([k[1] for k in kept], float).reshape(-1, 7),
        "discrete_valid": np.array([k[2] for k in kept], bool),
        "accepted0": np.array([k[0] for k in recorder.accepted], float).reshape(-1, 7),
        "accepted1": np.array([k[1] for k in recorder.accepted], float).reshape(-1, 7),
    }
    si.setMotionValidator(inner)  # no Python validator left in C++'s hands
    return out


def poses_of(states: np.ndarray) -> np.ndarray:
    return np.array([dymsum.ompl.se3_pose(*v) for v in states]).reshape(-1, 4, 4)


def _timed(n: int, budget: float, one: Callable[[int], Any]) -> tuple:
    """Runs ``one(i)`` for i = 0.. until n or ``budget`` seconds: (ns list, results)."""
    clock = time.perf_counter_ns
    start = time.perf_counter()
    ns, results = [], []
    for i in range(n):
        if time.perf_counter() - start > budget:
            break
        t0 = clock()
        r = one(i)
        ns.append(clock() - t0)
        results.append(r)
    return ns, results


def part_motions(p: Problem, checker: dymsum.MotionChecker, f: Fcl, args) -> dict:
    seconds = min(p.time_limit or args.record_time, args.record_time)
    rec = record_motions(p, seconds, args.motions, args.seed)
    s0, s1 = rec["states0"], rec["states1"]
    poses0, poses1 = poses_of(s0), poses_of(s1)
    acc0, acc1 = poses_of(rec["accepted0"]), poses_of(rec["accepted1"])
    out: dict = {"record_solved": rec["solved"], "record_time": rec["time"], "asked": rec["asked"], "kept": len(s0)}
    if args.motions_dir:
        folder = pathlib.Path(args.motions_dir)
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{p.name}.npz"
        np.savez_compressed(
            path, poses0=poses0, poses1=poses1, states0=s0, states1=s1, discrete_valid=rec["discrete_valid"], asked=rec["asked"],
            accepted_poses0=acc0, accepted_poses1=acc1,
        )
        out["file"] = str(path)

    # Every motion the discrete validator accepted during the run, certified by dymsum;
    # a contact is confirmed when fcl's own collide finds one just after dymsum's t_contact.
    misses, undecided, confirmed, done = [], 0, 0, 0
    start = time.perf_counter()
    for i in range(len(acc0)):
        if time.perf_counter() - start > args.motion_budget:
            break
        done += 1
        try:
            r = checker.check(acc0[i], acc1[i], 1e-6)
        except dymsum.MotionUndecided:
            undecided += 1
            continue
        if not r.free:
            misses.append((i, r.t_contact))
            confirmed += fcl_confirms(f, acc0[i], acc1[i], float(r.t_contact or 0.0))
    out["accepted"] = dict(
        n=len(acc0), done=done, contact=len(misses), undecided=undecided, fcl_confirmed=confirmed,
        t_contact=[float(t or 0.0) for _, t in misses[:10]],
        length=[float(np.linalg.norm(acc1[i][:3, 3] - acc0[i][:3, 3])) for i, _ in misses[:10]],
    )
    n = len(s0)
    if n == 0:
        return out

    # OMPL's DiscreteMotionValidator on a fresh setup (fcl state checks).
    ss, _ = app.simple_setup(p, "fcl")
    si = ss.getSpaceInformation()
    space = si.getStateSpace()
    mv = si.getMotionValidator()
    a, b = space.allocState(), space.allocState()

    def discrete(i):
        _set(a, s0[i])
        _set(b, s1[i])
        t0 = time.perf_counter_ns()
        r = mv.checkMotion(a, b)
        return r, time.perf_counter_ns() - t0

    ns_disc, res = _timed(n, args.motion_budget, discrete)
    disc_valid = np.array([r for r, _ in res], bool)
    disc_ns = [t for _, t in res]

    # dymsum's OMPL validator (the planner's yes/no check).
    ssd, _ = app.simple_setup(p, "dymsum", motion_checker=checker)
    sid = ssd.getSpaceInformation()
    vd = sid.getMotionValidator()
    c, d = sid.getStateSpace().allocState(), sid.getStateSpace().allocState()

    def validator(i):
        _set(c, s0[i])
        _set(d, s1[i])
        t0 = time.perf_counter_ns()
        r = vd.checkMotion(c, d)
        return r, time.perf_counter_ns() - t0

    _, res = _timed(n, args.motion_budget, validator)
    val_free = np.array([r for r, _ in res], bool)
    val_ns = [t for _, t in res]

    # dymsum's certified check on the poses.
    check = checker.check

    def certified(i):
        try:
            r = check(poses0[i], poses1[i], 1e-6)
            return ("free" if r.free else "contact", r.t_contact)
        except dymsum.MotionUndecided as e:
            return ("undecided", e.t_safe)

    dym_ns, dym = _timed(n, args.motion_budget, certified)

    # python-fcl's continuousCollide, default request (CCDM_TRANS, conservative advancement).
    fcl = f.fcl
    robot, env = f.robot, f.env

    def ccd(i):
        robot.setTransform(fcl.Transform(poses0[i][:3, :3], poses0[i][:3, 3]))
        result = fcl.ContinuousCollisionResult()
        toc = fcl.continuousCollide(robot, fcl.Transform(poses1[i][:3, :3], poses1[i][:3, 3]), env, fcl.Transform(), fcl.ContinuousCollisionRequest(), result)
        return bool(result.is_collide), float(toc)

    ccd_ns, ccd_res = _timed(n, args.motion_budget, ccd)

    # The motion FCL's CCDM_TRANS checks: the translation, at the start's rotation.
    def on_ccd_motion(i):
        end = poses1[i].copy()
        end[:3, :3] = poses0[i][:3, :3]
        try:
            return check(poses0[i], end, 1e-6).free
        except dymsum.MotionUndecided:
            return None

    trans_free = [on_ccd_motion(i) for i in range(len(ccd_res))]

    # Undecided motions: what the discrete validator said, and the check from the other end.
    undecided_notes: List[str] = []
    for i, (kind, t) in enumerate(dym):
        if kind != "undecided" or len(undecided_notes) >= 10:
            continue
        try:
            r = check(poses1[i], poses0[i], 1e-6)
            back = "free" if r.free else f"contact at t = {1 - (r.t_contact or 0.0):.6f}"
        except dymsum.MotionUndecided as e:
            back = f"undecided after t = {1 - e.t_safe:.6f}"
        disc = "—" if i >= len(disc_valid) else ("valid" if disc_valid[i] else "invalid")
        undecided_notes.append(f"motion {i}: certified free up to t = {t:.16g}; discrete validator: {disc}; checked from the other end: {back}")

    dym_kind = np.array([k for k, _ in dym])
    m = min(len(disc_valid), len(dym_kind))
    sampled_miss = np.flatnonzero(disc_valid[:m] & (dym_kind[:m] == "contact"))
    disc_stricter = np.flatnonzero(~disc_valid[:m] & (dym_kind[:m] == "free"))
    mv_ = min(len(val_free), len(dym_kind))
    val_mismatch = np.flatnonzero(val_free[:mv_] != (dym_kind[:mv_] == "free"))
    mc = min(len(ccd_res), len(dym_kind))
    ccd_hit = np.array([h for h, _ in ccd_res[:mc]], bool)
    # The rotation each motion turns by (the CCD holds the start's).
    turn = np.array([2 * math.acos(min(1.0, abs(float(np.dot(s0[i, 3:], s1[i, 3:]))))) for i in range(n)])
    out.update(
        discrete_done=len(disc_ns), discrete_us=median(disc_ns) / 1e3, discrete_valid=int(disc_valid.sum()),
        discrete_mean_us=float(np.mean(disc_ns)) / 1e3,
        validator_done=len(val_ns), validator_us=median(val_ns) / 1e3, validator_free=int(val_free.sum()),
        validator_mean_us=float(np.mean(val_ns)) / 1e3,
        dymsum_done=len(dym_ns), dymsum_us=median(dym_ns) / 1e3, dymsum_mean_us=float(np.mean(dym_ns)) / 1e3,
        dymsum_max_ms=max(dym_ns) / 1e6, dymsum_over_10ms=int(sum(t > 1e7 for t in dym_ns)),
        dymsum_free=int((dym_kind == "free").sum()), dymsum_contact=int((dym_kind == "contact").sum()),
        undecided=[int(i) for i in np.flatnonzero(dym_kind == "undecided")],
        ccd_done=len(ccd_ns), ccd_us=median(ccd_ns) / 1e3, ccd_collide=int(sum(h for h, _ in ccd_res)),
        ccd_only=int((ccd_hit & (dym_kind[:mc] != "contact")).sum()),
        dymsum_only_vs_ccd=int((~ccd_hit & (dym_kind[:mc] == "contact")).sum()),
        ccd_vs_trans=dict(
            both_contact=int(sum(h and f_ is False for h, f_ in zip(ccd_hit, trans_free))),
            ccd_only=int(sum(h and f_ is True for h, f_ in zip(ccd_hit, trans_free))),
            dymsum_only=int(sum((not h) and f_ is False for h, f_ in zip(ccd_hit, trans_free))),
            undecided=int(sum(f_ is None for f_ in trans_free)),
        ),
        undecided_notes=undecided_notes,
        sampling_misses=[int(i) for i in sampled_miss],
        sampling_miss_t=[float(dym[i][1]) for i in sampled_miss[:10]],
        discrete_stricter=[int(i) for i in disc_stricter],
        validator_mismatch=[int(i) for i in val_mismatch],
        median_turn_deg=float(np.degrees(np.median(turn))),
        recorded_discrete_valid=int(rec["discrete_valid"].sum()),
        recorded_vs_replayed=int((rec["discrete_valid"][: len(disc_valid)] != disc_valid).sum()),
    )
    return out


# ---------------------------------------------------------------- d. planning


def part_planning(p: Problem, checker: dymsum.MotionChecker, runs: int, cap: float, fcl_objects: Optional["Fcl"] = None) -> dict:
    seconds = min(p.time_limit or cap, cap)
    out: dict = {"limit": seconds}
    for which in ("dymsum", "fcl"):
        rows = []
        for _ in range(runs):
            r = app.plan(p, which, "RRTConnect", seconds, checker if which == "dymsum" else None)
            row = {k: r[k] for k in ("solved", "time", "state_checks", "motion_checks")}
            if r["solved"]:
                path = r["path"]
                bad, confirmed = 0, 0
                for x, y in zip(path, path[1:]):
                    try:
                        c = checker.check(x, y, 1e-6)
                    except dymsum.MotionUndecided:
                        bad += 1
                        continue
                    if not c.free:
                        bad += 1
                        confirmed += fcl_confirms(Fcl(p) if fcl_objects is None else fcl_objects, x, y, float(c.t_contact or 0.0))
                row["uncertified_motions"] = bad
                row["fcl_confirmed"] = confirmed
                row["length"] = r["length"]
            rows.append(row)
            log(f"  {which}: {'solved' if row['solved'] else 'not solved'} in {row['time']:.2f} s")
        out[which] = rows
    return out


# ---------------------------------------------------------------- driver


def guarded(results: dict, part: str, fn: Callable[[], dict]) -> None:
    t0 = time.perf_counter()
    try:
        results[part] = fn()
    except Exception as e:  # noqa: BLE001 - a failed part is reported, the rest goes on
        results[part] = {"error": f"{type(e).__name__}: {e}"}
        log(traceback.format_exc())
    results[part]["wall_s"] = time.perf_counter() - t0
    log(f"  {part} done in {results[part]['wall_s']:.1f} s")


def run_problem(cfg: pathlib.Path, args) -> dict:
    results: dict = {"cfg": cfg.name}
    try:
        p = load_problem(cfg)
    except Exception as e:  # noqa: BLE001
        results["error"] = f"{type(e).__name__}: {e}"
        return results
    p.name = cfg.stem  # the .cfg's file name (Apartment, not apartment_piano) names the rows and files
    results.update(
        name=p.name, robot_triangles=len(p.robot_faces), env_triangles=len(p.env_faces), time_limit=p.time_limit
    )
    checker = dymsum_checker(p)
    results["info"] = checker.info
    f = Fcl(p)
    parts = set(args.parts.split(","))
    if "build" in parts:
        guarded(results, "build", lambda: part_build(p))
    if "states" in parts:
        guarded(results, "states", lambda: part_states(p, checker, f, args.states, args.near, args.seed))
    if "motions" in parts:
        guarded(results, "motions", lambda: part_motions(p, checker, f, args))
    if "planning" in parts:
        guarded(results, "planning", lambda: part_planning(p, checker, args.runs, args.cap, f))
    return results


# ---------------------------------------------------------------- tables


def fmt(v, spec=".1f", none="—") -> str:
    if v is None:
        return none
    if isinstance(v, float) and not math.isfinite(v):
        return none
    return format(v, spec)


def ratio(a, b) -> str:
    if a is None or b is None or b == 0 or not math.isfinite(a / b):
        return "—"
    return f"{a / b:.1f}×"


def err(part: dict) -> Optional[str]:
    if not isinstance(part, dict) or not part:
        return "not run"
    return part.get("error")


def tables(rows: List[dict], header: str) -> str:
    out = [header, ""]
    ok = [r for r in rows if "error" not in r]
    for r in rows:
        if "error" in r:
            out.append(f"- {r['cfg']}: not read: {r['error']}")

    out += ["", "### a. Build time and memory", ""]
    out.append(
        "| problem | robot tris | env tris | dymsum build (ms) | fcl build (ms) | fcl/dymsum"
        " | dymsum RSS kept (MB) | dymsum RSS peak (MB) | fcl RSS kept (MB) | fcl RSS peak (MB) |"
    )
    out.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in ok:
        b = r.get("build", {})
        if err(b):
            out.append(f"| {r['name']} | {r['robot_triangles']} | {r['env_triangles']} | failed: {err(b)} | | | | | | |")
            continue
        out.append(
            f"| {r['name']} | {r['robot_triangles']} | {r['env_triangles']} | {fmt(b.get('dymsum_ms'), '.2f')} | {fmt(b.get('fcl_ms'), '.2f')}"
            f" | {ratio(b.get('fcl_ms'), b.get('dymsum_ms'))} | {fmt(b.get('dymsum_rss_mb'))} | {fmt(b.get('dymsum_peak_mb'))}"
            f" | {fmt(b.get('fcl_rss_mb'))} | {fmt(b.get('fcl_peak_mb'))} |"
        )

    out += ["", "### b. State checks, one call at a time from Python", ""]
    out.append(
        "| problem | states | colliding | dymsum `collides_at` (µs) | fcl `collide` (µs) | fcl/dymsum"
        " | dymsum p99 (µs) | fcl p99 (µs) | fcl/dymsum p99 | only dymsum collides | only fcl collides |"
    )
    out.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    notes = []
    for r in ok:
        s = r.get("states", {})
        if err(s):
            out.append(f"| {r['name']} | failed: {err(s)} | | | | | | | | | |")
            continue
        for kind, label in (("random", "random"), ("near", "near contact")):
            t = s.get(kind)
            if not t:
                continue
            # 99th percentiles: absent from files saved before they were.
            p99 = (t.get("dymsum_p99_us", math.nan), t.get("fcl_p99_us", math.nan))
            out.append(
                f"| {r['name']} | {t['n']} {label} | {t['colliding']} | {fmt(t['dymsum_us'])} | {fmt(t['fcl_us'])}"
                f" | {ratio(t['fcl_us'], t['dymsum_us'])} | {fmt(p99[0])} | {fmt(p99[1])} | {ratio(p99[1], p99[0])}"
                f" | {len(t['dymsum_only'])} | {len(t['fcl_only'])} |"
            )
            if t["dymsum_only"] or t["fcl_only"]:
                d = t.get("dymsum_only_fcl_distance") or []
                text = f"{r['name']}, {label} states: dymsum alone collides at {len(t['dymsum_only'])}"
                if d:
                    text += f" (fcl's distance there at most {max(d):.3g})"
                text += f", fcl alone at {len(t['fcl_only'])}"
                if "bisection_gap" in t:
                    text += f"; the two ends of a bisection are {t['bisection_gap']:.2g} apart (median)"
                notes.append(text)
    out += [f"- {n}" for n in notes]

    out += ["", "### c. Motion checks on the motions RRTConnect asked (fcl + DiscreteMotionValidator run)", ""]
    out.append(
        "| problem | asked (kept) | median turn | discrete `checkMotion` (µs) | fcl CCD default (µs) | dymsum `check` (µs)"
        " | dymsum validator (µs) | discrete/dymsum `check` | discrete/dymsum validator | dymsum free / contact / undecided"
        " | discrete valid, dymsum contact | discrete invalid, dymsum free | dymsum max (ms), >10 ms |"
    )
    out.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---|")
    ccd_rows = []
    mean_rows = []
    mnotes = []
    for r in ok:
        m = r.get("motions", {})
        if err(m):
            out.append(f"| {r['name']} | failed: {err(m)} | | | | | | | | | | | |")
            continue
        if not m.get("kept"):
            out.append(f"| {r['name']} | {m.get('asked', 0)} | | | | | | | | | | | |")
            continue
        done = {k: m[f"{k}_done"] for k in ("discrete", "ccd", "dymsum", "validator")}
        partial = "" if len(set(done.values())) == 1 and done["dymsum"] == m["kept"] else " (" + ", ".join(f"{k} {v}" for k, v in done.items()) + " done)"
        out.append(
            f"| {r['name']} | {m['asked']} ({m['kept']}){partial} | {m['median_turn_deg']:.0f}° | {fmt(m['discrete_us'])} | {fmt(m['ccd_us'])}"
            f" | {fmt(m['dymsum_us'])} | {fmt(m['validator_us'])} | {ratio(m['discrete_us'], m['dymsum_us'])}"
            f" | {ratio(m['discrete_us'], m['validator_us'])} | {m['dymsum_free']} / {m['dymsum_contact']} / {len(m['undecided'])}"
            f" | {len(m['sampling_misses'])} | {len(m['discrete_stricter'])} | {fmt(m['dymsum_max_ms'], '.2f')}, {m['dymsum_over_10ms']} |"
        )
        if "validator_mean_us" in m:
            mean_rows.append(
                f"| {r['name']} | {fmt(m['discrete_mean_us'])} | {fmt(m['validator_mean_us'])}"
                f" | {ratio(m['discrete_mean_us'], m['validator_mean_us'])} |"
            )
        v = m.get("ccd_vs_trans", {})
        ccd_rows.append(
            f"| {r['name']} | {m['ccd_done']} | {m['ccd_collide']} | {m['dymsum_contact']} | {m['ccd_only']} | {m['dymsum_only_vs_ccd']}"
            f" | {v.get('both_contact')} | {v.get('ccd_only')} | {v.get('dymsum_only')} | {v.get('undecided')} |"
        )
        if m.get("validator_mismatch"):
            mnotes.append(f"{r['name']}: dymsum's validator and `check` differ on motions {m['validator_mismatch'][:10]}")
        if m.get("recorded_vs_replayed"):
            mnotes.append(f"{r['name']}: the discrete validator answered {m['recorded_vs_replayed']} motions differently when replayed")
        acc = m.get("accepted")
        if acc:
            which = f"all {acc['n']}" if acc.get("done", acc["n"]) == acc["n"] else f"{acc['done']} (the time budget) of the {acc['n']}"
            text = f"{r['name']}: {which} motions the discrete validator accepted in the recording run: dymsum finds a contact in {acc['contact']}"
            if acc["contact"]:
                text += (
                    f" ({acc['fcl_confirmed']} confirmed by fcl's own `collide` at one of 1001 poses in [t_contact, t_contact + 0.01];"
                    f" first contacts at t = {', '.join(f'{t:.3f}' for t in acc['t_contact'])}{', …' if acc['contact'] > 10 else ''};"
                    f" motion lengths {', '.join(f'{x:.3g}' for x in acc['length'])})"
                )
            if acc["undecided"]:
                text += f", {acc['undecided']} undecided"
            mnotes.append(text)
        if m.get("sampling_misses"):
            mnotes.append(
                f"{r['name']}: {len(m['sampling_misses'])} motions accepted by the discrete validator touch the environment"
                f" (dymsum's first contact at t = {', '.join(f'{t:.3f}' for t in m['sampling_miss_t'])}{', …' if len(m['sampling_misses']) > 10 else ''})"
            )
        for note in m.get("undecided_notes", []):
            mnotes.append(f"{r['name']}: undecided (`MotionUndecided`) {note}")
        if m.get("discrete_stricter"):
            mnotes.append(f"{r['name']}: the discrete validator rejects motions dymsum certifies free: {m['discrete_stricter'][:10]}")
        if m.get("file"):
            mnotes.append(f"{r['name']}: motions saved to {m['file']} (RRTConnect {'solved' if m['record_solved'] else 'not solved'} in {m['record_time']:.1f} s)")
    out += [f"- {n}" for n in mnotes]
    if mean_rows:
        out += [
            "",
            "Means per motion (the same motions and calls; the free motions, which a certificate must cover whole,"
            " weigh more here than in the medians):",
            "",
            "| problem | discrete `checkMotion` mean (µs) | dymsum validator mean (µs) | discrete/dymsum validator |",
            "|---|---:|---:|---:|",
            *mean_rows,
        ]
    out += [
        "",
        "python-fcl's `continuousCollide` with `ContinuousCollisionRequest()` (conservative advancement, `CCDM_TRANS`:"
        " the translation only, at the start's rotation) against dymsum's `check` on the motion OMPL interpolates"
        " and on that translation-only motion:",
        "",
        "| problem | motions | CCD collides | dymsum contact (OMPL's motion) | CCD only | dymsum only"
        " | translation: both contact | translation: CCD only | translation: dymsum only | translation: undecided |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        *ccd_rows,
    ]

    out += ["", "### d. RRTConnect", ""]
    out.append(
        "| problem | limit (s) | dymsum solved | dymsum median (s) | dymsum state / motion checks | fcl solved | fcl median (s)"
        " | fcl state / motion checks | fcl paths certified free by dymsum |"
    )
    out.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in ok:
        d = r.get("planning", {})
        if err(d):
            out.append(f"| {r['name']} | failed: {err(d)} | | | | | | | |")
            continue
        cells = []
        for which in ("dymsum", "fcl"):
            runs = d[which]
            solved = [x for x in runs if x["solved"]]
            cells += [
                f"{len(solved)}/{len(runs)}",
                fmt(median(x["time"] for x in runs), ".2f"),
                f"{fmt(median(x['state_checks'] for x in runs), '.0f')} / {fmt(median(x['motion_checks'] for x in runs), '.0f')}",
            ]
        fsolved = [x for x in d["fcl"] if x["solved"]]
        certified = sum(x["uncertified_motions"] == 0 for x in fsolved)
        dsolved = [x for x in d["dymsum"] if x["solved"]]
        bad = sum(x["uncertified_motions"] > 0 for x in dsolved)
        uncert = sum(x["uncertified_motions"] for x in fsolved)
        conf = sum(x.get("fcl_confirmed", 0) for x in fsolved)
        text = f"{certified}/{len(fsolved)}"
        if uncert:
            text += f" ({uncert} motions with a contact, {conf} confirmed by fcl)"
        if bad:
            text += f" (dymsum's own: {bad} not)"
        cells.append(text)
        out.append(f"| {r['name']} | {d['limit']:g} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def header(args) -> str:
    import fcl

    try:
        from importlib.metadata import version

        ompl_version = version("ompl")
    except Exception:  # noqa: BLE001
        ompl_version = "?"
    build = ""
    try:
        so = pathlib.Path(dymsum._dymsum.__file__)
        build = f"; dymsum's extension built {time.strftime('%Y-%m-%d %H:%M', time.gmtime(so.stat().st_mtime))} UTC"
        head = subprocess.run(["git", "-C", str(HERE), "log", "-1", "--format=%h %cd", "--date=format:%Y-%m-%d %H:%M"], capture_output=True, text=True)
        if head.returncode == 0:
            build += f", repository at {head.stdout.strip()}"
    except Exception:  # noqa: BLE001
        pass
    return (
        f"## OMPL.app problems: dymsum {getattr(dymsum, '__version__', '')}{build}, against python-fcl {getattr(fcl, '__version__', '')}"
        f" and OMPL {ompl_version} (Python {platform.python_version()}, {platform.machine()}, {os.cpu_count()} CPUs)\n\n"
        f"`{' '.join(['bench_scenes.py'] + (args.argv if hasattr(args, 'argv') else []))}`: {args.states} random and {args.near} near-contact states,"
        f" at most {args.motions} recorded motions ({args.record_time:g} s RRTConnect run at most), {args.motion_budget:g} s per motion method,"
        f" {args.runs} planning runs with a cap of {args.cap:g} s. Times are medians of single calls from Python."
    )


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", nargs="?", default=DEFAULT_DIR, help=f"folder of OMPL.app .cfg files (default {DEFAULT_DIR})")
    parser.add_argument("--problems", help="comma-separated problem names (.cfg stems), in this order (default: all, smallest first)")
    parser.add_argument("--parts", default="build,states,motions,planning", help="which parts (default all)")
    parser.add_argument("--runs", type=int, default=5, help="planning runs per checker (default 5)")
    parser.add_argument("--cap", type=float, default=20.0, help="planning time limit cap, s (default 20; the .cfg's limit when lower)")
    parser.add_argument("--record-time", type=float, default=20.0, help="time limit of the recording RRTConnect run, s (default 20)")
    parser.add_argument("--states", type=int, default=2000, help="random states (default 2000)")
    parser.add_argument("--near", type=int, default=500, help="near-contact states (default 500)")
    parser.add_argument("--motions", type=int, default=2000, help="recorded motions kept (default 2000)")
    parser.add_argument("--motion-budget", type=float, default=60.0, help="seconds per motion-check method per problem (default 60)")
    parser.add_argument("--motions-dir", default=DEFAULT_MOTIONS_DIR, help=f"where the recorded motions go (default {DEFAULT_MOTIONS_DIR}; '' for nowhere)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the random states (default 1)")
    parser.add_argument("--save", help="append each problem's results to this JSON-lines file")
    parser.add_argument("--report", help="print the tables of a --save file and exit")
    args = parser.parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)

    if args.report:
        rows = [json.loads(line) for line in open(args.report, encoding="utf-8") if line.strip()]
        head = rows[0].get("header", "") if rows else ""
        print(tables([r for r in rows if "cfg" in r], head))
        return 0

    from ompl import util as ou

    ou.setLogLevel(ou.LOG_ERROR)
    folder = pathlib.Path(args.dir)
    if args.problems:
        cfgs = [folder / f"{name.strip()}.cfg" for name in args.problems.split(",") if name.strip()]
    else:
        from dymsum.omplapp import read_cfg

        def size(cfg):
            try:
                s = read_cfg(cfg)
                return sum((cfg.parent / s[f"problem.{k}"]).stat().st_size for k in ("robot", "world"))
            except Exception:  # noqa: BLE001
                return 0

        cfgs = sorted(folder.glob("*.cfg"), key=lambda c: (size(c), c.name))
    if not cfgs:
        parser.error(f"no .cfg in {folder}")
    head = header(args)
    if args.save:
        with open(args.save, "a", encoding="utf-8") as f:
            f.write(json.dumps({"header": head}) + "\n")
    rows = []
    for cfg in cfgs:
        log(f"{cfg.stem}:")
        t0 = time.perf_counter()
        r = run_problem(cfg, args)
        r["wall_s"] = time.perf_counter() - t0
        log(f"{cfg.stem}: {r['wall_s']:.1f} s")
        rows.append(r)
        if args.save:
            with open(args.save, "a", encoding="utf-8") as f:
                f.write(json.dumps(r, default=float) + "\n")
    print(tables(rows, head), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
