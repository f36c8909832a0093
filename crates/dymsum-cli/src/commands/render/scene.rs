//! The 2-D scene: projected, shaded polygons in painter's order.

use dymsum::polytope::Polytope;
use dymsum::sum::Facet;
use dymsum::{DVec3, DynamicSum, PolygonMesh, Pose};

/// A polygon is drawn iff its outward unit normal `n` has `n · v > FRONT_EPS`
/// (`v`: the unit vector towards the viewer).
pub const FRONT_EPS: f64 = 1e-9;

/// Colour of the faces of the sum (before shading).
const FACE_RGB: [f64; 3] = [0.74, 0.80, 0.90];
/// Colour of the highlighted facets (before shading).
const CHANGED_RGB: [f64; 3] = [0.90, 0.12, 0.10];
/// Outline of the faces.
pub const EDGE_RGB: [u8; 3] = [0x1a, 0x1a, 0x1a];
/// Outline of the highlighted facets.
pub const CHANGED_EDGE_RGB: [u8; 3] = [0x6e, 0x0a, 0x08];
/// Background.
pub const BACKGROUND_RGB: [u8; 3] = [0xff, 0xff, 0xff];
/// Ambient share of the Lambert shading.
const AMBIENT: f64 = 0.28;
/// Margin around the sum, as a fraction of the picture size.
const MARGIN: f64 = 0.04;

/// An orthographic view direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Azimuth about the z axis, degrees.
    pub azimuth_deg: f64,
    /// Elevation above the xy plane, degrees.
    pub elevation_deg: f64,
}

impl View {
    /// A view from azimuth and elevation in degrees.
    pub fn new(azimuth_deg: f64, elevation_deg: f64) -> View {
        View {
            azimuth_deg,
            elevation_deg,
        }
    }

    /// The screen basis `(right, up, toward the viewer)`, right-handed.
    pub fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let (sa, ca) = self.azimuth_deg.to_radians().sin_cos();
        let (se, ce) = self.elevation_deg.to_radians().sin_cos();
        let toward = DVec3::new(ce * ca, ce * sa, se);
        let right = DVec3::new(-sa, ca, 0.0);
        let up = DVec3::new(-se * ca, -se * sa, ce);
        (right, up, toward)
    }
}

/// A filled polygon in picture coordinates (pixels, y down).
#[derive(Clone, Debug)]
pub struct Shape {
    /// Corners.
    pub points: Vec<[f64; 2]>,
    /// Fill colour.
    pub fill: [u8; 3],
}

/// Everything to draw, in painter's order: faces, changed facets (filled and
/// outlined), then the face outlines on top.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Width and height in pixels.
    pub size: u32,
    /// The front faces of the merged sum.
    pub faces: Vec<Shape>,
    /// The highlighted (added, front-facing) facets.
    pub changed: Vec<Shape>,
    /// Outline width of the faces, pixels.
    pub edge_width: f64,
    /// Outline width of the changed facets, pixels.
    pub changed_edge_width: f64,
}

/// The corners and outward unit normal of one facet of the sum of `p` at
/// `pose_p` and `q` at `pose_q` (see the module docs of `render`). The
/// normal is zero for a degenerate ee-facet (parallel edges).
pub fn facet_geometry(
    p: &Polytope,
    pose_p: &Pose,
    q: &Polytope,
    pose_q: &Pose,
    facet: Facet,
) -> (Vec<DVec3>, DVec3) {
    let pv = |u: u32| pose_p.apply(p.vertex(u as usize));
    let qv = |w: u32| pose_q.apply(q.vertex(w as usize));
    let pn = |f: u32| pose_p.rotation.apply(p.unit_normal(f as usize));
    let qn = |g: u32| pose_q.rotation.apply(q.unit_normal(g as usize));
    match facet {
        Facet::Fv { p_face, q_vertex } => {
            let w = qv(q_vertex);
            let corners = p.face(p_face as usize).iter().map(|&u| pv(u) + w).collect();
            (corners, pn(p_face).normalize_or_zero())
        }
        Facet::Vf { p_vertex, q_face } => {
            let u = pv(p_vertex);
            let corners = q.face(q_face as usize).iter().map(|&w| u + qv(w)).collect();
            (corners, qn(q_face).normalize_or_zero())
        }
        Facet::Ee { p_edge, q_edge } => {
            let ep = p.edge(p_edge as usize);
            let eq = q.edge(q_edge as usize);
            let (a1, a2) = (pv(ep.vertices[0]), pv(ep.vertices[1]));
            let (b1, b2) = (qv(eq.vertices[0]), qv(eq.vertices[1]));
            let corners = vec![a1 + b1, a2 + b1, a2 + b2, a1 + b2];
            let n = (a2 - a1).cross(b2 - b1).normalize_or_zero();
            let inside = pn(ep.faces[0]) + pn(ep.faces[1]) + qn(eq.faces[0]) + qn(eq.faces[1]);
            (corners, if n.dot(inside) < 0.0 { -n } else { n })
        }
    }
}

