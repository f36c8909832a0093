//! A robot: links (each with its collision geometry as one
//! [`MeshBody`] in the link's frame, or none) joined by joints into a
//! tree, as a URDF describes it.

use glam::DVec3;

use super::error::RobotError;
use crate::body::MeshBody;
use crate::kernel::rotation::Pose;

/// How a joint moves its child link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointKind {
    /// Rigid.
    Fixed,
    /// A turn about the axis by the joint's value (radians) within
    /// `[lower, upper]`.
    Revolute {
        /// Least value.
        lower: f64,
        /// Greatest value.
        upper: f64,
    },
    /// A turn about the axis by any angle.
    Continuous,
    /// A move along the axis by the joint's value (metres) within
    /// `[lower, upper]`.
    Prismatic {
        /// Least value.
        lower: f64,
        /// Greatest value.
        upper: f64,
    },
}

/// A joint follows another: its value is `multiplier · q[joint] + offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct Mimic {
    /// The name of the joint followed.
    pub joint: String,
    /// The factor.
    pub multiplier: f64,
    /// The offset.
    pub offset: f64,
}

/// A joint as given: the child's frame is the parent's moved by `origin`,
/// then by the joint's motion along or about `axis` (in the child's
/// frame at zero, unit length not required).
#[derive(Clone, Debug)]
pub struct JointSpec {
    /// The joint's name.
    pub name: String,
    /// How it moves.
    pub kind: JointKind,
    /// The parent link's name.
    pub parent: String,
    /// The child link's name.
    pub child: String,
    /// The child frame at zero, in the parent's frame.
    pub origin: Pose,
    /// The axis (any non-zero length; ignored for fixed joints).
    pub axis: DVec3,
    /// Set when the joint follows another.
    pub mimic: Option<Mimic>,
}

/// A link as given: its name and collision geometry (in its own frame).
#[derive(Clone, Debug)]
pub struct LinkSpec {
    /// The link's name.
    pub name: String,
    /// The collision geometry, or `None` when it has none.
    pub body: Option<MeshBody>,
}

/// A joint of a built robot.
#[derive(Clone, Debug)]
pub(crate) struct Joint {
    pub(crate) spec: JointSpec,
    pub(crate) parent: usize,
    pub(crate) child: usize,
    /// The unit axis.
    pub(crate) axis: DVec3,
    /// The joint's value: `q[dof]`, or a mimic of one.
    pub(crate) value: Value,
}

/// Where a joint's value comes from.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Value {
    /// No value (a fixed joint).
    None,
    /// `q[k]`.
    Dof(usize),
    /// `multiplier · q[k] + offset`.
    Mimic(usize, f64, f64),
}

/// A robot: a tree of links joined by joints ([`Robot::new`]).
///
/// ```
/// use dymsum::robot::{JointKind, JointSpec, LinkSpec, Robot};
/// use dymsum::{DVec3, Pose};
/// let joint = JointSpec {
///     name: "elbow".into(),
///     kind: JointKind::Revolute { lower: -2.0, upper: 2.0 },
///     parent: "upper".into(),
///     child: "fore".into(),
///     origin: Pose::new(dymsum::Rotation::IDENTITY, DVec3::new(1.0, 0.0, 0.0)),
///     axis: DVec3::Z,
///     mimic: None,
/// };
/// let links = ["upper", "fore"].map(|n| LinkSpec { name: n.into(), body: None });
/// let robot = Robot::new(links.to_vec(), vec![joint])?;
/// assert_eq!(robot.joint_names(), ["elbow"]);
/// let poses = robot.forward(&[std::f64::consts::FRAC_PI_2])?;
/// // The forearm's x axis now points along y.
/// assert!((poses[1].rotation.apply(DVec3::X) - DVec3::Y).length() < 1e-15);
/// assert!(robot.forward(&[2.5]).is_err()); // beyond the limit
/// # Ok::<(), dymsum::robot::RobotError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Robot {
    pub(crate) links: Vec<LinkSpec>,
    /// Joints in an order where each parent link's pose is known first.
    pub(crate) joints: Vec<Joint>,
    /// The joints that are degrees of freedom, in configuration order.
    pub(crate) dofs: Vec<usize>,
    pub(crate) root: usize,
    /// The link pairs a checker tests, by index (smaller first).
    pub(crate) pairs: Vec<(usize, usize)>,
}

