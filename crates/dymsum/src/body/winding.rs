//! Whether a point lies inside a body, exactly: the winding number of its
//! enclosing triangles about the point (the signed count of a ray's
//! crossings with them) is not zero.
//!
//! Precondition: the point is on no triangle of the body (the scenes'
//! checker asks only after finding that no triangles of the two bodies
//! meet, and the point is a corner of one of them). A point in a classified
//! cell of the body's [`super::inside_grid`] is answered from the cell
//! instead, with the same answer (that module's docs).
//!
//! The ray is the segment from `p` to `q = p + L d`, `L` large enough that
//! `q` lies outside the body's box. It *crosses* triangle `abc` when `p`
//! and `q` lie strictly on opposite sides of its plane
//! (`orient3d(a, b, c, ·)` of opposite nonzero signs) and the line `pq`
//! passes strictly inside it (`orient3d(p, q, a, b)`, `(p, q, b, c)`,
//! `(p, q, c, a)` of one nonzero sign). It misses when the plane's signs
//! agree or one is zero (`p` in the plane but off the triangle, by the
//! precondition; `q` in the plane but outside the box), or when the edge
//! signs disagree strictly. Anything else (the segment in the plane, or
//! through an edge or a corner) is *degenerate*, and the next of a fixed
//! list of directions is tried. A crossing counts the triangle's weight
//! (how many coincident copies of it enclose) with a `+` sign when `p` lies
//! on its positive side (`orient3d(a, b, c, p) > 0`) and a `−` sign
//! otherwise. Each solid component is a cycle (every edge, split at the
//! vertices on it, run as often each way: [`crate::solid::soup`]), so the
//! signed count of a ray that is not degenerate and ends outside the
//! component's box is its winding number about `p`, the same for every such
//! ray; a component whose box does not hold `p` has winding number zero
//! there and is not counted. The point is inside when the winding number
//! of some body is not zero: a scene joins its obstacles into one body, and
//! each obstacle's components are summed by themselves (one obstacle's
//! inward shell, winding `−1` and inside it, must not cancel another
//! obstacle's solid around the same point). With every sign exact the answer is exact. A
//! point for which all directions are degenerate gets no answer from the
//! ray (`windings_by_ray` returns `None`; the queries then return
//! `QueryError::OutOfRange` naming it), never a guess; `inside_solid`
//! answers from a classified cell of the grid whatever that point's own
//! rays do.
//!
//! # Segments between points
//! A containment test asks one point per component, and the points of a
//! small part's many shells lie close together, while each ray walks the
//! other body's tree from its root and out of its box. Where the windings
//! about an earlier point `a` are known (per source, each component's
//! number, not only "inside"), those about the next point `p` follow from
//! the segment `ap` alone:
//!
//! `W(p) = W(a) − Σ s(T) w(T)` over the triangles `T` the segment
//! crosses, `s(T) = +1` where `a` lies on `T`'s positive side, else `−1`,
//!
//! with `W(x)` the ray's count from `x` (above: `+w` for a crossed
//! triangle with `x` on its positive side). Why: both ends are on no
//! triangle (the precondition). Each component is a cycle, so its winding
//! number is defined off its triangles, constant where the segment meets
//! none, and changes by `±w` exactly where the segment passes from one
//! side of a triangle to the other through its inside, with the sign that
//! makes the ray's count right: a ray from `a` that crosses `T` and ends
//! outside counts `s(T) w(T)`, and so does the segment from `a` across
//! `T`, whose far side has `s(T) w(T)` less. A segment is classified by
//! the same exact signs as a ray (`crossing(a, p, T)`: the segment's start
//! where the ray has its start, its end as `q`): it misses a
//! triangle whose plane it touches only at an end (an end in the plane is
//! off the triangle, by the precondition), and anything else that is not
//! a clean crossing (in the plane, through an edge or a corner) makes it
//! *degenerate*: then no answer is taken from it, and the point gets its
//! own ray as before. The components counted are every solid component
//! whose box meets the segment's (one whose box holds neither end winds
//! zero times about both, so its crossings sum to zero whether counted or
//! not), and the sum is kept per source, as the ray's is.
//!
//! Where many points lie in a small box (a part's shells at a pose), the
//! triangles whose boxes meet that box are listed once (up to a bound),
//! and each segment between two of those points reads the list instead of
//! walking the tree: a triangle the segment crosses has a point in the
//! segment's box, which lies in the points' box, so its box (which holds
//! it) meets that box and it is listed; those whose boxes miss the
//! segment's are skipped, as the tree's walk skips them (a far triangle
//! in the plane of both ends would make the segment degenerate). An
//! independent review (2026-12-01) checked that every segment's ends are
//! corners of the list's box, that every crossed triangle is listed, and
//! the bound's stop at 64 and 65; its remark, the skipping above, is
//! applied.
//!
//! A listed triangle keeps its corners as posed for the list (the floats
//! every segment's signs read, posed once) and the last point whose side
//! of its plane was found, with that side: consecutive segments share an
//! end, and the side is a function of the corners and the point's
//! coordinates alone, so it is read back for a point equal to that one
//! and found afresh for any other. Where many segments will read the list
//! (`query::scene::state`: more than eight corners), the triangles whose
//! planes have all eight corners of the list's box strictly on one side
//! (exact signs) are dropped from it, and so are those whose shadow on a
//! coordinate plane has the box's shadow strictly beyond one of its
//! edges (exact 2-D signs, `edge_clears_box`: on a face of a robot part
//! split into many triangles, every plane cuts the box while one triangle
//! of dozens meets it): every segment lies in that box, so it misses each
//! of them, and a miss adds nothing (not even a degenerate one: a
//! segment in the plane of a triangle it does not touch crosses nothing
//! there). Test:
//! `a_list_read_by_a_chain_of_segments_gives_the_rays_windings` (it fails
//! when a side is read for another point, and when a cutting plane is
//! dropped; and `query::scene::state`'s
//! `many_corners_by_a_face_read_one_culled_list` when the list is culled
//! for a smaller box than the corners'). On a Centauro head base (mm)
//! against a Cassie hip pitch link (m, 47 solids, all in one head cell
//! that meets its surface) this took the slowest random states from about
//! 1.07 M instructions to about 0.45 M (docs/BENCHMARKS.md, "One list,
//! posed once, and the corners together"). An independent review
//! (2026-12-01, sixth stop) checked that every segment's ends are corners
//! of the list's box (the `known` of the scene-corner loop is only ever
//! set to one of them), that a dropped triangle can only be missed, never
//! met degenerately, and that the side read back is a pure function of
//! equal coordinates (−0.0 and 0.0 alike; the NaN start equals nothing);
//! its mutations of the side and of the culled box fail the tests, and its
//! remark on this function's list contract is applied.
//!
//! A point is *known* when its windings were found by a ray or a segment,
//! or when the grid says it is outside (every source winds zero times
//! there) or reads it in an inside cell whose windings it kept (a
//! classified cell's answer holds for its points,
//! [`super::inside_grid`], and at a pose, `query::scene::state`'s "The grid
//! at a pose"). The segment is tried only where it is shorter than the
//! way out of the solids' box along an axis (a ray walks at least that);
//! this chooses the order of two exact methods, never an answer. So,
//! where no known point lies on a triangle, every answer is the ray's,
//! but where every ray of a point is degenerate and a segment is not:
//! that point is now decided instead of an error. In the scene checker's
//! first asking, before the walk, a known point may lie on a triangle
//! (the bodies touch), and a later point's windings may then be off by
//! that triangle's weight; any "inside" there is a collision anyway, and
//! an "outside" lets the walk find the contact
//! (`query::scene::state`, "Containment first"). Test:
//! `segments_between_points_give_the_rays_windings` (it fails when the
//! segment's crossings take the ray's sign). On a TIAGo Pro fingertip of
//! 22 shells near a human abdomen (example-robot-data), a random state
//! took 9% fewer instructions on average, the Centauro pelvis (945
//! shells) against a G1 ankle link 14% (docs/BENCHMARKS.md, "Segments
//! between points and no triangle against a leaf's box").
//!
//! An independent review (2026-12-01) found the argument and the code
//! sound: the sign against the ray's convention, the candidates (a box
//! holding an end always meets the segment's; the others sum to zero;
//! surfaces are never counted), the grid's "outside" as every source
//! winding zero, `parity` all zero after every state, no new panic. Its
//! randomized comparison with rays alone (clusters of 10 to 30 shells:
//! boxes, tetrahedra, inward shells, cavities, open boxes, double-sided
//! squares, beside and inside a box with a cavity, an island and a bar,
//! either side the larger body; identity, quarter and random turns;
//! offsets up to 3·10⁸; about 636,000 state checks and 1.2 million
//! segments) found no disagreement in any answer; a segment's windings
//! differed from its point's own ray only in the first askings of states
//! in contact, as above. Its wording remarks are applied.
//!
//! # A start outside
//! The first point of a containment test, or one far from the point
//! decided before, would take a ray: it walks the tree from the point out
//! of the solids' box. Where the body's grid has cells, a point `q` one
//! cell width from `p` (else two) along one of the rays' first six
//! directions (nearly along the axes: a thin box for the tree) is tried
//! instead, the first that the grid reads as outside (or, below, in an
//! inside cell whose windings it kept): then every source winds zero
//! times about `q`, and `q` lies on no triangle of a solid (its cell meets
//! none), so `q` is a known point and the segment `qp` decides `p` as
//! above (`W(q) = 0`), where it is shorter than the way out. In the
//! scene checker the body's grid is read at a pose as for a corner: `q` is
//! carried back with the same rounding bound, and read only where its whole
//! box of rounding lies in one such cell (`query::scene::state`, "The
//! grid at a pose"); that segment may leave the corners' box, which their
//! list holds for segments between corners only, so it walks the tree
//! instead of reading the list. A degenerate segment falls back to
//! the ray, counted. This chooses the method, never the answer.
//!
//! A cell read as inside serves as well where the grid kept its region's
//! windings (`body::inside_grid`, "Windings kept"): every point of the
//! region has those windings, per source, and at a pose too (the map back
//! to the body's frame keeps each winding number, "The grid at a pose"),
//! so `q` is a known point with `W(q)` the kept windings, and the segment
//! from it decides `p` by the same formula. Here the signs matter (for an
//! outside cell every number is zero, whatever the orientation): the
//! grid is read at a pose only where the matrix is near a rotation with
//! `det M > 0.5`, which keeps each number, sign included. The first corner of a part
//! deep in the other's solid, where no outside cell lies within two, took
//! a ray before (test `a_first_corner_deep_in_a_solid_starts_from_an_inside_cell`
//! in `query::scene::state`: 150 rays before, none now; on the Centauro
//! link 1 against the Solo upper leg the slowest random states' rays were
//! 90% of their instructions, and the 99th percentile of 2,000 fell from
//! 15.4 to 10.3 µs). Tests:
//! `a_lone_speck_starts_from_an_outside_cell` (here) and
//! `query::scene::state`'s `a_first_corner_starts_from_an_outside_cell`
//! (each fails when a cell read inside is taken for outside, the second
//! also when no start is tried). On the Centauro head base against the
//! Cassie hip pitch link the rays of 2,000 random states went from 283 to
//! 5 (the segments cost about as much: the first corner's way, through the
//! head's surface by the corners, is what the walk pays for).
//!
//! An independent review (2026-12-01, seventh stop) found this sound: the
//! start is never kept as `known` (that holds corners only), a seeded
//! segment reads neither the list nor the components found for the
//! corners' box, the start is read at the pose exactly as a corner is (so
//! every source winds zero there and it lies on no posed solid triangle;
//! unposed, the closed cell is parted from every solid triangle), and the
//! counters count it as a segment. It also checked `plane_against_box`'s
//! bound (`γ₈ ≈ 2⁻⁵⁰` against the margin `2⁻⁴⁸`; underflow, overflow and
//! NaN give `None` or a correct answer; the least and greatest sums are
//! the float values at two real corners) on 600,000 adversarial inputs
//! (subnormal, near overflow, nearly flat triangles, boxes on the plane or
//! within ulps of it): no answer differed from the exact signs. Its
//! wording remark (the start's segment *may* leave the corners' box) is
//! applied.
//!
//! # Second reading (2026-11-28)
//! An independent review found the cycle argument sound (every solid
//! component closed edge for edge, weights included, so posing keeps it a
//! cycle; `tests/review_cycle_balance.rs` checks it on 100,000 random grid
//! soups) and one wrong answer, mended: a scene joins its obstacles, and a
//! sum over all of them let one obstacle's inward shell (winding `−1`,
//! inside it) cancel another's solid around the same point
//! (`tests/review_joined_winding.rs`); each obstacle is now summed by
//! itself. A triangle that posing rounds to collinear corners no longer
//! makes every ray through its box degenerate.

