//! Exact configuration checks of a robot: against itself (the link pairs
//! kept) and against a scene of obstacles in the root's frame.
//!
//! Each link's collision geometry is a [`MeshBody`] in its own frame; a
//! configuration poses the links by [`Robot::forward`]. A link collides
//! with the scene as [`SceneChecker`] decides it at the link's pose, and
//! two links collide as `SceneChecker` decides the first at its pose
//! relative to the second (`pose_j⁻¹ ∘ pose_i`, composed in floats): the
//! scene checker's contact (touching counts, a link inside a closed link
//! or obstacle counts), exact on the posed vertices as computed.

use rayon::prelude::*;

use super::error::RobotError;
use super::kinematics::{compose, inverse};
use super::model::Robot;
use super::separation::Corners;
use crate::body::MeshBody;
use crate::kernel::rotation::Pose;
use crate::query::SceneChecker;

/// The most obstacles the motion search gives each a separating plane
/// (one plane test per obstacle a step: `robot::motion`).
pub(super) const PLANE_OBSTACLES: usize = 32;

/// A robot prepared for many configuration checks against a scene.
///
/// ```
/// use dymsum::robot::{JointKind, JointSpec, LinkSpec, Robot, RobotChecker};
/// use dymsum::robot::shapes::box_mesh;
/// use dymsum::query::MeshBody;
/// use dymsum::{DVec3, Pose, Rotation};
/// // Two bars 1 m long on a hinge at x = 1, the second bar folding back.
/// let bar = MeshBody::new(&box_mesh(DVec3::new(1.0, 0.1, 0.1)))?;
/// let placed = |x: f64| bar.placed(Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0)));
/// let links = vec![
///     LinkSpec { name: "a".into(), body: Some(placed(0.5)?) },
///     LinkSpec { name: "b".into(), body: Some(placed(0.5)?) },
///     LinkSpec { name: "c".into(), body: Some(placed(0.5)?) },
/// ];
/// let hinge = |name: &str, parent: &str, child: &str| JointSpec {
///     name: name.into(),
///     kind: JointKind::Revolute { lower: -3.1, upper: 3.1 },
///     parent: parent.into(),
///     child: child.into(),
///     origin: Pose::new(Rotation::IDENTITY, DVec3::new(1.0, 0.0, 0.0)),
///     axis: DVec3::Y,
///     mimic: None,
/// };
/// let robot = Robot::new(links, vec![hinge("j1", "a", "b"), hinge("j2", "b", "c")])?;
/// let checker = RobotChecker::new(robot, &[])?;
/// // Adjacent links are not checked: only a–c.
/// assert_eq!(checker.collision_pair_names(), [("a".to_string(), "c".to_string())]);
/// assert!(!checker.collides_at(&[0.0, 0.0])?);
/// // Folding both hinges by 160° brings c back over a.
/// let fold = 160f64.to_radians();
/// assert!(checker.collides_at(&[fold, fold])?);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct RobotChecker {
    robot: Robot,
    /// The link pairs checked, by index, and a checker of each (the first
    /// link against the second).
    pairs: Vec<(usize, usize)>,
    pair_checkers: Vec<SceneChecker>,
    /// Each link's hull corners (`None` without geometry): the motion
    /// search's plane certificate (`robot::separation`).
    corners: Vec<Option<Corners>>,
    /// Each obstacle's hull corners, when there are at most
    /// [`PLANE_OBSTACLES`] obstacles (else none: links against the scene
    /// are then certified by the swept test alone).
    obstacle_corners: Vec<Corners>,
    /// A checker of each link with geometry against the scene.
    scene_checkers: Vec<Option<SceneChecker>>,
}

impl std::fmt::Debug for RobotChecker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RobotChecker")
            .field("links", &self.robot.links.len())
            .field("dof", &self.robot.dof())
            .field("pairs", &self.pairs.len())
            .finish()
    }
}

/// One contact of a configuration: a link against another, or against
/// the scene (`None`).
pub type LinkContact = (String, Option<String>);