impl Robot {
    /// Builds and checks a robot: the links' names unique, every joint
    /// between two links, every link but one (the root) the child of
    /// exactly one joint, no loops; axes non-zero and finite, limits
    /// ordered and finite, mimics of degrees of freedom. Degrees of
    /// freedom are the revolute, continuous and prismatic joints that do
    /// not mimic another, in the order given.
    ///
    /// # Errors
    /// [`RobotError::NotATree`] or [`RobotError::BadJoint`], naming the
    /// element.
    pub fn new(links: Vec<LinkSpec>, joints: Vec<JointSpec>) -> Result<Robot, RobotError> {
        let index = |name: &str| links.iter().position(|l| l.name == name);
        for (i, l) in links.iter().enumerate() {
            if links[..i].iter().any(|m| m.name == l.name) {
                return Err(RobotError::NotATree(format!(
                    "link {:?} is named twice",
                    l.name
                )));
            }
        }
        let mut parent_joint: Vec<Option<usize>> = vec![None; links.len()];
        let mut built = Vec::with_capacity(joints.len());
        for (j, spec) in joints.iter().enumerate() {
            if joints[..j].iter().any(|o| o.name == spec.name) {
                return Err(RobotError::NotATree(format!(
                    "joint {:?} is named twice",
                    spec.name
                )));
            }
            let missing = |l: &str| {
                RobotError::NotATree(format!("joint {:?} names a missing link {l:?}", spec.name))
            };
            let parent = index(&spec.parent).ok_or_else(|| missing(&spec.parent))?;
            let child = index(&spec.child).ok_or_else(|| missing(&spec.child))?;
            if let Some(other) = parent_joint[child].replace(j) {
                return Err(RobotError::NotATree(format!(
                    "link {:?} is the child of two joints, {:?} and {:?}",
                    spec.child, joints[other].name, spec.name
                )));
            }
            let bad = |reason: &str| RobotError::BadJoint {
                joint: spec.name.clone(),
                reason: reason.into(),
            };
            if !spec.origin.translation.is_finite() {
                return Err(bad("the origin is not finite"));
            }
            let axis = match spec.kind {
                JointKind::Fixed => DVec3::Z,
                _ => {
                    let len = spec.axis.length();
                    if !len.is_finite() || len == 0.0 {
                        return Err(bad("the axis is zero or not finite"));
                    }
                    spec.axis / len
                }
            };
            if let JointKind::Revolute { lower, upper } | JointKind::Prismatic { lower, upper } =
                spec.kind
            {
                if !(lower.is_finite() && upper.is_finite() && lower <= upper) {
                    return Err(bad(&format!(
                        "the limits [{lower}, {upper}] are not finite and ordered"
                    )));
                }
            }
            built.push(Joint {
                spec: spec.clone(),
                parent,
                child,
                axis,
                value: Value::None,
            });
        }
        if links.is_empty() {
            return Err(RobotError::NotATree("the robot has no links".into()));
        }
        let roots: Vec<usize> = (0..links.len())
            .filter(|&l| parent_joint[l].is_none())
            .collect();
        let root = match roots.as_slice() {
            [r] => *r,
            [] => {
                return Err(RobotError::NotATree(
                    "no root link (every link is a child: a loop)".into(),
                ))
            }
            _ => {
                return Err(RobotError::NotATree(format!(
                    "more than one root link: {}",
                    roots
                        .iter()
                        .map(|&r| format!("{:?}", links[r].name))
                        .collect::<Vec<_>>()
                        .join(", ")
                )))
            }
        };
        // Order the joints from the root (breadth first); a joint never
        // reached lies on a loop.
        let mut order = Vec::with_capacity(built.len());
        let mut frontier = vec![root];
        while let Some(l) = frontier.pop() {
            for (j, joint) in built.iter().enumerate() {
                if joint.parent == l {
                    order.push(j);
                    frontier.push(joint.child);
                }
            }
        }
        if order.len() != built.len() {
            let lost = (0..built.len()).find(|j| !order.contains(j)).unwrap_or(0);
            return Err(RobotError::NotATree(format!(
                "joint {:?} lies on a loop (its links are not reached from the root {:?})",
                built[lost].spec.name, links[root].name
            )));
        }
        let mut joints: Vec<Joint> = order.iter().map(|&j| built[j].clone()).collect();
        // Degrees of freedom in the order the joints were given (`order[k]`
        // is the given index of the walk's `k`-th joint), then the mimics.
        let mut dofs = Vec::new();
        let mut by_given: Vec<usize> = (0..joints.len()).collect();
        by_given.sort_by_key(|&k| order[k]);
        for &k in &by_given {
            let j = &joints[k];
            if j.spec.kind != JointKind::Fixed && j.spec.mimic.is_none() {
                joints[k].value = Value::Dof(dofs.len());
                dofs.push(k);
            }
        }
        // Mimics, resolved to a degree of freedom through chains of mimics
        // (`m₂(m₁ q + o₁) + o₂`); a chain that never reaches one (a cycle,
        // a missing or fixed joint) is an error naming the joint.
        for k in 0..joints.len() {
            if joints[k].spec.mimic.is_none() || joints[k].spec.kind == JointKind::Fixed {
                continue;
            }
            let (mut at, mut scale, mut shift) = (k, 1.0f64, 0.0f64);
            let mut steps = 0;
            let resolved = loop {
                let Some(m) = joints[at].spec.mimic.clone() else {
                    break None;
                };
                if !(m.multiplier.is_finite() && m.offset.is_finite()) {
                    return Err(RobotError::BadJoint {
                        joint: joints[at].spec.name.clone(),
                        reason: "the mimic's multiplier or offset is not finite".into(),
                    });
                }
                shift += scale * m.offset;
                scale *= m.multiplier;
                let followed = joints.iter().position(|o| o.spec.name == m.joint);
                match followed.map(|f| (f, joints[f].value, joints[f].spec.kind)) {
                    Some((_, Value::Dof(d), _)) => break Some(d),
                    Some((f, _, kind)) if kind != JointKind::Fixed && steps < joints.len() => {
                        at = f;
                        steps += 1;
                    }
                    _ => break None,
                }
            };
            let Some(d) = resolved else {
                return Err(RobotError::BadJoint {
                    joint: joints[k].spec.name.clone(),
                    reason: format!(
                        "it mimics {:?}, which is missing, fixed, or a chain of mimics that reaches \
                         no degree of freedom",
                        joints[k].spec.mimic.as_ref().map_or("", |m| m.joint.as_str())
                    ),
                });
            };
            joints[k].value = Value::Mimic(d, scale, shift);
        }
        let mut robot = Robot {
            links,
            joints,
            dofs,
            root,
            pairs: Vec::new(),
        };
        robot.pairs = robot.default_pairs();
        Ok(robot)
    }

