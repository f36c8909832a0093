"""Export OMPL.app's 3-D problems as OBJ files for the Rust bench
``scenes_vs_parry`` (their licence forbids shipping them with dymsum).

    python python/benchmarks/export_scenes.py /path/to/omplapp/resources/3D OUT
    DYMSUM_SCENES=OUT cargo bench -p dymsum-bench --bench scenes_vs_parry

Each problem ``NAME.cfg`` becomes ``OUT/NAME/{robot.obj, env.obj,
bounds.txt}``: the meshes exactly as ``dymsum.omplapp.load_problem``
loads them (every triangle kept, the robot centred as OMPL.app does) and
the state space's bounds (``lo_x lo_y lo_z hi_x hi_y hi_z``).
"""

import pathlib
import sys

import numpy as np

from dymsum import omplapp


def write_obj(path, vertices, faces):
    with open(path, "w") as fh:
        fh.writelines(f"v {float(a)!r} {float(b)!r} {float(c)!r}\n" for a, b, c in np.asarray(vertices, float))
        fh.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in np.asarray(faces))


def main(src, out):
    for cfg in sorted(pathlib.Path(src).glob("*.cfg")):
        try:
            p = omplapp.load_problem(cfg)
        except Exception as e:  # a problem whose meshes are missing
            print(f"{cfg.stem}: skipped ({e})", file=sys.stderr)
            continue
        d = pathlib.Path(out) / cfg.stem
        d.mkdir(parents=True, exist_ok=True)
        write_obj(d / "robot.obj", p.robot_vertices, p.robot_faces)
        write_obj(d / "env.obj", p.env_vertices, p.env_faces)
        lo, hi = p.bounds
        (d / "bounds.txt").write_text(" ".join(repr(float(x)) for x in [*lo, *hi]) + "\n")
        print(f"{cfg.stem}: {len(p.robot_faces)} + {len(p.env_faces)} triangles")


if __name__ == "__main__":
    main(*sys.argv[1:3])