use std::borrow::Cow;

use glam::DVec3;

use crate::body::MeshBody;
use crate::kernel::predicates::{orient, orient2, Sign};
use crate::solid::aabb::Aabb;
use crate::solid::collinear;

/// The ray directions, tried in turn: nearly along each axis (thin ray
/// boxes for the tree), skewed by irrational-looking amounts so that
/// axis-aligned models rarely make a ray degenerate.
const DIRECTIONS: [[f64; 3]; 12] = [
    [1.0, 0.001_236_067_977, 0.000_707_106_781],
    [-1.0, 0.000_577_350_269, -0.001_414_213_562],
    [0.000_866_025_403, 1.0, 0.001_118_033_988],
    [-0.001_316_074_012, -1.0, 0.000_543_516_413],
    [0.000_693_147_180, -0.000_301_029_995, 1.0],
    [-0.000_271_828_182, 0.001_732_050_807, -1.0],
    [1.0, 0.618_033_988_749, 0.414_213_562_373],
    [-0.723_606_797_749, 1.0, -0.302_775_637_731],
    [0.267_949_192_431, -0.577_350_269_189, 1.0],
    [-1.0, -0.381_966_011_250, 0.732_050_807_568],
    [0.449_489_742_783, -1.0, -0.645_751_311_064],
    [-0.162_277_660_168, 0.236_067_977_499, -1.0],
];

/// The outcome of one ray against one triangle.
#[derive(PartialEq)]
enum Crossing {
    /// Crosses, with `p` on the triangle's positive side (`true`) or not.
    Crosses(bool),
    Misses,
    Degenerate,
}

fn crossing(p: DVec3, q: DVec3, t: [DVec3; 3]) -> Crossing {
    let (sp, sq) = (orient(t[0], t[1], t[2], p), orient(t[0], t[1], t[2], q));
    crossing_on_sides(p, q, t, sp, sq)
}

/// [`crossing`] given the sides of `t`'s plane that `p` and `q` lie on
/// (`orient(t, p)` and `orient(t, q)`).
fn crossing_on_sides(p: DVec3, q: DVec3, t: [DVec3; 3], sp: Sign, sq: Sign) -> Crossing {
    if sp == Sign::Zero && sq == Sign::Zero {
        // A triangle that posing rounded to collinear corners has no
        // inside to cross (its edges are other triangles' too, and they
        // still flag a ray through them); else the segment lies in the
        // plane.
        if collinear(t[0].to_array(), t[1].to_array(), t[2].to_array()) {
            return Crossing::Misses;
        }
        return Crossing::Degenerate;
    }
    if sp == sq || sp == Sign::Zero || sq == Sign::Zero {
        return Crossing::Misses;
    }
    let e = [
        orient(p, q, t[0], t[1]),
        orient(p, q, t[1], t[2]),
        orient(p, q, t[2], t[0]),
    ];
    let has = |s: Sign| e.contains(&s);
    if has(Sign::Positive) && has(Sign::Negative) {
        Crossing::Misses
    } else if has(Sign::Zero) {
        Crossing::Degenerate
    } else {
        Crossing::Crosses(sp == Sign::Positive)
    }
}

