//! Certified C-obstacle slabs: one convex region that contains *every*
//! C-obstacle slice `O ⊕ (−R·A)` for a whole range of robot orientations
//! `R` — between two consecutive orientations of a turn, or in a ball of
//! orientations in SO(3) — given as half-spaces `{x : N x ≤ d}` (what cell
//! decompositions and graphs of convex sets consume) or as a checked mesh.
//!
//! A slice ([`CObstacle::slice`]) holds for its one orientation; a planner that
//! samples orientations misses what happens between the samples. A slab
//! closes that gap conservatively: a translation outside the slab is free
//! at every orientation of its range.
//!
//! # What "certified" means
//! Let `ε = 2⁻⁴⁰` ([`ROTATION_SLACK`]), `r` bound `|a|` over the robot's
//! vertices (the robot turns about its own origin) and `R_O` bound `|o|`
//! over the obstacle's. For a 3×3 matrix `M` write `S(M) = O ⊕ (−M·A)`.
//!
//! * **Between two orientations** `R_k`, `R_{k+1}` ([`Rotation`]s): the slab
//!   contains `S(M)` — and the slice dymsum computes for `M`, with its
//!   rounded vertices — for every matrix `M` within `ε` (spectral norm) of
//!   a rotation `R` on a *shortest path* in SO(3) (a geodesic, of angle
//!   `≤ π`; both of them at angle `π`) from some rotation within angle `ε`
//!   of `R_k` to some rotation within angle `ε` of `R_{k+1}`.
//! * **In a cell** with centre `R_c` and radius `ρ < π`: the same for every
//!   `R` within angle `ρ + ε` of `R_c`.
//!
//! Turns about one axis ([`rotations_about_axis`]): the turn by angle `θ`
//! about an axis, for `θ` between two angles at most `π` apart, is a
//! shortest path between its ends, so a slab holds the slices of the turn
//! by **every real angle** in `[θ_k, θ_{k+1}]` about the exact axis, and of
//! every rotation [`Rotation::from_axis_angle`] computes there. The slack
//! `ε` covers the rotations as computed:
//!
//! * a stored [`Rotation`]'s matrix (`DMat3::from_quat` of a quaternion of
//!   norm `1 ± 4·2⁻⁵²`, entries within `2⁻⁴⁷` of `0`, `±1` snapped) differs
//!   from the exact rotation of its normalised quaternion by at most
//!   `2|1 − |q|²| + 3·(4u·2) + 3·2⁻⁴⁷ < 2.6·10⁻¹⁴ < 2⁻⁴⁵` in spectral
//!   norm (`u = 2⁻⁵³`; `DMat3::from_quat(λq̂) = λ²R(q̂) + (1 − λ²)I`);
//! * [`Rotation::from_axis_angle`] of a float angle `θ` about an axis scaled
//!   to `[1, 2)` by a power of two (exact; [`rotations_about_axis`] does so,
//!   so that the axis's squared length neither underflows nor overflows):
//!   the normalised axis is within `4u` of the exact one, `sin` and `cos`
//!   of `θ/2` within an ulp (the platform's libm; glibc, musl and macOS
//!   are), so the quaternion is within `12u`; snapping components below
//!   `10⁻¹⁴` and renormalising moves it by at most `4.1·10⁻¹⁴`; the rotation
//!   angle is at most twice the quaternion distance, `< 9·10⁻¹⁴ < 2⁻⁴³`;
//! * a step compared as `fl(θ_{k+1} − θ_k) ≤ π` (float `π`) is at most `π`
//!   plus half an ulp of `π`: the part of the turn beyond a half turn is
//!   within `2⁻⁵¹` of the half turn's end.
//!
//! # Why a slab contains the slices
//! Take a vertex `p` of `−A` (`|p| ≤ r`), and `R = E(t)·R_a` on a shortest
//! path from `R_a` to `R_b` (`E(t)` the turn by `tδ'` about a fixed axis,
//! `t ∈ [0, 1]`, `δ' = angle(R_a, R_b) ≤ π`). The points `E(t)R_a p` run on
//! a circle arc of radius at most `|p|` and angle `δ' ≤ π`, so each lies
//! within the **sagitta** `r·σ(δ')`, `σ(δ) = 1 − cos(δ/2) = 2 sin²(δ/4)`, of
//! the chord between the arc's ends (the arc is at most a half circle, so
//! the foot of the perpendicular falls on the chord). The ends `R_a p`,
//! `R_b p` are within `(ε + 2⁻⁴⁵) r` of `M_k p`, `M_{k+1} p` (the stored
//! matrices: `|R_a p − R_k p| ≤ 2 sin(ε/2)|p|`), and `|Mp − Rp| ≤ εr`, and
//! `δ' ≤ δ + 2ε` with `δ` the angle between `R_k` and `R_{k+1}`. Adding a
//! vertex `o` of `O`: every vertex `o + Mp` of `S(M)` lies within
//! `r(σ(δ + 2ε) + 3ε)` of the segment between `o + M_k p ∈ S(M_k)` and
//! `o + M_{k+1} p ∈ S(M_{k+1})`, so
//!
//! ```text
//! S(M) ⊆ conv(S(M_k) ∪ S(M_{k+1})) ⊕ ball(r(σ(δ + 2ε) + 3ε)).
//! ```
//!
//! In a cell, `|Rp − M_c p| ≤ 2 sin((ρ + ε)/2) r + 2⁻⁴⁵ r ≤ (ρ + 2ε) r`, so
//! `S(M) ⊆ S(M_c) ⊕ ball(r(ρ + 3ε))`.
//!
//! **The slices' rounding.** dymsum's mesh of a slice has the vertices
//! `fl(fl(M p) + o)`: each coordinate of `fl(M p)` is off by at most
//! `γ₃ Σ_j |M_ij||p_j| ≤ 3.01u·r` (rows of norm `≤ 1 + 2⁻⁴⁵`), the sum
//! adds `u(|Mp|_i + |o_i|)`, so a vertex is within `√3·u(4.02 r + R_O)
//! < e = 8·2⁻⁵²(r + R_O)` of its exact value. The mesh is the exact hull of
//! rounded vertices among which is the rounded counterpart of every
//! vertex of the exact slice (`sum::merge`: kept corners are the exact
//! slice's vertices, and a corner a repair leaves out lies inside the
//! checked result), so `S(M_k) ⊆ conv(mesh_k) ⊕ ball(e)`, and the slice
//! computed for `M` is within `e` of `S(M)`. With `H = conv(mesh_k ∪
//! mesh_{k+1})` (or `conv(mesh_c)`), every certified slice lies in
//! `H ⊕ ball(m)`, the **margin**
//!
//! ```text
//! m = r(σ(δ + 2ε) + 3ε) + 2e      (between orientations)
//! m = r(ρ + 3ε) + 2e              (in a cell)
//! ```
//!
//! **The half-spaces.** `H` is the exact hull of the float vertices
//! ([`crate::hull::convex_hull`] through [`Polytope::from_dvec3s`]: exact
//! predicates, maximal faces). For each face, `n` is its float unit normal
//! and the offset `d ≥ max_{v ∈ H} n·v + |n|·m`: the maximum is bounded
//! from above rigorously by the near-extreme search of `query::support`
//! (hill climbing, then every vertex within the float dot products' error
//! bound of the best; `H`'s vertices are exact, so its `η` is 0), `|n|`,
//! `σ` and every sum are rounded up. Then `H ⊕ ball(m) ⊆ {x : n·x ≤ d}`
//! for every face, whatever the rounding of `n`: the slab is never too
//! small. `σ(δ)` is bounded by `2(x − x³/6 + x⁵/120)²`, `x = min(δ, π)/4`
//! (`sin x` is below its quintic Taylor polynomial for `0 ≤ x ≤ π/2`),
//! rounded up; `δ` is bounded from above from the quaternions.
//!
//! A face whose unit normal is within `2⁻³⁰` of a kept neighbour's shares
//! that neighbour's plane: rounding bends the slices' faces of four or
//! more corners, and the exact hull splits them into nearly coplanar
//! triangles. Leaving a half-space out only enlarges the slab (its plane
//! turned by at most `2⁻³⁰` rad onto the neighbour's), and spares the
//! planner, and [`Slab::mesh`], thousands of slivers.
//!
//! # How tight
//! `H` is the hull of two slices of the swept set, so its support function
//! is at most the swept set's, and each plane reaches at most `m` beyond
//! the swept C-obstacle in its own direction: about `r δ²/8` for a step
//! `δ`, so four times more slices make the slabs sixteen times tighter
//! (the table in `docs/BENCHMARKS.md`, "Certified C-obstacle slabs").
//! Near a sharp vertex of `H` the polytope `{N x ≤ d}` reaches further, by
//! `m / cos` of half the angle between the planes there.
//!
//! The mesh of a slab, by exact polar duality ([`Slab::mesh`]), is made in
//! `slabs/mesh.rs`.
//!
//! ```
//! use dymsum::{DVec3, Polytope};
//! use dymsum::query::{certified_slabs_about_axis, full_turn_angles};
//! let corners = |x: f64, y: f64, z: f64| -> Vec<[f64; 3]> {
//!     (0..8).map(|i| [x * ((i & 1) as f64 - 0.5), y * (((i >> 1) & 1) as f64 - 0.5), z * (((i >> 2) & 1) as f64 - 0.5)]).collect()
//! };
//! let bar = Polytope::from_points(&corners(4.0, 0.2, 0.2))?;
//! let block = Polytope::from_points(&corners(1.0, 1.0, 1.0))?;
//! // 16 slabs covering a full turn about z.
//! let slabs = certified_slabs_about_axis(&bar, &block, DVec3::Z, &full_turn_angles(16))?;
//! assert_eq!(slabs.len(), 16);
//! // Half-spaces N x <= d ...
//! let s = &slabs[0];
//! assert_eq!(s.normals().len(), s.offsets().len());
//! // ... holding the bar's tip swept through the first sixteenth of a turn.
//! let tip = |angle: f64| DVec3::new(-2.0 * angle.cos(), -2.0 * angle.sin(), 0.0);
//! assert!(s.contains(tip(0.1)));
//! assert!(!s.contains(DVec3::new(3.0, 0.0, 0.0)));
//! // The same slab as a mesh, checked exactly.
//! let mesh = s.mesh()?;
//! assert!(mesh.faces.len() >= 6);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod mesh;

