//! `dymsum motion ROBOT OBSTACLE --from-xyz-wxyz POSE --to-xyz-wxyz POSE
//! [--tolerance T] [--budget N] [--json]`: whether the robot, moving straight from one
//! pose to the other (translation linear, rotation by slerp: OMPL's SE(2)
//! and SE(3) interpolation), touches the obstacle at any instant: certified
//! free, or the first contact bracketed within the tolerance (in the
//! motion's parameter `t` from 0 to 1), never by sampling.
//!
//! The arc of the rotation is decided from the quaternions as given (the
//! exact sign of their dot product: `--to-xyz-wxyz 0,0,0,-1e-300,0,0,1`
//! turns the short way, clockwise), and the search examines at most
//! `--budget` intervals (deterministic; past it the answer is undecided
//! with the certified `t_safe`).
//!
//! A body may be a union of convex pieces (`a.off+b.off`, or an OBJ file
//! with several objects), or a mesh file of any topology taken as
//! triangles ([`super::solid::load_contact_body`]: contact with a solid
//! component includes lying inside it, with a surface touching a
//! triangle); bodies of convex pieces keep the convex checker
//! ([`Validator`]). The obstacle stays put.

use std::io::Write;

use anyhow::Context;
use clap::Args;
use dymsum::query::{Motion, MotionCheck, Validator};
use serde::Serialize;

use super::query::{parse_pose, PoseArg};
use super::solid::load_contact_body;
use crate::stats::decimals;

/// Arguments of `dymsum motion`.
#[derive(Debug, Args)]
pub struct MotionArgs {
    /// The robot: a mesh file or built-in model name; several convex pieces
    /// joined with `+`, or an OBJ file with several objects, form a union;
    /// any other mesh file (open, double-sided, non-manifold, non-convex) is
    /// taken as triangles.
    #[arg(value_name = "ROBOT")]
    pub robot: String,
    /// The obstacle (fixed in the world): as ROBOT.
    #[arg(value_name = "OBSTACLE")]
    pub obstacle: String,
    /// The start pose: translation X,Y,Z, then the unit quaternion
    /// W,QX,QY,QZ (scalar first; renormalised); p becomes R p + t.
    #[arg(long = "from-xyz-wxyz", alias = "from", value_name = "X,Y,Z,W,QX,QY,QZ",
          value_parser = parse_pose, allow_hyphen_values = true)]
    pub from: PoseArg,
    /// The end pose, as --from-xyz-wxyz.
    #[arg(long = "to-xyz-wxyz", alias = "to", value_name = "X,Y,Z,W,QX,QY,QZ",
          value_parser = parse_pose, allow_hyphen_values = true)]
    pub to: PoseArg,
    /// The widest bracket of the first contact, in the motion's parameter t
    /// (0 at the start, 1 at the end).
    /// At least 2^-38 (about 3.6e-12), the smallest the search can bracket.
    #[arg(long, default_value_t = 1e-6, value_name = "T")]
    pub tolerance: f64,
    /// The most intervals the search examines before it gives up as
    /// undecided (with the time up to which the motion is certified free):
    /// a deterministic cap on the work of a motion grazing an obstacle.
    #[arg(long, default_value_t = dymsum::query::DEFAULT_BUDGET, value_name = "N",
          value_parser = clap::value_parser!(u64).range(1..))]
    pub budget: u64,
    /// One JSON object: `{"free":b,"t_safe":x|null,"t_contact":x|null,
    /// "contact_pose_xyz_wxyz":[..7]|null}`. `t_safe`: every t up to it is
    /// certified free (null when the robot collides at the start);
    /// `t_contact`: the robot touches or overlaps the obstacle there.
    #[arg(long)]
    pub json: bool,
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

/// The `--json` output, in this key order.
#[derive(Serialize)]
struct JsonAnswer {
    free: bool,
    t_safe: Option<f64>,
    t_contact: Option<f64>,
    contact_pose_xyz_wxyz: Option<[f64; 7]>,
}

/// Runs `dymsum motion`.
///
/// # Errors
/// ROBOT or OBSTACLE cannot be loaded; the tolerance is not in
/// `[2^-38, 1)`; a pose overflows `f64`; the motion grazes the obstacle
/// within rounding or uses up the budget (undecided); or `out` cannot be
/// written.
pub fn run(a: &MotionArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    super::stdin_for_one_operand(&[(&a.robot, "ROBOT"), (&a.obstacle, "OBSTACLE")])?;
    let robot = load_contact_body(&a.robot, "ROBOT", a.body)?;
    let obstacle = super::solid::placed(
        load_contact_body(&a.obstacle, "OBSTACLE", a.body)?,
        a.obstacle_pose.map(|p| p.pose),
    )?;
    let checker = Validator::new(&robot, &[obstacle])
        .context("preparing the check")?
        .with_budget(a.budget);
    let answer = checker
        .check(a.from.pose, a.to.pose, a.tolerance)
        .context("the motion check")?;
    let contact_pose = match answer {
        MotionCheck::Free => None,
        MotionCheck::Collides { t_contact, .. } => {
            let p = Motion::new(a.from.pose, a.to.pose).at(t_contact);
            let [w, x, y, z] = p.rotation.wxyz();
            let t = p.translation;
            Some([t.x, t.y, t.z, w, x, y, z].map(|v| v + 0.0))
        }
    };
    if a.json {
        let (t_safe, t_contact) = match answer {
            MotionCheck::Free => (None, None),
            MotionCheck::Collides { t_safe, t_contact } => (t_safe, Some(t_contact)),
        };
        let line = JsonAnswer {
            free: answer.is_free(),
            t_safe: t_safe.map(|t| t + 0.0),
            t_contact: t_contact.map(|t| t + 0.0),
            contact_pose_xyz_wxyz: contact_pose,
        };
        writeln!(out, "{}", serde_json::to_string(&line)?)?;
        return Ok(());
    }
    match answer {
        MotionCheck::Free => writeln!(out, "free: no contact at any t in [0, 1] (certified)")?,
        MotionCheck::Collides { t_safe, t_contact } => {
            let safe = t_safe.map_or("none (in contact at the start)".to_string(), |t| {
                decimals(t, 9)
            });
            writeln!(
                out,
                "collides: certified free up to t = {safe}, in contact at t = {}",
                decimals(t_contact, 9)
            )?;
            if let Some(p) = contact_pose {
                let text: Vec<String> = p.iter().map(|&v| decimals(v, 6)).collect();
                writeln!(
                    out,
                    "pose at contact (x,y,z,w,qx,qy,qz): {}",
                    text.join(",")
                )?;
            }
        }
    }
    Ok(())
}
