//! `dymsum query ROBOT OBSTACLE --pose-xyz-wxyz X,Y,Z,W,QX,QY,QZ [...] [--json]`:
//! for each robot pose, whether the robot collides with the obstacle, with
//! the exact penetration depth or the distance.
//!
//! The robot's coordinates `p` become `R p + t` (the flag lists `t` first,
//! then the quaternion `R` scalar first, as its name says; `--pose` is a
//! hidden alias); the obstacle stays put. Every reported direction points
//! from the robot towards the obstacle, colliding or apart: the depth or
//! the distance says which side. Consecutive poses are
//! answered by one contact tracker (DYMSUM updates between poses), with the
//! same answers as from-scratch queries.
//!
//! A body may be a union of convex pieces: several operands joined with `+`
//! (`a.off+b.off`), or an OBJ file with several objects or groups. For
//! unions, collision and distance are exact (any pair collides; the minimum
//! pairwise distance); the penetration depth of a colliding non-convex
//! union is the origin's distance to the boundary of the merged C-obstacle
//! mesh ([`ConvexUnion::penetration_depth_mesh`]: exact piece-pair sums,
//! their union by `boolmesh` in floats), with the direction; the witness
//! points are then `null`.
//!
//! A body may also be a mesh file of any topology (open, double-sided,
//! non-manifold, non-convex, several components), taken as triangles
//! ([`super::solid::load_contact_body`]). For such a body only collision
//! is exact so far: `--collision-only` answers it (contact with a solid
//! component includes lying inside it; with a surface, touching a
//! triangle), and without that flag the query is refused, the problem
//! first and the fix last, as no exact depth or distance of triangles
//! exists yet. `--collision-only` takes every body (convex pieces on the
//! convex fast path).

use std::io::Write;

use anyhow::{anyhow, Context};
use clap::Args;
use dymsum::query::{Body, ConvexPair, ConvexUnion, Proximity, UnionProximity, Validator};
use dymsum::{DVec3, Polytope, Pose, Rotation};
use serde::Serialize;

use super::short_name;
use super::solid::{body_pieces, load_contact_body, triangle_components};
use crate::stats::{decimals, fixed, short};

/// Arguments of `dymsum query`.
#[derive(Debug, Args)]
pub struct QueryArgs {
    /// The robot: a mesh file or built-in model name; several convex pieces
    /// joined with `+`, or an OBJ file with several objects, form a union;
    /// any other mesh file is taken as triangles (for `--collision-only`).
    #[arg(value_name = "ROBOT")]
    pub robot: String,
    /// The obstacle (fixed at the origin): as ROBOT.
    #[arg(value_name = "OBSTACLE")]
    pub obstacle: String,
    /// A robot pose: translation X,Y,Z, then the unit quaternion W,QX,QY,QZ
    /// (scalar first; renormalised); p becomes R p + t. Repeat for several
    /// poses.
    #[arg(long = "pose-xyz-wxyz", alias = "pose", value_name = "X,Y,Z,W,QX,QY,QZ",
          required = true, value_parser = parse_pose, allow_hyphen_values = true)]
    pub poses: Vec<PoseArg>,
    /// One JSON object per pose and line: `{"pose_xyz_wxyz":[..7],
    /// "collides":b,"depth":d,"distance":s,"direction":[x,y,z],
    /// "point_on_robot":[x,y,z],"point_on_obstacle":[x,y,z]}`. `direction`
    /// is the unit vector from the robot towards the obstacle, colliding or
    /// apart (colliding: move the robot by `-depth * direction` to
    /// separate); the points are the deepest points when colliding and the
    /// closest points when apart (in world coordinates).
    #[arg(long)]
    pub json: bool,
    /// Only whether the robot touches or overlaps the obstacle at each pose
    /// (exact), without depth or distance: the query that bodies given as
    /// triangles (open, double-sided, non-manifold or non-convex meshes)
    /// take. Prints `collides` or `apart` per pose; with `--json`,
    /// `{"pose_xyz_wxyz":[..7],"collides":b}`.
    #[arg(long)]
    pub collision_only: bool,
    /// How meshes are taken: `--strict`, `--decomposition`.
    #[command(flatten)]
    pub body: super::solid::BodyOptions,
    /// Where the obstacle stands: translation X,Y,Z, then the unit
    /// quaternion W,QX,QY,QZ (scalar first), applied once to its vertices
    /// (an obstacle given in its own frame); without it the obstacle is
    /// taken as given, in the world frame.
    #[arg(long = "obstacle-xyz-wxyz", value_name = "X,Y,Z,W,QX,QY,QZ",
          value_parser = parse_pose, allow_hyphen_values = true)]
    pub obstacle_pose: Option<PoseArg>,
}