use crate::kernel::exact::{self, Dyadic};
use crate::kernel::rotation::Rotation;
use crate::kernel::{bounds, Sign};
use crate::mesh::PolygonMesh;
use crate::polytope::Polytope;
use crate::query::cobstacle::halfspaces::HalfSpaces;
use crate::query::cobstacle::slices::CObstacle;
use crate::query::error::QueryError;
use crate::query::frame::up;
use crate::query::prep::BodyBounds;
use crate::query::proximity::support::{near_max, Marks};
use glam::DVec3;
pub use mesh::slab_meshes_par;
use rayon::prelude::*;

/// The slack `ε = 2⁻⁴⁰` by which every certified range of rotations is
/// widened (module docs): rotations within angle `ε` of the range's ends
/// or centre, and matrices within `ε` of those rotations, so that the
/// rotations dymsum computes (their rounding and snapping, below `2⁻⁴²`)
/// are covered.
pub const ROTATION_SLACK: f64 = 9.094_947_017_729_282e-13;

/// Faces of the slices' hull whose unit normals are within this (`2^-30`)
/// of a kept neighbour's share its plane (module docs).
const SAME_PLANE: f64 = 9.313_225_746_154_785e-10;

/// Normal components below this (`2^-200`) are set to zero.
const TINY_COMPONENT: f64 = 6.223_015_277_861_142e-61;

