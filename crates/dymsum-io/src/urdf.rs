//! Robots from URDF files (issue 37): links, joints and collision
//! geometry read with `urdf-rs` into a [`dymsum::robot::Robot`], an SRDF's
//! disabled collision pairs applied.
//!
//! * Joints: revolute, continuous, prismatic and fixed, with limits and
//!   mimics; floating, planar and spherical joints are refused, naming the
//!   joint.
//! * Collision geometry, each element placed by its `origin` (roll, pitch,
//!   yaw about fixed x, y, z) and joined into one body per link: meshes
//!   (OFF, OBJ, PLY, STL; with their `scale`), boxes exactly, spheres,
//!   cylinders and capsules as convex polytopes of 32 segments that
//!   contain them ([`dymsum::robot::shapes`]; the largest deviation per
//!   link is reported). Collada (`.dae`) meshes are read by `mesh-loader`,
//!   the scene's node transforms and unit composed by `crate::collada`.
//!   `<visual>` and `<material>` elements are skipped before parsing
//!   (only collisions are used). An SRDF's pairs naming links the URDF lacks are set aside.
//! * Mesh paths: absolute, `file://`, relative to the URDF's folder, or
//!   `package://NAME/REST`, found as `ROOT/NAME/REST` (or `ROOT/REST` when
//!   `ROOT`'s own name is `NAME`) under the given package roots; a
//!   `package://` path that leaves its root (`..`, or a package named `..`)
//!   is refused.
//! * The SRDF is read by an XML parser (a commented-out
//!   `disable_collisions` disables nothing; a second reading found the
//!   first version applied them), and so are the `<visual>` and
//!   `<material>` elements skipped before urdf-rs parses the rest.
//!
//! ```
//! use dymsum::robot::RobotChecker;
//! let urdf = r#"<robot name="two">
//!   <link name="base"><collision><geometry><box size="4 4 0.2"/></geometry></collision></link>
//!   <link name="arm"><collision><origin xyz="0 0 0.6"/><geometry><cylinder radius="0.05" length="1"/></geometry></collision></link>
//!   <link name="tip"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
//!   <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
//!     <axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
//!   <joint name="wrist" type="fixed"><parent link="arm"/><child link="tip"/><origin xyz="0 0 1.2"/></joint>
//! </robot>"#;
//! let loaded = dymsum_io::urdf::robot_from_str(urdf, std::path::Path::new("."), &[], None)?;
//! assert_eq!(loaded.robot.joint_names(), ["shoulder"]);
//! assert_eq!(loaded.robot.collision_pair_names(), [("base".to_string(), "tip".to_string())]);
//! let checker = RobotChecker::new(loaded.robot, &[])?;
//! assert!(!checker.collides_at(&[0.0])?);
//! // Turned down by 1.5 rad, the tip's ball (1.2 m out) dips below the plate's top.
//! assert!(checker.collides_at(&[1.5])?);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::{Component, Path, PathBuf};

use dymsum::glam::{DQuat, EulerRot};
use dymsum::query::MeshBody;
use dymsum::robot::shapes::{box_mesh, capsule_polytope, cylinder_polytope, sphere_polytope};
use dymsum::robot::{JointKind, JointSpec, LinkSpec, Mimic, Robot, RobotError};
use dymsum::{DVec3, PolygonMesh, Pose, Rotation};

/// Segments of the polytopes that hold spheres, cylinders and capsules.
const SEGMENTS: usize = 32;

/// What can go wrong reading a robot; each names the element at fault.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum UrdfError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The URDF's XML or structure could not be parsed.
    #[error("the URDF could not be parsed: {0}")]
    Parse(String),
    /// A joint of a type dymsum does not move (floating, planar,
    /// spherical).
    #[error("joint {joint:?}: type {kind} is not supported (revolute, continuous, prismatic and fixed are)")]
    UnsupportedJoint {
        /// The joint.
        joint: String,
        /// Its type.
        kind: String,
    },
    /// A link's collision geometry could not be read or used.
    #[error("link {link:?}: {reason}")]
    Geometry {
        /// The link.
        link: String,
        /// What is wrong (the mesh path included).
        reason: String,
    },
    /// The robot is not a valid tree, or a joint is malformed.
    #[error(transparent)]
    Robot(#[from] RobotError),
}