/// A parsed `--pose`: the 7 numbers as given, and the pose.
#[derive(Clone, Copy, Debug)]
pub struct PoseArg {
    /// `X,Y,Z,W,QX,QY,QZ` as given.
    pub values: [f64; 7],
    /// The rigid pose.
    pub pose: Pose,
}

/// Parses `X,Y,Z,W,QX,QY,QZ` (finite numbers, non-zero quaternion; `-0`
/// is kept as `0`).
///
/// # Errors
/// A message when there are not exactly 7 comma-separated values, a value
/// is not a finite number, or the quaternion is zero.
pub fn parse_pose(s: &str) -> Result<PoseArg, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 7 {
        return Err(format!(
            "expected 7 comma-separated numbers (X,Y,Z,W,QX,QY,QZ), got {}",
            parts.len()
        ));
    }
    let mut v = [0.0; 7];
    for (slot, p) in v.iter_mut().zip(&parts) {
        *slot = match p.parse::<f64>() {
            Ok(x) if x.is_finite() => x + 0.0,
            Ok(_) => return Err(format!("`{p}` is not a finite number")),
            Err(_) => return Err(format!("`{p}` is not a number")),
        };
    }
    let rotation = Rotation::from_wxyz(v[3], v[4], v[5], v[6])
        .ok_or_else(|| "the quaternion W,QX,QY,QZ is zero".to_string())?;
    Ok(PoseArg {
        values: v,
        pose: Pose::new(rotation, DVec3::new(v[0], v[1], v[2])),
    })
}

/// One line of `--json` output, in this key order. Every number goes
/// through [`no_negative_zero`].
#[derive(Serialize)]
struct JsonLine {
    pose_xyz_wxyz: [f64; 7],
    collides: bool,
    depth: Option<f64>,
    distance: f64,
    direction: Option<[f64; 3]>,
    point_on_robot: Option<[f64; 3]>,
    point_on_obstacle: Option<[f64; 3]>,
}

/// One line of `--collision-only --json` output.
#[derive(Serialize)]
struct JsonCollision {
    pose_xyz_wxyz: [f64; 7],
    collides: bool,
}

/// One pose's answer.
struct Answer {
    collides: bool,
    /// `None` only if the merged C-obstacle of a colliding non-convex union
    /// finds no overlap (never expected: collision is decided first).
    depth: Option<f64>,
    distance: f64,
    /// Unit vector from the robot towards the obstacle (the contact normal
    /// when colliding, the separation direction when apart).
    direction: Option<DVec3>,
    /// Witness points (robot, obstacle): the deepest points when colliding,
    /// the closest points when apart; `None` with `depth`.
    witnesses: Option<(DVec3, DVec3)>,
}

/// The unit direction from the robot (A) towards the obstacle (B): the
/// contact normal when they overlap, the separation direction when apart
/// (both point from A towards B in the library).
fn robot_to_obstacle(p: &Proximity) -> DVec3 {
    match p {
        Proximity::Penetrating(c) => c.normal,
        Proximity::Separated(s) => s.direction,
    }
}

fn from_proximity(p: &Proximity) -> Answer {
    let witnesses = match p {
        Proximity::Penetrating(c) => (c.point_on_a, c.point_on_b),
        Proximity::Separated(s) => (s.point_on_a, s.point_on_b),
    };
    Answer {
        collides: p.intersects(),
        depth: Some(p.depth()),
        distance: p.distance(),
        direction: Some(robot_to_obstacle(p)),
        witnesses: Some(witnesses),
    }
}

