"""A tour of dymsum from Python, notebook style: run it cell by cell or whole.

    pip install ./python          # from the repository root
    python python/examples/tour.py [OUTPUT_DIR]

Writes sum.off (and depth.png if matplotlib is installed) to OUTPUT_DIR,
created if missing (default: a fresh temporary folder, printed at the end);
nothing is written anywhere else.
"""

# %% Setup
import os
import sys
import tempfile
import time

import numpy as np

import dymsum

out = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="dymsum-tour-")
os.makedirs(out, exist_ok=True)
rng = np.random.default_rng(7)

# %% 1. Shapes: a point cloud (its exact hull), a built-in model, a mesh
cloud = rng.normal(size=(300, 3)) * [2.0, 1.0, 0.5]
ellipse = dymsum.load("ellipse")  # the paper's ellipsoid, 960 triangles
rock = dymsum.Polytope(cloud)  # parse and hull once, reuse everywhere
print(rock)
print("rock's convexity report:", rock.convexity_report)

# %% 2. Sum two shapes and save the result
# Poses are 4×4 homogeneous matrices; dymsum.pose builds one from a
# quaternion in scipy's (x, y, z, w) order and a translation.
turn = dymsum.pose([0.0, 0.0, np.sin(np.pi / 8), np.cos(np.pi / 8)], [0.0, 0.0, 1.0])
vertices, faces = dymsum.minkowski_sum(rock, ellipse, pose_a=turn)
print(f"rock ⊕ ellipse: {len(vertices)} vertices, {len(faces)} triangles")
path = os.path.join(out, "sum.off")
dymsum.save(path, vertices, faces)
print("wrote", path, "- volume", dymsum.load(path).volume)

# Merged polygon faces instead of triangles:
_, polygons = dymsum.minkowski_sum(rock, ellipse, pose_a=turn, polygons=True)
print(f"{len(polygons)} merged faces, the largest with {max(len(p) for p in polygons)} corners")

# %% 3. A rotating motion: DYMSUM keeps the sum up to date
dyn = dymsum.DynamicSum(rock, ellipse)
t0 = time.perf_counter()
for k in range(1, 501):
    angle = 2 * np.pi * k / 500
    report = dyn.update(dymsum.pose([0.0, np.sin(angle / 2), 0.0, np.cos(angle / 2)]))
dt = time.perf_counter() - t0
print(f"500 DYMSUM updates in {dt * 1e3:.1f} ms; last step repaired {report['errors']} errors, "
      f"{report['removed']} facets out, {report['added']} in, {dyn.facet_count} facets")

# %% 4. Track the contact of two bodies over a motion
# The rock spins and passes through the ellipsoid and out again.
tracker = dymsum.ContactTracker(rock, ellipse)
times = np.linspace(0.0, 1.0, 400)
depth, distance = [], []
for t in times:
    spin = [np.sin(2 * t), 0.0, 0.0, np.cos(2 * t)]  # (x, y, z, w)
    c = tracker.update(dymsum.pose(spin, [20.0 * t - 10.0, 0.5, 0.0]))
    depth.append(c.depth)
    distance.append(c.distance)
deepest = int(np.argmax(depth))
print(f"deepest penetration {depth[deepest]:.3f} at t = {times[deepest]:.3f}")
c = dymsum.contact(rock, ellipse, dymsum.pose([np.sin(2 * times[deepest]), 0, 0, np.cos(2 * times[deepest])],
                                              [20.0 * times[deepest] - 10.0, 0.5, 0.0]))
print("  the same from a fresh query:", c)

# %% 5. Plot depth (and distance) over time, if matplotlib is installed
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed: skipping the plot (pip install matplotlib)")
else:
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.plot(times, depth, label="penetration depth")
    ax.plot(times, distance, label="distance")
    ax.set_xlabel("time")
    ax.set_ylabel("length")
    ax.set_title("rock passing through the ellipsoid")
    ax.legend()
    fig.tight_layout()
    png = os.path.join(out, "depth.png")
    fig.savefig(png, dpi=100)
    print("wrote", png)

# %% 6. C-obstacle slices of a robot turning about z
quats = np.array([[0.0, 0.0, np.sin(a / 2), np.cos(a / 2)] for a in np.linspace(0, np.pi, 32)])
slices = dymsum.cobstacle_slices(rock, dymsum.load("box:4,1,1"), quats)
print(f"{len(slices)} C-obstacle slices, {min(len(v) for v, _ in slices)}–{max(len(v) for v, _ in slices)} vertices")

print("all outputs are in", out)
