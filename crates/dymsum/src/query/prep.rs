//! What the queries need of one body, computed once and kept with the
//! polytope ([`crate::polytope::Polytope`]'s slot for a higher layer's
//! data): its point reflection `−B` ([`Reflected`]), bounds for the posing
//! ([`BodyBounds`]), balls around its features ([`FeatureBalls`]) and caps
//! around its Gaussian cells ([`GaussCaps`]), together [`BodyPrep`].

use crate::kernel::bounds::up;
use crate::kernel::exact::{frame_exponent, mul_pow2, mul_pow2_vec};
use crate::kernel::rotation::Pose;
use crate::polytope::Polytope;
use glam::DVec3;

/// The point reflection `−B` of a body ([`Polytope::point_reflection`]),
/// numbered as `B`: vertex `i` of `−B` is `−b_i`, and faces and edges keep
/// their numbers, so a feature of `−B` names the same feature of `B`.
#[derive(Clone, Debug)]
pub struct Reflected {
    /// `−B` as a polytope.
    pub polytope: Polytope,
}

impl Reflected {
    /// Reflects `b` through the origin: exact (negation is exact) and
    /// linear in `b`'s size, nothing decided again
    /// ([`Polytope::point_reflection`]).
    pub fn new(b: &Polytope) -> Reflected {
        Reflected {
            polytope: b.point_reflection(),
        }
    }

    /// The pose of `−B` for `B` at `pose`: `−(R b + t) = R(−b) − t`.
    pub fn pose(pose: Pose) -> Pose {
        Pose::new(pose.rotation, -pose.translation)
    }
}

/// What the queries need of one body beyond the body itself, computed once
/// per body (on its first query) and kept by the body's [`Polytope`]
/// handle, so preparing a pair costs nothing after the first time.
#[derive(Debug)]
pub(crate) struct BodyPrep {
    /// Balls around the faces and edges (the separation's branch and
    /// bound).
    pub(in crate::query) balls: crate::query::prep::FeatureBalls,
    /// Reach and radius (the query frame's bounds).
    pub(in crate::query) bounds: crate::query::prep::BodyBounds,
    /// Error bounds of the arc normals under any rotation, exactly as the
    /// overlay's operands compute them (the body as A).
    pub(in crate::query) arc_err: Vec<f64>,
    /// What the body needs as B ([`BodyPrep::reflection`]): made when a
    /// pair first takes it as B, so that a body only ever A (a planner's
    /// robot) never holds it: it is a second polytope, about 70% of the
    /// rest of this preparation.
    reflection: std::sync::OnceLock<std::sync::Arc<Reflected>>,
    /// Caps holding each vertex's Gaussian cell and each edge's Gaussian
    /// arc (body frame): the certificates' quick rejections.
    pub(in crate::query) caps: crate::query::prep::GaussCaps,
    /// Per direction of [`SEED_DIRECTIONS`], a vertex extreme along it
    /// (body frame, floats): where GJK's first support search starts when
    /// the last query's support vertex is further from the answer
    /// ([`BodyPrep::seed`]).
    pub(in crate::query) seeds: [u32; SEED_DIRECTIONS],
}

/// How many directions [`BodyPrep::seeds`] covers: the 26 of the cube's
/// faces, edges and corners seen from its centre.
pub(in crate::query) const SEED_DIRECTIONS: usize = 26;

/// The unit directions of [`BodyPrep::seeds`].
static SEED_UNITS: std::sync::LazyLock<[DVec3; SEED_DIRECTIONS]> =
    std::sync::LazyLock::new(seed_directions);

fn seed_directions() -> [DVec3; SEED_DIRECTIONS] {
    let mut out = [DVec3::ZERO; SEED_DIRECTIONS];
    let mut n = 0;
    for x in -1..=1 {
        for y in -1..=1 {
            for z in -1..=1 {
                if (x, y, z) != (0, 0, 0) {
                    out[n] = DVec3::new(x as f64, y as f64, z as f64).normalize();
                    n += 1;
                }
            }
        }
    }
    out
}

impl BodyPrep {
    /// The data of `p`, computed on its first query and kept with the
    /// polytope (shared by every handle of it).
    pub(crate) fn of_cached(p: &Polytope) -> std::sync::Arc<BodyPrep> {
        p.derived(|| std::sync::Arc::new(BodyPrep::of(p)))
    }

    /// What `p`, whose preparation this is, needs as B: made on the first
    /// call and kept (two threads asking at once may both make it; one is
    /// kept).
    pub(crate) fn reflection(&self, p: &Polytope) -> std::sync::Arc<Reflected> {
        self.reflection
            .get_or_init(|| std::sync::Arc::new(Reflected::new(p)))
            .clone()
    }