/// Runs `dymsum query`.
///
/// # Errors
/// ROBOT or OBSTACLE cannot be loaded ([`load_contact_body`]); a body
/// taken as triangles without `--collision-only` (`depth_pieces`); a
/// query fails at a pose ([`dymsum::query::QueryError`], naming the pose:
/// coordinates beyond `f64`, or an internal error); or `out` cannot be
/// written.
pub fn run(a: &QueryArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    super::stdin_for_one_operand(&[(&a.robot, "ROBOT"), (&a.obstacle, "OBSTACLE")])?;
    let robot = load_contact_body(&a.robot, "ROBOT", a.body)?;
    let obstacle = super::solid::placed(
        load_contact_body(&a.obstacle, "OBSTACLE", a.body)?,
        a.obstacle_pose.map(|p| p.pose),
    )?;
    if a.collision_only {
        let validator = Validator::new(&robot, std::slice::from_ref(&obstacle))
            .context("preparing the query")?;
        let answers = a
            .poses
            .iter()
            .enumerate()
            .map(|(k, p)| {
                validator
                    .collides_at(p.pose)
                    .with_context(|| format!("pose {}", k + 1))
            })
            .collect::<anyhow::Result<Vec<bool>>>()?;
        for (p, &collides) in a.poses.iter().zip(&answers) {
            if a.json {
                let line = JsonCollision {
                    pose_xyz_wxyz: p.values.map(no_negative_zero),
                    collides,
                };
                writeln!(out, "{}", serde_json::to_string(&line)?)?;
            } else {
                let answer = if collides { "collides" } else { "apart" };
                writeln!(out, "{}: {answer}", pose_text(p))?;
            }
        }
        return Ok(());
    }
    let robot = depth_pieces(&robot, &a.robot, "ROBOT")?;
    let obstacle = depth_pieces(&obstacle, &a.obstacle, "OBSTACLE")?;
    let answers = if robot.len() == 1 && obstacle.len() == 1 {
        convex_answers(&robot[0], &obstacle[0], &a.poses)?
    } else {
        union_answers(robot, obstacle, &a.poses)?
    };
    for (p, ans) in a.poses.iter().zip(&answers) {
        if a.json {
            write_json_answer(out, p, ans)?;
        } else {
            write_text_answer(out, p, ans)?;
        }
    }
    Ok(())
}

/// The convex pieces of a body for the depth and distance ([`body_pieces`]).
///
/// # Errors
/// A body taken as triangles: what it is, that depth and distance need
/// convex pieces, then the fix (`--collision-only`, the pieces, or for
/// solids a decomposition).
fn depth_pieces(body: &Body, spec: &str, operand: &str) -> anyhow::Result<Vec<Polytope>> {
    if let Some(pieces) = body_pieces(body) {
        return Ok(pieces);
    }
    let Body::Mesh(mesh) = body else {
        return Err(anyhow!("{operand} has no pieces"));
    };
    let r = mesh.report();
    let what = match (r.solids, r.surfaces) {
        (0, 1) => ": not a closed solid",
        (0, _) => ": not closed solids",
        (_, 0) => ", not convex",
        _ => "",
    };
    let pieces = if r.surfaces == 0 {
        "give the body's convex pieces as files joined with `+` or as OBJ objects, or take it \
         apart with `--decomposition vhacd` (approximate)"
    } else {
        "or give the body's convex pieces as files joined with `+` or as OBJ objects"
    };
    Err(anyhow!(
        "{operand} ({}) is a triangle mesh ({}{what}): distance and penetration depth need \
         bodies given as convex pieces; fix: add `--collision-only` for the exact collision \
         yes/no, {pieces}",
        short_name(spec),
        triangle_components(&r)
    ))
}

/// Answers for two convex bodies: one tracker carried from pose to pose.
fn convex_answers(
    robot: &Polytope,
    obstacle: &Polytope,
    poses: &[PoseArg],
) -> anyhow::Result<Vec<Answer>> {
    let pair = ConvexPair::new(robot, obstacle).context("preparing the query")?;
    let mut tracker = pair
        .tracker(poses[0].pose, Pose::IDENTITY)
        .context("the first pose")?;
    let mut answers = Vec::with_capacity(poses.len());
    for (k, p) in poses.iter().enumerate() {
        let prox = if k == 0 {
            *tracker.last()
        } else {
            tracker
                .update(p.pose, Pose::IDENTITY)
                .with_context(|| format!("pose {}", k + 1))?
        };
        answers.push(from_proximity(&prox));
    }
    Ok(answers)
}