impl RobotChecker {
    /// Prepares `robot` against `obstacles` (in the root link's frame;
    /// may be empty), checking the robot's collision pairs
    /// ([`Robot::collision_pairs`]: by default every pair of links with
    /// geometry not joined by a joint).
    ///
    /// # Errors
    /// [`RobotError::Query`] when a checker cannot be built.
    pub fn new(robot: Robot, obstacles: &[MeshBody]) -> Result<RobotChecker, RobotError> {
        let scene_checkers = robot
            .links
            .iter()
            .map(|l| match (&l.body, obstacles.is_empty()) {
                (Some(b), false) => SceneChecker::new(b, obstacles).map(Some),
                _ => Ok(None),
            })
            .collect::<Result<Vec<_>, _>>()?;
        let pairs = robot.pairs.clone();
        let body = |l: usize| robot.links[l].body.as_ref();
        let pair_checkers = pairs
            .iter()
            .map(|&(i, j)| match (body(i), body(j)) {
                (Some(a), Some(b)) => Ok(SceneChecker::new(a, std::slice::from_ref(b))?),
                _ => Err(RobotError::BadPair("a link without geometry".into())),
            })
            .collect::<Result<Vec<_>, RobotError>>()?;
        let corners = robot
            .links
            .iter()
            .map(|l| l.body.as_ref().map(|b| Corners::new(b.vertices())))
            .collect();
        let obstacle_corners = if obstacles.len() <= PLANE_OBSTACLES {
            obstacles
                .iter()
                .map(|o| Corners::new(o.vertices()))
                .collect()
        } else {
            Vec::new()
        };
        Ok(RobotChecker {
            robot,
            pairs,
            pair_checkers,
            corners,
            obstacle_corners,
            scene_checkers,
        })
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The link pairs checked, by name.
    pub fn collision_pair_names(&self) -> Vec<(String, String)> {
        self.robot.collision_pair_names()
    }

    /// Whether the robot at configuration `q` touches itself (a pair kept)
    /// or the scene (exact; module docs).
    ///
    /// # Errors
    /// [`RobotError::BadConfiguration`] (naming the joint) or
    /// [`RobotError::Query`].
    pub fn collides_at(&self, q: &[f64]) -> Result<bool, RobotError> {
        let poses = self.robot.forward(q)?;
        for (l, c) in self.scene_checkers.iter().enumerate() {
            if let Some(c) = c {
                if c.collides_at(poses[l])? {
                    return Ok(true);
                }
            }
        }
        for (&(i, j), c) in self.pairs.iter().zip(&self.pair_checkers) {
            if c.collides_at(relative(&poses, i, j))? {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// [`RobotChecker::collides_at`] for many configurations, in parallel,
    /// in order.
    ///
    /// # Errors
    /// The first error, in order.
    pub fn collides_many(&self, qs: &[Vec<f64>]) -> Result<Vec<bool>, RobotError> {
        qs.par_iter().map(|q| self.collides_at(q)).collect()
    }

    /// Every contact at configuration `q`: each link against the scene,
    /// then each pair kept, in order.
    ///
    /// # Errors
    /// As [`RobotChecker::collides_at`].
    pub fn colliding_pairs(&self, q: &[f64]) -> Result<Vec<LinkContact>, RobotError> {
        let poses = self.robot.forward(q)?;
        let name = |l: usize| self.robot.links[l].name.clone();
        let mut out = Vec::new();
        for (l, c) in self.scene_checkers.iter().enumerate() {
            if let Some(c) = c {
                if c.collides_at(poses[l])? {
                    out.push((name(l), None));
                }
            }
        }
        for (&(i, j), c) in self.pairs.iter().zip(&self.pair_checkers) {
            if c.collides_at(relative(&poses, i, j))? {
                out.push((name(i), Some(name(j))));
            }
        }
        Ok(out)
    }

    /// A certified lower bound on the distance between the links and the
    /// scene and between the pairs kept at configuration `q` (`0` in
    /// contact; `f64::INFINITY` when nothing is checked), the least of
    /// [`SceneChecker::distance_at`] over them.
    ///
    /// # Errors
    /// As [`RobotChecker::collides_at`].
    pub fn distance_at(&self, q: &[f64]) -> Result<f64, RobotError> {
        let poses = self.robot.forward(q)?;
        let mut best = f64::INFINITY;
        for (l, c) in self.scene_checkers.iter().enumerate() {
            if let Some(c) = c {
                best = best.min(c.distance_at(poses[l])?);
            }
        }
        for (&(i, j), c) in self.pairs.iter().zip(&self.pair_checkers) {
            best = best.min(c.distance_at(relative(&poses, i, j))?);
        }
        Ok(best)
    }
}

impl RobotChecker {
    /// The checkers measured by a motion search, numbered: each link's
    /// against the scene (`(link, None)`), then each pair's.
    pub(super) fn measured_pairs(
        &self,
    ) -> impl Iterator<Item = (usize, &SceneChecker, (usize, Option<usize>))> {
        let scene = self
            .scene_checkers
            .iter()
            .enumerate()
            .filter_map(|(l, c)| c.as_ref().map(|c| (c, (l, None))));
        let pairs = self
            .pairs
            .iter()
            .zip(&self.pair_checkers)
            .map(|(&(i, j), c)| (c, (i, Some(j))));
        scene.chain(pairs).enumerate().map(|(k, (c, p))| (k, c, p))
    }

    /// Whether the measured checker's body at the links' poses is more
    /// than `reach` from its scene, certified (`false`: not proved).
    pub(super) fn apart_by(
        &self,
        c: &SceneChecker,
        poses: &[Pose],
        i: usize,
        j: Option<usize>,
        reach: f64,
    ) -> bool {
        let pose = match j {
            Some(j) => relative(poses, i, j),
            None => poses[i],
        };
        c.apart_at(pose, reach)
    }

    /// Each obstacle's hull corners (empty past [`PLANE_OBSTACLES`]).
    pub(super) fn obstacle_corners(&self) -> &[Corners] {
        &self.obstacle_corners
    }

    /// Link `l`'s hull corners (`None` without geometry).
    pub(super) fn corners(&self, l: usize) -> Option<&Corners> {
        self.corners[l].as_ref()
    }

    /// The largest norm of a scene point (`0` without a scene).
    pub(super) fn scene_size(&self) -> f64 {
        self.scene_checkers
            .iter()
            .flatten()
            .map(|c| c.scene().reach)
            .fold(0.0, f64::max)
    }
}

/// Link `i`'s pose in link `j`'s frame.
fn relative(poses: &[Pose], i: usize, j: usize) -> Pose {
    compose(&inverse(&poses[j]), &poses[i])
}
