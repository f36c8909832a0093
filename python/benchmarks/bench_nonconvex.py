"""Minkowski sums of non-convex bodies: dymsum (exact piece sums merged by
Manifold) against manifold3d's own ``Manifold.minkowski_sum``.

    pip install ./python scipy manifold3d coacd
    python python/benchmarks/bench_nonconvex.py [--repeats 3] [--coacd] [--cgal target/cgal_minkowski]

Rows (A non-convex; B convex or non-convex; triangle counts of the meshes
handed to manifold3d):

* ``L + cube@(10,0,0)``: the issue's case, B not containing the origin;
* ``comb K + ball``: a comb of K teeth (boxes) plus a convex ball (the hull
  of Manifold's sphere);
* ``comb K + L``: both non-convex, B an L containing the origin;
* ``cube(10) - sphere(6, n) + sphere(1)``: the OpenSCAD-style case, A built
  by Manifold's boolean. dymsum takes A as an exact convex decomposition:
  the complement of a convex S (containing the origin) in a box C is the
  union over the triangles f of S of ``C ∩ cone(f) ∩ {x : n_f·x ≥ d_f}``
  (a point of C outside S is beyond the facet where its ray from the origin
  leaves S), so the pieces are exact (their vertices rounded); with
  ``--coacd`` also through CoACD's approximate decomposition (its time and
  reported volume error in their own columns).

* ``..., boundary``: the same A as one closed mesh, summed with
  ``decomposition="boundary"`` (no decomposition: one exact piece per
  triangle of A, plus A moved by a point of B);
* with ``--cgal BINARY``: CGAL's exact Nef ``minkowski_sum_3`` on the same
  meshes for the smallest rows (python/benchmarks/cgal/cgal_minkowski.cpp,
  built against Debian's libcgal-dev; ``--cgal-timeout`` seconds each,
  default 600, as the issue's "where it finishes in 10 minutes").

Times are medians over the repeats (manifold3d's once beyond 20 s); the
decomposition (``decomp``) is timed separately and not in ``dymsum``; the
"ratio with decomposition" column adds it.
Correctness: the volume against a reference: the exact volume of a union of
boxes (coordinate compression) where A and B are boxes, else the volume of
the union over piece pairs of scipy's hulls (Qhull) of pairwise vertex sums
merged by Manifold (``hulls``: no dymsum code), and manifold3d's volume
where B contains the origin (where its answer is right).
"""

import argparse
import importlib.metadata
import itertools
import json
import os
import platform
import statistics
import subprocess
import tempfile
import time

import manifold3d as m3d
import numpy as np
from scipy.spatial import ConvexHull

import dymsum

M = m3d.Manifold


def median_time(f, repeats, budget=20.0):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
        if times[-1] > budget:
            break
    return statistics.median(times), len(times), out


def box(lo, hi):
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])


def box_union_volume(boxes):
    axes = [np.unique(np.concatenate([[lo[k], hi[k]] for lo, hi in boxes])) for k in range(3)]
    lo = np.array([b[0] for b in boxes])
    hi = np.array([b[1] for b in boxes])
    vol = 0.0
    for i, j, k in itertools.product(*(range(len(a) - 1) for a in axes)):
        c = np.array([(axes[0][i] + axes[0][i + 1]) / 2, (axes[1][j] + axes[1][j + 1]) / 2, (axes[2][k] + axes[2][k + 1]) / 2])
        if np.any(np.all(c > lo, axis=1) & np.all(c < hi, axis=1)):
            vol += (axes[0][i + 1] - axes[0][i]) * (axes[1][j + 1] - axes[1][j]) * (axes[2][k + 1] - axes[2][k])
    return vol


def boxes_manifold(boxes):
    return M.batch_boolean([M.cube(tuple(np.subtract(hi, lo))).translate(tuple(lo)) for lo, hi in boxes], m3d.OpType.Add)


def comb(k):
    """A spine and k teeth, 0.6 wide with gaps of 0.4: non-convex, genus 0."""
    spine = ((0.0, 0.0, 0.0), (k * 1.0, 1.0, 1.0))
    return [spine] + [((i * 1.0, 1.0, 0.0), (i + 0.6, 4.0, 1.0)) for i in range(k)]


def ball(segments, radius=0.3):
    v = np.array(M.sphere(radius, segments).to_mesh64().vert_properties[:, :3])
    return v[ConvexHull(v).vertices]