/// A robot read from a URDF.
#[derive(Debug)]
pub struct LoadedRobot {
    /// The robot (its collision pairs less the SRDF's disabled ones).
    pub robot: Robot,
    /// For each link with a sphere, cylinder or capsule: the largest
    /// distance from its polytope's vertices to the exact shape.
    pub deviations: Vec<(String, f64)>,
    /// The SRDF's disabled pairs of links the URDF has.
    pub disabled: Vec<(String, String)>,
    /// The SRDF's disabled pairs naming a link the URDF lacks (set aside).
    pub ignored: Vec<(String, String)>,
}

/// Reads the URDF at `path` (meshes resolved against its folder and the
/// package roots `package_dirs`) and the SRDF at `srdf`, if given.
///
/// # Errors
/// [`UrdfError`], naming the file, joint or link.
pub fn load_robot(
    path: &Path,
    srdf: Option<&Path>,
    package_dirs: &[PathBuf],
) -> Result<LoadedRobot, UrdfError> {
    let read = |p: &Path| {
        std::fs::read_to_string(p).map_err(|source| UrdfError::Io {
            path: p.to_path_buf(),
            source,
        })
    };
    let text = read(path)?;
    let srdf_text = srdf.map(read).transpose()?;
    let base = path.parent().unwrap_or(Path::new("."));
    robot_from_str(&text, base, package_dirs, srdf_text.as_deref())
}

/// [`load_robot`] from the URDF's text, relative mesh paths resolved
/// against `base`, and the SRDF's text.
///
/// # Errors
/// As [`load_robot`].
pub fn robot_from_str(
    urdf: &str,
    base: &Path,
    package_dirs: &[PathBuf],
    srdf: Option<&str>,
) -> Result<LoadedRobot, UrdfError> {
    let parsed = urdf_rs::read_from_string(&without_visuals(urdf))
        .map_err(|e| UrdfError::Parse(e.to_string()))?;
    let mut deviations = Vec::new();
    let mut links = Vec::with_capacity(parsed.links.len());
    for link in &parsed.links {
        let (body, deviation) = link_body(link, base, package_dirs)?;
        if deviation > 0.0 {
            deviations.push((link.name.clone(), deviation));
        }
        links.push(LinkSpec {
            name: link.name.clone(),
            body,
        });
    }
    let joints = parsed
        .joints
        .iter()
        .map(joint_spec)
        .collect::<Result<Vec<_>, _>>()?;
    let mut robot = Robot::new(links, joints)?;
    // An SRDF often names links this URDF lacks (one SRDF for several
    // variants of a robot): those pairs are set aside, as MoveIt does.
    let names = robot
        .link_names()
        .iter()
        .map(|n| n.to_string())
        .collect::<Vec<_>>();
    let (disabled, ignored): (Vec<_>, Vec<_>) = srdf
        .map(disabled_pairs)
        .transpose()?
        .unwrap_or_default()
        .into_iter()
        .partition(|(a, b)| names.contains(a) && names.contains(b));
    robot.disable_pairs(&disabled)?;
    Ok(LoadedRobot {
        robot,
        deviations,
        disabled,
        ignored,
    })
}

fn pose_of(origin: &urdf_rs::Pose) -> Pose {
    let [x, y, z] = origin.xyz.0;
    let [roll, pitch, yaw] = origin.rpy.0;
    let q = DQuat::from_euler(EulerRot::ZYX, yaw, pitch, roll);
    let rotation = Rotation::from_wxyz(q.w, q.x, q.y, q.z).unwrap_or(Rotation::IDENTITY);
    Pose::new(rotation, DVec3::new(x, y, z))
}

fn joint_spec(j: &urdf_rs::Joint) -> Result<JointSpec, UrdfError> {
    use urdf_rs::JointType as T;
    let (lower, upper) = (j.limit.lower, j.limit.upper);
    let kind = match j.joint_type {
        T::Fixed => JointKind::Fixed,
        T::Revolute => JointKind::Revolute { lower, upper },
        T::Continuous => JointKind::Continuous,
        T::Prismatic => JointKind::Prismatic { lower, upper },
        ref other => {
            return Err(UrdfError::UnsupportedJoint {
                joint: j.name.clone(),
                kind: format!("{other:?}").to_lowercase(),
            })
        }
    };
    Ok(JointSpec {
        name: j.name.clone(),
        kind,
        parent: j.parent.link.clone(),
        child: j.child.link.clone(),
        origin: pose_of(&j.origin),
        axis: DVec3::from(j.axis.xyz.0),
        mimic: j.mimic.as_ref().map(|m| Mimic {
            joint: m.joint.clone(),
            multiplier: m.multiplier.unwrap_or(1.0),
            offset: m.offset.unwrap_or(0.0),
        }),
    })
}