    /// Computes the data of `p` (its reflection only when asked).
    fn of(p: &Polytope) -> BodyPrep {
        let (mut arcs, mut arc_err) = (Vec::new(), Vec::new());
        crate::sum::rotate_arcs(p, None, &mut arcs, &mut arc_err);
        BodyPrep {
            balls: crate::query::prep::FeatureBalls::of(p),
            bounds: crate::query::prep::BodyBounds::of(p),
            arc_err,
            reflection: std::sync::OnceLock::new(),
            caps: crate::query::prep::GaussCaps::of(p),
            seeds: SEED_UNITS.map(|d| {
                let best = (0..p.vertex_count())
                    .max_by(|&i, &j| d.dot(p.vertex(i)).total_cmp(&d.dot(p.vertex(j))));
                best.unwrap_or(0) as u32
            }),
        }
    }

    /// The seed vertex of the direction of [`SEED_DIRECTIONS`] nearest
    /// `d` (body frame): a start for a support search along `d` that is
    /// never far from the answer, whatever the last query was. Only a
    /// start: the search itself decides.
    pub(in crate::query) fn seed(&self, d: DVec3) -> u32 {
        let mut best = (f64::NEG_INFINITY, 0);
        for (k, e) in SEED_UNITS.iter().enumerate() {
            let score = e.dot(d);
            if score > best.0 {
                best = (score, k);
            }
        }
        self.seeds[best.1]
    }
}

/// What a query needs to know about one body, computed once per pair (body
/// frame units): the largest `|v|`, the vertex mean and the largest
/// distance of a vertex from it.
#[derive(Clone, Debug)]
pub(in crate::query) struct BodyBounds {
    /// Largest `|v|` (rounded up; may be infinite for coordinates near
    /// `f64::MAX`).
    pub reach: f64,
    /// Largest `|v − mean|` (rounded up).
    pub radius: f64,
}

impl BodyBounds {
    /// The bounds of `p`, computed in its own power-of-two frame (so that
    /// no square underflows or overflows) and scaled back.
    pub(in crate::query) fn of(p: &Polytope) -> BodyBounds {
        let exp = p.frame_exponent();
        let v: Vec<DVec3> = p.vertices().iter().map(|&x| mul_pow2_vec(x, exp)).collect();
        let n = v.len() as f64;
        let mean = v.iter().fold(DVec3::ZERO, |s, &x| s + x) / n;
        let reach = up(v.iter().map(|x| x.length()).fold(0.0, f64::max));
        let radius = up(v.iter().map(|x| (*x - mean).length()).fold(0.0, f64::max))
            + 4.0 * f64::EPSILON * reach;
        BodyBounds {
            reach: up(mul_pow2(reach, -exp)),
            radius: up(mul_pow2(radius, -exp)),
        }
    }
}

/// For each face of a body, the largest distance from the mean of its
/// corners to a corner; and for each edge, half its length. All in the
/// body's own power-of-two frame
/// (coordinates times `2^exp`, the largest magnitude in `[1, 2)`), so
/// nothing underflows or overflows at any scale, and rounded up.
#[derive(Clone, Debug, Default)]
pub(in crate::query) struct FeatureBalls {
    pub(in crate::query) exp: i32,
    /// Each face's corners' mean (body frame).
    pub(in crate::query) face_centre: Vec<DVec3>,
    pub(in crate::query) face_radius: Vec<f64>,
    pub(in crate::query) half_edge: Vec<f64>,
}

impl FeatureBalls {
    /// The balls of `p`'s faces and edges.
    pub(in crate::query) fn of(p: &Polytope) -> FeatureBalls {
        let exp = frame_exponent(p.vertices().iter().flat_map(|v| v.to_array()));
        let v: Vec<DVec3> = p.vertices().iter().map(|&x| mul_pow2_vec(x, exp)).collect();
        let (face_centre, face_radius) = (0..p.face_count())
            .map(|f| {
                let face = p.face(f);
                let c = mean(face.iter().map(|&i| v[i as usize]), face.len());
                let r = up(face
                    .iter()
                    .map(|&i| (v[i as usize] - c).length())
                    .fold(0.0, f64::max));
                (mul_pow2_vec(c, -exp), r)
            })
            .unzip();
        let half_edge = (0..p.edge_count())
            .map(|e| {
                let [x, y] = p.edge(e).vertices;
                up(0.5 * (v[x as usize] - v[y as usize]).length())
            })
            .collect();
        FeatureBalls {
            exp,
            face_centre,
            face_radius,
            half_edge,
        }
    }

    /// A length of these balls in the query's frame (`2^k` world).
    #[inline]
    pub(in crate::query) fn in_frame(&self, r: f64, k: i32) -> f64 {
        mul_pow2(r, k - self.exp)
    }

    /// The radius of face `f`'s ball (about its corners' mean) in the
    /// query's frame.
    #[inline]
    pub(in crate::query) fn face(&self, f: u32, k: i32) -> f64 {
        self.in_frame(self.face_radius[f as usize], k)
    }

