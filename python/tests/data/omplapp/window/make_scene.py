"""Writes the `window` test scene: COLLADA files laid out as SketchUp 8
writes them (the exporter of OMPL.app's problems), a .cfg and a .path.

    python make_scene.py [OUT_DIR]      # default: this file's folder

Numbers are designed in the frame OMPL.app works in (Assimp's, after it
turns a Z_UP file to Y up) and written in the file's own frame, through the
node matrices and the inverse of Assimp's up-axis turn, so a loader that
gets any of those steps wrong puts the geometry elsewhere. The .path is
written by `make_path` against the robot centre that libassimp 5.2.5 gives
(`CENTRE` below: what OMPL.app subtracts); each state was checked free with
python-fcl (test_omplapp.py checks it again).
"""

import math
import pathlib
import sys

import numpy as np

# Assimp turns Z_UP files by (x, y, z) -> (x, z, -y); the file holds the inverse.
TO_FILE = np.array([[1.0, 0, 0], [0, 0, -1.0], [0, 1.0, 0]])

# OMPL.app's robot centre for window_robot.dae, from libassimp 5.2.5
# (JoinIdenticalVertices, every mesh's vertices incl. the edge lines, float32).
CENTRE = (0.352499604, 0.157499984, 0.0224998482)


def rot_z(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    m = np.eye(4)
    m[:2, :2] = [[c, -s], [s, c]]
    return m


def translate(t):
    m = np.eye(4)
    m[:3, 3] = t
    return m


def box_faces(lo, hi):
    """The 6 faces of a box as (4 corners counter-clockwise seen from outside, normal)."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = lambda i, j, k: ((x0, x1)[i], (y0, y1)[j], (z0, z1)[k])  # noqa: E731
    return [
        ([c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)], (0, 0, -1)),
        ([c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)], (0, 0, 1)),
        ([c(0, 0, 0), c(1, 0, 0), c(1, 0, 1), c(0, 0, 1)], (0, -1, 0)),
        ([c(0, 1, 0), c(0, 1, 1), c(1, 1, 1), c(1, 1, 0)], (0, 1, 0)),
        ([c(0, 0, 0), c(0, 0, 1), c(0, 1, 1), c(0, 1, 0)], (-1, 0, 0)),
        ([c(1, 0, 0), c(1, 1, 0), c(1, 1, 1), c(1, 0, 1)], (1, 0, 0)),
    ]


def fmt(values):
    return " ".join("%.7f" % v for v in np.asarray(values, dtype=float).ravel())


def geometry_xml(gid, boxes, to_file, double_sided, edges=True):
    """One <geometry> with SketchUp's layout: a position and a normal source
    (each face's corners written again with its normal), <vertices> joining
    them, <triangles> (the back faces again, reversed, when double-sided)
    and <lines> for the box edges."""
    pos, nor, tris, lines = [], [], [], []
    for lo, hi in boxes:
        for corners, normal in box_faces(lo, hi):
            for sign in (1, -1) if double_sided else (1,):
                base = len(pos)
                n = np.asarray(normal, float) * sign
                for p in corners:
                    pos.append(to_file[:3, :3] @ np.asarray(p, float) + to_file[:3, 3])
                    nor.append(to_file[:3, :3] @ n)
                quad = [base, base + 1, base + 2, base + 3] if sign > 0 else [base, base + 3, base + 2, base + 1]
                tris += [quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]]
        # the 12 edges, over the front corners of the first and second faces
        first = len(pos) - (6 * (2 if double_sided else 1)) * 4
        bottom = [first + i for i in range(4)]
        top = [first + (8 if double_sided else 4) + i for i in (0, 3, 2, 1)]
        for i in range(4 if edges else 0):
            lines += [bottom[i], bottom[(i + 1) % 4], top[i], top[(i + 1) % 4], bottom[i], top[i]]
    n = len(pos)
    return f"""        <geometry id="{gid}">
            <mesh>
                <source id="{gid}-pos">
                    <float_array id="{gid}-pos-a" count="{3 * n}">{fmt(pos)}</float_array>
                    <technique_common>
                        <accessor count="{n}" source="#{gid}-pos-a" stride="3">
                            <param name="X" type="float" />
                            <param name="Y" type="float" />
                            <param name="Z" type="float" />
                        </accessor>
                    </technique_common>
                </source>
                <source id="{gid}-nor">
                    <float_array id="{gid}-nor-a" count="{3 * n}">{fmt(nor)}</float_array>
                    <technique_common>
                        <accessor count="{n}" source="#{gid}-nor-a" stride="3">
                            <param name="X" type="float" />
                            <param name="Y" type="float" />
                            <param name="Z" type="float" />
                        </accessor>
                    </technique_common>
                </source>
                <vertices id="{gid}-vtx">
                    <input semantic="POSITION" source="#{gid}-pos" />
                    <input semantic="NORMAL" source="#{gid}-nor" />
                </vertices>
                <triangles count="{len(tris) // 3}" material="Material2">
                    <input offset="0" semantic="VERTEX" source="#{gid}-vtx" />
                    <p>{" ".join(map(str, tris))}</p>
                </triangles>
{lines_xml(gid, lines)}            </mesh>
        </geometry>
"""


def lines_xml(gid, lines):
    if not lines:
        return ""
    return f"""                <lines count="{len(lines) // 2}" material="Material3">
                    <input offset="0" semantic="VERTEX" source="#{gid}-vtx" />
                    <p>{" ".join(map(str, lines))}</p>
                </lines>
"""


BIND = """<bind_material>
                            <technique_common>
                                <instance_material symbol="Material2" target="#M1" />
                                <instance_material symbol="Material3" target="#M2" />
                            </technique_common>
                        </bind_material>"""

TAIL = """    <library_materials>
        <material id="M1" name="material_0"><instance_effect url="#E1" /></material>
        <material id="M2" name="edge_color000255"><instance_effect url="#E2" /></material>
    </library_materials>
    <library_effects>
        <effect id="E1"><profile_COMMON><technique sid="COMMON"><lambert><diffuse><color>0.6 0.6 0.6 1</color></diffuse></lambert></technique></profile_COMMON></effect>
        <effect id="E2"><profile_COMMON><technique sid="COMMON"><constant><transparent opaque="A_ONE"><color>0 0 0 1</color></transparent><transparency><float>1</float></transparency></constant></technique></profile_COMMON></effect>
    </library_effects>
    <scene>
        <instance_visual_scene url="#VS" />
    </scene>
</COLLADA>
"""


def head(extra_asset=""):
    return f"""<?xml version="1.0" encoding="UTF-8" standalone="no" ?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
    <asset>
        <contributor>
            <authoring_tool>dymsum make_scene.py (SketchUp 8 layout)</authoring_tool>
        </contributor>
        <created>2026-01-01T00:00:00Z</created>
        <modified>2026-01-01T00:00:00Z</modified>{extra_asset}
        <up_axis>Z_UP</up_axis>
    </asset>
"""


def matrix_xml(m):
    return f"<matrix>{fmt(m)}</matrix>"


# ---------------------------------------------------------------------------
# The scene, in OMPL.app's frame: a wall 0.5 thick (y in [0, 0.5]) over
# x, z in [-5, 5] with a square window x, z in [-0.575, 0.575]; the robot a rod
# 3 long (x) with a square section 0.8 and a knob 0.25 high on one end, which
# passes the window only turned end-on.

HOLE = 0.575
WALL = [  # (lo, hi) in the world
    ((-5.0, 0.0, -5.0), (-HOLE, 0.5, 5.0)),
    ((HOLE, 0.0, -5.0), (5.0, 0.5, 5.0)),
    ((-HOLE, 0.0, -5.0), (HOLE, 0.5, -HOLE)),
    ((-HOLE, 0.0, HOLE), (HOLE, 0.5, 5.0)),
]
ROD = ((-1.5, -0.4, -0.4), (1.5, 0.4, 0.4))
KNOB = ((1.0, 0.4, -0.1), (1.35, 0.65, 0.25))  # on the rod's +y side near its +x end
ENV_NODE = translate((2.0, -3.0, 1.0)) @ rot_z(30.0)  # the env group's <matrix> (file frame)
ROBOT_NODE = translate((7.0, 5.0, -2.0)) @ rot_z(-75.0)
KNOB_NODE = translate((0.5, 0.25, 0.0))  # the knob's <instance_node> matrix, inside ROBOT_NODE


def world_to_local(node):
    """file-local coordinates of a world point: inverse node matrix after the inverse up turn."""
    m = np.eye(4)
    m[:3, :3] = TO_FILE
    return np.linalg.inv(node) @ m


def env_xml():
    local = world_to_local(ENV_NODE)
    # the two side slabs are one geometry (a slab from the origin) placed
    # twice by <instance_node>s, at the file-local image of their low corner
    size = tuple(np.array(WALL[0][1]) - np.array(WALL[0][0]))
    slab = [((0.0, 0.0, 0.0), size)]
    slab_local = np.eye(4)
    slab_local[:3, :3] = local[:3, :3]
    nodes = "".join(
        f"""
                <node id="side{i}" name="instance_{i}">
                    {matrix_xml(translate((local @ np.array([*lo, 1.0]))[:3]))}
                    <instance_node url="#slab" />
                </node>"""
        for i, (lo, _) in enumerate(WALL[:2])
    )
    return (
        head()
        + f"""    <library_visual_scenes>
        <visual_scene id="VS">
            <node name="SketchUp">
                <node id="wall" name="group_0">
                    {matrix_xml(ENV_NODE)}
                    <instance_geometry url="#beams">
                        {BIND}
                    </instance_geometry>{nodes}
                </node>
            </node>
        </visual_scene>
    </library_visual_scenes>
    <library_nodes>
        <node id="slab" name="skp_slab">
            <instance_geometry url="#slabgeo">
                {BIND}
            </instance_geometry>
        </node>
    </library_nodes>
    <library_geometries>
"""
        + geometry_xml("beams", WALL[2:], local, double_sided=True)
        + geometry_xml("slabgeo", slab, slab_local, double_sided=True)
        + "    </library_geometries>\n"
        + TAIL
    )


def robot_xml():
    local = world_to_local(ROBOT_NODE)
    knob_local = np.linalg.inv(KNOB_NODE) @ local
    return (
        head()
        + f"""    <library_visual_scenes>
        <visual_scene id="VS">
            <node name="SketchUp">
                <node id="robot" name="instance_0">
                    {matrix_xml(ROBOT_NODE)}
                    <instance_geometry url="#rod">
                        {BIND}
                    </instance_geometry>
                    <node id="knobplace" name="instance_1">
                        {matrix_xml(KNOB_NODE)}
                        <instance_node url="#knob" />
                    </node>
                </node>
            </node>
        </visual_scene>
    </library_visual_scenes>
    <library_nodes>
        <node id="knob" name="skp_knob">
            <instance_geometry url="#knobgeo">
                {BIND}
            </instance_geometry>
        </node>
    </library_nodes>
    <library_geometries>
"""
        + geometry_xml("rod", [ROD], local, double_sided=True)
        + geometry_xml("knobgeo", [KNOB], knob_local, double_sided=False, edges=False)
        + "    </library_geometries>\n"
        + TAIL
    )


CFG = """[problem]
name = window
robot = window_robot.dae
world = window_env.dae
{start}
{goal}
volume.min.x = -6.0
volume.min.y = -6.0
volume.min.z = -6.0
volume.max.x = 6.0
volume.max.y = 6.0
volume.max.z = 6.0

[benchmark]
time_limit=10.0
mem_limit=1000.0
run_count=10

[planner]
rrtconnect=
"""


def make_path(centre):
    """States (x y z qx qy qz qw): in front of the wall the rod turns end-on
    (90 degrees about z), passes the window, and behind the wall turns half
    a turn about its own y axis (the goal).
    The translation is that of the robot's frame, whose origin is OMPL.app's
    centre: it is placed so that the middle of the rod and knob's section
    (designed (0, 0.125, 0)) goes through the window's middle, 0.05 from
    the window's sides (0.175 from its top and bottom)."""
    states = []
    off = np.array([0.0, 0.125, 0.0]) - np.asarray(centre, float)  # in the centred frame

    def add(y, yaw, roll):
        # rotation: yaw about z, then roll about the (turned) y axis
        qz = (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
        qy = (0.0, math.sin(roll / 2), 0.0, math.cos(roll / 2))
        x1, y1, z1, w1 = qz
        x2, y2, z2, w2 = qy
        q = (w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
             w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2)
        r = quat_matrix(q)
        t = np.array([0.0, y, 0.0]) - r @ off
        states.append((*t, *q))

    for i in range(11):  # turn end-on at y = 3
        add(3.0, math.pi / 2 * i / 10, 0.0)
    for i in range(1, 25):  # through the window
        add(3.0 - 6.0 * i / 24, math.pi / 2, 0.0)
    for i in range(1, 11):  # turn about y behind the wall
        add(-3.0, math.pi / 2, math.pi * i / 10)
    return states


def quat_matrix(q):
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def cfg_state(which, state):
    """A state as .cfg lines: position, axis and angle (OMPL's setAxisAngle)."""
    x, y, z, qx, qy, qz, qw = state
    theta = 2.0 * math.atan2(math.sqrt(qx * qx + qy * qy + qz * qz), qw)
    n = math.sqrt(qx * qx + qy * qy + qz * qz)
    axis = (qx / n, qy / n, qz / n) if n > 0 else (1.0, 0.0, 0.0)
    g = lambda v: "%.10g" % (float(v) + 0.0)  # noqa: E731
    lines = [f"{which}.x = {g(x)}", f"{which}.y = {g(y)}", f"{which}.z = {g(z)}", f"{which}.theta = {g(theta)}"]
    lines += [f"{which}.axis.{a} = {g(v)}" for a, v in zip("xyz", axis)]
    return "\n".join(lines)


def main(out):
    out = pathlib.Path(out)
    (out / "window_env.dae").write_text(env_xml())
    (out / "window_robot.dae").write_text(robot_xml())
    if CENTRE is not None:
        states = make_path(CENTRE)
        (out / "window.cfg").write_text(CFG.format(start=cfg_state("start", states[0]), goal=cfg_state("goal", states[-1])))
        (out / "window.path").write_text("".join(" ".join("%.10g" % (float(v) + 0.0) for v in s) + "\n" for s in states))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent)
