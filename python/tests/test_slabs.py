"""Certified C-obstacle slabs (``cobstacle_slices(..., certified=True)``)
against an independent oracle: dense slices between the end rotations,
computed here with scipy's rotations as all pairwise differences ``o − R a``
(their hull is the slice), must satisfy every half-space ``normals @ x <=
offsets`` as floats, with no tolerance; the hull of the two end slices
alone (the slab without its sagitta term) must not hold them."""

import numpy as np
import pytest
from conftest import sphere_points
from scipy.spatial import ConvexHull, HalfspaceIntersection
from scipy.spatial.transform import Rotation, Slerp

import dymsum

BAR = dymsum.load("box:4,0.2,0.2")
BLOCK = dymsum.load("box")


def slice_points(robot, obstacle, rotation):
    """Every ``o − R a``: the slice ``obstacle ⊕ (−R·robot)`` is their hull."""
    turned = rotation.apply(np.array(robot))
    return (np.array(obstacle)[:, None, :] - turned[None, :, :]).reshape(-1, 3)


def worst(slab, points):
    """The largest ``n·x − d`` over the points and the half-spaces (> 0: outside)."""
    return (points @ slab.normals.T - slab.offsets).max()


def check_holds(slab, robot, obstacle, rotations):
    """Every point of every sampled slice is in the slab, as floats and
    exactly; returns how far the farthest one pokes out of the end slices'
    hull (the half-spaces pulled back by the margin)."""
    beyond_hull = -np.inf
    for r in rotations:
        pts = slice_points(robot, obstacle, r)
        assert worst(slab, pts) <= 0.0, (r.as_quat(), worst(slab, pts))
        assert slab.contains(pts).all()
        beyond_hull = max(beyond_hull, (pts @ slab.normals.T - (slab.offsets - slab.margin)).max())
    return beyond_hull


def sagitta(radius, angle):
    return radius * (1.0 - np.cos(angle / 2.0))


@pytest.mark.parametrize("count", [4, 8, 32])
def test_slabs_about_an_axis_hold_every_slice_and_the_sagitta_is_needed(count):
    angles = np.linspace(0.0, 2.0 * np.pi, count + 1)
    turns = Rotation.from_rotvec(np.outer(angles, [0.0, 0.0, 1.0]))
    slabs = dymsum.cobstacle_slices(BAR, BLOCK, turns, certified=True)
    assert len(slabs) == count
    reach = np.linalg.norm(BAR.vertices, axis=1).max()
    for k, slab in enumerate(slabs):
        assert slab.normals.shape == (len(slab), 3) and slab.offsets.shape == (len(slab),)
        assert np.allclose(np.linalg.norm(slab.normals, axis=1), 1.0)
        step = angles[k + 1] - angles[k]
        # The margin is the sagitta of the robot's farthest vertex, bounded
        # from above by a Taylor polynomial, plus rounding terms far below.
        assert sagitta(reach, step) <= slab.margin <= sagitta(reach, step) * (1 + 1e-5) + 1e-9
        assert slab.angle >= step and slab.angle <= step + 1e-9
        ends = Rotation.from_quat(slab.rotations)
        assert np.allclose(ends.as_matrix(), turns[k : k + 2].as_matrix(), atol=1e-15)
        dense = Rotation.from_rotvec(np.outer(np.linspace(angles[k], angles[k + 1], 41), [0, 0, 1]))
        beyond = check_holds(slab, BAR.vertices, BLOCK.vertices, dense)
        # Between the ends the bar's corners leave the hull of the end
        # slices by a good part of the sagitta (a quarter of it with 32
        # slabs, 90% with 4): a slab without it would fail.
        assert beyond > 0.1 * sagitta(reach, step), (k, beyond, slab.margin)


