"""One mesh, one answer, whichever door it comes in by (issues 33 §3 and
34), from Python: the mesh files of the three-front-door test
(crates/dymsum-cli/tests/front_doors.rs reads them into Rust's ladder, the
one loader and the command line) given to ``MotionChecker`` as paths and as
``(vertices, faces)`` arrays take the same path as the command line takes
them (convex pieces or triangles, the same cleaning counts) and give the
same answers as ``dymsum query --collision-only``.
"""

import subprocess
from pathlib import Path

import numpy as np

import dymsum
from conftest import cli

FAMILY = Path(__file__).resolve().parents[2] / "crates" / "dymsum-cli" / "tests" / "fixtures" / "front_doors"

# The files, and whether each is taken as convex pieces (the rest: triangles).
CONVEX = {
    "touching.off": True,
    "cavity.off": False,
    "t_junction.off": True,
    "fin.off": False,
    "open.off": False,
    "inward.off": False,
    "dented.off": False,
    "objects.obj": True,
    "lidless_objects.obj": False,
}

PROBES = [
    [1.0, 1.0, 1.0],
    [3.0, 1.0, 1.0],
    [2.0, 2.0, 2.0],
    [0.5, 2.0, 2.0],
    [5.0, 1.0, 1.0],
    [1.0, -1.0, 2.5],
    [1.0, 1.0, 2.125],
    [1.0, 1.0, 2.125 - 0.5e-6],
]


def read_arrays(path):
    """The file as one (vertices, faces) mesh (OFF, or OBJ's `v` and `f`
    lines), faces as given (quads and triangles)."""
    lines = path.read_text().splitlines()
    if path.suffix == ".off":
        nv, nf = (int(x) for x in lines[1].split()[:2])
        v = [[float(x) for x in line.split()] for line in lines[2 : 2 + nv]]
        f = [[int(x) for x in line.split()[1:]] for line in lines[2 + nv : 2 + nv + nf]]
    else:
        v = [[float(x) for x in line.split()[1:]] for line in lines if line.startswith("v ")]
        f = [[int(x) - 1 for x in line.split()[1:]] for line in lines if line.startswith("f ")]
    return np.array(v, float), f


def test_paths_and_arrays_take_the_family_as_the_command_line_does():
    exe = cli()
    robot = dymsum.load("box:0.25")
    assert sorted(p.name for p in FAMILY.iterdir()) == sorted(CONVEX)
    for name, convex in CONVEX.items():
        path = FAMILY / name
        args = [exe, "query", "box:0.25", str(path), "--collision-only"]
        for p in PROBES:
            args += ["--pose-xyz-wxyz", ",".join(repr(x) for x in p) + ",1,0,0,0"]
        out = subprocess.run(args, check=True, capture_output=True, text=True)
        by_cli = [line.endswith(": collides") for line in out.stdout.splitlines()]
        assert len(by_cli) == len(PROBES), (name, out.stdout)
        for door in (str(path), path, read_arrays(path)):
            checker = dymsum.MotionChecker(robot, [door])
            info = checker.info
            assert (info["path"] == "convex") == convex, (name, type(door), info)
            if not convex:
                # The command line's note counts the same triangles.
                assert f", {info['obstacles']['triangles']} triangles" in out.stderr, (name, out.stderr)
            by_python = [checker.collides_at(dymsum.pose(translation=p)) for p in PROBES]
            assert by_python == by_cli, (name, type(door))