/// `π` rounded up (the next float above `f64::consts::PI`).
const PI_UP: f64 = 3.141_592_653_589_793_6;

pub use crate::query::error::SlabError;

/// The orientations a slab is certified for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SlabCover {
    /// Every rotation on a shortest path from `from` to `to` (widened by
    /// [`ROTATION_SLACK`], see the module docs).
    Path {
        /// The first end.
        from: Rotation,
        /// The second end.
        to: Rotation,
        /// An upper bound on the angle between them (radians), slack
        /// included.
        angle: f64,
    },
    /// Every rotation within `radius` of `centre` (widened by
    /// [`ROTATION_SLACK`]).
    Cell {
        /// The centre.
        centre: Rotation,
        /// The radius (radians).
        radius: f64,
    },
}

/// A certified C-obstacle slab: the half-spaces `{x : n_i·x ≤ d_i}` whose
/// intersection contains every slice `O ⊕ (−R·A)` for the orientations
/// `R` of its [`SlabCover`] (see the [module docs](self) for the precise
/// statement). Built by [`CObstacle::certified_slabs`],
/// [`CObstacle::certified_slab_in_cell`], [`CObstacle::certified_slabs_in_cells`]
/// and the functions of this module.
#[derive(Clone, Debug)]
pub struct Slab {
    planes: HalfSpaces,
    hull: Polytope,
    margin: f64,
    cover: SlabCover,
}

impl Slab {
    /// The unit outward normals `n_i`, one per face of [`Slab::hull`] (float
    /// constructions; the containment holds for them as they are).
    pub fn normals(&self) -> &[DVec3] {
        self.planes.normals()
    }

    /// The offsets `d_i`, rounded outward: the slab is `{x : n_i·x ≤ d_i}`.
    pub fn offsets(&self) -> &[f64] {
        self.planes.offsets()
    }