impl MeshBody {
    /// Whether `p` (in the body's frame, on none of its triangles) lies
    /// where the winding number of its enclosing triangles is not zero,
    /// exactly ([`super::winding`]): read from the body's grid where it
    /// knows ([`super::inside_grid`]), else by a segment or a ray. `known`
    /// may hold an earlier point and its windings: then the segment from it
    /// decides when it is shorter than a ray would be (module docs,
    /// "Segments between points"; exact when that point too is on none of
    /// the body's triangles); it is left holding `p` and its windings when
    /// they were found. `parity` is a scratch buffer.
    pub(crate) fn inside_solid(
        &self,
        p: DVec3,
        known: &mut Option<Known>,
        parity: &mut Vec<u8>,
        tally: &mut ContainmentStats,
    ) -> Option<bool> {
        match self.inside_grid().classify(p, 0.0) {
            Some(true) => {
                tally.by_grid += 1;
                Some(true)
            }
            Some(false) => {
                tally.by_grid += 1;
                *known = Some(Known::outside(p));
                Some(false)
            }
            None => {
                let placed = self.unposed();
                // Where no point decided before is near, a start in a
                // cell by `p`'s whose windings the grid knows (module
                // docs, "A start outside").
                let grid = self.inside_grid();
                let from = segment_start(
                    known.as_ref(),
                    p,
                    &self.solid_tree.root(),
                    grid.cell_width(),
                    |q| grid.windings_at(q, 0.0),
                );
                let along = from.as_ref().and_then(|k| {
                    let mut candidates = Vec::new();
                    self.solid_tree
                        .for_each_meeting(&Aabb::of([k.at.to_array(), p.to_array()]), |c| {
                            candidates.push(self.solid_components[c])
                        });
                    placed.windings_along(&candidates, k, p, None, parity)
                });
                let windings = match tally.count(from.is_some(), along) {
                    Some(w) => w,
                    None => placed.windings_by_ray(&self.candidates_at(p), p, parity)?,
                };
                let inside = some_winds(&windings);
                *known = Some(Known { at: p, windings });
                Some(inside)
            }
        }
    }

    /// [`MeshBody::inside_solid`] by a ray alone.
    #[cfg(test)]
    pub(crate) fn inside_by_ray(&self, p: DVec3, parity: &mut Vec<u8>) -> Option<bool> {
        self.windings_by_ray(p, parity).map(|w| some_winds(&w))
    }

    /// The windings about `p` (in the body's frame, on none of its
    /// triangles) by a ray alone (the grid's own regions are classified
    /// by it); `None` where every direction is degenerate.
    pub(crate) fn windings_by_ray(&self, p: DVec3, parity: &mut Vec<u8>) -> Option<Windings> {
        self.unposed()
            .windings_by_ray(&self.candidates_at(p), p, parity)
    }

    /// The solid components whose box holds `p` (the others wind zero
    /// times about it).
    fn candidates_at(&self, p: DVec3) -> Vec<u32> {
        let mut candidates = Vec::new();
        let at = p.to_array();
        self.solid_tree
            .for_each_meeting(&Aabb { lo: at, hi: at }, |k| {
                candidates.push(self.solid_components[k])
            });
        candidates
    }

    /// The body where it stands, in its own frame.
    #[allow(clippy::type_complexity)]
    fn unposed(
        &self,
    ) -> Placed<
        '_,
        impl Fn(u32) -> DVec3 + '_,
        impl Fn(usize) -> Aabb + '_,
        impl Fn(usize) -> Aabb + '_,
        impl Fn(usize) -> Aabb + '_,
    > {
        let (boxes, bounds) = (self.tree().boxes(), self.tree().bounds());
        Placed {
            body: self,
            vertex: |v| self.vertices[v as usize],
            node_box: |n| bounds[n],
            item_box: |t| boxes[t],
            component_box: |c| self.component_boxes[c],
        }
    }
}

/// The winding numbers about a point, per source (a joined scene's
/// obstacles each count by themselves: one's inward shell must not cancel
/// another's solid): `(source, number)`, each source at most once, a
/// source not listed winding zero times.
pub(crate) type Windings = Vec<(u32, i64)>;

/// Whether some source winds about the point: it lies inside a solid.
pub(crate) fn some_winds(w: &Windings) -> bool {
    w.iter().any(|e| e.1 != 0)
}

/// How the containment tests of a [`SceneChecker`]'s queries decided their
/// points ([`SceneChecker::containment_stats`]): every method is exact, so
/// none of these is a fallback from a guess; they say where the time goes.
///
/// [`SceneChecker`]: crate::query::SceneChecker
/// [`SceneChecker::containment_stats`]: crate::query::SceneChecker::containment_stats
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ContainmentStats {
    /// Points the inside grid decided (a cell wholly inside or outside).
    pub by_grid: u64,
    /// Points decided by the segment from the point decided before them
    /// (module docs, "Segments between points").
    pub by_segment: u64,
    /// Points decided by a ray of their own: those no segment was tried
    /// for, and those of [`ContainmentStats::segment_fallbacks`].
    pub by_ray: u64,
    /// Segments that were degenerate (they met a triangle's edge or
    /// vertex, or lay in its plane), their point then decided by a ray.
    pub segment_fallbacks: u64,
    /// Triangles listed for many segments whose plane a float bound could
    /// not place against the corners' box, placed by eight exact signs
    /// instead (module docs, "Segments between points").
    pub plane_cull_fallbacks: u64,
    /// State checks decided whole by one body's grid: the other body's
    /// box lay in its cells, all classified alike, so no point was asked
    /// (`query::scene::state`, "One cell holds a body").
    pub bodies_by_grid: u64,
    /// State checks decided whole by one point: no triangle of one body
    /// came near the other body's box, so every point of that box has the
    /// same answer (`query::scene::state`, "No triangle by a body").
    pub bodies_by_region: u64,
}

impl ContainmentStats {
    /// Counts a point past the grid: whether a segment was tried, and what
    /// it gave (`None`: the point goes on to a ray), passed through.
    pub(crate) fn count(&mut self, tried: bool, along: Option<Windings>) -> Option<Windings> {
        match (&along, tried) {
            (Some(_), _) => self.by_segment += 1,
            (None, true) => {
                self.segment_fallbacks += 1;
                self.by_ray += 1;
            }
            (None, false) => self.by_ray += 1,
        }
        along
    }

    /// The two tallies added.
    pub(crate) fn add(&mut self, other: &ContainmentStats) {
        self.by_grid += other.by_grid;
        self.by_segment += other.by_segment;
        self.by_ray += other.by_ray;
        self.segment_fallbacks += other.segment_fallbacks;
        self.plane_cull_fallbacks += other.plane_cull_fallbacks;
        self.bodies_by_grid += other.bodies_by_grid;
        self.bodies_by_region += other.bodies_by_region;
    }
}

/// A point on none of the body's triangles and its [`Windings`]: where the
/// next segment starts (module docs, "Segments between points").
#[derive(Clone)]
pub(crate) struct Known {
    pub(crate) at: DVec3,
    pub(crate) windings: Windings,
}

impl Known {
    /// A point outside every solid: every source winds zero times.
    pub(crate) fn outside(at: DVec3) -> Known {
        Known {
            at,
            windings: Vec::new(),
        }
    }
}

/// A point whose windings the grid knows near `p`, where a segment to `p`
/// can start (module docs, "A start outside"): `p` moved one cell width
/// `cell`, else two, along the rays' first six directions (nearly along
/// the axes, so the segment's box is thin), the first for which
/// `windings_at` (the grid's reading: an empty list for a point in an
/// outside cell, the region's kept ones in an inside cell) knows them.
fn classified_start(
    p: DVec3,
    cell: f64,
    windings_at: impl Fn(DVec3) -> Option<Windings>,
) -> Option<Known> {
    [cell, 2.0 * cell].into_iter().find_map(|step| {
        DIRECTIONS[..6].iter().find_map(|d| {
            let q = p + DVec3::from(*d) * step;
            windings_at(q).map(|windings| Known { at: q, windings })
        })
    })
}

