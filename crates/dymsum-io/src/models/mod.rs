//! The built-in model library: the paper's 13 models, the tessellated cubes
//! of the paper's Fig. 5 and parametric primitives, resolved by name.
//!
//! [`model`] turns a name into a [`PolygonMesh`]; [`catalogue`] lists what
//! exists. Names are case-insensitive and surrounding whitespace is ignored.
//! Parametric names take their parameters after colons, numbers within a
//! group separated by commas, e.g. `tcube:10`, `box:2,1,1`,
//! `cylinder:36:1,2`, `random:1000:7`.
//!
//! Every mesh except `random:…` is closed, convex and has its polygonal faces
//! counter-clockwise seen from outside. Generated models are centred at the
//! origin (the centre of their bounding box); the reference models from
//! Efi Fogel's collection keep their original coordinates.
//!
//! # The paper's models
//!
//! | name | aliases | triangles | what |
//! | --- | --- | --- | --- |
//! | `cone` | | 78 | a 40-gon base (circumradius 1, z = -1) and apex (z = 1) |
//! | `cube` | | 12 | Fogel's `cube.off` |
//! | `cylinder` | | 140 | a 36-gon prism, circumradius 1, height 2 |
//! | `dd` | `dioctagonal_dipyramid` | 32 | Fogel's dioctagonal dipyramid |
//! | `ellipse` | `ellipsoid-fogel`, `ellipsoid.off` | 960 | Fogel's `ellipsoid.off` |
//! | `gs1`..`gs4` | `geodesic_sphere1`.. | 80, 180, 320, 500 | Fogel's geodesic spheres |
//! | `hp` | `hexagonal_pyramid` | 10 | Fogel's hexagonal pyramid |
//! | `t` | `triakis_icosahedron` | 60 | Fogel's triakis icosahedron |
//! | `ti` | `truncated_icosidodecahedron` | 236 | Fogel's truncated icosidodecahedron |
//! | `vrod` | `v-rod` | 324 | a capsule, see below |
//!
//! The paper does not describe its `v-rod`. Ours is a capsule along z
//! (`capsule:27:3:0.5,4`): radius 0.5, a cylindrical part of length 4 (total
//! length 5), 27 vertices around each ring, 3 rings per hemisphere at
//! latitudes 60°, 30° and 0°, closed by polar fans. That is 2·27 polar
//! triangles + 2·2·27 cap quadrilaterals + 27 cylinder quadrilaterals =
//! 4·27·3 = 324 triangles when fan-triangulated; every vertex lies on a cap
//! sphere, so it is strictly convex at every vertex.
//!
//! `ellipsoid_1.0_0.5_0.5` is Fogel's flatter ellipsoid (the same mesh with
//! semi-axes 1, 0.5, 0.5; 960 triangles); it is not one of the paper's 13.
//!
//! # Parametric families
//!
//! * `tcube:K` (K = 1..=100, default 1): the paper's Fig. 5 cube, 10×10×10,
//!   each face split into K×K squares of 2 triangles (12 K² triangles).
//! * `box[:X,Y,Z]` or `box:S`: a box with side lengths X, Y, Z (default 1).
//! * `sphere[:N]`: geodesic sphere of radius 1, frequency N (1..=32,
//!   default 4): each icosahedron face split into N² triangles, projected
//!   onto the sphere (20 N² triangles). `sphere:1` is the icosahedron.
//! * `ellipsoid:A,B,C[:N]`: the geodesic sphere of frequency N (default 4)
//!   scaled to semi-axes A, B, C along x, y, z.
//! * `cylinder:N[:R,H]`: prism over a regular N-gon (N = 3..=10⁴), circumradius
//!   R (default 1), height H (default 2).
//! * `cone:N[:R,H]`: pyramid over a regular N-gon (N = 3..=10⁴), circumradius R (default
//!   1), height H (default 2).
//! * `capsule:N:K[:R,L]`: capsule with N vertices per ring (N = 3..), K
//!   rings per hemisphere (N·K at most 5000), radius R (default 0.5), cylindrical length L
//!   (default 4, may be 0): 4 N K triangles.
//! * `random:N[:SEED]`: N (4..=10⁶) points uniformly in the unit ball from
//!   ChaCha8 seeded with SEED (default 0); identical on every platform.
//!   **The returned mesh has no faces: its `vertices` are a point cloud**
//!   whose convex hull the caller builds.
//! * `tetra`, `octa`, `dodeca`, `icosa` (also the full `…hedron` names):
//!   regular solids with circumradius 1.
//!
//! Every size parameter (side, radius, height, length, semi-axis) must be
//! from 1e-150 to 1e150 ([`SIZE_MIN`], [`SIZE_MAX`]; a capsule's L may also
//! be 0). The count limits ([`SPHERE_MAX`], [`AROUND_MAX`], [`RINGS_MAX`],
//! [`CAPSULE_MAX`], [`RANDOM_MAX`]) keep every accepted model loadable in a
//! few seconds; a parameter beyond a limit is refused with the limit named.