    /// The slab as [`HalfSpaces`] (the same planes).
    pub fn half_spaces(&self) -> &HalfSpaces {
        &self.planes
    }

    /// The number of half-spaces.
    pub fn len(&self) -> usize {
        self.planes.len()
    }

    /// `true` when the slab has no half-space (never: a slab is bounded).
    pub fn is_empty(&self) -> bool {
        self.planes.is_empty()
    }

    /// The exact hull of the slices the slab was built from (the two ends'
    /// slices, or the cell centre's), whose face planes, pushed out by
    /// [`Slab::margin`], are the half-spaces.
    pub fn hull(&self) -> &Polytope {
        &self.hull
    }

    /// How far each plane is pushed beyond the hull (per unit of normal
    /// length): the sagitta or `r·ρ` term plus the rounding terms.
    pub fn margin(&self) -> f64 {
        self.margin
    }

    /// The orientations the slab is certified for.
    pub fn cover(&self) -> SlabCover {
        self.cover
    }

    /// Whether `x` satisfies every `n_i·x ≤ d_i`, decided exactly (a float
    /// filter, then exact arithmetic); `false` for a non-finite `x`.
    pub fn contains(&self, x: DVec3) -> bool {
        x.is_finite()
            && self
                .planes
                .normals()
                .iter()
                .zip(self.planes.offsets())
                .all(|(&n, &d)| slack_sign(n, d, x) != Sign::Negative)
    }
}

/// The exact sign of `d − n·x`: a float filter, then exact arithmetic.
fn slack_sign(n: DVec3, d: f64, x: DVec3) -> Sign {
    let (v, err) = bounds::dot(n, 0.0, x, 0.0);
    let diff = d - v;
    let bound = 1.01 * (err + diff.abs() * f64::EPSILON) + f64::MIN_POSITIVE;
    Sign::certified(diff, bound).unwrap_or_else(|| {
        Dyadic::from_f64(d)
            .sub(&exact::dot(&exact::exact(n), &exact::exact(x)))
            .sign()
    })
}

/// A float at least `x` and at least the value `x` was rounded from, when
/// `x` is the result of one rounded operation (one ulp up, or more).
#[inline]
fn above(x: f64) -> f64 {
    x + (x.abs() * f64::EPSILON + f64::MIN_POSITIVE)
}

/// A float at most `x` (the mirror of [`above`]).
#[inline]
fn below(x: f64) -> f64 {
    -above(-x)
}

/// The largest coordinate magnitude of `points`.
fn max_coordinate(points: &[DVec3]) -> f64 {
    points
        .iter()
        .fold(0.0, |m: f64, v| m.max(v.abs().max_element()))
}

/// An upper bound on the sagitta factor `σ(δ) = 1 − cos(δ/2)` for an
/// angle bound `delta ≥ 0` (module docs): `2 sin²(x)`, `x = min(δ, π)/4`,
/// with `sin x ≤ x − x³/6 + x⁵/120`, rounded up.
fn sagitta_factor(delta: f64) -> f64 {
    let x = delta.clamp(0.0, PI_UP) / 4.0;
    let x2 = x * x;
    let s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0));
    // About ten roundings of relative size u each, squared and doubled:
    // (1 + 64·2^-52) covers them with room to spare.
    2.0 * s * s * (1.0 + 64.0 * f64::EPSILON) + f64::MIN_POSITIVE
}

/// An upper bound on the angle of the rotation between `a` and `b`: the
/// float angle (`Rotation::angle_to`: a quaternion product, a norm and an
/// `atan2`, each within a few ulps) plus `2⁻⁴⁵`.
fn angle_bound(a: &Rotation, b: &Rotation) -> f64 {
    up(a.angle_to(b)) + 2.842_170_943_040_401e-14
}

/// The bounds shared by every slab of one robot and obstacle.
#[derive(Clone, Copy, Debug)]
struct Reach {
    /// `r`: the robot's largest `|a|`, rounded up.
    robot: f64,
    /// `e`: the rounding of a slice vertex, `8·2⁻⁵²(r + R_O)`, rounded up.
    slice_rounding: f64,
}

impl Reach {
    fn of(c: &CObstacle) -> Result<Reach, QueryError> {
        let robot = BodyBounds::of(c.reflected_robot()).reach;
        let obstacle = BodyBounds::of(c.obstacle()).reach;
        let slice_rounding = up(8.0 * f64::EPSILON * up(robot + obstacle));
        if !slice_rounding.is_finite() {
            return Err(QueryError::OutOfRange(
                "the robot's or the obstacle's coordinates are too large for a slab's bounds"
                    .into(),
            ));
        }
        Ok(Reach {
            robot,
            slice_rounding,
        })
    }