    /// Every pair of links with geometry except those joined by a joint
    /// (adjacent links touch by design, as MoveIt's default has it).
    fn default_pairs(&self) -> Vec<(usize, usize)> {
        let adjacent = self.adjacent_pairs();
        let with_body: Vec<usize> = (0..self.links.len())
            .filter(|&l| self.links[l].body.is_some())
            .collect();
        let mut pairs = Vec::new();
        for (k, &i) in with_body.iter().enumerate() {
            for &j in &with_body[k + 1..] {
                if !adjacent.contains(&(i, j)) && !adjacent.contains(&(j, i)) {
                    pairs.push((i, j));
                }
            }
        }
        pairs
    }

    /// The link pairs checked, by index (by default every pair of links
    /// with geometry not joined by a joint).
    pub fn collision_pairs(&self) -> &[(usize, usize)] {
        &self.pairs
    }

    /// The link pairs checked, by name.
    pub fn collision_pair_names(&self) -> Vec<(String, String)> {
        let name = |l: usize| self.links[l].name.clone();
        self.pairs
            .iter()
            .map(|&(i, j)| (name(i), name(j)))
            .collect()
    }

    /// Sets the link pairs checked, by name (each pair once; order within
    /// a pair does not matter).
    ///
    /// # Errors
    /// [`RobotError::BadPair`] naming a missing link, a link without
    /// geometry or a link paired with itself.
    pub fn set_collision_pairs(&mut self, pairs: &[(String, String)]) -> Result<(), RobotError> {
        let mut out = Vec::new();
        for (a, b) in pairs {
            let p = self.pair_index(a, b)?;
            if !out.contains(&p) {
                out.push(p);
            }
        }
        self.pairs = out;
        Ok(())
    }