mod generators;

use dymsum::PolygonMesh;

/// Why a model name could not be resolved.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ModelError {
    /// No built-in model has this name. Fix: use a name listed by
    /// [`catalogue`] (`dymsum models`); `suggestion` holds the closest one
    /// when a name is near enough.
    #[error("unknown model `{name}`{}", suggestion_text(.suggestion))]
    Unknown {
        /// The name as given.
        name: String,
        /// The closest known name, if any is close.
        suggestion: Option<String>,
    },
    /// The model exists but a parameter is missing, unparsable or out of
    /// range (`message` names the parameter and the allowed range). Fix: use
    /// the syntax listed by [`catalogue`], e.g. `tcube:10` or `box:1,2,3`.
    #[error("bad parameter for model `{name}`: {message}")]
    BadParameter {
        /// The name as given.
        name: String,
        /// Which parameter is wrong and what is allowed.
        message: String,
    },
    /// An embedded reference model failed to parse. This is a bug in
    /// dymsum-io (the embedded files are checked by its tests); please
    /// report it.
    #[error("embedded model `{name}` is corrupt: {message} (a bug in dymsum-io)")]
    Embedded {
        /// The model name.
        name: String,
        /// The parser's message.
        message: String,
    },
}

fn suggestion_text(s: &Option<String>) -> String {
    match s {
        Some(s) => format!(" (did you mean `{s}`? `dymsum models` lists all models)"),
        None => " (`dymsum models` lists all models)".to_string(),
    }
}

/// One entry of the model catalogue.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ModelInfo {
    /// The name, or for parametric families the syntax (e.g. `tcube:K`).
    pub name: &'static str,
    /// What the model is, with aliases and parameter meanings.
    pub description: &'static str,
    /// Triangle count in the paper (fan-triangulated), for the paper's models.
    pub paper_triangles: Option<usize>,
    /// Where the geometry comes from.
    pub source: &'static str,
    /// A concrete name that [`model`] resolves (equal to `name` for fixed
    /// models, e.g. `tcube:10` for `tcube:K`).
    pub example: &'static str,
}

const FOGEL: &str = "Efi Fogel's collection (efifogel/sgal, data/vrml/polyhedra), converted to OFF";
const GENERATED: &str = "generated";