/// Newell's normal of a polygon, normalised (zero if degenerate).
fn newell_normal(points: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        n += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    n.normalize_or_zero()
}

/// Lambert shading of `rgb` for outward unit normal `n` and unit light `l`.
fn shade(rgb: [f64; 3], n: DVec3, l: DVec3) -> [u8; 3] {
    let k = AMBIENT + (1.0 - AMBIENT) * n.dot(l).max(0.0);
    rgb.map(|c| (c * k * 255.0).round().clamp(0.0, 255.0) as u8)
}

/// The orthographic projection of the view onto the picture square, fitted
/// so that the given points fill it up to the margin.
struct Projection {
    right: DVec3,
    up: DVec3,
    /// Picture side in pixels.
    px: f64,
    /// Pixels per model unit.
    scale: f64,
    /// The centre of the fitted points' projection (model units).
    centre: [f64; 2],
}

impl Projection {
    fn fit(points: &[DVec3], right: DVec3, up: DVec3, size: u32) -> Projection {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for v in points {
            let s = [v.dot(right), v.dot(up)];
            for k in 0..2 {
                lo[k] = lo[k].min(s[k]);
                hi[k] = hi[k].max(s[k]);
            }
        }
        let px = size as f64;
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let scale = if extent > 0.0 {
            px * (1.0 - 2.0 * MARGIN) / extent
        } else {
            1.0
        };
        let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
        Projection {
            right,
            up,
            px,
            scale,
            centre,
        }
    }

    /// Picture coordinates of `v` (y down).
    fn apply(&self, v: DVec3) -> [f64; 2] {
        [
            0.5 * self.px + self.scale * (v.dot(self.right) - self.centre[0]),
            0.5 * self.px - self.scale * (v.dot(self.up) - self.centre[1]),
        ]
    }
}

impl Scene {
    /// Projects the merged mesh and the `added` facets of the current sum.
    pub fn build(
        mesh: &PolygonMesh,
        sum: &DynamicSum,
        added: &[Facet],
        view: View,
        size: u32,
    ) -> Scene {
        let (right, up, toward) = view.basis();
        let light = (-0.45 * right + 0.65 * up + 1.0 * toward).normalize();
        let verts: Vec<DVec3> = mesh.vertices.iter().map(|&v| DVec3::from(v)).collect();
        let projection = Projection::fit(&verts, right, up, size);
        // A polygon with outward normal `n`, if it faces the viewer.
        let front_shape = |corners: &[DVec3], n: DVec3, rgb: [f64; 3]| {
            (n.dot(toward) > FRONT_EPS).then(|| Shape {
                points: corners.iter().map(|&v| projection.apply(v)).collect(),
                fill: shade(rgb, n, light),
            })
        };
        let faces = mesh
            .faces
            .iter()
            .filter_map(|f| {
                let pts: Vec<DVec3> = f.iter().map(|&i| verts[i]).collect();
                front_shape(&pts, newell_normal(&pts), FACE_RGB)
            })
            .collect();
        let (pose_p, pose_q) = (sum.pose_p(), sum.pose_q());
        let changed = added
            .iter()
            .filter_map(|&facet| {
                let (corners, n) = facet_geometry(sum.p(), &pose_p, sum.q(), &pose_q, facet);
                front_shape(&corners, n, CHANGED_RGB)
            })
            .collect();
        let px = size as f64;
        Scene {
            size,
            faces,
            changed,
            edge_width: (px * 0.0011).max(0.5),
            changed_edge_width: (px * 0.0005).max(0.25),
        }
    }
}