/// The link's collision elements joined into one body (or none), and the
/// largest deviation of a primitive's polytope.
fn link_body(
    link: &urdf_rs::Link,
    base: &Path,
    package_dirs: &[PathBuf],
) -> Result<(Option<MeshBody>, f64), UrdfError> {
    let bad = |reason: String| UrdfError::Geometry {
        link: link.name.clone(),
        reason,
    };
    let (mut vertices, mut faces): (Vec<[f64; 3]>, Vec<Vec<usize>>) = (Vec::new(), Vec::new());
    let mut deviation = 0.0f64;
    for c in &link.collision {
        use urdf_rs::Geometry as G;
        let primitive = |made: Option<(PolygonMesh, f64)>, what: &str| {
            made.ok_or_else(|| {
                bad(format!(
                    "the {what} has a size that is not positive and finite"
                ))
            })
        };
        let mesh = match &c.geometry {
            G::Box { size } => {
                let s = DVec3::from(size.0);
                if !(s.is_finite() && s.min_element() > 0.0) {
                    return Err(bad(format!("the box's size {:?} is not positive", size.0)));
                }
                box_mesh(s)
            }
            G::Sphere { radius } => {
                let (m, d) = primitive(
                    positive(&[*radius]).and_then(|_| sphere_polytope(*radius, SEGMENTS)),
                    "sphere",
                )?;
                deviation = deviation.max(d);
                m
            }
            G::Cylinder { radius, length } => {
                let made = positive(&[*radius, *length])
                    .and_then(|_| cylinder_polytope(*radius, *length, SEGMENTS));
                let (m, d) = primitive(made, "cylinder")?;
                deviation = deviation.max(d);
                m
            }
            G::Capsule { radius, length } => {
                let made = positive(&[*radius, *length])
                    .and_then(|_| capsule_polytope(*radius, *length, SEGMENTS));
                let (m, d) = primitive(made, "capsule")?;
                deviation = deviation.max(d);
                m
            }
            G::Mesh { filename, scale } => {
                let path = resolve(filename, base, package_dirs).map_err(&bad)?;
                let collada = path
                    .extension()
                    .is_some_and(|e| e.eq_ignore_ascii_case("dae"));
                let mut m = if collada {
                    crate::collada::read_collada(&path)
                        .map_err(|e| bad(format!("mesh {}: {e}", path.display())))?
                } else {
                    crate::formats::read_mesh(&path)
                        .map_err(|e| bad(format!("mesh {}: {e}", path.display())))?
                };
                if let Some(s) = scale {
                    let s = DVec3::from(s.0);
                    if !(s.is_finite() && s.abs().min_element() > 0.0) {
                        return Err(bad(format!("mesh {}: scale {:?}", path.display(), s)));
                    }
                    for v in &mut m.vertices {
                        *v = (DVec3::from(*v) * s).to_array();
                    }
                    if s.x * s.y * s.z < 0.0 {
                        for f in &mut m.faces {
                            f.reverse();
                        }
                    }
                }
                m
            }
        };
        let at = pose_of(&c.origin);
        let offset = vertices.len();
        vertices.extend(
            mesh.vertices
                .iter()
                .map(|v| at.apply(DVec3::from(*v)).to_array()),
        );
        faces.extend(
            mesh.faces
                .iter()
                .map(|f| f.iter().map(|&k| k + offset).collect()),
        );
    }
    if faces.is_empty() {
        return Ok((None, 0.0));
    }
    let body = MeshBody::new(&PolygonMesh::new(vertices, faces))
        .map_err(|e| bad(format!("the collision geometry is not usable: {e}")))?;
    Ok((Some(body), deviation))
}

/// The URDF without its `<visual>` and `<material>` elements: only the
/// collision geometry is used, and a material may not parse (a
/// `<texture/>` without a file name, as some robots ship). Elements are
/// found by an XML parser (comments and CDATA are not elements); a text
/// that is not XML is left for urdf-rs to refuse.
fn without_visuals(urdf: &str) -> String {
    let Ok(doc) = roxmltree::Document::parse(urdf) else {
        return urdf.to_string();
    };
    let mut ranges: Vec<std::ops::Range<usize>> = doc
        .descendants()
        .filter(|n| n.is_element() && matches!(n.tag_name().name(), "visual" | "material"))
        .filter(|n| {
            // Outermost only (a material inside a removed visual goes with it).
            !n.ancestors()
                .skip(1)
                .any(|a| a.is_element() && matches!(a.tag_name().name(), "visual" | "material"))
        })
        .map(|n| n.range())
        .collect();
    ranges.sort_by_key(|r| std::cmp::Reverse(r.start));
    let mut out = urdf.to_string();
    for r in ranges {
        out.replace_range(r, "");
    }
    out
}