/// Lists every built-in model and parametric family, the paper's 13 first.
pub fn catalogue() -> Vec<ModelInfo> {
    let fixed = |name, description, tris, source| ModelInfo {
        name,
        description,
        paper_triangles: tris,
        source,
        example: name,
    };
    let family = |name, example, description| ModelInfo {
        name,
        description,
        paper_triangles: None,
        source: GENERATED,
        example,
    };
    vec![
        fixed("cone", "pyramid over a regular 40-gon (circumradius 1, height 2); = cone:40", Some(78), GENERATED),
        fixed("cube", "cube (Fogel's cube.off)", Some(12), FOGEL),
        fixed("cylinder", "prism over a regular 36-gon (circumradius 1, height 2); = cylinder:36", Some(140), GENERATED),
        fixed("dd", "dioctagonal dipyramid (alias DD, dioctagonal_dipyramid)", Some(32), FOGEL),
        fixed("ellipse", "ellipsoid with 512 quads/triangles (alias ellipsoid-fogel)", Some(960), FOGEL),
        fixed("gs1", "geodesic sphere 1 (alias GS1, geodesic_sphere1)", Some(80), FOGEL),
        fixed("gs2", "geodesic sphere 2 (alias GS2, geodesic_sphere2)", Some(180), FOGEL),
        fixed("gs3", "geodesic sphere 3 (alias GS3, geodesic_sphere3)", Some(320), FOGEL),
        fixed("gs4", "geodesic sphere 4 (alias GS4, geodesic_sphere4)", Some(500), FOGEL),
        fixed("hp", "hexagonal pyramid (alias HP, hexagonal_pyramid)", Some(10), FOGEL),
        fixed("t", "triakis icosahedron (alias T, triakis_icosahedron)", Some(60), FOGEL),
        fixed("ti", "truncated icosidodecahedron (alias TI, truncated_icosidodecahedron)", Some(236), FOGEL),
        fixed("vrod", "capsule rod, not described by the paper: radius 0.5, cylinder length 4, 27 around, 3 rings per cap (alias v-rod); = capsule:27:3:0.5,4", Some(324), GENERATED),
        fixed("ellipsoid_1.0_0.5_0.5", "Fogel's flatter ellipsoid, semi-axes 1, 0.5, 0.5 (960 triangles)", None, FOGEL),
        family("tcube:K", "tcube:10", "the paper's Fig. 5 cube: 10x10x10, each face K x K squares of 2 triangles (12 K^2 triangles), K = 1..100"),
        family("box:X,Y,Z", "box:1,2,3", "box with side lengths X, Y, Z (box:S for a cube, box alone = 1,1,1); sizes 1e-150..1e150"),
        family("sphere:N", "sphere:4", "geodesic sphere, radius 1, icosahedron faces split N x N (20 N^2 triangles), N = 1..32, default 4"),
        family("ellipsoid:A,B,C[:N]", "ellipsoid:2,1,0.5:4", "geodesic sphere of frequency N (default 4) scaled to semi-axes A, B, C"),
        family("cylinder:N[:R,H]", "cylinder:12:1,3", "prism over a regular N-gon (N = 3..10000), circumradius R (default 1), height H (default 2)"),
        family("cone:N[:R,H]", "cone:12:1,3", "pyramid over a regular N-gon (N = 3..10000), circumradius R (default 1), height H (default 2)"),
        family("capsule:N:K[:R,L]", "capsule:16:4", "capsule: N around, K rings per cap, radius R (default 0.5), cylinder length L (default 4, may be 0); 4 N K triangles, N K <= 5000"),
        family("random:N[:SEED]", "random:1000:7", "point cloud (NO faces: build the hull) of N (4..1000000) points uniform in the unit ball, ChaCha8 seeded with SEED (default 0)"),
        family("tetra", "tetra", "regular tetrahedron, circumradius 1 (alias tetrahedron)"),
        family("octa", "octa", "regular octahedron, circumradius 1 (alias octahedron)"),
        family("dodeca", "dodeca", "regular dodecahedron, circumradius 1 (alias dodecahedron)"),
        family("icosa", "icosa", "regular icosahedron, circumradius 1 (alias icosahedron)"),
    ]
}

