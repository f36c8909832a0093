//! Review (B): every Solid component of `clean_soup` is closed edge for
//! edge (each undirected edge run as often each way, counted with the
//! triangles' weights), so it stays a cycle whatever its vertices are
//! moved to. Random soups on a small grid (many collinear vertices,
//! T-junctions, duplicates, backs, zero-area triangles).

use dymsum::solid::soup::{clean_soup, ComponentKind};
use dymsum::PolygonMesh;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;

fn check(m: &PolygonMesh) -> usize {
    let Ok(s) = clean_soup(m) else { return 0 };
    let mut solids = 0;
    for c in &s.components {
        if c.kind != ComponentKind::Solid {
            continue;
        }
        solids += 1;
        let mut net: HashMap<(usize, usize), i64> = HashMap::new();
        for &t in &c.triangles {
            let f = &s.mesh.faces[t];
            let w = i64::from(s.weights[t]);
            assert!(w > 0);
            for e in 0..3 {
                let (a, b) = (f[e], f[(e + 1) % 3]);
                let (k, d) = if a < b { ((a, b), 1) } else { ((b, a), -1) };
                *net.entry(k).or_default() += d * w;
            }
        }
        if let Some((k, n)) = net.iter().find(|(_, &n)| n != 0) {
            panic!(
                "edge {k:?} unbalanced ({n}) in {:?}\nfaces {:?}",
                m.vertices, m.faces
            );
        }
    }
    solids
}

#[test]
fn solid_components_are_closed_edge_for_edge() {
    let mut r = ChaCha8Rng::seed_from_u64(7);
    let mut solids = 0;
    for _ in 0..100000 {
        let nv = r.random_range(4..10);
        let vertices: Vec<[f64; 3]> = (0..nv)
            .map(|_| [0, 1, 2].map(|_| f64::from(r.random_range(0..3i32))))
            .collect();
        let nf = r.random_range(1..14);
        let mut faces: Vec<Vec<usize>> = Vec::new();
        for _ in 0..nf {
            if r.random_bool(0.4) {
                // a closed tetrahedron (either orientation), sharing the grid
                let v: Vec<usize> = (0..4).map(|_| r.random_range(0..nv)).collect();
                for f in [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]] {
                    let f: Vec<usize> = f.iter().map(|&i| v[i]).collect();
                    faces.push(if r.random_bool(0.9) {
                        f
                    } else {
                        f.into_iter().rev().collect()
                    });
                }
            } else if !faces.is_empty() && r.random_bool(0.3) {
                // a copy or a back of an earlier face
                let f = faces[r.random_range(0..faces.len())].clone();
                faces.push(if r.random_bool(0.5) {
                    f
                } else {
                    f.into_iter().rev().collect()
                });
            } else {
                let k = if r.random_bool(0.8) { 3 } else { 4 };
                faces.push((0..k).map(|_| r.random_range(0..nv)).collect());
            }
        }
        solids += check(&PolygonMesh::new(vertices, faces));
    }
    eprintln!("{solids} solid components checked");
    assert!(solids > 100);
}
