//! Collada (`.dae`) triangles for robots' meshes (issue 37): the geometry
//! read by `mesh-loader`, placed here.
//!
//! `mesh-loader` 0.1 places geometry itself, but composes a nested node's
//! transform after its parent's (child · parent), applies the file's
//! `<unit>` to coordinates and not to translations, skips transforms
//! within 0.01 of the identity, walks every visual scene (the last
//! instance of a geometry wins) and returns geometry nothing instances.
//! So here it only reads the triangles: the document it is given has one
//! visual scene of one bare node per `<instance_geometry>` and the unit 1,
//! and the placement of each instance is composed in `f64` from the
//! active scene (Collada's order: a node's transform elements multiplied
//! left to right, a child's world matrix `parent · child`, the unit
//! scaling everything), then applied to that geometry's triangles; a
//! geometry nothing instances is left out. Refused, by name: a geometry
//! instanced twice, `<instance_node>`, and `<lookat>` or `<skew>` above an
//! instance. `up_axis` is not applied (as mesh-loader and ROS's tools do).
//! The unit is (as rviz does); pinocchio, through coal's use of assimp,
//! skips it, so a file whose unit is not 1 differs from pinocchio's.
//!
//! # Independent review (2026-11-29)
//! A second reading confirmed the composition order (mesh-loader reads
//! `<matrix>` row by row, `<rotate>` in degrees, and post-multiplies) and
//! found five ways the first version, which handed mesh-loader a
//! flattened scene with the transforms in it, placed wrong or extra
//! geometry: transforms within 0.01 of the identity dropped, other visual
//! scenes winning, a unit after the scene applied twice, geometry nothing
//! instances returned raw, and a camera's `<lookat>` refusing the file.
//! All are mended by composing placements here; each has a test.

use dymsum::glam::{DMat4, DVec3};
use dymsum::PolygonMesh;

/// The triangles of the Collada file at `path`, placed (module docs), in
/// metres.
pub(crate) fn read_collada(path: &std::path::Path) -> Result<PolygonMesh, String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    collada_mesh(&text)
}

/// [`read_collada`] from the file's text.
pub(crate) fn collada_mesh(text: &str) -> Result<PolygonMesh, String> {
    let (bare, placed) = bare_scene(text)?;
    let scene = mesh_loader::collada::from_str(&bare).map_err(|e| e.to_string())?;
    let (mut vertices, mut faces) = (Vec::new(), Vec::new());
    for mesh in &scene.meshes {
        // Only instanced geometry, each by its own placement.
        let Some(m) = placed
            .iter()
            .find(|p| p.names.contains(&mesh.name))
            .map(|p| p.matrix)
        else {
            continue;
        };
        let offset = vertices.len();
        vertices.extend(
            mesh.vertices
                .iter()
                .map(|v| m.transform_point3(DVec3::from(v.map(f64::from))).to_array()),
        );
        faces.extend(
            mesh.faces
                .iter()
                .map(|f| f.iter().map(|&k| k as usize + offset).collect::<Vec<_>>()),
        );
    }
    if faces.is_empty() {
        return Err("the Collada file's scene places no triangles".into());
    }
    if faces.iter().flatten().any(|&k| k >= vertices.len()) {
        return Err("a Collada face names a missing vertex".into());
    }
    if vertices.iter().flatten().any(|x| !x.is_finite()) {
        return Err("a placed Collada vertex is not finite".into());
    }
    Ok(PolygonMesh::new(vertices, faces))
}

/// An instanced geometry: the names mesh-loader may give it (its id and
/// its name) and its placement.
struct Placed {
    names: Vec<String>,
    matrix: DMat4,
}