/// Embedded reference models: (file stem, OFF text).
const FOGEL_FILES: &[(&str, &str)] = &[
    ("cube", include_str!("../../models/fogel/cube.off")),
    (
        "dioctagonal_dipyramid",
        include_str!("../../models/fogel/dioctagonal_dipyramid.off"),
    ),
    (
        "ellipsoid",
        include_str!("../../models/fogel/ellipsoid.off"),
    ),
    (
        "ellipsoid_1.0_0.5_0.5",
        include_str!("../../models/fogel/ellipsoid_1.0_0.5_0.5.off"),
    ),
    (
        "geodesic_sphere1",
        include_str!("../../models/fogel/geodesic_sphere1.off"),
    ),
    (
        "geodesic_sphere2",
        include_str!("../../models/fogel/geodesic_sphere2.off"),
    ),
    (
        "geodesic_sphere3",
        include_str!("../../models/fogel/geodesic_sphere3.off"),
    ),
    (
        "geodesic_sphere4",
        include_str!("../../models/fogel/geodesic_sphere4.off"),
    ),
    (
        "hexagonal_pyramid",
        include_str!("../../models/fogel/hexagonal_pyramid.off"),
    ),
    (
        "triakis_icosahedron",
        include_str!("../../models/fogel/triakis_icosahedron.off"),
    ),
    (
        "truncated_icosidodecahedron",
        include_str!("../../models/fogel/truncated_icosidodecahedron.off"),
    ),
];

