//! A digest of what the exact mesh cleaning makes of each mesh, to compare
//! two builds of it (a change meant to keep the cleaning's answers, as the
//! cleaning's speed-ups of issue 35 were): `cargo run --release -p
//! dymsum-bench --example soup_digest -- FILE...` prints, per file, the
//! cleaned triangle count, triangles set aside, edges split, triangles
//! flipped and a hash of the cleaned triangles, weights and components.
use std::hash::{Hash, Hasher};
fn main() {
    for f in std::env::args().skip(1) {
        let mesh = dymsum_io::formats::read_mesh(std::path::Path::new(&f)).expect("a mesh");
        let s = dymsum::solid::soup::clean_soup(&mesh).expect("clean");
        let mut h = std::collections::hash_map::DefaultHasher::new();
        s.mesh.faces.hash(&mut h);
        s.weights.hash(&mut h);
        for c in &s.components {
            c.triangles.hash(&mut h);
            (c.kind == dymsum::solid::soup::ComponentKind::Solid).hash(&mut h);
        }
        println!(
            "{f} {} {} {} {} {:x}",
            s.mesh.faces.len(),
            s.set_aside,
            s.split_edges,
            s.flipped,
            h.finish()
        );
    }
}