def test_slabs_between_random_rotations_hold_the_slerp(rng):
    robot = sphere_points(30, rng, radii=(1.5, 0.4, 0.3)) + [0.2, -0.1, 0.3]
    obstacle = sphere_points(40, rng, radii=(0.7, 1.0, 0.5)) + [1.0, 2.0, -1.0]
    reach = np.linalg.norm(robot, axis=1).max()
    for trial in range(6):
        start = Rotation.random(random_state=rng)
        axis = rng.normal(size=3)
        angle = rng.uniform(0.05, 3.0)
        end = Rotation.from_rotvec(axis / np.linalg.norm(axis) * angle) * start
        (slab,) = dymsum.cobstacle_slices(robot, obstacle, Rotation.concatenate([start, end]), certified=True)
        assert abs(slab.angle - angle) <= 1e-9
        assert slab.margin >= sagitta(reach, angle)
        path = Slerp([0.0, 1.0], Rotation.concatenate([start, end]))(np.linspace(0.0, 1.0, 33))
        beyond = check_holds(slab, robot, obstacle, path)
        assert beyond > 0.0, trial


def test_the_mesh_contains_the_half_spaces_and_little_more():
    turns = Rotation.from_rotvec(np.outer([0.3, 0.9], [1.0, 2.0, 0.5]) / np.linalg.norm([1.0, 2.0, 0.5]))
    (slab,) = dymsum.cobstacle_slices(BAR, "gs2", turns, certified=True)
    vertices, faces = slab.mesh()
    assert faces.shape[1] == 3 and faces.max() < len(vertices)
    polygons = slab.mesh(polygons=True)[1]
    assert all(len(p) >= 3 for p in polygons)
    # The vertices of {normals @ x <= offsets}, by scipy's half-space
    # intersection about an interior point.
    centre = vertices.mean(axis=0)
    assert slab.contains(centre)
    corners = HalfspaceIntersection(np.hstack([slab.normals, -slab.offsets[:, None]]), centre).intersections
    scale = np.abs(vertices).max()
    mesh = ConvexHull(vertices)
    assert (corners @ mesh.equations[:, :3].T + mesh.equations[:, 3]).max() <= 1e-9 * scale
    # The mesh's corners are those of the half-spaces pushed out by about
    # 2^-40 of the size, which moves a corner between nearly parallel
    # planes much further: little, still.
    assert worst(slab, vertices) <= 1e-6 * scale
    assert not slab.contains(centre + 10 * scale * slab.normals[0])


def test_contains_is_exact_and_takes_one_point_or_many():
    turns = Rotation.from_rotvec([[0, 0, 0], [0, 0, np.pi / 8]])
    (slab,) = dymsum.cobstacle_slices(BAR, BLOCK, turns, certified=True)
    n, d = slab.normals[0], slab.offsets[0]
    # Just inside and just outside the first plane, on its foot from the
    # origin.
    x = n * d
    inside = [bool(slab.contains(x + n * t)) for t in (-1e-9, 0.0, 1e-9)]
    assert inside[0] and not inside[2]
    assert isinstance(slab.contains([0.0, 0.0, 0.0]), bool)
    got = slab.contains(np.array([[0, 0, 0], [np.nan, 0, 0], [np.inf, 0, 0], [2.0, 0.3, 0]]))
    assert got.dtype == bool and got.tolist() == [True, False, False, True]
    assert slab.contains(np.zeros((0, 3))).shape == (0,)
    with pytest.raises(ValueError, match="points"):
        slab.contains(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="points"):
        slab.contains([1.0, 2.0])
    with pytest.raises(ValueError, match="read-only"):
        slab.normals[0, 0] = 1.0
    assert not slab.normals.flags.writeable and not slab.offsets.flags.writeable


