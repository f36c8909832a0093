//! Times what Python's `MotionChecker((v, f), [(v, f)])` builds from a
//! mesh file, in Rust (issue 35): the body and the obstacle through the
//! ladder (`Body::from_mesh_with`) and the `Validator` over them.
//! `cargo run --release -p dymsum-bench --example validator_probe -- FILE...`
//! prints the fastest of `REPEAT` (default 20) builds per file and the
//! checker's path.
use std::time::Instant;

use dymsum::body::BodyOptions;
use dymsum::query::{Body, Validator};

fn main() {
    let repeat: usize = std::env::var("REPEAT")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(20);
    for f in std::env::args().skip(1) {
        let mesh = dymsum_io::formats::read_mesh(std::path::Path::new(&f)).expect("a mesh");
        let (mut best, mut path) = (f64::INFINITY, "");
        for _ in 0..repeat.max(1) {
            let t = Instant::now();
            let build = || {
                Body::from_mesh_with(&mesh, &BodyOptions::default())
                    .expect("a body")
                    .0
            };
            let (body, obstacle) = (build(), build());
            let v = Validator::new(&body, &[obstacle]).expect("a validator");
            best = best.min(t.elapsed().as_secs_f64());
            path = match v {
                Validator::Convex(_) => "convex",
                Validator::Mesh(_) => "triangles",
            };
        }
        println!(
            "{f}: {} faces, {:.3} ms ({path})",
            mesh.faces.len(),
            best * 1e3
        );
    }
}