    /// The margin `r·(factor + 3ε) + 2e`, rounded up.
    fn margin(&self, factor: f64) -> f64 {
        up(up(self.robot * up(factor + 3.0 * ROTATION_SLACK)) + 2.0 * self.slice_rounding)
    }
}

/// The vertices of a slice's mesh.
fn slice_points(mesh: &PolygonMesh) -> Vec<DVec3> {
    mesh.vertices.iter().map(|&v| DVec3::from(v)).collect()
}

/// The slab around the hull of `points` with every plane pushed out by
/// `margin` (module docs).
fn slab_around(points: &[DVec3], margin: f64, cover: SlabCover) -> Result<Slab, QueryError> {
    let hull = Polytope::from_dvec3s(points)
        .map_err(|e| QueryError::Inconsistent(format!("the hull of the slices failed: {e}")))?;
    let scale = max_coordinate(hull.vertices());
    let (mut marks, mut set) = (Marks::default(), Vec::new());
    let mut normals = Vec::with_capacity(hull.face_count());
    let mut offsets = Vec::with_capacity(hull.face_count());
    let mut kept: Vec<Option<DVec3>> = Vec::with_capacity(hull.face_count());
    for f in 0..hull.face_count() {
        // Components below 2^-200 are dropped (the offset is computed for
        // the normal as kept), so exact evaluations of the planes stay
        // within a few hundred bits.
        let n = DVec3::from(hull.unit_normal(f).to_array().map(|x| {
            if x.abs() < TINY_COMPONENT {
                0.0
            } else {
                x
            }
        }));
        // A face nearly coplanar with a kept neighbour shares its plane.
        let twin = hull.face_edges(f).iter().any(|&e| {
            let [l, r] = hull.edge(e as usize).faces;
            let g = if l as usize == f { r } else { l } as usize;
            g < f && kept[g].is_some_and(|m| (m - n).length() <= SAME_PLANE)
        });
        if twin {
            kept.push(None);
            continue;
        }
        kept.push(Some(n));
        let top = near_max(
            &hull,
            |v| hull.vertex(v as usize),
            n,
            hull.face(f)[0],
            0.0,
            0.0,
            scale,
            &mut marks,
            &mut set,
        );
        let d = above(above(top.upper) + above(up(n.length()) * margin));
        if !d.is_finite() || !n.is_finite() {
            return Err(QueryError::OutOfRange(format!(
                "a slab offset overflows f64 (face {f} of the slices' hull)"
            )));
        }
        normals.push(n);
        offsets.push(d);
    }
    Ok(Slab {
        planes: HalfSpaces::from_parts(normals, offsets),
        hull,
        margin,
        cover,
    })
}

/// The slab between two consecutive orientations and their slices' vertices.
fn slab_between(
    reach: &Reach,
    (from, to): (Rotation, Rotation),
    (p, q): (&[DVec3], &[DVec3]),
) -> Result<Slab, QueryError> {
    let angle = angle_bound(&from, &to) + 2.0 * ROTATION_SLACK;
    let margin = reach.margin(sagitta_factor(angle));
    let points: Vec<DVec3> = p.iter().chain(q).copied().collect();
    slab_around(&points, margin, SlabCover::Path { from, to, angle })
}

