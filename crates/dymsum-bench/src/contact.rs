//! The contact-tracking workload shared by the `tracker_vs_parry` bench and
//! the `tracker_timing` example: body A turns about a fixed axis at a given
//! number of steps per turn while it slides in and out of contact with B,
//! which turns slowly the other way; and the same poses and shapes for
//! parry3d-f64's GJK/EPA `contact`.

use dymsum::query::Proximity;
use dymsum::{DVec3, Polytope, Pose, Rotation};
use parry3d_f64::math::{Pose as ParryPose, Rotation as ParryRotation, Vector};
use parry3d_f64::query::Contact;
use parry3d_f64::shape::ConvexPolyhedron;

/// Largest distance of a vertex from the shape's origin.
pub fn radius(p: &Polytope) -> f64 {
    p.vertices().iter().map(|v| v.length()).fold(0.0, f64::max)
}

/// `frames` poses of A and B: A turns about `(1, 2, 3)` by `2π /
/// steps_per_turn` per frame and slides along x between `±1.1 (r_A + r_B)`
/// (one slide out, through B and back every 1000 frames, whatever the
/// resolution), B turns about `(−2, 0.5, 1)` at 0.7 of A's rate the other
/// way. About 30–70% of the frames are in contact.
///
/// # Panics
/// Never for the fixed, non-zero axes.
pub fn contact_motion(
    a: &Polytope,
    b: &Polytope,
    steps_per_turn: f64,
    frames: usize,
) -> Vec<(Pose, Pose)> {
    let reach = 1.1 * (radius(a) + radius(b));
    let step = std::f64::consts::TAU / steps_per_turn;
    let (axis_a, axis_b) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(-2.0, 0.5, 1.0));
    (0..frames)
        .map(|k| {
            let s = k as f64 * step;
            let slide = std::f64::consts::TAU * k as f64 / 1000.0;
            (
                Pose::new(
                    Rotation::from_axis_angle(axis_a, s).expect("non-zero axis"),
                    DVec3::new(reach * slide.cos(), 0.3, 0.1),
                ),
                Pose::new(
                    Rotation::from_axis_angle(axis_b, -0.7 * s).expect("non-zero axis"),
                    DVec3::ZERO,
                ),
            )
        })
        .collect()
}

/// The polytope as parry's convex polyhedron (the hull of its vertices).
///
/// # Panics
/// If parry cannot build the hull (not for a valid polytope).
pub fn parry_shape(p: &Polytope) -> ConvexPolyhedron {
    let v: Vec<Vector> = p
        .vertices()
        .iter()
        .map(|v| Vector::new(v.x, v.y, v.z))
        .collect();
    ConvexPolyhedron::from_convex_hull(&v).expect("parry's hull of a polytope")
}

/// The pose as parry's.
pub fn parry_pose(p: Pose) -> ParryPose {
    let q = p.rotation.quat();
    let t = p.translation;
    ParryPose::from_parts(
        Vector::new(t.x, t.y, t.z),
        ParryRotation::from_xyzw(q.x, q.y, q.z, q.w),
    )
}

/// How our answer for one frame compares with parry's `contact` (with
/// prediction 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Agreement {
    /// Both in contact: `|parry's depth − ours|`.
    Depths(f64),
    /// Both apart.
    Apart,
    /// Only we report a contact.
    OnlyOurs,
    /// Only parry reports a contact.
    OnlyParry,
}

/// Compares our answer with parry's for one frame.
pub fn agreement(ours: &Proximity, theirs: Option<&Contact>) -> Agreement {
    match theirs {
        Some(t) if ours.intersects() => Agreement::Depths((-t.dist - ours.depth()).abs()),
        None if ours.intersects() => Agreement::OnlyOurs,
        Some(t) if t.dist < 0.0 => Agreement::OnlyParry,
        _ => Agreement::Apart,
    }
}
