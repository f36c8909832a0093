//! Times the build of mesh bodies (issue 35): `cargo run --release -p
//! dymsum-bench --example build_probe -- FILE...` prints, per file, the
//! read, `MeshBody::new` and a `SceneChecker` against itself.
use std::time::Instant;

use dymsum::query::{MeshBody, SceneChecker};

fn main() {
    for f in std::env::args().skip(1) {
        let t = Instant::now();
        let mesh = dymsum_io::formats::read_mesh(std::path::Path::new(&f)).expect("a mesh");
        let read = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let body = MeshBody::new(&mesh).expect("a body");
        let new = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let checker = SceneChecker::new(&body, std::slice::from_ref(&body)).expect("a checker");
        let pair = t.elapsed().as_secs_f64();
        std::hint::black_box(checker);
        println!(
            "{f}: {} faces; read {:.1} ms, MeshBody::new {:.1} ms, SceneChecker::new {:.1} ms; {:?}",
            mesh.faces.len(),
            read * 1e3,
            new * 1e3,
            pair * 1e3,
            body.report()
        );
    }
}
