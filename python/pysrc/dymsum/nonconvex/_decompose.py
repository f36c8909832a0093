"""Splitting a non-convex solid into convex pieces: its exactly convex shells, or an approximate decomposition (CoACD, V-HACD) with its volume error."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .. import _dymsum as _ext
from ._types import DECOMPOSITIONS, MeshUnionError, _NeedsDecomposition, _manifold3d
from ._checks import _as_mesh, _submesh, check_closed_mesh, signed_volume


def _to_manifold(m3d: Any, vertices: np.ndarray, faces: np.ndarray, what: str) -> Any:
    mesh = m3d.Mesh64(
        vert_properties=np.array(vertices, dtype=np.float64, order="C"),  # a writable copy
        tri_verts=np.array(faces, dtype=np.uint64, order="C"),
    )
    man = m3d.Manifold(mesh)
    if man.status() != m3d.Error.NoError:
        raise MeshUnionError(f"Manifold refused {what}: {man.status()}")
    return man


def _decompose(vertices: np.ndarray, faces: np.ndarray, method: str, options: Dict[str, Any]) -> List[np.ndarray]:
    """Convex parts (point arrays) of a closed mesh by an optional library."""
    if method == "coacd":
        try:
            import coacd
        except ImportError as e:
            raise ImportError("decomposition='coacd' needs the coacd package: pip install coacd") from e
        coacd.set_log_level("error")
        parts = coacd.run_coacd(coacd.Mesh(vertices, faces.astype(np.int32)), **options)
        return [np.asarray(p[0], dtype=np.float64) for p in parts]
    if method == "vhacd":
        try:
            import vhacdx
        except ImportError as e:
            raise ImportError("decomposition='vhacd' needs the vhacdx package: pip install vhacdx") from e
        parts = vhacdx.compute_vhacd(vertices, faces.astype(np.uint32), **options)
        return [np.asarray(p[0], dtype=np.float64) for p in parts]
    raise ValueError(f"unknown decomposition {method!r}: use one of {', '.join(map(repr, DECOMPOSITIONS))}")


def _volume_error(pieces: Sequence[Any], vertices: np.ndarray, faces: np.ndarray, shells: Sequence[np.ndarray]) -> Dict[str, float]:
    """How far the union of the pieces is from the input mesh, the union of
    its ``shells`` (by Manifold)."""
    m3d = _manifold3d()
    union = m3d.Manifold.batch_boolean(
        [_to_manifold(m3d, p.vertices, p.faces, f"decomposition piece {i}") for i, p in enumerate(pieces)], m3d.OpType.Add
    )
    vin = signed_volume(vertices, faces)
    out: Dict[str, float] = {"input_volume": vin, "union_volume": union.volume()}
    try:
        if len(shells) == 1:
            inp = _to_manifold(m3d, vertices, faces, "the input mesh")
        else:
            # Overlapping shells: the input is their union.
            inp = m3d.Manifold.batch_boolean(
                [_to_manifold(m3d, *_submesh(vertices, faces[s]), f"shell {k} of the input") for k, s in enumerate(shells)],
                m3d.OpType.Add,
            )
            vin = out["input_volume"] = inp.volume()
    except MeshUnionError:
        # The input is not a valid manifold for Manifold: the volumes only.
        out["volume_error"] = abs(union.volume() - vin) / vin
        return out
    extra = (union - inp).volume()
    missing = (inp - union).volume()
    out["added_volume"] = extra
    out["missing_volume"] = missing
    out["volume_error"] = (extra + missing) / vin
    return out


def check_solid(vertices: Any, faces: Any) -> Optional[str]:
    """Why the triangle mesh ``(vertices, faces)`` is not a solid, or
    ``None`` when it is (dymsum's exact check, in Rust: each shell closed,
    consistently oriented, edge- and vertex-manifold, crossing itself
    nowhere, of positive volume; no zero-area triangle; no face listed twice
    or back to back; shells may overlap each other)."""
    try:
        _ext.check_solid(vertices, faces)
    except ValueError as e:
        return str(e)
    return None


def _solid_shells(vertices: np.ndarray, faces: np.ndarray, name: Optional[str]) -> List[np.ndarray]:
    """The shells (face indices) of a mesh given as a solid; ``ValueError``
    naming the argument when it is not one."""
    try:
        return list(_ext.check_solid(vertices, faces))
    except ValueError as e:
        prefix = f"{name}: " if name else ""
        raise ValueError(
            f"{prefix}not a solid: {e}; a non-convex body must be a closed mesh whose shells each bound a "
            "region (repair the mesh, or give its convex pieces as dymsum.ConvexUnion([...]))"
        ) from None


def convex_pieces(
    shape: Any,
    decomposition: Optional[str] = None,
    options: Optional[Dict[str, Any]] = None,
    *,
    name: Optional[str] = None,
) -> Tuple[List[Any], Dict[str, Any]]:
    """The convex pieces of a body, and how they were obtained.

    A :class:`ConvexUnion` gives its pieces; a convex shape (anything
    :class:`Polytope` accepts) is one piece; a mesh ``(vertices, faces)``
    (or an object with ``.vertices`` and ``.faces``) that is not convex is
    first checked exactly to be a solid (:func:`check_solid`; else
    ``ValueError``, prefixed by ``name``, the argument's name): the body is
    the union of its shells. The shells are taken as pieces when every one
    is exactly convex; otherwise the non-convex shells are decomposed, one
    by one, by ``decomposition`` (``"coacd"`` or ``"vhacd"``), and the
    volume error of the union of the parts against the input is reported.
    """
    opts = dict(options or {})
    if isinstance(shape, _ext.ConvexUnion):
        return list(shape.pieces), {"method": "given", "exact": True}
    if isinstance(shape, _ext.Polytope):
        return [shape], {"method": "convex", "exact": True}
    path = _path_of(shape)
    if path is not None:
        try:
            return [_ext.Polytope(path)], {"method": "convex", "exact": True}
        except ValueError:
            return _path_pieces(path, decomposition, opts, name)
    mesh = _mesh_of(shape)
    if mesh is None:
        return [_named_polytope(shape, name)], {"method": "convex", "exact": True}
    try:
        return [_ext.Polytope(shape)], {"method": "convex", "exact": True}
    except ValueError as convex_error:
        refusal = str(convex_error)
        if refusal.startswith("a: "):  # the constructor's own name for its argument
            refusal = refusal[3:]
    try:
        vertices, faces = _as_mesh(*mesh)
    except ValueError:
        raise ValueError(f"{name}: {refusal}" if name else refusal) from None
    # Exactly a solid, or refused: nothing from an invalid mesh goes on.
    shells = _solid_shells(vertices, faces, name)
    pieces: List[Any] = []
    rest: List[np.ndarray] = []
    for shell in shells:
        cv, cf = _submesh(vertices, faces[shell])
        try:
            pieces.append(_ext.Polytope((cv, cf), strict=True))
        except ValueError:
            rest.append(shell)
    if not rest:
        return pieces, {"method": "components", "exact": True, "components": len(pieces)}
    if decomposition is None or decomposition == "boundary":
        raise _NeedsDecomposition(
            f"{name + ': ' if name else ''}a non-convex mesh ({refusal}) needs a convex decomposition: pass decomposition='coacd' "
            "or decomposition='vhacd' (optional packages coacd / vhacdx), or give its convex pieces "
            "as dymsum.ConvexUnion([...]); minkowski_sum also takes decomposition='boundary' "
            "(exact, when the other body is convex or in convex pieces)",
            vertices,
            faces,
            shells,
        )
    if decomposition not in DECOMPOSITIONS:
        raise ValueError(f"unknown decomposition {decomposition!r}: use one of {', '.join(map(repr, DECOMPOSITIONS))}")
    parts = []
    for shell in rest:
        dv, df = _submesh(vertices, faces[shell])
        parts.extend(_decompose(dv, df, decomposition, opts))
    decomposed = []
    flat = 0
    for p in parts:
        try:
            decomposed.append(_ext.Polytope(p))
        except ValueError as e:
            # A flat (zero-volume) part adds nothing to the union; any
            # other refusal is an error.
            if "degenerate input" not in str(e):
                raise
            flat += 1
    if not decomposed:
        raise ValueError(f"the {decomposition} decomposition returned no solid part")
    info: Dict[str, Any] = {
        "method": decomposition,
        "exact": False,
        "options": opts,
        "convex_components": len(pieces),
        "parts": len(decomposed),
        "flat_parts_dropped": flat,
    }
    pieces = pieces + decomposed
    info.update(_volume_error(pieces, vertices, faces, shells))
    return pieces, info


def _mesh_of(shape: Any) -> Optional[Tuple[Any, Any]]:
    """``(vertices, faces)`` when ``shape`` is given as a mesh, else ``None``."""
    if hasattr(shape, "vertices") and hasattr(shape, "faces"):
        return shape.vertices, shape.faces
    if isinstance(shape, (tuple, list)) and len(shape) == 2:
        f = np.asarray(shape[1]) if not isinstance(shape[1], (str, bytes)) else None
        v = np.asarray(shape[0]) if not isinstance(shape[0], (str, bytes)) else None
        if f is not None and v is not None and f.ndim == 2 and f.shape[1] == 3 and v.ndim == 2 and v.shape[1] == 3:
            if np.issubdtype(f.dtype, np.integer):
                return shape[0], shape[1]
    return None


def _is_nonconvex_solid(shape: Any) -> bool:
    """A closed triangle mesh that dymsum refuses as a polytope."""
    if isinstance(shape, (_ext.ConvexUnion, _ext.Polytope)):
        return False
    mesh = _mesh_of(shape)
    if mesh is None:
        return False
    try:
        vertices, faces = _as_mesh(*mesh)
    except ValueError:
        return False
    try:
        _ext.Polytope((vertices, faces))
        return False
    except ValueError:
        pass
    # A closed mesh (every edge paired, however badly) goes on as a
    # non-convex body, where the exact solid check says what is wrong with
    # it; an open one keeps the convex loader's refusal.
    why = check_closed_mesh(vertices, faces)
    return why is None or "no opposite half-edge" not in why


def _named_polytope(shape: Any, name: Optional[str]) -> Any:
    """``Polytope(shape)``, its error said of the argument ``name`` (the
    constructor names its own argument ``a``)."""
    try:
        return _ext.Polytope(shape)
    except (ValueError, OSError) as e:
        text = str(e)
        if name and name != "a" and text.startswith("a: "):
            raise type(e)(f"{name}: {text[3:]}") from None
        raise


def _path_of(shape: Any) -> Optional[str]:
    """The file path ``shape`` names, if it names an existing file."""
    if isinstance(shape, (str, os.PathLike)):
        path = os.fspath(shape)
        if isinstance(path, str) and os.path.isfile(path):
            return path
    return None


def _path_pieces(
    path: str, decomposition: Optional[str], options: Optional[Dict[str, Any]], name: Optional[str] = None
) -> Tuple[List[Any], Dict[str, Any]]:
    """Convex pieces of a mesh file that ``Polytope`` refuses: the bodies of
    the file (OBJ objects), each convex or split as :func:`convex_pieces`
    splits a mesh."""
    bodies = _ext.read_mesh_bodies(path)
    if len(bodies) == 1:
        _, v, f = bodies[0]
        return convex_pieces((v, f), decomposition, options, name=name)
    pieces: List[Any] = []
    objects = []
    for obj, v, f in bodies:
        got, how = convex_pieces((v, f) if len(f) else v, decomposition, options, name=f"{name or path} (object {obj!r})")
        pieces.extend(got)
        objects.append({"name": obj, **how})
    info: Dict[str, Any] = {"method": "objects", "exact": all(o["exact"] for o in objects), "objects": objects}
    return pieces, info


def _is_union_operand(shape: Any) -> bool:
    """A body that is not one convex polytope: a :class:`ConvexUnion`, a
    closed non-convex mesh, or a mesh file holding either."""
    if isinstance(shape, _ext.ConvexUnion):
        return True
    path = _path_of(shape)
    if path is not None:
        try:
            _ext.Polytope(path)
            return False
        except ValueError:
            pass
        try:
            bodies = _ext.read_mesh_bodies(path)
        except (ValueError, OSError):
            return False
        if len(bodies) > 1:
            return True
        return _is_nonconvex_solid((bodies[0][1], bodies[0][2]))
    return _is_nonconvex_solid(shape)