/// The first child element of `n` named `name`.
fn child<'a, 'i>(n: roxmltree::Node<'a, 'i>, name: &str) -> Option<roxmltree::Node<'a, 'i>> {
    n.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

/// `s` with XML's special characters escaped (attribute values).
fn escaped(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The document mesh-loader reads (module docs) and the placements.
fn bare_scene(text: &str) -> Result<(String, Vec<Placed>), String> {
    let doc = roxmltree::Document::parse(text).map_err(|e| format!("not XML: {e}"))?;
    let root = doc.root_element();
    let unit_node = child(root, "asset").and_then(|a| child(a, "unit"));
    let unit = match unit_node.and_then(|u| u.attribute("meter")) {
        Some(m) => m
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|u| u.is_finite() && *u > 0.0)
            .ok_or_else(|| format!("the unit {m:?} is not a positive number"))?,
        None => 1.0,
    };
    let scene_url = child(root, "scene")
        .and_then(|s| child(s, "instance_visual_scene"))
        .and_then(|i| i.attribute("url"))
        .ok_or("no <instance_visual_scene> in <scene>")?;
    let id = scene_url.trim_start_matches('#');
    let scene = root
        .descendants()
        .find(|n| n.tag_name().name() == "visual_scene" && n.attribute("id") == Some(id))
        .ok_or_else(|| format!("no visual scene {id:?}"))?;
    let library = scene
        .parent()
        .filter(|p| p.tag_name().name() == "library_visual_scenes");
    let library = library.ok_or("the visual scene is not in <library_visual_scenes>")?;
    let mut instances: Vec<(String, DMat4)> = Vec::new();
    let top = DMat4::from_scale(DVec3::splat(unit));
    for node in scene.children().filter(|c| c.tag_name().name() == "node") {
        collect(node, top, &mut instances)?;
    }
    let mut placed = Vec::new();
    for (url, matrix) in &instances {
        let gid = url.trim_start_matches('#');
        if placed.iter().any(|p: &Placed| p.names[0] == gid) {
            return Err(format!("geometry {url:?} is instanced more than once"));
        }
        let mut names = vec![gid.to_string()];
        if let Some(g) = root
            .descendants()
            .find(|n| n.tag_name().name() == "geometry" && n.attribute("id") == Some(gid))
        {
            names.extend(g.attribute("name").map(str::to_string));
        }
        placed.push(Placed {
            names,
            matrix: *matrix,
        });
    }
    // One bare node per instance, in the only visual scene; the unit 1.
    let mut scenes = format!(
        "<library_visual_scenes><visual_scene id=\"{}\">",
        escaped(id)
    );
    for (k, (url, _)) in instances.iter().enumerate() {
        scenes.push_str(&format!(
            "<node id=\"dymsum_bare_{k}\"><instance_geometry url=\"{}\"/></node>",
            escaped(url)
        ));
    }
    scenes.push_str("</visual_scene></library_visual_scenes>");
    let mut edits: Vec<(std::ops::Range<usize>, String)> = vec![(library.range(), scenes)];
    if let Some(u) = unit_node {
        edits.push((u.range(), "<unit meter=\"1\"/>".to_string()));
    }
    edits.sort_by_key(|(r, _)| std::cmp::Reverse(r.start));
    let mut out = text.to_string();
    for (r, with) in edits {
        out.replace_range(r, &with);
    }
    Ok((out, placed))
}

/// The matrix of one transform element (`None` for other elements).
fn transform_of(e: roxmltree::Node<'_, '_>) -> Result<Option<DMat4>, String> {
    let name = e.tag_name().name();
    if !matches!(name, "matrix" | "translate" | "rotate" | "scale") {
        return Ok(None);
    }
    let values: Vec<f64> = e
        .text()
        .unwrap_or("")
        .split_whitespace()
        .map(|v| {
            v.parse::<f64>()
                .map_err(|_| format!("<{name}> holds {v:?}, not a number"))
        })
        .collect::<Result<_, _>>()?;
    let want = match name {
        "matrix" => 16,
        "rotate" => 4,
        _ => 3,
    };
    if values.len() != want || values.iter().any(|v| !v.is_finite()) {
        return Err(format!(
            "<{name}> holds {} numbers, not {want} finite ones",
            values.len()
        ));
    }
    let v3 = DVec3::new(values[0], values[1], values[2]);
    Ok(Some(match name {
        // Row by row, as Collada writes it.
        "matrix" => DMat4::from_cols_array(&std::array::from_fn(|k| values[(k % 4) * 4 + k / 4])),
        "translate" => DMat4::from_translation(v3),
        "scale" => DMat4::from_scale(v3),
        _ => {
            let len = v3.length();
            if len == 0.0 {
                DMat4::IDENTITY
            } else {
                DMat4::from_axis_angle(v3 / len, values[3].to_radians())
            }
        }
    }))
}

/// Every `<instance_geometry>` under `node` with its placement (`outer`
/// the placement of `node`'s parent).
fn collect(
    node: roxmltree::Node<'_, '_>,
    outer: DMat4,
    out: &mut Vec<(String, DMat4)>,
) -> Result<(), String> {
    let places_geometry = node
        .descendants()
        .any(|d| d.tag_name().name() == "instance_geometry");
    if !places_geometry {
        return Ok(()); // cameras, lights, empty nodes
    }
    let mut m = outer;
    for c in node.children().filter(|c| c.is_element()) {
        match c.tag_name().name() {
            "lookat" | "skew" => {
                return Err(format!(
                    "<{}> transforms above a geometry are not read",
                    c.tag_name().name()
                ))
            }
            _ => {
                if let Some(t) = transform_of(c)? {
                    m *= t;
                }
            }
        }
    }
    for c in node.children().filter(|c| c.is_element()) {
        match c.tag_name().name() {
            "instance_geometry" => {
                let url = c
                    .attribute("url")
                    .ok_or("an <instance_geometry> without a url")?;
                out.push((url.to_string(), m));
            }
            "instance_node" => return Err("<instance_node> is not read".into()),
            "node" => collect(c, m, out)?,
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOC: &str = r##"<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="UNIT"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries>
    <geometry id="tet" name="tet"><mesh>
      <source id="tet-pos"><float_array id="tet-pos-array" count="12">0 0 0 1 0 0 0 1 0 0 0 1</float_array>
        <technique_common><accessor source="#tet-pos-array" count="4" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <vertices id="tet-vtx"><input semantic="POSITION" source="#tet-pos"/></vertices>
      <triangles count="4"><input semantic="VERTEX" source="#tet-vtx" offset="0"/><p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s">NODES</visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>"##;

    /// Where the tetrahedron's corner at the origin and the one at x = 1
    /// land.
    fn corners(unit: &str, nodes: &str) -> [[f64; 3]; 2] {
        let m = collada_mesh(&DOC.replace("UNIT", unit).replace("NODES", nodes)).unwrap();
        // Triangle 0 is (0, 2, 1): its first corner is vertex 0, its last vertex 1.
        let f = &m.faces[0];
        [m.vertices[f[0]], m.vertices[f[2]]]
    }

    fn near(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-6)
    }

    /// A parent's rotation turns its child's translation, the unit scales
    /// translations too, and transform elements compose left to right.
    #[test]
    fn nested_nodes_and_units_compose_as_collada_says() {
        let nested = r##"<node id="p"><rotate>0 0 1 90</rotate><node id="c"><translate>1 0 0</translate><instance_geometry url="#tet"/></node></node>"##;
        let [o, x] = corners("1", nested);
        assert!(
            near(o, [0.0, 1.0, 0.0]) && near(x, [0.0, 2.0, 0.0]),
            "{o:?} {x:?}"
        );
        let moved =
            r##"<node id="n"><translate>2 0 0</translate><instance_geometry url="#tet"/></node>"##;
        let [o, x] = corners("0.5", moved);
        assert!(
            near(o, [1.0, 0.0, 0.0]) && near(x, [1.5, 0.0, 0.0]),
            "{o:?} {x:?}"
        );
        let both = r##"<node id="n"><translate>2 0 0</translate><rotate>0 0 1 90</rotate><instance_geometry url="#tet"/></node>"##;
        let [o, x] = corners("1", both);
        assert!(
            near(o, [2.0, 0.0, 0.0]) && near(x, [2.0, 1.0, 0.0]),
            "{o:?} {x:?}"
        );
    }

    /// The review's cases: a small translation (mesh-loader drops those
    /// within 0.01 of the identity), another visual scene placing the same
    /// geometry, the asset after the scene, a geometry nothing instances,
    /// and a camera's `<lookat>`.
    #[test]
    fn small_moves_other_scenes_late_units_and_cameras() {
        let small = r##"<node id="n"><translate>0.005 0 0</translate><instance_geometry url="#tet"/></node>"##;
        let [o, _] = corners("1", small);
        assert!(near(o, [0.005, 0.0, 0.0]), "{o:?}");
        let other = DOC.replace("UNIT", "1").replace(
            "NODES</visual_scene>",
            r##"<node id="n"><translate>1 0 0</translate><instance_geometry url="#tet"/></node></visual_scene><visual_scene id="s2"><node id="m"><instance_geometry url="#tet"/></node></visual_scene>"##,
        );
        let m = collada_mesh(&other).unwrap();
        assert!(
            m.vertices.iter().all(|v| v[0] >= 1.0 - 1e-12),
            "{:?}",
            m.vertices
        );
        let late = DOC
            .replace("<asset><unit meter=\"UNIT\"/><up_axis>Z_UP</up_axis></asset>", "")
            .replace("</COLLADA>", "<asset><unit meter=\"0.5\"/></asset></COLLADA>")
            .replace("NODES", r##"<node id="n"><translate>2 0 0</translate><instance_geometry url="#tet"/></node>"##);
        let m = collada_mesh(&late).unwrap();
        let xs: Vec<f64> = m.vertices.iter().map(|v| v[0]).collect();
        assert!(
            xs.iter().all(|&x| (1.0 - 1e-12..=1.5 + 1e-12).contains(&x)),
            "{xs:?}"
        );
        assert!(collada_mesh(&DOC.replace("UNIT", "1").replace("NODES", "")).is_err());
        let camera = r##"<node id="cam"><lookat>1 1 1 0 0 0 0 0 1</lookat></node><node id="n"><instance_geometry url="#tet"/></node>"##;
        let [o, _] = corners("1", camera);
        assert!(near(o, [0.0, 0.0, 0.0]), "{o:?}");
    }

    #[test]
    fn what_is_not_read_is_named() {
        let twice = r##"<node id="a"><instance_geometry url="#tet"/></node><node id="b"><instance_geometry url="#tet"/></node>"##;
        let err = collada_mesh(&DOC.replace("UNIT", "1").replace("NODES", twice)).unwrap_err();
        assert!(err.contains("more than once"), "{err}");
        let skew =
            r##"<node id="a"><skew>45 0 1 0 1 0 0</skew><instance_geometry url="#tet"/></node>"##;
        let err = collada_mesh(&DOC.replace("UNIT", "1").replace("NODES", skew)).unwrap_err();
        assert!(err.contains("skew"), "{err}");
        assert!(collada_mesh("<COLLADA>").is_err());
    }
}