/// Fixed names (lower case) and what they resolve to.
#[derive(Clone, Copy)]
enum Fixed {
    Fogel(&'static str),
    Cone,
    Cylinder,
    Vrod,
    Tetra,
    Octa,
    Dodeca,
    Icosa,
}

const FIXED_NAMES: &[(&str, Fixed)] = &[
    ("cone", Fixed::Cone),
    ("cube", Fixed::Fogel("cube")),
    ("cylinder", Fixed::Cylinder),
    ("dd", Fixed::Fogel("dioctagonal_dipyramid")),
    (
        "dioctagonal_dipyramid",
        Fixed::Fogel("dioctagonal_dipyramid"),
    ),
    ("ellipse", Fixed::Fogel("ellipsoid")),
    ("ellipsoid-fogel", Fixed::Fogel("ellipsoid")),
    ("ellipsoid.off", Fixed::Fogel("ellipsoid")),
    (
        "ellipsoid_1.0_0.5_0.5",
        Fixed::Fogel("ellipsoid_1.0_0.5_0.5"),
    ),
    ("gs1", Fixed::Fogel("geodesic_sphere1")),
    ("gs2", Fixed::Fogel("geodesic_sphere2")),
    ("gs3", Fixed::Fogel("geodesic_sphere3")),
    ("gs4", Fixed::Fogel("geodesic_sphere4")),
    ("geodesic_sphere1", Fixed::Fogel("geodesic_sphere1")),
    ("geodesic_sphere2", Fixed::Fogel("geodesic_sphere2")),
    ("geodesic_sphere3", Fixed::Fogel("geodesic_sphere3")),
    ("geodesic_sphere4", Fixed::Fogel("geodesic_sphere4")),
    ("hp", Fixed::Fogel("hexagonal_pyramid")),
    ("hexagonal_pyramid", Fixed::Fogel("hexagonal_pyramid")),
    ("t", Fixed::Fogel("triakis_icosahedron")),
    ("triakis_icosahedron", Fixed::Fogel("triakis_icosahedron")),
    ("ti", Fixed::Fogel("truncated_icosidodecahedron")),
    (
        "truncated_icosidodecahedron",
        Fixed::Fogel("truncated_icosidodecahedron"),
    ),
    ("vrod", Fixed::Vrod),
    ("v-rod", Fixed::Vrod),
    ("tetra", Fixed::Tetra),
    ("tetrahedron", Fixed::Tetra),
    ("octa", Fixed::Octa),
    ("octahedron", Fixed::Octa),
    ("dodeca", Fixed::Dodeca),
    ("dodecahedron", Fixed::Dodeca),
    ("icosa", Fixed::Icosa),
    ("icosahedron", Fixed::Icosa),
];

/// Parametric family names (lower case).
const FAMILIES: &[&str] = &[
    "tcube",
    "box",
    "sphere",
    "ellipsoid",
    "cylinder",
    "cone",
    "capsule",
    "random",
];

/// The paper's cone: 40-gon base.
const CONE_SIDES: usize = 40;
/// The paper's cylinder: 36-gon.
const CYLINDER_SIDES: usize = 36;
/// `vrod`: vertices around each ring.
const VROD_AROUND: usize = 27;
/// `vrod`: rings per hemispherical cap (including the equator ring).
const VROD_RINGS_PER_CAP: usize = 3;
/// `vrod`: radius.
const VROD_RADIUS: f64 = 0.5;
/// `vrod`: length of the cylindrical part.
const VROD_LENGTH: f64 = 4.0;
/// Side of the Fig. 5 cube.
const TCUBE_SIDE: f64 = 10.0;
/// Largest `tcube` K (the paper's Fig. 5 goes to K = 10; 100 is 120,000 triangles).
const TCUBE_MAX: usize = 100;
// The size limits below keep every accepted model loadable in a few seconds
// (`dymsum info`, release build, one core: sphere:32 3.3 s, cylinder:10000
// 1.9 s, capsule:100:50 2.0 s, tcube:100 0.6 s, random:1000000 1.0 s); the
// mesh validation is what grows fastest with size.
/// Largest geodesic frequency (20 · 32² = 20,480 triangles).
pub const SPHERE_MAX: usize = 32;
/// Largest polygon side count for cylinders, cones and capsules.
pub const AROUND_MAX: usize = 10_000;
/// Largest number of capsule rings per cap.
pub const RINGS_MAX: usize = 1_000;
/// Largest capsule N·K (vertices per cap).
pub const CAPSULE_MAX: usize = 5_000;
/// Largest random point count.
pub const RANDOM_MAX: usize = 1_000_000;
/// Largest size parameter (side, radius, length, semi-axis) of a model.
pub const SIZE_MAX: f64 = 1e150;
/// Smallest positive size parameter of a model.
pub const SIZE_MIN: f64 = 1e-150;

/// Resolves a built-in model name (case-insensitive; see the module docs
/// and [`catalogue`] for the names and parametric syntax).
///
/// Never panics: unknown names give [`ModelError::Unknown`] with the closest
/// name as a suggestion, bad parameters give [`ModelError::BadParameter`].
/// `random:N:SEED` returns a point cloud (a mesh with no faces).
///
/// # Errors
/// [`ModelError::Unknown`] for a name that is no model (with a suggestion
/// when one is close); [`ModelError::BadParameter`] for a missing,
/// unparsable or out-of-range parameter, or parameters given to a fixed
/// model; [`ModelError::Embedded`] only if an embedded reference model fails
/// to parse (a bug in dymsum-io).
pub fn model(name: &str) -> Result<PolygonMesh, ModelError> {
    let key = name.trim().to_lowercase();
    if let Some((_, fixed)) = FIXED_NAMES.iter().find(|(n, _)| *n == key) {
        return build_fixed(name, *fixed);
    }
    let (family, params) = match key.split_once(':') {
        Some((f, p)) => (f.trim(), Some(p)),
        None => (key.as_str(), None),
    };
    if FIXED_NAMES.iter().any(|(n, _)| *n == family) && !FAMILIES.contains(&family) {
        return Err(bad(name, format!("`{family}` takes no parameters")));
    }
    let p = Params {
        name,
        groups: parameter_groups(params),
    };
    match family {
        "tcube" => {
            p.max_groups(1)?;
            let k = p.int_or(0, 0, "K", 1, 1, TCUBE_MAX)?;
            Ok(generators::tessellated_cube(TCUBE_SIDE, k))
        }
        "box" => build_box(&p),
        "sphere" => {
            p.max_groups(1)?;
            let n = p.int_or(0, 0, "N (frequency)", 4, 1, SPHERE_MAX)?;
            Ok(generators::geodesic_sphere(n))
        }
        "ellipsoid" => build_ellipsoid(&p),
        "cylinder" | "cone" => build_prism_or_cone(&p, family),
        "capsule" => build_capsule(&p),
        "random" => build_random(&p),
        _ => Err(ModelError::Unknown {
            name: name.to_string(),
            suggestion: suggest(family, params),
        }),
    }
}

/// The parameters after a family name, `a,b:c` → `[[a, b], [c]]` (trimmed).
fn parameter_groups(params: Option<&str>) -> Vec<Vec<&str>> {
    match params {
        None => Vec::new(),
        Some(p) => p
            .split(':')
            .map(|g| g.split(',').map(str::trim).collect())
            .collect(),
    }
}

/// `box`, `box:S` or `box:X,Y,Z`.
fn build_box(p: &Params<'_>) -> Result<PolygonMesh, ModelError> {
    p.max_groups(1)?;
    let g = p.group(0);
    let (x, y, z) = match g.len() {
        0 => (1.0, 1.0, 1.0),
        1 => {
            let s = p.positive(0, 0, "S (side length)", 1.0)?;
            (s, s, s)
        }
        3 => (
            p.positive(0, 0, "X", 1.0)?,
            p.positive(0, 1, "Y", 1.0)?,
            p.positive(0, 2, "Z", 1.0)?,
        ),
        n => {
            return Err(bad(
                p.name,
                format!("box takes 1 or 3 sizes (box:S or box:X,Y,Z), got {n}"),
            ))
        }
    };
    Ok(generators::box_mesh(x, y, z))
}

/// `ellipsoid:A,B,C[:N]`.
fn build_ellipsoid(p: &Params<'_>) -> Result<PolygonMesh, ModelError> {
    p.max_groups(2)?;
    if p.group(0).len() != 3 {
        return Err(bad(
            p.name,
            "ellipsoid needs three semi-axes: ellipsoid:A,B,C[:N] \
             (use `ellipse` for the paper's ellipsoid)"
                .to_string(),
        ));
    }
    let a = p.positive(0, 0, "A", 1.0)?;
    let b = p.positive(0, 1, "B", 1.0)?;
    let c = p.positive(0, 2, "C", 1.0)?;
    let n = p.int_or(1, 0, "N (frequency)", 4, 1, SPHERE_MAX)?;
    Ok(generators::ellipsoid(a, b, c, n))
}

/// `cylinder:N[:R,H]` or `cone:N[:R,H]` (`family` says which).
fn build_prism_or_cone(p: &Params<'_>, family: &str) -> Result<PolygonMesh, ModelError> {
    p.max_groups(2)?;
    if p.group(0).is_empty() {
        return Err(bad(p.name, format!("{family} needs N: {family}:N[:R,H]")));
    }
    let n = p.int_or(0, 0, "N (sides)", 0, 3, AROUND_MAX)?;
    let (r, h) = p.pair(1, ("R", 1.0), ("H", 2.0))?;
    Ok(if family == "cone" {
        generators::cone(n, r, h)
    } else {
        generators::cylinder(n, r, h)
    })
}

/// `capsule:N:K[:R,L]`, with N·K at most [`CAPSULE_MAX`].
fn build_capsule(p: &Params<'_>) -> Result<PolygonMesh, ModelError> {
    p.max_groups(3)?;
    if p.group(0).is_empty() || p.group(1).is_empty() {
        return Err(bad(
            p.name,
            "capsule needs N and K: capsule:N:K[:R,L]".into(),
        ));
    }
    let n = p.int_or(0, 0, "N (around)", 0, 3, AROUND_MAX)?;
    let k = p.int_or(1, 0, "K (rings per cap)", 0, 1, RINGS_MAX)?;
    if n.saturating_mul(k) > CAPSULE_MAX {
        return Err(bad(
            p.name,
            format!("N·K must be at most {CAPSULE_MAX}, got {n}·{k}"),
        ));
    }
    if p.group(2).len() > 2 {
        return Err(bad(p.name, "capsule takes at most R,L".into()));
    }
    let r = p.positive(2, 0, "R", VROD_RADIUS)?;
    let l = p.non_negative(2, 1, "L", VROD_LENGTH)?;
    Ok(generators::capsule(n, k, r, l))
}

/// `random:N[:SEED]`: a point cloud.
fn build_random(p: &Params<'_>) -> Result<PolygonMesh, ModelError> {
    p.max_groups(2)?;
    if p.group(0).is_empty() {
        return Err(bad(p.name, "random needs N: random:N[:SEED]".into()));
    }
    let n = p.int_or(0, 0, "N (points)", 0, 4, RANDOM_MAX)?;
    let seed = match p.single(1, 0) {
        None => 0,
        Some(s) => s.parse::<u64>().map_err(|_| {
            bad(
                p.name,
                format!("SEED must be an integer from 0 to {}, got `{s}`", u64::MAX),
            )
        })?,
    };
    if p.group(1).len() > 1 {
        return Err(bad(p.name, "random takes one SEED".into()));
    }
    Ok(generators::random_ball(n, seed))
}

fn build_fixed(name: &str, fixed: Fixed) -> Result<PolygonMesh, ModelError> {
    Ok(match fixed {
        Fixed::Fogel(stem) => return fogel(name, stem),
        Fixed::Cone => generators::cone(CONE_SIDES, 1.0, 2.0),
        Fixed::Cylinder => generators::cylinder(CYLINDER_SIDES, 1.0, 2.0),
        Fixed::Vrod => {
            generators::capsule(VROD_AROUND, VROD_RINGS_PER_CAP, VROD_RADIUS, VROD_LENGTH)
        }
        Fixed::Tetra => generators::tetrahedron(),
        Fixed::Octa => generators::octahedron(),
        Fixed::Dodeca => generators::dodecahedron(),
        Fixed::Icosa => generators::icosahedron(),
    })
}

/// Parses one of the embedded Fogel models.
fn fogel(name: &str, stem: &str) -> Result<PolygonMesh, ModelError> {
    let text = FOGEL_FILES
        .iter()
        .find(|(s, _)| *s == stem)
        .map(|(_, t)| *t)
        .ok_or_else(|| ModelError::Embedded {
            name: name.to_string(),
            message: "not embedded".to_string(),
        })?;
    let source = format!("{stem}.off");
    crate::formats::read_mesh_bytes(text.as_bytes(), crate::formats::Format::Off, &source).map_err(
        |e| ModelError::Embedded {
            name: name.to_string(),
            message: e.to_string(),
        },
    )
}

/// A number for a message: plain when short, else in `{:e}` form with at
/// most 6 significant digits (never hundreds of digits).
pub(crate) fn short_number(v: f64) -> String {
    let plain = format!("{v}");
    if plain.len() <= 12 {
        plain
    } else {
        let e = format!("{v:.5e}");
        // Trim trailing zeros of the mantissa: 1.00000e300 -> 1e300.
        match e.split_once('e') {
            Some((m, x)) if m.contains('.') => {
                format!("{}e{x}", m.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => e,
        }
    }
}

fn bad(name: &str, message: String) -> ModelError {
    ModelError::BadParameter {
        name: name.to_string(),
        message,
    }
}

/// Parameter groups after the family name: `a,b:c` is `[[a, b], [c]]`.
struct Params<'a> {
    name: &'a str,
    groups: Vec<Vec<&'a str>>,
}

impl Params<'_> {
    fn group(&self, g: usize) -> &[&str] {
        match self.groups.get(g) {
            // `tcube:` gives one empty group: treat as absent.
            Some(v) if v.len() == 1 && v[0].is_empty() => &[],
            Some(v) => v,
            None => &[],
        }
    }

    fn single(&self, g: usize, i: usize) -> Option<&str> {
        self.group(g).get(i).copied()
    }

    fn max_groups(&self, n: usize) -> Result<(), ModelError> {
        if self.groups.len() > n {
            Err(bad(
                self.name,
                format!(
                    "too many `:`-separated parameter groups ({}, at most {n})",
                    self.groups.len()
                ),
            ))
        } else {
            Ok(())
        }
    }

    fn int_or(
        &self,
        g: usize,
        i: usize,
        what: &str,
        default: usize,
        min: usize,
        max: usize,
    ) -> Result<usize, ModelError> {
        if self.group(g).len() > 1 {
            return Err(bad(self.name, format!("{what} must be a single integer")));
        }
        let Some(s) = self.single(g, i) else {
            return Ok(default);
        };
        match s.parse::<usize>() {
            Ok(v) if (min..=max).contains(&v) => Ok(v),
            _ => Err(bad(
                self.name,
                format!("{what} must be an integer from {min} to {max}, got `{s}`"),
            )),
        }
    }

    fn number(&self, g: usize, i: usize, what: &str, default: f64) -> Result<f64, ModelError> {
        let Some(s) = self.single(g, i) else {
            return Ok(default);
        };
        match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(bad(self.name, format!("{what} must be finite, got `{s}`"))),
            Err(_) => Err(bad(
                self.name,
                format!("{what} must be a number, got `{s}`"),
            )),
        }
    }

