"""What a mesh encloses (issue 33 §1, §3), from Python.

A mesh body is the set of points on its triangles together with the points
of non-zero winding number of its enclosing part: touching solids enclose,
a cavity is outside, T-junctions and fins do not open a closed box. Each
case is judged by an oracle written from the boxes the mesh was made of
(closed-interval tests, exact on these dyadic coordinates), in both roles
(the mesh as the obstacle and as the moving body), and by the command
line (`dymsum query --collision-only`), which must answer the same.
"""

import subprocess

import numpy as np

import dymsum
from conftest import cli

QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]


def corners(lo, hi):
    return [[hi[k] if (i >> k) & 1 else lo[k] for k in range(3)] for i in range(8)]


def boxes(cells, outward=None):
    """Closed boxes in one mesh, each with its own corners (identical
    coordinates merge when cleaned); ``outward[i]`` False: an inward shell."""
    outward = outward or [True] * len(cells)
    v, f = [], []
    for (lo, hi), out in zip(cells, outward):
        base = len(v)
        v.extend(corners(lo, hi))
        for q in QUADS:
            q = [base + i for i in q]
            for t in ([q[0], q[1], q[2]], [q[0], q[2], q[3]]):
                f.append(t if out else t[::-1])
    return np.array(v, float), np.array(f, np.int64)


def cube(h):
    return boxes([([-h] * 3, [h] * 3)])


def meets(a, b):
    return all(a[0][k] <= b[1][k] and b[0][k] <= a[1][k] for k in range(3))


def holds_strictly(a, b):
    return all(a[0][k] < b[0][k] and b[1][k] < a[1][k] for k in range(3))


def around(c, h):
    return ([x - h for x in c], [x + h for x in c])


def collides(mesh, c, h):
    """Both roles; they must agree."""
    as_obstacle = dymsum.MotionChecker(cube(h), [mesh]).collides_at(dymsum.pose(translation=c))
    as_body = dymsum.MotionChecker(mesh, [cube(h)]).collides_at(dymsum.pose(translation=[-x for x in c]))
    assert as_obstacle == as_body, (c, h)
    return as_obstacle


UNIT = ([0.0] * 3, [1.0] * 3)


def test_boxes_sharing_a_face_an_edge_or_a_corner_enclose():
    for other in [([1.0, 0, 0], [2.0, 1, 1]), ([1.0, 1, 0], [2.0, 2, 1]), ([1.0] * 3, [2.0] * 3)]:
        cells = [UNIT, other]
        mesh = boxes(cells)
        for c in ([0.5] * 3, [1.5, 0.5, 0.5], [1.5, 1.5, 0.5], [1.5] * 3, [3.0] * 3):
            assert collides(mesh, c, 0.125) == any(meets(b, around(c, 0.125)) for b in cells), (other, c)
        # Two closed, exactly convex shells: their union, on the convex
        # path (one ladder for Python and the command line, issue 34).
        assert dymsum.MotionChecker(cube(0.1), [mesh]).info["path"] == "convex"


def test_a_cavity_is_outside_and_a_box_inside_it_is_not():
    outer, cavity = ([0.0] * 3, [4.0] * 3), ([1.0] * 3, [3.0] * 3)
    inner = ([1.0, 1.5, 1.5], [1.5, 2.5, 2.5])
    for cells, outward in [([outer, cavity], [True, False]), ([outer, cavity, inner], [True, False, True])]:
        mesh = boxes(cells, outward)
        for c, h in [([2.0] * 3, 0.25), ([1.25, 2, 2], 0.25), ([1.25, 2, 2], 0.125), ([0.5, 2, 2], 0.25), ([2.5, 2, 2], 0.25)]:
            p = around(c, h)
            expected = (meets(outer, p) and not holds_strictly(cavity, p)) or (len(cells) == 3 and meets(inner, p))
            assert collides(mesh, c, h) == expected, (len(cells), c, h)
        info = dymsum.MotionChecker(cube(0.1), [mesh]).info["obstacles"]
        assert info["flipped"] == 0 and not info["inverted"]


def t_junction_box(fill):
    v = corners([0.0] * 3, [2.0, 1.0, 1.0]) + [[1.0, 0.0, 1.0]]
    f = [q for q in QUADS if q != [4, 5, 7, 6]] + [[4, 8, 6], [8, 7, 6], [8, 5, 7]] + ([[4, 5, 8]] if fill else [])
    return np.array(v, float), f