/// Where the segment to `p` starts, if one is tried: `known` where the
/// segment from it is shorter than the way out of `solids`
/// ([`segment_is_shorter`]), else a point of a cell whose windings the
/// grid knows ([`classified_start`], `cell` and `windings_at` as there)
/// where its segment is; `Cow::Owned` for the latter (module docs, "A
/// start outside").
pub(crate) fn segment_start<'a>(
    known: Option<&'a Known>,
    p: DVec3,
    solids: &Aabb,
    cell: f64,
    windings_at: impl Fn(DVec3) -> Option<Windings>,
) -> Option<Cow<'a, Known>> {
    let shorter = |k: &Known| segment_is_shorter(k.at, p, solids);
    match known {
        Some(k) if shorter(k) => Some(Cow::Borrowed(k)),
        _ => classified_start(p, cell, windings_at)
            .filter(|k| shorter(k))
            .map(Cow::Owned),
    }
}

/// Whether the segment from `a` to `p` is shorter (in its longest
/// coordinate) than the way from `p` out of `solids` along an axis, the
/// least a ray would walk: only which is tried first, never an answer.
fn segment_is_shorter(a: DVec3, p: DVec3, solids: &Aabb) -> bool {
    let exit = (0..3)
        .map(|k| (p[k] - solids.lo[k]).min(solids.hi[k] - p[k]))
        .fold(f64::INFINITY, f64::min);
    (p - a).abs().max_element() < exit
}

/// A triangle listed once for many segments ([`Placed::triangles_meeting`]):
/// its index, its corners where the body stands (posed once), their box,
/// and the last point whose side of its plane was found, with that side
/// (consecutive segments share an end: its side is found once; a pure
/// function of the corners and the point's coordinates, so a point with
/// the same coordinates has the same side).
pub(crate) struct Listed {
    t: usize,
    corners: [DVec3; 3],
    bounds: Aabb,
    side: std::cell::Cell<(DVec3, Sign)>,
}

impl Listed {
    /// [`crossing`] of the segment from `p` to `q`, the side of `p` read
    /// from the last asking where it was that one's `q`.
    fn crossing(&self, p: DVec3, q: DVec3) -> Crossing {
        let t = self.corners;
        let (last, side) = self.side.get();
        let sp = if last == p {
            side
        } else {
            orient(t[0], t[1], t[2], p)
        };
        let sq = orient(t[0], t[1], t[2], q);
        self.side.set((q, sq));
        crossing_on_sides(p, q, t, sp, sq)
    }
}

/// Drops from `list` the triangles proven to miss `region`: those whose
/// plane has every corner of `region` strictly on one side (exact signs),
/// and those an edge of whose shadow on a coordinate plane has the box's
/// shadow strictly on its outer side ([`edge_clears_box`], exact signs).
/// No segment inside `region` meets such a triangle, so each of its
/// segments' crossings with it would be a miss (module docs, "Segments
/// between points"). The plane is tried first by [`plane_against_box`], a
/// certified float bound; only where that cannot tell are its eight exact
/// signs found. Returns how many triangles needed them (the filter's
/// fallbacks, counted in [`ContainmentStats::plane_cull_fallbacks`]).
pub(crate) fn keep_triangles_meeting(list: &mut Vec<Listed>, region: &Aabb) -> u64 {
    let corners: [DVec3; 8] = std::array::from_fn(|k| {
        DVec3::from([0, 1, 2].map(|a| {
            if k >> a & 1 == 0 {
                region.lo[a]
            } else {
                region.hi[a]
            }
        }))
    });
    let mut fallbacks = 0;
    list.retain(|l| {
        let t = l.corners;
        let plane_cuts = match plane_against_box(t, region) {
            Some(cuts) => cuts,
            None => {
                fallbacks += 1;
                let first = orient(t[0], t[1], t[2], corners[0]);
                first == Sign::Zero
                    || corners[1..]
                        .iter()
                        .any(|&c| orient(t[0], t[1], t[2], c) != first)
            }
        };
        plane_cuts && !edge_clears_box(t, region)
    });
    fallbacks
}

/// Whether the triangle `t` and the box `b` are apart along one of the
/// nine axes `eₖ × (tⱼ − tᵢ)` of the separating-axis test (a coordinate
/// axis across an edge), decided by exact signs: their shadows on the
/// coordinate plane across `eₖ`, the triangle's `ABC` and the box's
/// rectangle, lie on the two sides of the line through an edge `PQ` of
/// `ABC`, the rectangle strictly. `f(X) = orient2(P, Q, X)` is affine in
/// `X` with gradient `(−(Q − P)_y, (Q − P)_x)`, whose signs are the exact
/// comparisons of `P`'s and `Q`'s coordinates; so the rectangle's corner
/// that takes `f` farthest toward the third corner `R`'s side `σ =
/// orient2(P, Q, R)` is known exactly, and where `f` is `−σ` there, every
/// point of the rectangle has `σ f < 0` while every point of `ABC` has
/// `σ f ≥ 0`: the shadows are apart, so are `t` and `b`. A shadow that is
/// a segment or a point (`σ = 0`) is not tried. `false` settles nothing.
fn edge_clears_box(t: [DVec3; 3], b: &Aabb) -> bool {
    (0..3).any(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let shadow = t.map(|p| [p[i], p[j]]);
        let side = orient2(shadow[0], shadow[1], shadow[2]);
        side != Sign::Zero
            && (0..3).any(|e| {
                let (p, q) = (shadow[e], shadow[(e + 1) % 3]);
                // The gradient of `side · f`: the corner's coordinate on
                // each axis is the box's end it points to.
                let toward = |d: f64, end: usize| {
                    let up = if side == Sign::Positive {
                        d > 0.0
                    } else {
                        d < 0.0
                    };
                    if up {
                        b.hi[end]
                    } else {
                        b.lo[end]
                    }
                };
                let corner = [toward(p[1] - q[1], i), toward(q[0] - p[0], j)];
                orient2(p, q, corner) == side.flip()
            })
    })
}

/// Whether the plane of the triangle `t` meets the box `b` (`Some(false)`:
/// every corner of `b` strictly on one side, as eight exact `orient3d`
/// would say; `Some(true)`: corners strictly on both sides), when floats
/// settle it; `None` otherwise.
///
/// With `u = b − a`, `v = c − a` (the triangle `abc`), `n = u × v` and
/// `w = x − a` all in floats, `s(x) = n · w` has, against the exact
/// `(U × V) · W`, an error of at most `γ₈ P(x)`: each of the determinant's
/// six products goes through at most eight roundings (three differences,
/// two products, the cross product's subtraction, two sums), and `P(x)` is
/// the sum of their absolute values, here bounded by the float
/// `Σᵢ (|u_j v_k| + |u_k v_j|) max(|lo_i − a_i|, |hi_i − a_i|)` times a
/// margin (`2⁻⁴⁸ P`, over three times `γ₈`, covers that bound's own
/// rounding), plus `(1 + max |w|) 10⁻³⁰⁰` for products that underflow
/// (an underflow in `n`, at most a few `2⁻¹⁰⁷⁵`, is then multiplied by
/// `w`; differences that underflow are exact). The least and the
/// greatest of `s` over the corners are bounded by the sums of the least
/// and the greatest terms (rounding is monotone), so a least above the
/// error puts every corner strictly on the positive side, a greatest below
/// minus it every corner strictly on the negative side. Overflow gives an
/// infinite or NaN bound, which settles nothing.
fn plane_against_box(t: [DVec3; 3], b: &Aabb) -> Option<bool> {
    let (a, u, v) = (t[0], t[1] - t[0], t[2] - t[0]);
    let n = u.cross(v);
    let size = DVec3::new(
        (u.y * v.z).abs() + (u.z * v.y).abs(),
        (u.z * v.x).abs() + (u.x * v.z).abs(),
        (u.x * v.y).abs() + (u.y * v.x).abs(),
    );
    let (mut least, mut most, mut bound, mut far) = (0.0, 0.0, 0.0, 0.0f64);
    for i in 0..3 {
        let (wlo, whi) = (b.lo[i] - a[i], b.hi[i] - a[i]);
        let (lo, hi) = (n[i] * wlo, n[i] * whi);
        least += lo.min(hi);
        most += lo.max(hi);
        let w = wlo.abs().max(whi.abs());
        bound += size[i] * w;
        far = far.max(w);
    }
    let error = bound * (1.0 / (1u64 << 48) as f64) + (1.0 + far) * 1e-300;
    if least > error || most < -error {
        Some(false)
    } else if least < -error && most > error {
        Some(true)
    } else {
        None
    }
}

