"""dymsum's certified motion validator against OMPL's DiscreteMotionValidator.

    pip install ./python ompl pytest scipy
    python python/benchmarks/bench_ompl.py [--motions N] [--repeats R] [--plans P]

On the scenes of ``python/examples/ompl_se2.py`` and ``ompl_se3.py`` (an
L-shaped body and walls 0.02 thick with openings), with the same exact
state check (``dymsum.ompl.StateChecker``) behind every validator:

* **per-motion cost**: ``SpaceInformation.checkMotion(s1, s2)`` over N
  random motions from valid start states (the random-motion workload of
  ``python/tests/test_ompl.py``: long motions with any turn, one in three
  crossing a wall along its thin axis with a small turn, half turns, and in
  SE(3) turns below OMPL's arc-length threshold), with dymsum's
  ``CertifiedMotionValidator``, with OMPL's ``DiscreteMotionValidator`` at
  its default resolution (states 1% of the space's extent apart), and at a
  fine one (0.1%: a step shorter than a wall is thick); the median over R
  repeats of the mean time per motion, and the mean number of exact state
  checks per motion;
* **misses**: how many of the motions that touch an obstacle each validator
  accepts, against the dense oracle of the tests (OMPL's interpolation at
  10⁵ instants, exact queries behind a conservative box prefilter);
* **planning**: P runs of the examples' planner (RRTConnect, 10 s limit,
  then OMPL's path simplification) with each validator: how many found a
  path, the median planning time, the median simplification time, and, of
  the simplified paths, how many touch an obstacle and how many of their
  motions do (the dense oracle), and how many motions dymsum's certified
  check does not certify free.

Prints markdown tables (docs/BENCHMARKS.md, "Motion validation against
OMPL"). OMPL's RNG is seeded once with ``--seed``; OMPL does not reseed
planners created later, so the P runs differ but the whole run repeats.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import pathlib
import platform
import statistics
import time

import numpy as np

import dymsum
import dymsum.ompl as dom

HERE = pathlib.Path(__file__).resolve().parent
os.environ.setdefault("DYMSUM_REQUIRE_OMPL", "1")


def load(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# The tests' OMPL helpers: the interpolation oracle, the random motions.
T = load(HERE.parent / "tests" / "test_ompl.py", "test_ompl")


def space_of(name, bounds):
    return T.se2_space(*bounds) if name == "ompl_se2" else T.se3_space(*bounds)


def workload(name, mod, n, seed):
    """N motions from valid start states: ``(v1, v2)`` value tuples."""
    robot, obstacles = mod.scene()
    space = space_of(name, mod.BOUNDS)
    si, v = T.certified_si(space, robot, obstacles)
    rng = np.random.default_rng(seed)
    a = space.allocState()
    out = []
    while len(out) < n:
        for v1, v2 in T.random_motions(v.state_checker.kind, rng, n, mod.BOUNDS, obstacles):
            if si.isValid(T.set_state(a, v1)):
                out.append((v1, v2))
    return out[:n]


def validators(name, mod):
    """``{label: (SpaceInformation, StateChecker)}``, each over its own
    space (OMPL keeps the checking resolution in the space)."""
    robot, obstacles = mod.scene()
    checker = dymsum.MotionChecker(robot, obstacles)
    out = {}
    si = T.ob.SpaceInformation(space_of(name, mod.BOUNDS))
    v = dom.setup_validators(si, checker)
    si.setup()
    out["dymsum certified"] = (si, v.state_checker)
    for label, resolution in (("OMPL discrete, 1% (default)", 0.01), ("OMPL discrete, 0.1%", 0.001)):
        si = T.ob.SpaceInformation(space_of(name, mod.BOUNDS))
        v = dom.setup_state_checker(si, checker)
        si.setStateValidityCheckingResolution(resolution)
        si.setup()
        assert si.getStateValidityCheckingResolution() == resolution
        out[label] = (si, v.state_checker)
    return out


def touching_motions(mod, motions, vals):
    """(N,) bool: the dense oracle finds a touching instant. Where dymsum
    rejects with a contact at ``t_contact``, the instants up to just past it
    are asked first (nothing before ``t_safe`` touches: the tests check it),
    and the whole motion only when none of them touches."""
    robot, obstacles = mod.scene()
    oracle = T.Oracle(robot, obstacles)
    si, _ = vals["dymsum certified"]
    mv = si.getMotionValidator()
    space = si.getStateSpace()
    out = []
    for v1, v2 in motions:
        r = mv.check(T.state(space, *v1), T.state(space, *v2))
        hit = False
        if r.t_contact is not None:
            hit = oracle.motion_hits(v1, v2, t_max=min(1.0, r.t_contact + 1e-3))[1].any()
        out.append(hit or oracle.motion_hits(v1, v2)[1].any())
    return np.array(out)


def per_motion(name, mod, motions, repeats):
    vals = validators(name, mod)
    t0 = time.perf_counter()
    touching = touching_motions(mod, motions, vals)
    oracle_s = time.perf_counter() - t0
    rows = {}
    for label, (si, sc) in vals.items():
        space = si.getStateSpace()
        states = [(T.state(space, *v1), T.state(space, *v2)) for v1, v2 in motions]
        verdicts = np.array([si.checkMotion(a, b) for a, b in states])
        checked0 = sc.checked
        times = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            for a, b in states:
                si.checkMotion(a, b)
            times.append((time.perf_counter() - t0) / len(states))
        checks = (sc.checked - checked0) / (repeats * len(states))
        rows[label] = {
            "us": statistics.median(times) * 1e6,
            "checks": checks,
            "accepted": int(verdicts.sum()),
            "misses": int((verdicts & touching).sum()),
            "below": int((~verdicts & ~touching).sum()),
        }
    return rows, int(touching.sum()), oracle_s


def plan_once(mod, discrete, seconds, oracle):
    """The examples' ``plan``, keeping the path: planning and
    simplification times, whether a path was found, its length, and its
    motions: how many, how many dymsum does not certify free, and how many
    the dense oracle finds touching."""
    ss, v = mod.simple_setup(discrete)
    solved = ss.solve(seconds)
    out = {"found": bool(solved) and ss.haveExactSolutionPath(), "time": ss.getLastPlanComputationTime()}
    if not out["found"]:
        return out
    t0 = time.perf_counter()
    ss.simplifySolution()
    out["simplify"] = time.perf_counter() - t0
    path = ss.getSolutionPath()
    values = [T.values_of(s) for s in path.getStates()]
    checks = dom.certified_path(ss, path, v.checker)
    out.update(
        length=path.length(),
        motions=len(checks),
        uncertified=sum(not c.free for c in checks),
        touching=sum(oracle.motion_hits(v1, v2)[1].any() for v1, v2 in zip(values, values[1:])),
    )
    return out


def planning(mod, plans, seconds):
    robot, obstacles = mod.scene()
    oracle = T.Oracle(robot, obstacles)
    rows = {}
    for label, discrete in (("dymsum certified", False), ("OMPL discrete, 1% (default)", True)):
        runs = [plan_once(mod, discrete, seconds, oracle) for _ in range(plans)]
        found = [r for r in runs if r["found"]]
        nan = float("nan")
        rows[label] = {
            "found": len(found),
            "time": statistics.median(r["time"] for r in runs),
            "simplify": statistics.median(r["simplify"] for r in found) if found else nan,
            "length": statistics.median(r["length"] for r in found) if found else nan,
            "paths touching": sum(r["touching"] > 0 for r in found),
            "motions": sum(r["motions"] for r in found),
            "touching": sum(r["touching"] for r in found),
            "uncertified": sum(r["uncertified"] for r in found),
        }
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--motions", type=int, default=1000)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--plans", type=int, default=20)
    ap.add_argument("--seconds", type=float, default=10.0, help="planning time limit per run")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    from ompl import util as ou

    ou.setLogLevel(ou.LOG_ERROR)
    ou.RNG.setSeed(args.seed)
    from importlib.metadata import version

    print(
        f"# {platform.node()} {platform.processor()} python {platform.python_version()} "
        f"OMPL {version('ompl')} numpy {np.__version__}; "
        f"{args.motions} motions, {args.repeats} repeats, {args.plans} plans"
    )
    examples = HERE.parent / "examples"
    scenes = [(n, load(examples / f"{n}.py", n)) for n in ("ompl_se2", "ompl_se3")]

    print()
    print("Per motion (`SpaceInformation.checkMotion`), the same exact state check behind each:")
    print()
    print("| scene | validator | µs per motion | ÷ dymsum | state checks per motion | accepted | touching motions accepted | rejected, no touching instant sampled |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    notes = []
    for name, mod in scenes:
        motions = workload(name, mod, args.motions, 20 if name == "ompl_se2" else 21)
        rows, touching, oracle_s = per_motion(name, mod, motions, args.repeats)
        base = rows["dymsum certified"]["us"]
        scene = f"{'SE(2)' if name == 'ompl_se2' else 'SE(3)'} ({touching}/{len(motions)} touch)"
        for label, r in rows.items():
            print(
                f"| {scene} | {label} | {r['us']:.1f} | {r['us'] / base:.2f} | {r['checks']:.1f} | "
                f"{r['accepted']} | {r['misses']} | {r['below']} |"
            )
        notes.append(f"{name}: the dense oracle took {oracle_s:.1f} s for {len(motions)} motions")
    print()
    for note in notes:
        print(note)

    print()
    print(f"Planning ({args.plans} runs of RRTConnect, {args.seconds:g} s limit, then simplification):")
    print()
    print(
        "| scene | validator | paths found | median planning s | ÷ dymsum | median simplification s | median length "
        "| paths touching an obstacle | their motions touching (dense oracle) | motions not certified by dymsum |"
    )
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, mod in scenes:
        rows = planning(mod, args.plans, args.seconds)
        base = rows["dymsum certified"]["time"]
        scene = "SE(2)" if name == "ompl_se2" else "SE(3)"
        for label, r in rows.items():
            print(
                f"| {scene} | {label} | {r['found']}/{args.plans} | {r['time']:.3f} | {r['time'] / base:.2f} | "
                f"{r['simplify']:.3f} | {r['length']:.2f} | {r['paths touching']} | "
                f"{r['touching']}/{r['motions']} | {r['uncertified']} |"
            )


if __name__ == "__main__":
    main()