impl CObstacle {
    /// The certified slabs between consecutive orientations: slab `k`
    /// contains every slice for the rotations on a shortest path from
    /// `orientations[k]` to `orientations[k + 1]` (module docs), so `K`
    /// orientations give `K − 1` slabs (repeat the first orientation at the
    /// end to close a turn). The slices are computed by one dynamic sum
    /// moved from orientation to orientation, as [`CObstacle::slices`].
    ///
    /// ```
    /// use dymsum::query::{rotations_about_axis, full_turn_angles};
    /// use dymsum::{CObstacle, DVec3, Polytope};
    /// let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])?;
    /// let block = Polytope::from_points(&[[2., 0., 0.], [3., 0., 0.], [2., 1., 0.], [2., 0., 1.]])?;
    /// let cobst = CObstacle::new(&tet, &block)?;
    /// let turns = rotations_about_axis(DVec3::new(1.0, 2.0, 3.0), &full_turn_angles(12))?;
    /// let slabs = cobst.certified_slabs(&turns)?;
    /// assert_eq!(slabs.len(), 12);
    /// // Every slice is inside the slabs next to it.
    /// for (k, turn) in turns.iter().enumerate().take(12) {
    ///     let slice = cobst.slice(*turn)?;
    ///     let inside = |s: &dymsum::query::Slab| slice.vertices.iter().all(|&v| s.contains(v.into()));
    ///     assert!(inside(&slabs[k]) && inside(&slabs[(k + 11) % 12]));
    /// }
    /// assert_eq!(cobst.certified_slabs_par(&turns)?.len(), 12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`QueryError::Slab`] ([`SlabError::TooFewOrientations`]) for fewer
    /// than two orientations; those of [`CObstacle::slices`] (a slice's
    /// mesh); [`QueryError::OutOfRange`] when a bound or offset overflows
    /// `f64`; [`QueryError::Inconsistent`] only for an internal error.
    pub fn certified_slabs(&self, orientations: &[Rotation]) -> Result<Vec<Slab>, QueryError> {
        let reach = self.slab_reach(orientations)?;
        let mut out = Vec::with_capacity(orientations.len() - 1);
        let mut previous: Option<Vec<DVec3>> = None;
        for (k, slice) in self.slices(orientations).enumerate() {
            let points = slice_points(&slice?);
            if let Some(p) = &previous {
                let ends = (orientations[k - 1], orientations[k]);
                out.push(slab_between(&reach, ends, (p, &points))?);
            }
            previous = Some(points);
        }
        Ok(out)
    }

    /// [`CObstacle::certified_slabs`] on rayon's threads: the slices in
    /// parallel chunks ([`CObstacle::map_par`]), then the slabs in parallel
    /// (the same slabs, in order).
    ///
    /// # Errors
    /// The same as [`CObstacle::certified_slabs`] (the first in order).
    pub fn certified_slabs_par(&self, orientations: &[Rotation]) -> Result<Vec<Slab>, QueryError> {
        let reach = self.slab_reach(orientations)?;
        let slices: Vec<Vec<DVec3>> = self
            .map_par(orientations, |_, _, s| {
                s.try_to_mesh().map(|m| slice_points(&m))
            })?
            .into_iter()
            .collect::<Result<_, _>>()?;
        (0..orientations.len() - 1)
            .into_par_iter()
            .map(|k| {
                let ends = (orientations[k], orientations[k + 1]);
                slab_between(&reach, ends, (&slices[k], &slices[k + 1]))
            })
            .collect()
    }

    /// Checks that there are at least two orientations; the bounds.
    fn slab_reach(&self, orientations: &[Rotation]) -> Result<Reach, QueryError> {
        if orientations.len() < 2 {
            return Err(SlabError::TooFewOrientations {
                count: orientations.len(),
            }
            .into());
        }
        Reach::of(self)
    }

    /// The certified slab of an orientation cell: it contains every slice
    /// for the rotations within angle `radius` of `centre` (module docs),
    /// the centre's slice with every face plane pushed out by
    /// `r·radius` (and the rounding terms).
    ///
    /// ```
    /// use dymsum::{CObstacle, DVec3, Polytope, Rotation};
    /// let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])?;
    /// let cobst = CObstacle::new(&tet, &tet)?;
    /// let centre = Rotation::from_axis_angle(DVec3::new(1.0, 1.0, 0.0), 0.3).ok_or("axis")?;
    /// let slab = cobst.certified_slab_in_cell(centre, 0.05)?;
    /// let near = Rotation::from_axis_angle(DVec3::new(0.0, 1.0, 1.0), 0.04).ok_or("axis")?.then(&centre);
    /// assert!(cobst.slice(near)?.vertices.iter().all(|&v| slab.contains(v.into())));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`QueryError::Slab`] ([`SlabError::BadRadius`]) unless
    /// `0 ≤ radius < π`; those of [`CObstacle::slice`];
    /// [`QueryError::OutOfRange`] when a bound or offset overflows `f64`;
    /// [`QueryError::Inconsistent`] only for an internal error.
    pub fn certified_slab_in_cell(
        &self,
        centre: Rotation,
        radius: f64,
    ) -> Result<Slab, QueryError> {
        let margin = self.cell_margin(radius)?;
        let points = slice_points(&self.slice(centre)?);
        slab_around(&points, margin, SlabCover::Cell { centre, radius })
    }

