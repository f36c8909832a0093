//! `dymsum render P Q -o picture.svg|png`: a picture of `P ⊕ Q` like the
//! paper's Fig. 1 (issue 4 §4).
//!
//! # What is drawn
//!
//! * **The sum.** `P` at the pose `--rotate-p-wxyz`/`--translate-p`, `Q` at the
//!   identity, summed by DYMSUM ([`DynamicSum::new`]). With
//!   `--highlight-after-wxyz H`, P is then turned further by `H`
//!   ([`DynamicSum::rotate_p_by`]) and the picture shows the sum **after**
//!   the turn. The merged faces of the sum ([`DynamicSum::try_to_mesh`]) are
//!   drawn in an orthographic projection from the direction `--view
//!   AZIMUTH,ELEVATION` (degrees; default `30,20`), Lambert-shaded by a light
//!   fixed relative to the viewer, each front face outlined (its visible
//!   edges). Back faces are culled; the front faces of a convex polytope
//!   never overlap, so no depth sorting is needed.
//! * **The highlighted facets** (only with `--highlight-after-wxyz`). The
//!   update's [`UpdateReport::added`](dymsum::UpdateReport::added) lists the *facets* (fv, vf and ee
//!   pieces of the overlay, finer than the merged faces) of the new sum that
//!   were not in the sum before the turn. Each such facet that faces the
//!   viewer is drawn over the faces as one red, Lambert-shaded polygon with a
//!   thin dark-red outline; in the SVG it is exactly one
//!   `<polygon class="changed" …>`. The removed facets belong to the old sum
//!   and are not drawn.
//!
//! # The facing rule (shared by faces and highlighted facets)
//!
//! Let `v` be the unit vector towards the viewer:
//! `v = (cos el cos az, cos el sin az, sin el)` (z is up). A polygon is drawn
//! iff its outward unit normal `n` has `n · v > 1e-9` ([`FRONT_EPS`]). For a
//! facet, `n` is (in world coordinates, P posed and Q at its pose):
//!
//! * `Fv{f, w}`: P's unit normal of face `f` rotated by P's rotation;
//! * `Vf{u, g}`: Q's unit normal of face `g` rotated by Q's rotation;
//! * `Ee{e, e2}`: `normalize(dP × dQ)` of the two edge directions, signed so
//!   that `n · (a + b + c + d) > 0` where `a, b` (`c, d`) are the posed unit
//!   normals of the two faces of P's edge `e` (Q's edge `e2`). Parallel edges
//!   give a zero vector: such a facet has zero area and is never drawn.
//!
//! A face of the merged mesh uses its Newell normal, normalised.
//!
//! The facet's corners are `P vertex + Q vertex` (posed): `Fv{f, w}`: the
//! corners of P's face `f` plus `w`; `Vf{u, g}`: `u` plus the corners of Q's
//! face `g`; `Ee{e, e2}`: the parallelogram `a1+b1, a2+b1, a2+b2, a1+b2` of
//! the two edges' endpoints.
//!
//! # Output
//!
//! SVG (hand-written, no text, coordinates with two decimals) or PNG (our
//! own scanline rasteriser with 4×4 supersampling, encoded by the pure-Rust
//! `png` crate; no fonts, no system libraries). Both are deterministic: the
//! same inputs give byte-identical files.

mod raster;
mod scene;
mod svg;

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use dymsum::sum::Facet;
use dymsum::{DVec3, DynamicSum, Pose, Rotation};

use super::short_name;
use super::solid::load_single_body;
use crate::values::{parse_quaternion, parse_vector};

pub use scene::{facet_geometry, View, FRONT_EPS};

/// Arguments of `dymsum render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// First operand P (the one that turns): a mesh file or a built-in model name.
    #[arg(value_name = "P")]
    pub p: String,
    /// Second operand Q: a mesh file or a built-in model name.
    #[arg(value_name = "Q")]
    pub q: String,
    /// The picture; the format follows the extension (.svg or .png). A
    /// missing folder is created.
    #[arg(short, long, value_name = "OUT", value_parser = parse_picture_path)]
    pub output: PathBuf,
    /// Rotate P about the origin by this unit quaternion, scalar first (W,X,Y,Z; renormalised).
    #[arg(long = "rotate-p-wxyz", alias = "rotate-p", value_name = "W,X,Y,Z",
          value_parser = parse_quaternion, allow_hyphen_values = true)]
    pub rotate_p: Option<Rotation>,
    /// Then translate P by this vector.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vector, allow_hyphen_values = true)]
    pub translate_p: Option<DVec3>,
    /// Turn P further by this unit quaternion (W,X,Y,Z, scalar first) and draw the sum after the turn, the
    /// facets the turn added (those facing the viewer) in red.
    #[arg(long = "highlight-after-wxyz", alias = "highlight-after", value_name = "W,X,Y,Z",
          value_parser = parse_quaternion, allow_hyphen_values = true)]
    pub highlight_after: Option<Rotation>,
    /// Width and height of the picture in pixels (16 to 8192).
    #[arg(long, value_name = "PX", default_value_t = 800,
          value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub size: u32,
    /// View direction: azimuth about the z axis and elevation above the xy plane, in degrees.
    #[arg(long, value_name = "AZIMUTH,ELEVATION", default_value = "30,20",
          value_parser = parse_view, allow_hyphen_values = true)]
    pub view: View,
    /// Refuse meshes that are convex only within tolerance.
    #[arg(long)]
    pub strict: bool,
}