/// Answers for bodies of several convex pieces, pose by pose.
fn union_answers(
    robot: Vec<Polytope>,
    obstacle: Vec<Polytope>,
    poses: &[PoseArg],
) -> anyhow::Result<Vec<Answer>> {
    let (ru, ou) = (
        ConvexUnion::new(robot).ok_or_else(|| anyhow!("ROBOT has no pieces"))?,
        ConvexUnion::new(obstacle).ok_or_else(|| anyhow!("OBSTACLE has no pieces"))?,
    );
    let single = ru.pieces().len() == 1 && ou.pieces().len() == 1;
    poses
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let q = ru
                .query(p.pose, &ou, Pose::IDENTITY)
                .with_context(|| format!("pose {}", k + 1))?;
            let mut ans = from_union_proximity(&q, single);
            if ans.collides && ans.depth.is_none() {
                let d = ru
                    .penetration_depth_mesh(p.pose, &ou, Pose::IDENTITY)
                    .with_context(|| format!("pose {}: the depth of the union", k + 1))?;
                if let Some(d) = d {
                    ans.depth = Some(d.depth);
                    ans.direction = (d.depth > 0.0).then_some(d.normal);
                }
            }
            Ok(ans)
        })
        .collect()
}

/// The answer of a union query; `single` when both unions have one piece
/// (then a collision's depth is known).
fn from_union_proximity(q: &UnionProximity, single: bool) -> Answer {
    match q {
        UnionProximity::Colliding(hits) if single => {
            let c = hits[0].1;
            Answer {
                collides: true,
                depth: Some(c.depth),
                distance: 0.0,
                direction: Some(c.normal),
                witnesses: Some((c.point_on_a, c.point_on_b)),
            }
        }
        UnionProximity::Colliding(_) => Answer {
            collides: true,
            depth: None,
            distance: 0.0,
            direction: None,
            witnesses: None,
        },
        UnionProximity::Separated(_, s) => Answer {
            collides: false,
            depth: Some(0.0),
            distance: s.distance,
            direction: Some(s.direction),
            witnesses: Some((s.point_on_a, s.point_on_b)),
        },
    }
}

/// `x`, with `-0.0` as `0.0` (the sign of a zero component is noise, and
/// `-0.0` in the output reads as a different answer).
fn no_negative_zero(x: f64) -> f64 {
    x + 0.0
}

/// A vector for the JSON output, with no negative zero.
fn json_vec(v: DVec3) -> [f64; 3] {
    v.to_array().map(no_negative_zero)
}

/// One answer as a JSON line.
fn write_json_answer(out: &mut dyn Write, p: &PoseArg, ans: &Answer) -> anyhow::Result<()> {
    let line = JsonLine {
        pose_xyz_wxyz: p.values.map(no_negative_zero),
        collides: ans.collides,
        depth: ans.depth.map(no_negative_zero),
        distance: no_negative_zero(ans.distance),
        direction: ans.direction.map(json_vec),
        point_on_robot: ans.witnesses.map(|w| json_vec(w.0)),
        point_on_obstacle: ans.witnesses.map(|w| json_vec(w.1)),
    };
    writeln!(out, "{}", serde_json::to_string(&line)?)?;
    Ok(())
}

/// A pose as text: `t = (x, y, z), q = (w, qx, qy, qz)`.
fn pose_text(p: &PoseArg) -> String {
    let v = p.values.map(short);
    format!(
        "t = ({}, {}, {}), q = ({}, {}, {}, {})",
        v[0], v[1], v[2], v[3], v[4], v[5], v[6]
    )
}

/// One answer as a line of text.
fn write_text_answer(out: &mut dyn Write, p: &PoseArg, ans: &Answer) -> std::io::Result<()> {
    let pose = pose_text(p);
    let dir = |d: Option<DVec3>| match d {
        Some(d) => format!(
            "({}, {}, {})",
            decimals(d.x, 6),
            decimals(d.y, 6),
            decimals(d.z, 6)
        ),
        None => "n/a".to_string(),
    };
    if !ans.collides {
        return writeln!(
            out,
            "{pose}: apart, distance {}, direction robot to obstacle {}",
            fixed(ans.distance, 9),
            dir(ans.direction)
        );
    }
    match ans.depth {
        Some(depth) => writeln!(
            out,
            "{pose}: collides, depth {}, direction robot to obstacle {}",
            fixed(depth, 9),
            dir(ans.direction)
        ),
        None => writeln!(
            out,
            "{pose}: collides (depth of a non-convex union is not supported)"
        ),
    }
}