    /// The certified slabs of the cells of one `radius` about each of
    /// `centres` (one slab per centre, in order): slab `k` contains every
    /// slice for the rotations within angle `radius` of `centres[k]`, as
    /// [`CObstacle::certified_slab_in_cell`] (module docs), the centres'
    /// slices computed by one dynamic sum moved from centre to centre, as
    /// [`CObstacle::slices`] (fastest when consecutive centres are close).
    ///
    /// ```
    /// use dymsum::{CObstacle, DVec3, Polytope, Rotation};
    /// let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])?;
    /// let cobst = CObstacle::new(&tet, &tet)?;
    /// let centres: Vec<Rotation> = (0..4)
    ///     .map(|k| Rotation::from_axis_angle(DVec3::new(1.0, 1.0, 0.0), 0.2 * k as f64).ok_or("axis"))
    ///     .collect::<Result<_, _>>()?;
    /// let slabs = cobst.certified_slabs_in_cells(&centres, 0.1)?;
    /// assert_eq!(slabs.len(), 4);
    /// let near = Rotation::from_axis_angle(DVec3::Z, 0.1).ok_or("axis")?.then(&centres[2]);
    /// assert!(cobst.slice(near)?.vertices.iter().all(|&v| slabs[2].contains(v.into())));
    /// assert_eq!(cobst.certified_slabs_in_cells_par(&centres, 0.1)?[2].offsets(), slabs[2].offsets());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// Those of [`CObstacle::certified_slab_in_cell`] (the first in order);
    /// those of [`CObstacle::slices`].
    pub fn certified_slabs_in_cells(
        &self,
        centres: &[Rotation],
        radius: f64,
    ) -> Result<Vec<Slab>, QueryError> {
        let margin = self.cell_margin(radius)?;
        self.slices(centres)
            .zip(centres)
            .map(|(slice, &centre)| {
                let cover = SlabCover::Cell { centre, radius };
                slab_around(&slice_points(&slice?), margin, cover)
            })
            .collect()
    }

    /// [`CObstacle::certified_slabs_in_cells`] on rayon's threads: the
    /// slices in parallel chunks ([`CObstacle::map_par`]), then the slabs
    /// in parallel (the same slabs, in order).
    ///
    /// # Errors
    /// The same as [`CObstacle::certified_slabs_in_cells`] (the first in
    /// order).
    pub fn certified_slabs_in_cells_par(
        &self,
        centres: &[Rotation],
        radius: f64,
    ) -> Result<Vec<Slab>, QueryError> {
        let margin = self.cell_margin(radius)?;
        let slices: Vec<Vec<DVec3>> = self
            .map_par(centres, |_, _, s| s.try_to_mesh().map(|m| slice_points(&m)))?
            .into_iter()
            .collect::<Result<_, _>>()?;
        slices
            .par_iter()
            .zip(centres)
            .map(|(points, &centre)| {
                slab_around(points, margin, SlabCover::Cell { centre, radius })
            })
            .collect()
    }

    /// Checks a cell radius (`0 ≤ radius < π`); the margin `r·ρ` plus the
    /// rounding terms (module docs).
    fn cell_margin(&self, radius: f64) -> Result<f64, QueryError> {
        if !(0.0..std::f64::consts::PI).contains(&radius) {
            return Err(SlabError::BadRadius { radius }.into());
        }
        Ok(Reach::of(self)?.margin(radius))
    }
}

/// The angles `2πk/n` for `k = 0..=n` (the last is `2π`, the same rotation
/// as the first): `n` slabs covering a full turn with
/// [`certified_slabs_about_axis`].
pub fn full_turn_angles(n: usize) -> Vec<f64> {
    (0..=n)
        .map(|k| std::f64::consts::TAU * k as f64 / n as f64)
        .collect()
}

/// The rotations about `axis` by `angles`, checked for slabs: the axis
/// non-zero and finite (scaled to `[1, 2)` by a power of two first, so
/// that its length is accurate at any scale), at least two angles, all
/// finite, strictly increasing, consecutive ones at most `π` apart.
///
/// # Errors
/// The offending input as a [`SlabError`].
pub fn rotations_about_axis(axis: DVec3, angles: &[f64]) -> Result<Vec<Rotation>, SlabError> {
    let bad_axis = || SlabError::BadAxis {
        axis: axis.to_array(),
    };
    if !axis.is_finite() || axis == DVec3::ZERO {
        return Err(bad_axis());
    }
    let axis = exact::mul_pow2_vec(axis, exact::frame_exponent(axis.to_array().into_iter()));
    if angles.len() < 2 {
        return Err(SlabError::TooFewOrientations {
            count: angles.len(),
        });
    }
    for (index, &angle) in angles.iter().enumerate() {
        if !angle.is_finite() {
            return Err(SlabError::NonFiniteAngle { index, angle });
        }
        if index > 0 {
            let previous = angles[index - 1];
            if angle <= previous {
                return Err(SlabError::NotIncreasing {
                    index,
                    previous,
                    angle,
                });
            }
            let step = angle - previous;
            if step > std::f64::consts::PI {
                return Err(SlabError::StepTooLarge { index, step });
            }
        }
    }
    angles
        .iter()
        .map(|&a| Rotation::from_axis_angle(axis, a).ok_or_else(bad_axis))
        .collect()
}