def complement_pieces(cube_half, sphere_vertices):
    """Exact convex pieces of box − hull(S), S containing the origin: one per
    triangle f of S, ``C ∩ cone(f) ∩ {n_f·x ≥ d_f}`` (the cone from the
    origin over f). A point of C outside S lies in the cone of the facet
    where its ray leaves S, beyond that facet's plane; the pieces meet only
    on their boundaries. Each is the exact hull of the vertices of its 10
    half-spaces (every feasible triple-plane point), all triangles solved
    at once (vectorised)."""
    hull = ConvexHull(sphere_vertices)
    tri = hull.points[hull.simplices]  # (T, 3, 3)
    eq = hull.equations
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    flip = np.einsum("ij,ij->i", np.cross(b - a, c - a), eq[:, :3]) < 0
    b, c = np.where(flip[:, None], c, b), np.where(flip[:, None], b, c)
    t = len(tri)
    n = np.empty((t, 10, 3))
    off = np.zeros((t, 10))
    n[:, :6] = np.array([np.eye(3)[k] * sgn for k in range(3) for sgn in (1.0, -1.0)])
    off[:, :6] = cube_half
    n[:, 6], n[:, 7], n[:, 8] = -np.cross(a, b), -np.cross(b, c), -np.cross(c, a)
    n[:, 9], off[:, 9] = -eq[:, :3], eq[:, 3]
    triples = np.array(list(itertools.combinations(range(10), 3)))  # (120, 3)
    m = n[:, triples]  # (T, 120, 3, 3)
    rhs = off[:, triples]  # (T, 120, 3)
    det = np.linalg.det(m)
    ok = np.abs(det) >= 1e-12
    m[~ok] = np.eye(3)
    x = np.linalg.solve(m, rhs[..., None])[..., 0]  # (T, 120, 3)
    feasible = ok & np.all(np.einsum("tpk,tqk->tpq", x, n) <= off[:, None, :] + 1e-9 * cube_half, axis=2)
    pieces = []
    for k in range(t):
        cand = x[k][feasible[k]]
        if len(cand) < 4:
            continue
        try:
            pieces.append(dymsum.Polytope(cand))
        except ValueError:
            pass  # flat: no volume
    return pieces


def hull_union_volume(pieces_a, pieces_b):
    """Volume of the union over piece pairs of scipy's hulls (Qhull) of
    pairwise vertex sums, merged by Manifold: no dymsum code involved."""
    hulls = []
    for p, q in itertools.product(pieces_a, pieces_b):
        pts = (np.asarray(p)[:, None, :] + np.asarray(q)[None, :, :]).reshape(-1, 3)
        h = ConvexHull(pts)
        tri = h.simplices.copy()
        t = pts[tri]
        flip = np.einsum("ij,ij->i", np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), h.equations[:, :3]) < 0
        tri[flip] = tri[flip][:, ::-1]
        used, inv = np.unique(tri, return_inverse=True)
        mesh = m3d.Mesh64(vert_properties=np.ascontiguousarray(pts[used]), tri_verts=inv.reshape(-1, 3).astype(np.uint64))
        hulls.append(M(mesh))
    return M.batch_boolean(hulls, m3d.OpType.Add).volume()


def run_cgal(binary, a_man, b_man, timeout):
    """CGAL's Nef ``minkowski_sum_3`` on the same meshes (OFF files), in a
    subprocess with a time limit: (seconds, volume) or (None, reason)."""
    with tempfile.TemporaryDirectory() as d:
        paths = []
        for name, man in (("a", a_man), ("b", b_man)):
            m = man.to_mesh64()
            path = os.path.join(d, f"{name}.off")
            dymsum.save(path, np.array(m.vert_properties[:, :3]), np.array(m.tri_verts, dtype=np.int64))
            paths.append(path)
        try:
            out = subprocess.run([binary, *paths], capture_output=True, text=True, timeout=timeout, check=True)
        except subprocess.TimeoutExpired:
            return None, f"> {timeout:.0f} s"
        except subprocess.CalledProcessError as e:
            return None, f"failed: {e.stderr.strip()[:60]}"
    r = json.loads(out.stdout)
    return r["seconds"], r["volume"]