def test_t_junctions_and_fins_keep_the_inside():
    for fill in (False, True):
        mesh = t_junction_box(fill)
        assert collides(mesh, [1.0, 0.5, 0.5], 0.25)
        assert not collides(mesh, [3.0, 0.5, 0.5], 0.25)
    v, f = boxes([UNIT])
    fin = (np.vstack([v, [[0.5, -1.0, 1.5]]]), np.vstack([f, [[4, 5, 8]]]))
    assert collides(fin, [0.5] * 3, 0.25)
    assert not collides(fin, [0.5, -0.5, 2.0], 0.1)
    info = dymsum.MotionChecker(cube(0.1), [fin]).info["obstacles"]
    assert (info["solids"], info["surfaces"], info["set_aside"]) == (1, 1, 1)


def test_inward_input_is_turned_and_reported():
    mesh = boxes([UNIT, ([1.0, 0, 0], [2.0, 1, 1])], [False, False])
    assert collides(mesh, [0.5] * 3, 0.25)
    assert dymsum.MotionChecker(cube(0.1), [mesh]).info["obstacles"]["inverted"]


def test_a_random_grid_union_against_its_boxes():
    rng = np.random.default_rng(33)
    for _ in range(6):
        cells = []
        for _ in range(rng.integers(1, 5)):
            lo = rng.integers(0, 4, 3).astype(float)
            cells.append((lo.tolist(), (lo + rng.integers(1, 3, 3)).tolist()))
        mesh = boxes(cells)
        for _ in range(10):
            c = (rng.integers(-2, 48, 3) / 8 + 1 / 16).tolist()
            h = 1 / 16 if rng.integers(2) else 1 / 32
            assert collides(mesh, c, h) == any(meets(b, around(c, h)) for b in cells), (cells, c, h)


def write_off(path, mesh):
    v, f = mesh
    lines = ["OFF", f"{len(v)} {len(f)} 0"]
    lines += [" ".join(repr(float(x)) for x in p) for p in np.asarray(v)]
    lines += [f"{len(face)} " + " ".join(str(int(i)) for i in face) for face in f]
    path.write_text("\n".join(lines) + "\n")


def test_python_and_the_command_line_answer_alike(tmp_path):
    exe = cli()
    v, f = boxes([([0.0] * 3, [2.0] * 3)])
    dent_v = np.vstack([v, [[1.0, 1.0, 2.0 - 1e-6]]])
    top = [t for t in f.tolist() if not all(v[i][2] == 2.0 for i in t)]
    dented = (dent_v, top + [[4, 5, 8], [5, 7, 8], [7, 6, 8], [6, 4, 8]])
    family = {
        "touching": boxes([([0.0] * 3, [2.0] * 3), ([2.0, 0, 0], [4.0, 2, 2])]),
        "cavity": boxes([([0.0] * 3, [4.0] * 3), ([1.0] * 3, [3.0] * 3)], [True, False]),
        "t_junction": t_junction_box(False),
        "dented": dented,
    }
    probes = [[1.0, 1.0, 1.0], [3.0, 1.0, 1.0], [2.0, 2.0, 2.0], [0.5, 2.0, 2.0], [1.0, 1.0, 2.125 - 0.5e-6]]
    robot = dymsum.load("box:0.25")
    for name, mesh in family.items():
        path = tmp_path / f"{name}.off"
        write_off(path, mesh)
        args = [exe, "query", "box:0.25", str(path), "--collision-only"]
        for p in probes:
            args += ["--pose-xyz-wxyz", ",".join(repr(x) for x in p) + ",1,0,0,0"]
        out = subprocess.run(args, check=True, capture_output=True, text=True)
        by_cli = [line.endswith(": collides") for line in out.stdout.splitlines()]
        for door in (mesh, str(path)):  # arrays and the file itself
            checker = dymsum.MotionChecker(robot, [door])
            by_python = [checker.collides_at(dymsum.pose(translation=p)) for p in probes]
            assert by_python == by_cli, (name, door is mesh)
    # The probe in the dent is free: nothing replaced the dented box by its hull.
    assert not dymsum.MotionChecker(robot, [dented]).collides_at(dymsum.pose(translation=probes[-1]))