    /// The centre of face `f`'s ball (body frame).
    #[inline]
    pub(in crate::query) fn face_centre(&self, f: u32) -> DVec3 {
        self.face_centre[f as usize]
    }

    /// Half the length of edge `e` in the query's frame.
    #[inline]
    pub(in crate::query) fn edge(&self, e: u32, k: i32) -> f64 {
        self.in_frame(self.half_edge[e as usize], k)
    }
}

/// Spherical caps holding a body's Gaussian cells (one per vertex) and arcs
/// (one per edge), in the body's frame: a cell is the spherical polygon of
/// its corners, inside any cap (no wider than a hemisphere) holding the
/// corners; an arc lies in the cap about its midpoint through its ends.
/// Turned with the body, they let the searches skip a cell that cannot
/// hold a direction, and pairs of arcs that cannot cross, with one dot
/// product each; the exact predicates decide the rest.
#[derive(Clone, Debug, Default)]
pub(crate) struct GaussCaps {
    /// Per vertex: the cap's unit centre and the cosine of its angle
    /// (`-1.0`, no rejection, for a cell wider than a hemisphere).
    pub(in crate::query) cells: Vec<(DVec3, f64)>,
    /// Per edge: the unit centre and the cosine of half the arc.
    pub(in crate::query) arcs: Vec<(DVec3, f64)>,
}

impl GaussCaps {
    /// The caps of `p`.
    pub(crate) fn of(p: &crate::polytope::Polytope) -> GaussCaps {
        let cells = (0..p.vertex_count())
            .map(|v| {
                let ring = p.ring(v);
                let sum = ring
                    .iter()
                    .fold(DVec3::ZERO, |s, r| s + p.unit_normal(r.face as usize));
                let len = sum.length();
                if len.is_nan() || len <= 1e-3 {
                    return (DVec3::X, -1.0);
                }
                let c = sum / len;
                let cos = ring
                    .iter()
                    .map(|r| c.dot(p.unit_normal(r.face as usize)))
                    .fold(1.0, f64::min);
                (c, if cos > 1e-3 { cos } else { -1.0 })
            })
            .collect();
        let arcs = p
            .edges()
            .iter()
            .map(|e| {
                let (a, b) = (
                    p.unit_normal(e.faces[0] as usize),
                    p.unit_normal(e.faces[1] as usize),
                );
                let mid = a + b;
                let len = mid.length();
                if len.is_nan() || len <= 1e-6 {
                    return (DVec3::X, -1.0);
                }
                let c = mid / len;
                (c, c.dot(a).min(c.dot(b)))
            })
            .collect();
        GaussCaps { cells, arcs }
    }
}

/// The mean of `n` points.
#[inline]
pub(in crate::query) fn mean(points: impl Iterator<Item = DVec3>, n: usize) -> DVec3 {
    points.fold(DVec3::ZERO, |s, p| s + p) / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::ConvexPair;

    fn cube(half: f64, centre: [f64; 3]) -> Polytope {
        let corners: Vec<[f64; 3]> = (0..8)
            .map(|i| [0, 1, 2].map(|k| centre[k] + if i >> k & 1 == 0 { -half } else { half }))
            .collect();
        Polytope::from_points(&corners).expect("a cube")
    }

    /// A body only ever A (a planner's robot) holds no reflection; the
    /// first pair that takes it as B makes it, and later pairs share it.
    #[test]
    fn only_a_body_taken_as_b_holds_its_reflection() {
        let (robot, wall) = (cube(0.5, [0.0; 3]), cube(1.0, [3.0, 0.0, 0.0]));
        let pair = ConvexPair::new(&robot, &wall).expect("a pair");
        assert!(BodyPrep::of_cached(&robot).reflection.get().is_none());
        assert!(BodyPrep::of_cached(&wall).reflection.get().is_some());
        assert!(std::sync::Arc::ptr_eq(
            &pair.refl_b,
            &ConvexPair::new(&wall, &wall).expect("a pair").refl_b
        ));
        let swapped = ConvexPair::new(&wall, &robot).expect("a pair");
        let made = BodyPrep::of_cached(&robot).reflection(&robot);
        assert!(std::sync::Arc::ptr_eq(&swapped.refl_b, &made));
        // The reflection keeps the body's numbering.
        for v in 0..robot.vertex_count() {
            assert_eq!(made.polytope.vertex(v), -robot.vertex(v));
        }
        // The answers do not depend on which pair made it.
        let at =
            |x: f64| crate::Pose::new(crate::Rotation::IDENTITY, glam::DVec3::new(x, 0.0, 0.0));
        assert!(swapped.intersects(at(0.0), at(2.0)).expect("a verdict"));
        assert!(!swapped.intersects(at(0.0), at(5.0)).expect("a verdict"));
    }
}