/// Certified slabs of `robot` turning about `axis` among `obstacle`: slab
/// `k` holds every slice for the turns by the angles in
/// `[angles[k], angles[k + 1]]` (so `K` angles give `K − 1` slabs; pass
/// [`full_turn_angles`] for a full turn), computed sequentially by one
/// dynamic sum (see [`CObstacle::certified_slabs`] and the module docs).
///
/// # Errors
/// The input checks of [`rotations_about_axis`] as [`QueryError::Slab`],
/// then those of [`CObstacle::new`] and [`CObstacle::certified_slabs`].
pub fn certified_slabs_about_axis(
    robot: &Polytope,
    obstacle: &Polytope,
    axis: DVec3,
    angles: &[f64],
) -> Result<Vec<Slab>, QueryError> {
    let turns = rotations_about_axis(axis, angles)?;
    CObstacle::new(robot, obstacle)?.certified_slabs(&turns)
}

/// [`certified_slabs_about_axis`] on rayon's threads (the same slabs).
///
/// # Errors
/// The same as [`certified_slabs_about_axis`].
pub fn certified_slabs_about_axis_par(
    robot: &Polytope,
    obstacle: &Polytope,
    axis: DVec3,
    angles: &[f64],
) -> Result<Vec<Slab>, QueryError> {
    let turns = rotations_about_axis(axis, angles)?;
    CObstacle::new(robot, obstacle)?.certified_slabs_par(&turns)
}

/// The certified slab of `robot` among `obstacle` for every orientation
/// within angle `radius` of `centre` (see
/// [`CObstacle::certified_slab_in_cell`]).
///
/// # Errors
/// Those of [`CObstacle::new`] and [`CObstacle::certified_slab_in_cell`].
pub fn certified_slab_in_cell(
    robot: &Polytope,
    obstacle: &Polytope,
    centre: Rotation,
    radius: f64,
) -> Result<Slab, QueryError> {
    CObstacle::new(robot, obstacle)?.certified_slab_in_cell(centre, radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sagitta_bound_is_above_the_sagitta_and_tight() {
        for i in 0..=1000 {
            let delta = std::f64::consts::PI * i as f64 / 1000.0;
            // 1 − cos(δ/2) without cancellation.
            let exact = 2.0 * (delta / 4.0).sin().powi(2);
            let bound = sagitta_factor(delta);
            assert!(bound >= exact, "δ = {delta}: {bound} < {exact}");
            assert!(
                bound <= exact * 1.0002 + 1e-300,
                "δ = {delta}: {bound} vs {exact}"
            );
        }
        // Beyond π the bound stays at the half turn's (the path is shortest).
        assert_eq!(sagitta_factor(4.0), sagitta_factor(PI_UP));
        assert!(sagitta_factor(PI_UP) >= 1.0);
    }

    #[test]
    fn the_rotation_slack_is_two_to_the_minus_forty() {
        assert_eq!(ROTATION_SLACK, 2f64.powi(-40));
        assert_eq!(PI_UP, f64::from_bits(std::f64::consts::PI.to_bits() + 1));
        assert_eq!(
            angle_bound(&Rotation::IDENTITY, &Rotation::IDENTITY),
            2f64.powi(-45)
        );
    }

    #[test]
    fn rounding_helpers_move_outward() {
        for x in [0.0, 1.0, -1.0, 1e-310, -1e300, 3.5e-20] {
            assert!(above(x) > x && below(x) < x, "{x}");
        }
    }

    #[test]
    fn exact_side_decides_ties_and_near_ties() {
        let n = DVec3::new(0.6, 0.8, 0.0);
        let x = DVec3::new(1.0, 1.0, 5.0);
        let d = n.dot(x); // 1.4 rounded: the exact n·x differs from it
        let exact_side = slack_sign(n, d, x);
        let diff = Dyadic::from_f64(d)
            .sub(&exact::dot(&exact::exact(n), &exact::exact(x)))
            .sign();
        assert_eq!(exact_side, diff);
        assert_eq!(slack_sign(DVec3::X, 1.0, DVec3::X), Sign::Zero);
        assert_eq!(
            slack_sign(DVec3::X, 1.0, DVec3::new(1.0 + f64::EPSILON, 0.0, 0.0)),
            Sign::Negative
        );
    }
}