/// The picture formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PictureFormat {
    /// Scalable vector graphics.
    Svg,
    /// Portable network graphics (RGB, 8 bits).
    Png,
}

impl PictureFormat {
    /// The format for a path's extension (case-insensitive).
    pub fn from_path(path: &std::path::Path) -> Option<PictureFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "svg" => Some(PictureFormat::Svg),
            "png" => Some(PictureFormat::Png),
            _ => None,
        }
    }
}

/// Checks that the output path ends in `.svg` or `.png`.
///
/// # Errors
/// A message when the extension is neither (any case).
pub fn parse_picture_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match PictureFormat::from_path(&path) {
        Some(_) => Ok(path),
        None => Err(format!(
            "`{s}` has no picture extension (expected .svg or .png)"
        )),
    }
}

/// Parses `AZIMUTH,ELEVATION` in degrees (elevation from -90 to 90).
///
/// # Errors
/// A message when there are not exactly 2 comma-separated values, a value
/// is not a finite number, or the elevation lies outside `-90..=90`.
pub fn parse_view(s: &str) -> Result<View, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 2 {
        return Err(format!(
            "expected 2 comma-separated numbers (AZIMUTH,ELEVATION in degrees), got {}",
            parts.len()
        ));
    }
    let mut v = [0.0; 2];
    for (x, p) in v.iter_mut().zip(&parts) {
        *x = match p.parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            Ok(_) => return Err(format!("`{p}` is not a finite number")),
            Err(_) => return Err(format!("`{p}` is not a number")),
        };
    }
    if !(-90.0..=90.0).contains(&v[1]) {
        return Err(format!(
            "the elevation `{}` must be between -90 and 90 degrees",
            parts[1]
        ));
    }
    Ok(View::new(v[0], v[1]))
}

/// Draws the picture.
///
/// # Errors
/// The output is not `.svg` or `.png`; P or Q cannot be loaded; the sum,
/// the further turn or the mesh fails ([`dymsum::SumError`],
/// [`dymsum::sum::MeshError`]); PNG encoding fails; or the picture or `out`
/// cannot be written (an earlier picture is kept).
pub fn run(a: &RenderArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    let format = PictureFormat::from_path(&a.output)
        .with_context(|| format!("{}: not a .svg or .png file", a.output.display()))?;
    super::stdin_for_one_operand(&[(&a.p, "P"), (&a.q, "Q")])?;
    let p = load_single_body(&a.p, "P", a.strict, "render")?;
    let q = load_single_body(&a.q, "Q", a.strict, "render")?;
    let pose_p = Pose::new(
        a.rotate_p.unwrap_or(Rotation::IDENTITY),
        a.translate_p.unwrap_or(DVec3::ZERO),
    );
    let name = format!("{} ⊕ {}", short_name(&a.p), short_name(&a.q));
    let mut dynamic = DynamicSum::new(&p.polytope, pose_p, &q.polytope, Pose::IDENTITY)
        .with_context(|| format!("{} ⊕ {}", a.p, a.q))?;
    let added = match a.highlight_after {
        Some(turn) => {
            let report = dynamic.rotate_p_by(turn);
            Some(report.added)
        }
        None => None,
    };
    let mesh = super::validated(dynamic.mesh_with_precision(), "the sum")?;
    let scene = scene::Scene::build(
        &mesh,
        &dynamic,
        added.as_deref().unwrap_or(&[]),
        a.view,
        a.size,
    );
    let bytes = match format {
        PictureFormat::Svg => svg::to_svg(&scene, &name).into_bytes(),
        PictureFormat::Png => raster::to_png(&scene)?,
    };
    super::create_parent_dir(&a.output)?;
    dymsum_io::atomic::write_atomic_bytes(&a.output, &bytes).context("writing the picture")?;
    write_summary(
        out,
        &name,
        mesh.faces.len(),
        &scene,
        added.as_deref(),
        &a.output,
    )
}

/// The one-line report: faces, faces drawn, the facets the turn added and
/// those highlighted, the file written.
fn write_summary(
    out: &mut dyn Write,
    name: &str,
    faces: usize,
    scene: &scene::Scene,
    added: Option<&[Facet]>,
    output: &Path,
) -> anyhow::Result<()> {
    let front = scene.faces.len();
    match added {
        Some(added) => writeln!(
            out,
            "{name}: {faces} faces ({front} drawn); the turn added {} facets, {} highlighted (facing the viewer); wrote {}",
            added.len(),
            scene.changed.len(),
            output.display()
        )?,
        None => writeln!(
            out,
            "{name}: {faces} faces ({front} drawn); wrote {}",
            output.display()
        )?,
    }
    Ok(())
}