def test_parallel_equals_sequential_and_refusals():
    turns = Rotation.from_rotvec(np.outer(np.linspace(0, np.pi, 7), [1.0, 0.0, 0.0]))
    seq = dymsum.cobstacle_slices("gs1", "box:2,1,1", turns, certified=True)
    par = dymsum.cobstacle_slices("gs1", "box:2,1,1", turns, parallel=True, certified=True)
    assert len(seq) == len(par) == 6
    for a, b in zip(seq, par):
        assert np.array_equal(a.normals, b.normals) and np.array_equal(a.offsets, b.offsets)
        assert a.margin == b.margin
    with pytest.raises(ValueError, match="at least 2"):
        dymsum.cobstacle_slices("gs1", "box", turns[:1], certified=True)
    with pytest.raises(ValueError, match="polygons"):
        dymsum.cobstacle_slices("gs1", "box", turns, polygons=True, certified=True)
    assert "half-spaces" in repr(seq[0])


def cell_samples(centre, radius, count, rng):
    """``count`` rotations ``E * centre`` with ``E`` a turn about a random
    axis by an angle in ``[0, radius]`` (every third by ``radius`` itself,
    the cell's rim), by scipy."""
    axes = rng.normal(size=(count, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    angles = rng.uniform(0.0, radius, size=count)
    angles[::3] = radius
    samples = Rotation.from_rotvec(axes * angles[:, None]) * centre
    assert ((samples * centre.inv()).magnitude() <= radius * (1 + 1e-12) + 1e-12).all()
    return samples


@pytest.mark.parametrize("radius", [0.0, 0.05, 0.3, 1.0, 2.5])
def test_cells_hold_every_slice_within_the_radius_and_need_the_r_rho_term(rng, radius):
    robot = sphere_points(30, rng, radii=(1.5, 0.4, 0.3)) + [0.2, -0.1, 0.3]
    obstacle = sphere_points(40, rng, radii=(0.7, 1.0, 0.5)) + [1.0, 2.0, -1.0]
    reach = np.linalg.norm(robot, axis=1).max()
    centres = Rotation.random(4, random_state=rng)
    slabs = dymsum.cobstacle_slices(robot, obstacle, centres, certified=True, cell_radius=radius)
    par = dymsum.cobstacle_slices(robot, obstacle, centres, parallel=True, certified=True, cell_radius=radius)
    assert len(slabs) == len(par) == 4
    for k, slab in enumerate(slabs):
        assert np.array_equal(slab.normals, par[k].normals) and np.array_equal(slab.offsets, par[k].offsets)
        assert slab.cell_radius == radius and slab.angle == radius
        assert slab.rotations.shape == (1, 4)
        assert (Rotation.from_quat(slab.rotations[0]) * centres[k].inv()).magnitude() <= 1e-12
        # The margin is r·rho plus rounding terms far below it.
        assert reach * radius <= slab.margin <= reach * radius * (1 + 1e-9) + 1e-9
        beyond = check_holds(slab, robot, obstacle, cell_samples(centres[k], radius, 30, rng))
        if radius > 0:
            # The sampled slices leave the centre slice by a good part of
            # r·rho: the centre slice's hull alone (no r·rho term) fails.
            assert beyond > 0.2 * reach * radius, (k, beyond, slab.margin)


def test_cell_refusals_and_the_path_slabs_have_no_radius():
    centres = Rotation.from_rotvec([[0, 0, 0], [0, 0.5, 0]])
    for bad in (-0.1, np.nan, np.pi, 4.0, np.inf):
        with pytest.raises(ValueError, match="cell radius"):
            dymsum.cobstacle_slices(BAR, BLOCK, centres, certified=True, cell_radius=bad)
    with pytest.raises(ValueError, match="certified=True"):
        dymsum.cobstacle_slices(BAR, BLOCK, centres, cell_radius=0.1)
    (one,) = dymsum.cobstacle_slices(BAR, BLOCK, centres[:1], certified=True, cell_radius=0.1)
    assert slab_ok(one)
    (path,) = dymsum.cobstacle_slices(BAR, BLOCK, centres, certified=True)
    assert path.cell_radius is None and path.rotations.shape == (2, 4)


def slab_ok(slab):
    """A bounded slab: its half-spaces hold the origin region they were built around."""
    return len(slab) >= 6 and slab.contains(np.zeros(3)) and not slab.contains([10.0, 0.0, 0.0])
