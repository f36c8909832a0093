//! Times the build of mesh bodies (issue 35): `cargo run --release -p
//! dymsum-bench --example build_probe -- FILE...` prints, per file, the
//! read, `MeshBody::new`, the body ladder (`Body::from_mesh_with`, what
//! Python builds) and a `SceneChecker` against itself. With
//! `REPEAT=n` in the environment each build runs n times (for a profiler)
//! and the time is the fastest run's.
use std::time::Instant;

use dymsum::query::{MeshBody, SceneChecker};

fn main() {
    for f in std::env::args().skip(1) {
        let t = Instant::now();
        let mesh = dymsum_io::formats::read_mesh(std::path::Path::new(&f)).expect("a mesh");
        let read = t.elapsed().as_secs_f64();
        let repeat: usize = std::env::var("REPEAT")
            .ok()
            .and_then(|r| r.parse().ok())
            .unwrap_or(1);
        let mut new = f64::INFINITY;
        let mut body = None;
        for _ in 0..repeat.max(1) {
            let t = Instant::now();
            body = Some(MeshBody::new(&mesh).expect("a body"));
            new = new.min(t.elapsed().as_secs_f64());
        }
        let body = body.expect("built at least once");
        let mut ladder = f64::INFINITY;
        let mut rung = None;
        for _ in 0..repeat.max(1) {
            let t = Instant::now();
            let (_, report) =
                dymsum::query::Body::from_mesh_with(&mesh, &Default::default()).expect("a body");
            ladder = ladder.min(t.elapsed().as_secs_f64());
            rung = Some(report.rung);
        }
        let t = Instant::now();
        let checker = SceneChecker::new(&body, std::slice::from_ref(&body)).expect("a checker");
        let pair = t.elapsed().as_secs_f64();
        std::hint::black_box(checker);
        println!(
            "{f}: {} faces; read {:.1} ms, MeshBody::new {:.2} ms, Body::from_mesh_with {:.2} ms ({:?}), SceneChecker::new {:.1} ms; \
             refuted convex by an edge {}; {:?}",
            mesh.faces.len(),
            read * 1e3,
            new * 1e3,
            ladder * 1e3,
            rung.expect("built at least once"),
            pair * 1e3,
            dymsum::body::mesh::exactly_convex_refuted_by_edges(),
            body.report()
        );
    }
}