def row(name, a_union, b_union, a_man, b_man, reference, repeats, b_has_origin, decomp=None, decomp_s=0.0, decomposition=None, cgal=None):
    print(f"{name}: A {a_man.num_tri()} + B {b_man.num_tri()} triangles", end="", flush=True)
    kw = {"decomposition": decomposition} if decomposition else {}
    ours_t, ours_n, ours = median_time(lambda: dymsum.minkowski_sum(a_union, b_union, **kw), repeats)
    print(f"; dymsum {ours_t:.3f} s", end="", flush=True)
    man_t, man_n, theirs = median_time(lambda: a_man.minkowski_sum(b_man), repeats)
    print(f"; manifold3d {man_t:.3f} s", end="", flush=True)
    cgal_t, cgal_v = run_cgal(cgal[0], a_man, b_man, cgal[1]) if cgal else (None, "not run")
    print(f"; CGAL {cgal_t if cgal_t is None else round(cgal_t, 3)} {cgal_v}", flush=True)
    ref_vol, ref_err, ref_kind = reference
    ours_rel = abs(ours.volume - ref_vol) / ref_vol
    man_rel = abs(theirs.volume() - ref_vol) / ref_vol
    agree = abs(ours.volume - theirs.volume()) / theirs.volume()
    return {
        "case": name,
        "tris": f"{a_man.num_tri()} + {b_man.num_tri()}",
        "pairs": f"{ours.info['pairs'] - ours.info['pairs_culled']}/{ours.info['pairs']}",
        "decomp": decomp,
        "dymsum_s": ours_t,
        "decomp_s": decomp_s,
        "cgal": (f"{cgal_t * 1e3:.0f} ms, volume {cgal_v:.10g}" if cgal_t is not None else cgal_v),
        "manifold_s": man_t,
        "runs": f"{ours_n}/{man_n}",
        "ratio": ours_t / man_t,
        "ratio_all": (ours_t + decomp_s) / man_t,
        "vol": ours.volume,
        "ref": f"{ref_vol:.10g}" + (f" ± {ref_err:.2g}" if ref_err else "") + f" ({ref_kind})",
        "ours_rel": ours_rel,
        "man_vol": theirs.volume(),
        "man_rel": man_rel,
        "agree": agree if b_has_origin else None,
        "shells": f"{ours.info['shells']}/{len(theirs.decompose())}",
        "valid": dymsum.nonconvex.check_closed_mesh(ours.vertices, ours.faces) is None,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--coacd", action="store_true", help="also the cube - sphere row through CoACD")
    ap.add_argument("--cgal", metavar="BINARY", help="also CGAL's Nef minkowski_sum_3 (python/benchmarks/cgal/cgal_minkowski.cpp)")
    ap.add_argument("--cgal-timeout", type=float, default=600.0, help="seconds per CGAL row (default 600)")
    ap.add_argument("--segments", default="16,24,40,120", help="sphere segments of the cube - sphere rows")
    a = ap.parse_args()
    cgal = (a.cgal, a.cgal_timeout) if a.cgal else None
    print(
        f"median of {a.repeats} (manifold3d once when over 20 s); Python {platform.python_version()}, "
        f"dymsum {dymsum.__version__}, manifold3d {importlib.metadata.version('manifold3d')}"
    )
    rows = []

    # The issue's case.
    L = [((0, 0, 0), (3, 1, 1)), ((0, 0, 0), (1, 3, 1))]
    cb = ((10, 0, 0), (10.5, 0.5, 0.5))
    rows.append(
        row(
            "L + cube 0.5 @ (10,0,0)",
            dymsum.ConvexUnion([box(*b) for b in L]),
            box(*cb),
            boxes_manifold(L),
            boxes_manifold([cb]),
            (box_union_volume([(np.add(l0, cb[0]), np.add(l1, cb[1])) for l0, l1 in L]), 0, "exact"),
            a.repeats,
            False,
            cgal=cgal,
        )
    )

    # Combs plus a convex ball, and plus a non-convex L around the origin.
    small_L = [((-0.3, -0.3, -0.3), (0.6, 0.3, 0.3)), ((-0.3, -0.3, -0.3), (0.3, 0.6, 0.3))]
    for k, seg in ((4, 16), (16, 32), (32, 64)):
        teeth = comb(k)
        bv = ball(seg)
        pa = [box(*b) for b in teeth]
        rows.append(
            row(
                f"comb {k} + ball ({len(bv)} v)",
                dymsum.ConvexUnion(pa),
                bv,
                boxes_manifold(teeth),
                M.hull_points(bv),
                (hull_union_volume(pa, [bv]), 0, "hulls"),
                a.repeats,
                True,
                cgal=cgal if k == 4 else None,
            )
        )
    for k in (4, 16, 64):
        teeth = comb(k)
        exact = box_union_volume([(np.add(t0, s0), np.add(t1, s1)) for t0, t1 in teeth for s0, s1 in small_L])
        rows.append(
            row(
                f"comb {k} + L (both non-convex)",
                dymsum.ConvexUnion([box(*b) for b in teeth]),
                dymsum.ConvexUnion([box(*b) for b in small_L]),
                boxes_manifold(teeth),
                boxes_manifold(small_L),
                (exact, 0, "exact"),
                a.repeats,
                True,
                cgal=cgal if k == 4 else None,
            )
        )

    # OpenSCAD-style: (cube(10) - sphere(6)) + sphere(1).
    bv = ball(16, 1.0)
    for seg in map(int, a.segments.split(",")):
        sv = np.array(M.sphere(6, seg).to_mesh64().vert_properties[:, :3])
        a_man = M.cube((10, 10, 10), True) - M.hull_points(sv)
        t = time.perf_counter()
        pieces = complement_pieces(5.0, sv)
        dt = time.perf_counter() - t
        pa = [p.vertices for p in pieces]
        rows.append(
            row(
                f"cube(10) - sphere(6, {seg}) + sphere(1), exact pieces",
                dymsum.ConvexUnion(pieces),
                bv,
                a_man,
                M.hull_points(bv),
                (hull_union_volume(pa, [bv]), 0, "hulls"),
                a.repeats,
                True,
                decomp=f"{len(pieces)} exact, {dt:.2f} s",
                decomp_s=dt,
                cgal=cgal if seg == 16 else None,
            )
        )
        m = a_man.to_mesh64()
        av, af = np.array(m.vert_properties[:, :3]), np.array(m.tri_verts, dtype=np.int64)
        rows.append(
            row(
                f"cube(10) - sphere(6, {seg}) + sphere(1), boundary",
                (av, af),
                bv,
                a_man,
                M.hull_points(bv),
                (hull_union_volume(pa, [bv]), 0, "hulls of the exact pieces"),
                a.repeats,
                True,
                decomp=f"none: boundary, {len(af)} triangles",
                decomposition="boundary",
            )
        )
        if a.coacd and seg == 24:
            m = a_man.to_mesh64()
            v, f = np.array(m.vert_properties[:, :3]), np.array(m.tri_verts, dtype=np.int64)
            t = time.perf_counter()
            cpieces, info = dymsum.convex_pieces((v, f), "coacd")
            dt = time.perf_counter() - t
            rows.append(
                row(
                    f"cube(10) - sphere(6, {seg}) + sphere(1), CoACD",
                    dymsum.ConvexUnion(cpieces),
                    bv,
                    a_man,
                    M.hull_points(bv),
                    (hull_union_volume(pa, [bv]), 0, "hulls of the exact pieces"),
                    a.repeats,
                    True,
                    decomp=f"{len(cpieces)} CoACD, {dt:.1f} s, volume error {info['volume_error']:.2%}",
                )
            )

    print()
    print("| case | triangles (A + B) | pairs kept | decomposition | dymsum | manifold3d | ratio | ratio with decomposition | CGAL Nef | dymsum volume | reference | dymsum rel. err | manifold3d volume | manifold3d rel. err | shells (dymsum/manifold3d) | valid |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(
            f"| {r['case']} | {r['tris']} | {r['pairs']} | {r['decomp'] or 'given'} | {r['dymsum_s'] * 1e3:.1f} ms | "
            f"{r['manifold_s'] * 1e3:.1f} ms | {r['ratio']:.2f}× | {r['ratio_all']:.2f}× | {r['cgal']} | {r['vol']:.10g} | {r['ref']} | {r['ours_rel']:.1e} | "
            f"{r['man_vol']:.10g} | {r['man_rel']:.1e} | {r['shells']} | {r['valid']} |"
        )
    print()
    for r in rows:
        if r["agree"] is not None:
            print(f"{r['case']}: dymsum vs manifold3d volume (B contains the origin): rel. diff {r['agree']:.1e}")


if __name__ == "__main__":
    main()