    fn positive(&self, g: usize, i: usize, what: &str, default: f64) -> Result<f64, ModelError> {
        let v = self.number(g, i, what, default)?;
        if (SIZE_MIN..=SIZE_MAX).contains(&v) {
            Ok(v)
        } else {
            Err(bad(
                self.name,
                format!(
                    "{what} must be from {SIZE_MIN:e} to {SIZE_MAX:e}, got {}",
                    short_number(v)
                ),
            ))
        }
    }

    fn non_negative(
        &self,
        g: usize,
        i: usize,
        what: &str,
        default: f64,
    ) -> Result<f64, ModelError> {
        let v = self.number(g, i, what, default)?;
        if v == 0.0 || (SIZE_MIN..=SIZE_MAX).contains(&v) {
            Ok(v.abs()) // normalises -0 to 0
        } else {
            Err(bad(
                self.name,
                format!(
                    "{what} must be 0 or from {SIZE_MIN:e} to {SIZE_MAX:e}, got {}",
                    short_number(v)
                ),
            ))
        }
    }

    /// An optional `R,H` group: both or neither.
    fn pair(
        &self,
        g: usize,
        (a, da): (&str, f64),
        (b, db): (&str, f64),
    ) -> Result<(f64, f64), ModelError> {
        match self.group(g).len() {
            0 | 2 => Ok((self.positive(g, 0, a, da)?, self.positive(g, 1, b, db)?)),
            n => Err(bad(
                self.name,
                format!("give both {a},{b} (got {n} numbers)"),
            )),
        }
    }
}

/// Closest known name to an unknown family, if close enough.
fn suggest(family: &str, params: Option<&str>) -> Option<String> {
    let candidates = FIXED_NAMES
        .iter()
        .map(|(n, _)| *n)
        .chain(FAMILIES.iter().copied());
    let (best, dist) = candidates
        .map(|c| (c, edit_distance(family, c)))
        .min_by_key(|&(_, d)| d)?;
    let limit = (family.chars().count() / 2).max(1);
    if family.is_empty() || dist > limit || dist == 0 {
        return None;
    }
    // Prefer the canonical spelling of an alias.
    let best = canonical(best);
    Some(match params {
        Some(p) if FAMILIES.contains(&best) => format!("{best}:{p}"),
        _ => best.to_string(),
    })
}

fn canonical(alias: &'static str) -> &'static str {
    match alias {
        "v-rod" => "vrod",
        "ellipsoid-fogel" | "ellipsoid.off" => "ellipse",
        other => other,
    }
}

/// Levenshtein distance over chars.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        cur[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}
