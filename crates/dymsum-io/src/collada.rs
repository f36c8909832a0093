//! Collada (`.dae`) triangles for robots' meshes (issue 37): the geometry
//! read by `mesh-loader`, the scene's transforms composed here.
//!
//! `mesh-loader` 0.1 composes a nested node's transform *after* its
//! parent's (child · parent, so a rotated parent does not turn its
//! child's translation) and applies the file's `<unit>` only to the
//! coordinates, not to the nodes' translations; and it places each
//! geometry once however often it is instanced. Within one node its
//! transform elements compose right. So the scene is first flattened
//! here: each `<instance_geometry>` becomes a node of its own under the
//! scene, holding a scale by the unit and then every transform element
//! from the outermost node down, in document order (Collada's own order:
//! `M = M_parent · M_child`, elements left to right); the unit becomes 1.
//! A geometry instanced twice, `<instance_node>`, `<lookat>` and `<skew>`
//! are refused, naming them.

use dymsum::PolygonMesh;

/// The triangles of the Collada file at `path`, placed (module docs), in
/// metres.
pub(crate) fn read_collada(path: &std::path::Path) -> Result<PolygonMesh, String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    collada_mesh(&text)
}

/// [`read_collada`] from the file's text.
pub(crate) fn collada_mesh(text: &str) -> Result<PolygonMesh, String> {
    let flat = flattened(text)?;
    let scene = mesh_loader::collada::from_str(&flat).map_err(|e| e.to_string())?;
    let (mut vertices, mut faces) = (Vec::new(), Vec::new());
    for mesh in &scene.meshes {
        let offset = vertices.len();
        vertices.extend(mesh.vertices.iter().map(|v| v.map(f64::from)));
        faces.extend(
            mesh.faces
                .iter()
                .map(|f| f.iter().map(|&k| k as usize + offset).collect::<Vec<_>>()),
        );
    }
    if faces.is_empty() {
        return Err("the Collada file has no triangles".into());
    }
    if faces.iter().flatten().any(|&k| k >= vertices.len()) {
        return Err("a Collada face names a missing vertex".into());
    }
    Ok(PolygonMesh::new(vertices, faces))
}

/// The document with its visual scene flattened and its unit 1 (module
/// docs).
fn flattened(text: &str) -> Result<String, String> {
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
    let mut instances: Vec<(String, String)> = Vec::new();
    for node in scene.children().filter(|c| c.tag_name().name() == "node") {
        collect(node, text, String::new(), &mut instances)?;
    }
    let mut seen = std::collections::HashSet::new();
    if let Some((url, _)) = instances.iter().find(|(url, _)| !seen.insert(url.clone())) {
        return Err(format!("geometry {url:?} is instanced more than once"));
    }
    let mut flat = format!("<visual_scene id=\"{id}\">");
    for (k, (url, transforms)) in instances.iter().enumerate() {
        flat.push_str(&format!(
            "<node id=\"dymsum_flat_{k}\"><scale>{unit:e} {unit:e} {unit:e}</scale>{transforms}\
             <instance_geometry url=\"{url}\"/></node>"
        ));
    }
    flat.push_str("</visual_scene>");
    // Replaced from the end: the scene, then the unit (in the asset,
    // before it).
    let mut out = String::with_capacity(text.len());
    let r = scene.range();
    let tail = &text[r.end..];
    let mut head = text[..r.start].to_string();
    if let Some(u) = unit_node {
        let ur = u.range();
        if ur.end <= r.start {
            head = format!(
                "{}<unit meter=\"1\"/>{}",
                &text[..ur.start],
                &text[ur.end..r.start]
            );
        }
    }
    out.push_str(&head);
    out.push_str(&flat);
    out.push_str(tail);
    Ok(out)
}

/// The first child element of `n` named `name`.
fn child<'a, 'i>(n: roxmltree::Node<'a, 'i>, name: &str) -> Option<roxmltree::Node<'a, 'i>> {
    n.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

/// Every `<instance_geometry>` under `node`, with the transform elements
/// from the outermost node down (source text, in order).
fn collect(
    node: roxmltree::Node<'_, '_>,
    text: &str,
    outer: String,
    out: &mut Vec<(String, String)>,
) -> Result<(), String> {
    let mut transforms = outer;
    for c in node.children().filter(|c| c.is_element()) {
        match c.tag_name().name() {
            "matrix" | "translate" | "rotate" | "scale" => transforms.push_str(&text[c.range()]),
            "lookat" | "skew" => {
                return Err(format!("<{}> transforms are not read", c.tag_name().name()))
            }
            _ => {}
        }
    }
    for c in node.children().filter(|c| c.is_element()) {
        match c.tag_name().name() {
            "instance_geometry" => {
                let url = c
                    .attribute("url")
                    .ok_or("an <instance_geometry> without a url")?;
                out.push((url.to_string(), transforms.clone()));
            }
            "instance_node" => return Err("<instance_node> is not read".into()),
            "node" => collect(c, text, transforms.clone(), out)?,
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