fn positive(xs: &[f64]) -> Option<()> {
    xs.iter().all(|x| x.is_finite() && *x > 0.0).then_some(())
}

/// The file a mesh URI names (module docs).
fn resolve(uri: &str, base: &Path, package_dirs: &[PathBuf]) -> Result<PathBuf, String> {
    if let Some(rest) = uri.strip_prefix("package://") {
        // `package:///name/…` (some robots write three slashes) is read as
        // `package://name/…`.
        let rest = rest.trim_start_matches('/');
        let (package, inner) = rest.split_once('/').unwrap_or((rest, ""));
        if package.is_empty() || package == "." || package == ".." || package.contains('\\') {
            return Err(format!("mesh {uri:?}: {package:?} is not a package name"));
        }
        let inner = Path::new(inner);
        if inner.components().any(|c| {
            matches!(
                c,
                Component::ParentDir | Component::RootDir | Component::Prefix(_)
            )
        }) {
            return Err(format!(
                "mesh {uri:?} leaves its package root (paths inside a package may not use `..`)"
            ));
        }
        for root in package_dirs {
            let mut candidates = vec![root.join(package).join(inner)];
            if root.file_name().is_some_and(|n| n == package) {
                candidates.push(root.join(inner));
            }
            if let Some(found) = candidates.into_iter().find(|c| c.is_file()) {
                return Ok(found);
            }
        }
        return Err(format!(
            "mesh {uri:?} is not found under the package roots given ({})",
            if package_dirs.is_empty() {
                "none".to_string()
            } else {
                package_dirs
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        ));
    }
    let path = PathBuf::from(uri.strip_prefix("file://").unwrap_or(uri));
    let path = if path.is_absolute() {
        path
    } else {
        base.join(path)
    };
    if !path.is_file() {
        return Err(format!("mesh {uri:?}: no file at {}", path.display()));
    }
    Ok(path)
}

/// The `disable_collisions` pairs of an SRDF (`link1`, `link2`
/// attributes; everything else in it, comments included, is ignored). An
/// SRDF that is not XML disables nothing and is an error.
///
/// # Errors
/// [`UrdfError::Parse`] naming the XML error.
pub fn disabled_pairs(srdf: &str) -> Result<Vec<(String, String)>, UrdfError> {
    let doc = roxmltree::Document::parse(srdf)
        .map_err(|e| UrdfError::Parse(format!("the SRDF is not XML: {e}")))?;
    Ok(doc
        .descendants()
        .filter(|n| n.is_element() && n.tag_name().name() == "disable_collisions")
        .filter_map(|n| {
            Some((
                n.attribute("link1")?.to_string(),
                n.attribute("link2")?.to_string(),
            ))
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visuals_and_materials_are_skipped() {
        let urdf = r#"<robot><material name="m"><texture/></material><link name="a">
            <!-- <visual> kept for later -->
            <visual><geometry><mesh/></geometry><material name="x"/></visual><visual/>
            <visualise/><collision/></link></robot>"#;
        let out = without_visuals(urdf);
        // Only the comment's `<visual>` is left.
        assert_eq!(out.matches("<visual").count(), 2, "{out}"); // the comment's and <visualise/>
        assert!(!out.contains("<visual/>") && !out.contains("<material"));
        assert!(
            out.contains("<visualise/>")
                && out.contains("<collision/>")
                && out.contains("kept for later -->")
        );
        assert!(roxmltree::Document::parse(&out).is_ok());
    }

    #[test]
    fn package_names_stay_inside_their_root() {
        for uri in ["package://../x/m.stl", "package://./m.stl", "package://"] {
            let err = resolve(uri, Path::new("."), &[PathBuf::from("/tmp")]).unwrap_err();
            assert!(err.contains("package name"), "{uri}: {err}");
        }
    }

    #[test]
    fn srdf_pairs_are_read_with_either_quote_and_comments_ignored() {
        let srdf = r#"<robot name="r">
            <disable_collisions link1="a" link2="b" reason="Adjacent"/>
            <!-- <disable_collisions link1="x" link2="y" reason="Never"/> -->
            <disable_collisions reason=' link1="z"' link2='d' link1='c' />
            <group name="arm"/>
        </robot>"#;
        assert_eq!(
            disabled_pairs(srdf).unwrap(),
            [("a".into(), "b".into()), ("c".into(), "d".into())]
        );
        assert!(disabled_pairs("<robot>").is_err());
    }
}