    /// Stops checking the pairs named (an SRDF's disabled collisions);
    /// pairs not checked anyway are ignored.
    ///
    /// # Errors
    /// [`RobotError::BadPair`] naming a missing link.
    pub fn disable_pairs(&mut self, pairs: &[(String, String)]) -> Result<(), RobotError> {
        for (a, b) in pairs {
            let (i, j) = (self.link_index(a)?, self.link_index(b)?);
            self.pairs.retain(|&p| p != (i.min(j), i.max(j)));
        }
        Ok(())
    }

    /// The index of the link named `name`, for a collision pair.
    fn link_index(&self, name: &str) -> Result<usize, RobotError> {
        self.links
            .iter()
            .position(|l| l.name == name)
            .ok_or_else(|| RobotError::BadPair(format!("no link {name:?}")))
    }

    fn pair_index(&self, a: &str, b: &str) -> Result<(usize, usize), RobotError> {
        let (i, j) = (self.link_index(a)?, self.link_index(b)?);
        if i == j {
            return Err(RobotError::BadPair(format!("link {a:?} with itself")));
        }
        for l in [i, j] {
            if self.links[l].body.is_none() {
                return Err(RobotError::BadPair(format!(
                    "link {:?} has no collision geometry",
                    self.links[l].name
                )));
            }
        }
        Ok((i.min(j), i.max(j)))
    }

    /// The degrees of freedom's joint names, in configuration order.
    pub fn joint_names(&self) -> Vec<&str> {
        self.dofs
            .iter()
            .map(|&k| self.joints[k].spec.name.as_str())
            .collect()
    }

    /// The links' names, in the order given (the order of
    /// [`Robot::forward`]'s poses).
    pub fn link_names(&self) -> Vec<&str> {
        self.links.iter().map(|l| l.name.as_str()).collect()
    }

    /// The links as given.
    pub fn links(&self) -> &[LinkSpec] {
        &self.links
    }

    /// The root link's index.
    pub fn root(&self) -> usize {
        self.root
    }

    /// Each degree of freedom's limits `(lower, upper)`, in
    /// [`Robot::joint_names`] order (a continuous joint's are infinite):
    /// the bounds of a planner's joint space.
    pub fn joint_limits(&self) -> Vec<(f64, f64)> {
        self.dofs
            .iter()
            .map(|&k| match self.joints[k].spec.kind {
                JointKind::Revolute { lower, upper } | JointKind::Prismatic { lower, upper } => {
                    (lower, upper)
                }
                _ => (f64::NEG_INFINITY, f64::INFINITY),
            })
            .collect()
    }

    /// The number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.dofs.len()
    }

    /// The pairs of links joined by a joint (parent, child), by index.
    pub fn adjacent_pairs(&self) -> Vec<(usize, usize)> {
        self.joints.iter().map(|j| (j.parent, j.child)).collect()
    }
}