/// A body where it stands: its vertex `v` at `vertex(v)`, and boxes holding
/// what its tree's node `n`, triangle `t` and component `c` hold there:
/// `node_box(n)`, `item_box(t)`, `component_box(c)` (boxes larger than the
/// exact ones only make the walk reach more triangles; each is then
/// decided exactly).
pub(crate) struct Placed<'a, V, N, I, C> {
    pub(crate) body: &'a MeshBody,
    pub(crate) vertex: V,
    pub(crate) node_box: N,
    pub(crate) item_box: I,
    pub(crate) component_box: C,
}

impl<V, N, I, C> Placed<'_, V, N, I, C>
where
    V: Fn(u32) -> DVec3,
    N: Fn(usize) -> Aabb,
    I: Fn(usize) -> Aabb,
    C: Fn(usize) -> Aabb,
{
    /// The windings about `p` (on none of the body's triangles) of the
    /// `candidates` components (those whose box holds `p`; the others wind
    /// zero times about it), by a ray (module docs). The ray leaves the
    /// candidates' joint box the shortest way first; `None` when every
    /// direction is degenerate. `parity` is a scratch buffer marking
    /// components (all zero between calls).
    pub(crate) fn windings_by_ray(
        &self,
        candidates: &[u32],
        p: DVec3,
        parity: &mut Vec<u8>,
    ) -> Option<Windings> {
        if candidates.is_empty() {
            return Some(Vec::new());
        }
        let joint = candidates.iter().fold(Aabb::EMPTY, |b, &c| {
            b.join(&(self.component_box)(c as usize))
        });
        let span = (0..3)
            .map(|k| joint.hi[k] - joint.lo[k])
            .fold(0.0, f64::max);
        // The distance to leave the joint box along each direction's main axis.
        let exit = |d: &[f64; 3]| {
            let k = (0..3)
                .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
                .unwrap_or(0);
            if d[k] > 0.0 {
                joint.hi[k] - p[k]
            } else {
                p[k] - joint.lo[k]
            }
        };
        let mut order = DIRECTIONS.map(|d| (exit(&d), d));
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, d) in order {
            let length = 2.0 * (exit(&d) + span * 0.002) + 1e-300;
            let q = p + DVec3::from(d) * length;
            if joint.holds(q.to_array()) {
                continue; // not far enough (only at the limits of f64)
            }
            let mut windings = Vec::new();
            if self.count_crossings(candidates, p, q, 1, None, &mut windings, parity) {
                return Some(windings);
            }
        }
        None
    }

    /// The windings about `p` (on none of the body's triangles) from those
    /// about `from.at` and the crossings of the segment between them with
    /// the `candidates` components (every solid component whose box meets
    /// the segment's; module docs, "Segments between points"); `None` where
    /// the segment is degenerate.
    ///
    /// With `listed`, the triangles are taken from that list instead of the
    /// tree (those whose boxes meet the segment's, as the walk would reach
    /// them): it must hold every one of those whose planes cut a box
    /// holding both ends ([`Placed::triangles_meeting`] of that box, then
    /// perhaps [`keep_triangles_meeting`] for it).
    pub(crate) fn windings_along(
        &self,
        candidates: &[u32],
        from: &Known,
        p: DVec3,
        listed: Option<&[Listed]>,
        parity: &mut Vec<u8>,
    ) -> Option<Windings> {
        let mut windings = from.windings.clone();
        self.count_crossings(candidates, from.at, p, -1, listed, &mut windings, parity)
            .then_some(windings)
    }

    /// The triangles whose boxes meet `region`, with their corners where
    /// the body stands, or `None` where there are more than `most`.
    pub(crate) fn triangles_meeting(&self, region: &Aabb, most: usize) -> Option<Vec<Listed>> {
        let mut listed = Vec::new();
        let mut within = true;
        self.body
            .tree()
            .meeting_while(&self.node_box, &self.item_box, region, |t| {
                let corners = self.body.triangles[t].map(&self.vertex);
                listed.push(Listed {
                    t,
                    corners,
                    bounds: Aabb::of(corners.map(|c| c.to_array())),
                    // No point yet (NaN equals nothing).
                    side: std::cell::Cell::new((DVec3::NAN, Sign::Zero)),
                });
                within = listed.len() <= most;
                within
            });
        within.then_some(listed)
    }

    /// Adds to `windings`, `sign` times, the signed crossings of the
    /// segment from `p` to `q` with the triangles of the `candidates`
    /// components (a crossing counts the triangle's weight, `+` where `p`
    /// lies on its positive side); `false` where the segment is degenerate
    /// (`windings` then means nothing).
    #[allow(clippy::too_many_arguments)]
    fn count_crossings(
        &self,
        candidates: &[u32],
        p: DVec3,
        q: DVec3,
        sign: i64,
        listed: Option<&[Listed]>,
        windings: &mut Windings,
        parity: &mut Vec<u8>,
    ) -> bool {
        let body = self.body;
        if parity.len() < body.components.len() {
            parity.resize(body.components.len(), 0);
        }
        for &c in candidates {
            parity[c as usize] = 1;
        }
        let mut degenerate = false;
        let segment = Aabb {
            lo: p.min(q).to_array(),
            hi: p.max(q).to_array(),
        };
        let mut count = |t: usize, cross: &dyn Fn() -> Crossing| {
            let c = body.component_of[t] as usize;
            if degenerate || parity[c] == 0 {
                return;
            }
            match cross() {
                Crossing::Crosses(positive) => {
                    let w = i64::from(body.weights[t]) * if positive { sign } else { -sign };
                    let source = body.source_of[c];
                    match windings.iter_mut().find(|e| e.0 == source) {
                        Some(e) => e.1 += w,
                        None => windings.push((source, w)),
                    }
                }
                Crossing::Misses => {}
                Crossing::Degenerate => degenerate = true,
            }
        };
        match listed {
            // Those whose boxes meet the segment's, as the tree's walk
            // reaches: a far triangle in the plane of both ends would call
            // the segment degenerate.
            Some(list) => list
                .iter()
                .filter(|l| l.bounds.meets(&segment))
                .for_each(|l| count(l.t, &|| l.crossing(p, q))),
            None => {
                body.tree()
                    .for_each_meeting_with(&self.node_box, &self.item_box, &segment, |t| {
                        count(t, &|| crossing(p, q, body.triangles[t].map(&self.vertex)))
                    })
            }
        }
        for &c in candidates {
            parity[c as usize] = 0;
        }
        !degenerate
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::PolygonMesh;

    fn cube(lo: f64, hi: f64) -> PolygonMesh {
        let corners: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                let pick = |k: usize| if i >> k & 1 == 0 { lo } else { hi };
                [pick(0), pick(1), pick(2)]
            })
            .collect();
        crate::polytope::Polytope::from_points(&corners)
            .unwrap()
            .to_mesh()
    }

    fn inside(body: &MeshBody, p: [f64; 3]) -> bool {
        body.inside_solid(
            p.into(),
            &mut None,
            &mut Vec::new(),
            &mut ContainmentStats::default(),
        )
        .unwrap()
    }

    #[test]
    fn nested_cubes_and_points_on_their_axes() {
        // Two nested solid cubes (each a solid): inside either counts.
        let mut m = cube(0.0, 4.0);
        let inner = cube(1.0, 3.0);
        let base = m.vertices.len();
        m.vertices.extend(inner.vertices);
        m.faces.extend(
            inner
                .faces
                .iter()
                .map(|f| f.iter().map(|v| v + base).collect()),
        );
        let body = MeshBody::new(&m).unwrap();
        assert_eq!(body.report().solids, 2);
        // Points level with edges and corners (axis-aligned rays would be
        // degenerate for many of them).
        for p in [
            [0.5, 0.5, 0.5],
            [2.0, 2.0, 2.0],
            [0.5, 1.0, 3.0],
            [3.5, 2.0, 1.0],
        ] {
            assert!(inside(&body, p), "{p:?}");
        }
        for p in [
            [-1.0, 1.0, 1.0],
            [5.0, 0.0, 0.0],
            [2.0, 2.0, 4.5],
            [4.0 + 1e-12, 1.0, 1.0],
        ] {
            assert!(!inside(&body, p), "{p:?}");
        }
    }

    /// Appends the box `[lo, hi]` (per axis) to a mesh, outward or inward
    /// (an inward shell winds −1 about its inside; `inside_grid`'s
    /// `push_box`), every corner then turned by `turn` (a generic turn: few
    /// segments lie in a face's plane).
    fn push_box(m: &mut PolygonMesh, lo: [f64; 3], hi: [f64; 3], outward: bool, turn: glam::DMat3) {
        let from = m.vertices.len();
        crate::body::inside_grid::tests::push_box(m, lo, hi, outward, 1);
        for v in &mut m.vertices[from..] {
            *v = (turn * DVec3::from(*v)).to_array();
        }
    }

    /// The float bound of `plane_against_box` against eight exact signs:
    /// random triangles and boxes at scales from 10⁻³⁰⁰ to 10³⁰⁰, boxes
    /// cut by the plane, clear of it, touching it at a corner or a face,
    /// and within a few ulps of it. Every answer it gives is the exact one,
    /// and it gives one for most boxes that are not within rounding of the
    /// plane.
    #[test]
    fn the_plane_cull_bound_agrees_with_the_exact_signs() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(48);
        let exact = |t: [DVec3; 3], b: &Aabb| {
            let signs: Vec<Sign> = (0..8)
                .map(|k| {
                    let c =
                        DVec3::from(
                            [0, 1, 2].map(|a| if k >> a & 1 == 0 { b.lo[a] } else { b.hi[a] }),
                        );
                    orient(t[0], t[1], t[2], c)
                })
                .collect();
            !(signs[0] != Sign::Zero && signs.iter().all(|&s| s == signs[0]))
        };
        // Generic boxes at scales whose cubes stay normal floats, and how
        // many of those the bound told.
        let (mut told, mut clear, mut generic) = (0, 0, 0);
        for round in 0..20_000 {
            let exponent = rng.random_range(-300..=300);
            let scale = 10f64.powi(exponent);
            let off = DVec3::from([0; 3].map(|_| rng.random_range(-4.0..4.0))) * scale;
            let mut pt = || off + DVec3::from([0; 3].map(|_| rng.random_range(-1.0..1.0))) * scale;
            let t = [pt(), pt(), pt()];
            let (lo, mut hi) = (pt(), pt());
            hi = lo.max(hi);
            let lo = lo.min(hi);
            let mut b = Aabb {
                lo: lo.to_array(),
                hi: hi.to_array(),
            };
            match round % 4 {
                // A box with a corner on a triangle's corner, or a point
                // of its plane nudged by an ulp.
                1 => b.lo = t[rng.random_range(0..3)].to_array(),
                2 => {
                    let w: [f64; 3] = [0; 3].map(|_| rng.random_range(0.0..1.0));
                    let p = (t[0] * w[0] + t[1] * w[1] + t[2] * (1.0 - w[0] - w[1] + w[2]))
                        / (1.0 + w[2]);
                    let ulp = |x: f64| f64::from_bits(x.abs().to_bits() + 1) - x.abs();
                    b = Aabb {
                        lo: p.to_array(),
                        hi: p
                            .to_array()
                            .map(|x| x + ulp(x) * rng.random_range(0.0..4.0)),
                    };
                }
                // A flat box (a point) anywhere.
                3 => b.hi = b.lo,
                _ => {}
            }
            let truth = exact(t, &b);
            let answer = plane_against_box(t, &b);
            if let Some(cuts) = answer {
                assert_eq!(cuts, truth, "round {round}: {t:?} {b:?}");
            }
            if round % 4 == 0 && exponent.abs() <= 90 {
                generic += 1;
                told += usize::from(answer.is_some());
                clear += usize::from(!truth);
            }
        }
        assert!(
            told * 100 > generic * 99 && clear * 5 > generic,
            "{told} told, {clear} clear of {generic}"
        );
    }

    /// The windings with their zero entries dropped, in order of source.
    fn normal(mut w: Windings) -> Windings {
        w.retain(|e| e.1 != 0);
        w.sort_unstable();
        w
    }

    /// A joined body of two sources, its boxes' corners turned by `turn`.
    /// Source 0: a box with a cavity, an overlapping box (winding 2 where
    /// they overlap), and an inward shell apart. Source 1: a box around the
    /// inward shell and part of the rest.
    fn two_sources(turn: glam::DMat3) -> MeshBody {
        let mut a = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut a, [0.0; 3], [4.0; 3], true, turn);
        push_box(&mut a, [1.0; 3], [2.0; 3], false, turn);
        push_box(&mut a, [3.0, 3.0, 0.5], [6.0, 5.0, 2.0], true, turn);
        push_box(&mut a, [7.0, 0.0, 0.0], [8.0, 1.0, 1.0], false, turn);
        let mut b = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut b, [3.5, -0.5, -0.5], [8.5, 1.5, 1.5], true, turn);
        MeshBody::join(&[MeshBody::new(&a).unwrap(), MeshBody::new(&b).unwrap()])
    }

    /// Module docs, "Segments between points": one list made for a small
    /// box, read by a chain of segments between points in it (each
    /// triangle's side of the last end carried to the next segment), and
    /// the same list without the triangles whose planes clear the box
    /// or shadows clear the box (`keep_triangles_meeting`), give each point
    /// the ray's windings. Fails when a carried side is read for another
    /// point, and when the planes or the edges kept are the wrong ones.
    #[test]
    fn a_list_read_by_a_chain_of_segments_gives_the_rays_windings() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(36);
        let (mut along, mut listed, mut kept) = (0, 0, 0);
        for round in 0..60 {
            let turn = glam::DMat3::from_quat(glam::DQuat::from_euler(
                glam::EulerRot::XYZ,
                rng.random_range(-3.0..3.0),
                rng.random_range(-3.0..3.0),
                rng.random_range(-3.0..3.0),
            ));
            let body = two_sources(if round % 3 == 0 {
                glam::DMat3::IDENTITY
            } else {
                turn
            });
            let placed = body.unposed();
            let mut parity = Vec::new();
            let all: Vec<u32> = body.solid_components.clone();
            // A box of side 0.2 to 2 about the cavity's, the overlap's and
            // the inward shell's walls.
            let centre = DVec3::new(
                rng.random_range(0.5..8.5),
                rng.random_range(-0.5..5.0),
                rng.random_range(-0.5..2.5),
            );
            let half = DVec3::splat(rng.random_range(0.1..1.0));
            let points: Vec<DVec3> = (0..30)
                .map(|_| {
                    centre
                        + half
                            * DVec3::new(
                                rng.random_range(-1.0..1.0),
                                rng.random_range(-1.0..1.0),
                                rng.random_range(-1.0..1.0),
                            )
                })
                .collect();
            let region = Aabb::of(points.iter().map(|p| p.to_array()));
            let whole = placed.triangles_meeting(&region, usize::MAX).unwrap();
            let mut culled = placed.triangles_meeting(&region, usize::MAX).unwrap();
            keep_triangles_meeting(&mut culled, &region);
            listed += whole.len();
            kept += culled.len();
            let ray = |p: DVec3, parity: &mut Vec<u8>| {
                placed.windings_by_ray(&body.candidates_at(p), p, parity)
            };
            for list in [&whole, &culled] {
                let mut known = Known {
                    at: points[0],
                    windings: ray(points[0], &mut parity).unwrap(),
                };
                for &p in &points[1..] {
                    let expected = ray(p, &mut parity).expect("a generic point");
                    if let Some(w) = placed.windings_along(&all, &known, p, Some(list), &mut parity)
                    {
                        along += 1;
                        assert_eq!(normal(w), normal(expected.clone()), "round {round}");
                    }
                    known = Known {
                        at: p,
                        windings: expected,
                    };
                }
            }
        }
        assert!(along > 3_000, "{along} segments decided");
        assert!(kept < listed, "{kept} of {listed} triangles kept");
    }

    /// `edge_clears_box` against a plain separating-axis test on small
    /// integer coordinates (every product and sum exact in floats): it
    /// says apart exactly where, on a coordinate plane where the
    /// triangle's shadow is a triangle, the box's shadow lies strictly
    /// beyond an edge's line, away from the third corner; and the oracle
    /// then finds an axis that parts the triangle and the box strictly.
    /// Fails when a corner is taken toward the wrong end or on the wrong
    /// side.
    #[test]
    fn an_edge_clearing_a_box_parts_them_as_the_separating_axes_say() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(35);
        let centre_and_half = |b: &Aabb| {
            let (lo, hi) = (DVec3::from(b.lo), DVec3::from(b.hi));
            ((lo + hi) * 0.5, (hi - lo) * 0.5)
        };
        // Whether `axis` parts the two strictly.
        let parts = |axis: DVec3, t: &[DVec3; 3], b: &Aabb| {
            let on_t = t.map(|p| axis.dot(p));
            let (c, h) = centre_and_half(b);
            let (c, r) = (axis.dot(c), axis.abs().dot(h));
            on_t.iter().all(|&v| v > c + r) || on_t.iter().all(|&v| v < c - r)
        };
        let (mut cleared, mut kept) = (0, 0);
        for _ in 0..200_000 {
            let mut point = || {
                DVec3::from(std::array::from_fn::<f64, 3, _>(|_| {
                    f64::from(rng.random_range(-6i32..=6))
                }))
            };
            let t = [point(), point(), point()];
            let (a, z) = (point(), point());
            let b = Aabb {
                lo: a.min(z).to_array(),
                hi: a.max(z).to_array(),
            };
            let mut expected = false;
            for k in 0..3 {
                let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                let shadow = t.map(|p| [p[i], p[j]]);
                if orient2(shadow[0], shadow[1], shadow[2]) == Sign::Zero {
                    continue;
                }
                for e in 0..3 {
                    let n = DVec3::AXES[k].cross(t[(e + 1) % 3] - t[e]);
                    let (line, third) = (n.dot(t[e]), n.dot(t[(e + 2) % 3]));
                    let (c, h) = centre_and_half(&b);
                    let (c, r) = (n.dot(c), n.abs().dot(h));
                    expected |= if third > line {
                        c + r < line
                    } else {
                        c - r > line
                    };
                }
            }
            let says = edge_clears_box(t, &b);
            assert_eq!(says, expected, "{t:?} {b:?}");
            if says {
                cleared += 1;
                let normal = (t[1] - t[0]).cross(t[2] - t[0]);
                let mut axes: Vec<DVec3> = (0..9)
                    .map(|m| DVec3::AXES[m / 3].cross(t[(m % 3 + 1) % 3] - t[m % 3]))
                    .collect();
                axes.extend(DVec3::AXES);
                axes.push(normal);
                assert!(
                    axes.iter().any(|&n| n != DVec3::ZERO && parts(n, &t, &b)),
                    "{t:?} {b:?}"
                );
            } else {
                kept += 1;
            }
        }
        assert!(cleared > 10_000 && kept > 10_000, "{cleared} {kept}");
    }

    /// Module docs, "Segments between points": the windings carried along
    /// a segment from a known point are the ray's at its end, for every
    /// source of a joined body (nested shells, a cavity, an inward shell,
    /// overlapping solids of one source and of two), from points decided by
    /// rays and from points known to be outside. Fails when a crossing's
    /// sign along the segment is taken as the ray's, or when the
    /// segment's candidates leave out a component it crosses.
    #[test]
    fn segments_between_points_give_the_rays_windings() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(35);
        let (mut along, mut degenerate) = (0, 0);
        for round in 0..40 {
            let turn = if round % 4 == 0 {
                glam::DMat3::IDENTITY
            } else {
                glam::DMat3::from_quat(glam::DQuat::from_euler(
                    glam::EulerRot::XYZ,
                    rng.random_range(-3.0..3.0),
                    rng.random_range(-3.0..3.0),
                    rng.random_range(-3.0..3.0),
                ))
            };
            let body = two_sources(turn);
            let placed = body.unposed();
            let mut parity = Vec::new();
            let all: Vec<u32> = body.solid_components.clone();
            let ray = |p: DVec3, parity: &mut Vec<u8>| {
                placed.windings_by_ray(&body.candidates_at(p), p, parity)
            };
            let point = |rng: &mut rand_chacha::ChaCha8Rng| {
                turn * DVec3::new(
                    rng.random_range(-1.0..9.0),
                    rng.random_range(-1.0..6.0),
                    rng.random_range(-1.0..5.0),
                )
            };
            let mut known = Known::outside(turn * DVec3::new(-1.0, -1.0, -1.0));
            for _ in 0..50 {
                let p = point(&mut rng);
                let expected = ray(p, &mut parity).expect("a generic point");
                // Every solid component, or those whose box meets the
                // segment's: the same windings.
                let segment = Aabb::of([known.at.to_array(), p.to_array()]);
                let meeting: Vec<u32> = all
                    .iter()
                    .copied()
                    .filter(|&c| body.component_boxes[c as usize].meets(&segment))
                    .collect();
                // The triangles listed once for a box holding both ends
                // serve as the tree does.
                let list = placed.triangles_meeting(&segment, usize::MAX).unwrap();
                for (candidates, listed) in
                    [(&all, None), (&meeting, None), (&all, Some(&list[..]))]
                {
                    match placed.windings_along(candidates, &known, p, listed, &mut parity) {
                        Some(w) => {
                            along += 1;
                            assert_eq!(normal(w), normal(expected.clone()), "round {round}");
                        }
                        None => degenerate += 1,
                    }
                }
                if list.len() > 1 {
                    assert!(placed.triangles_meeting(&segment, list.len() - 1).is_none());
                }
                // `inside_solid` answers as the ray does, whichever way.
                let mut carried = Some(Known {
                    at: known.at,
                    windings: known.windings.clone(),
                });
                assert_eq!(
                    body.inside_solid(
                        p,
                        &mut carried,
                        &mut parity,
                        &mut ContainmentStats::default()
                    ),
                    Some(some_winds(&expected))
                );
                assert!(parity.iter().all(|&x| x == 0));
                known = Known {
                    at: p,
                    windings: expected,
                };
            }
        }
        assert!(along > 4_000, "{along} segments decided");
        assert!(degenerate < along / 10, "{degenerate} degenerate segments");
        // A segment in a face's plane through the face is degenerate: no
        // answer, never a guess.
        let mut m = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut m, [0.0; 3], [1.0; 3], true, glam::DMat3::IDENTITY);
        let body = MeshBody::new(&m).unwrap();
        let from = Known::outside(DVec3::new(-1.0, 0.5, 1.0));
        let all = body.solid_components.clone();
        assert!(body
            .unposed()
            .windings_along(
                &all,
                &from,
                DVec3::new(2.0, 0.5, 1.0),
                None,
                &mut Vec::new()
            )
            .is_none());
    }

    /// A listed triangle far along a segment's own plane must not make it
    /// degenerate (the tree's walk never reaches it): an L-shaped prism,
    /// and a segment inside it level with the inner wall at `y = 1`.
    #[test]
    fn a_listed_far_face_in_the_segments_plane_is_skipped() {
        let l = [
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        let mut vertices: Vec<[f64; 3]> = l.iter().map(|p| [p[0], p[1], 0.0]).collect();
        vertices.extend(l.iter().map(|p| [p[0], p[1], 1.0]));
        let mut faces = vec![vec![6, 7, 8, 9, 10, 11], vec![0, 5, 4, 3, 2, 1]];
        for a in 0..6 {
            let b = (a + 1) % 6;
            faces.push(vec![a, b, b + 6, a + 6]);
        }
        let body = MeshBody::new(&PolygonMesh::new(vertices, faces)).unwrap();
        let placed = body.unposed();
        let mut parity = Vec::new();
        let (p0, p) = (DVec3::new(0.5, 1.0, 0.5), DVec3::new(0.7, 1.0, 0.5));
        let at = placed
            .windings_by_ray(&body.candidates_at(p0), p0, &mut parity)
            .unwrap();
        assert!(some_winds(&at));
        let from = Known {
            at: p0,
            windings: at,
        };
        let all = body.solid_components.clone();
        let region = Aabb {
            lo: [0.0; 3],
            hi: [3.0, 3.0, 1.0],
        };
        let list = placed.triangles_meeting(&region, usize::MAX).unwrap();
        let along = placed.windings_along(&all, &from, p, Some(&list), &mut parity);
        assert_eq!(along.map(normal), Some(normal(from.windings.clone())));
    }

    /// A box with a cubic cavity, and a body of tiny cubes (one solid each)
    /// at `lows` (their lowest corners), as a scene checker sees them.
    fn cavity_and_specks(lows: &[[f64; 3]]) -> crate::query::SceneChecker {
        cavity_and_specks_beside(lows, &[])
    }

    /// [`cavity_and_specks`] with more obstacles.
    fn cavity_and_specks_beside(
        lows: &[[f64; 3]],
        more: &[PolygonMesh],
    ) -> crate::query::SceneChecker {
        let id = glam::DMat3::IDENTITY;
        let mut scene = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut scene, [0.0; 3], [10.0; 3], true, id);
        push_box(&mut scene, [1.0; 3], [9.0; 3], false, id);
        let mut specks = PolygonMesh::new(Vec::new(), Vec::new());
        for lo in lows {
            push_box(&mut specks, *lo, lo.map(|x| x + 1e-4), true, id);
        }
        let body = MeshBody::new(&specks).unwrap();
        let scene: Vec<MeshBody> = std::iter::once(&scene)
            .chain(more)
            .map(|m| MeshBody::new(m).unwrap())
            .collect();
        crate::query::SceneChecker::new(&body, &scene).unwrap()
    }

    /// Whether [`cavity_and_specks`] collide where they stand, and how the
    /// containment test decided its points.
    fn at_rest(lows: &[[f64; 3]]) -> (bool, ContainmentStats) {
        use crate::kernel::rotation::{Pose, Rotation};
        let checker = cavity_and_specks(lows);
        let collides = checker
            .collides_at(Pose::new(Rotation::IDENTITY, DVec3::ZERO))
            .unwrap();
        (collides, checker.containment_stats())
    }

    /// Module docs, "A start outside", in the scene's own frame: specks (the
    /// body) by the cavity's two faces across x of a finely cut shell (the
    /// scene), on either side, each asked alone. Every answer is the scene's own ray's,
    /// and each is decided by a segment from an outside cell, none by a
    /// ray.
    #[test]
    fn a_lone_speck_starts_from_an_outside_cell() {
        use crate::body::inside_grid::tests::push_box as cut_box;
        use crate::kernel::rotation::{Pose, Rotation};
        let mut shell = PolygonMesh::new(Vec::new(), Vec::new());
        cut_box(&mut shell, [0.0; 3], [90.0; 3], true, 8);
        cut_box(&mut shell, [25.0, 20.0, 20.0], [70.0, 70.0, 70.0], false, 8);
        let scene = MeshBody::new(&shell).unwrap();
        let mut inside = 0;
        for i in 0..40 {
            // By either face across x, so that some first cells tried are
            // inside the wall.
            let face = if i % 2 == 0 { 25.0 } else { 70.0 };
            let x = face + if i % 3 == 0 { -0.3 } else { 0.2 } + 1e-3 * f64::from(i);
            let lo = [x, 30.0 + 0.7 * f64::from(i), 45.0];
            let mut speck = PolygonMesh::new(Vec::new(), Vec::new());
            push_box(
                &mut speck,
                lo,
                lo.map(|x| x + 1e-2),
                true,
                glam::DMat3::IDENTITY,
            );
            let checker = crate::query::SceneChecker::new(
                &MeshBody::new(&speck).unwrap(),
                std::slice::from_ref(&scene),
            )
            .unwrap();
            let exact = scene
                .inside_by_ray(DVec3::from(lo), &mut Vec::new())
                .unwrap();
            let pose = Pose::new(Rotation::IDENTITY, DVec3::ZERO);
            assert_eq!(checker.collides_at(pose).unwrap(), exact, "speck at {lo:?}");
            inside += usize::from(exact);
            let stats = checker.containment_stats();
            assert_eq!(
                (stats.by_ray, stats.by_segment),
                (0, 1),
                "speck at {lo:?}: {stats:?}"
            );
        }
        assert!(inside > 5 && inside < 35, "{inside} inside");
    }

    /// The containment counters: specks in the cavity close to one wall
    /// (one grid cell, which meets the wall, so the grid cannot decide)
    /// lie in a box no wall comes near, so the first one's ray decides
    /// them all (`query::scene::state`, "No triangle by a body"); with an
    /// open sheet between two of them (it meets their box, not them), the
    /// first takes a ray and each next one a segment.
    #[test]
    fn specks_by_walls_are_decided_by_one_ray_and_segments() {
        let lows: Vec<[f64; 3]> = (0..5)
            .map(|i| [1.001, 5.0 + 3e-4 * f64::from(i), 5.0])
            .collect();
        let (collides, stats) = at_rest(&lows);
        assert!(!collides);
        let none = ContainmentStats::default();
        assert_eq!(
            stats,
            ContainmentStats {
                by_ray: 1,
                bodies_by_region: 1,
                ..none
            }
        );
        // An open sheet between the third and fourth specks meets their box.
        let y = 5.0 + 3e-4 * 2.5;
        let sheet = PolygonMesh::new(
            vec![
                [1.0005, y, 4.5],
                [1.5, y, 4.5],
                [1.5, y, 5.5],
                [1.0005, y, 5.5],
            ],
            vec![vec![0, 1, 2, 3]],
        );
        let checker = cavity_and_specks_beside(&lows, &[sheet]);
        let rest = crate::kernel::rotation::Pose::new(
            crate::kernel::rotation::Rotation::IDENTITY,
            DVec3::ZERO,
        );
        assert!(!checker.collides_at(rest).unwrap());
        assert_eq!(
            checker.containment_stats(),
            ContainmentStats {
                by_segment: 4,
                by_ray: 1,
                ..none
            }
        );
    }

    /// A segment through the centre of a cavity's face (on the diagonal
    /// that splits it into triangles) is degenerate: its end is decided by
    /// a ray, and the fallback is counted.
    #[test]
    fn a_segment_through_a_faces_diagonal_falls_back_to_a_ray_and_is_counted() {
        let (collides, stats) = at_rest(&[[1.001, 5.0, 5.0], [0.9995, 5.0, 5.0]]);
        assert!(collides);
        assert_eq!(
            stats,
            ContainmentStats {
                by_grid: 0,
                by_segment: 0,
                by_ray: 2,
                segment_fallbacks: 1,
                plane_cull_fallbacks: 0,
                bodies_by_grid: 0,
                bodies_by_region: 0
            }
        );
    }
}
