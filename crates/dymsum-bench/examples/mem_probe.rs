//! The memory a mesh body's build needs (issue 35), in this process:
//! `cargo run --release -p dymsum-bench --example mem_probe -- FILE`
//! reads the mesh, resets the peak resident memory
//! (`/proc/self/clear_refs`, Linux), then prints the peak and the resident
//! memory added by `MeshBody::new`, then by a `SceneChecker` of the body
//! against itself (its trees). With `AS_PYTHON=1`, what Python's
//! `MotionChecker((v, f), [(v, f)])` builds instead: two copies of the
//! mesh through the ladder side by side, then the validator.
use dymsum::query::{MeshBody, SceneChecker};

/// (VmRSS, VmHWM) in KiB.
fn status() -> (i64, i64) {
    let s = std::fs::read_to_string("/proc/self/status").expect("Linux's /proc");
    let get = |k: &str| {
        s.lines()
            .find(|l| l.starts_with(k))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|v| v.parse::<i64>().ok())
            .expect("a field of /proc/self/status")
    };
    (get("VmRSS:"), get("VmHWM:"))
}

/// Prints the peak and the resident memory added since `rss0` (KiB).
fn report(what: &str, rss0: i64) {
    let (rss, hwm) = status();
    println!(
        "{what}: peak +{} KiB, stays +{} KiB",
        hwm - rss0,
        rss - rss0
    );
}

fn main() {
    let f = std::env::args().nth(1).expect("a mesh file");
    let mesh = dymsum_io::formats::read_mesh(std::path::Path::new(&f)).expect("a mesh");
    if std::env::var("AS_PYTHON").is_ok_and(|v| v == "1") {
        let copies = [mesh.clone(), mesh];
        std::fs::write("/proc/self/clear_refs", "5").expect("the peak reset");
        let (rss0, _) = status();
        let build = |m: &dymsum::PolygonMesh| {
            dymsum::query::Body::from_mesh_with(m, &Default::default())
                .expect("a body")
                .0
        };
        // Side by side from 20,000 faces in all, as Python builds them.
        let bodies: Vec<dymsum::query::Body> = if 2 * copies[0].faces.len() >= 20_000 {
            std::thread::scope(|s| {
                let other = s.spawn(|| build(&copies[1]));
                let first = build(&copies[0]);
                vec![first, other.join().expect("the second build")]
            })
        } else {
            copies.iter().map(build).collect()
        };
        drop(copies);
        report("bodies", rss0);
        let v = dymsum::query::Validator::new(&bodies[0], &bodies[1..]).expect("a validator");
        drop(bodies);
        report("validator", rss0);
        std::hint::black_box(v);
        return;
    }
    std::fs::write("/proc/self/clear_refs", "5").expect("the peak reset");
    let (rss0, _) = status();
    let body = MeshBody::new(&mesh).expect("a body");
    report("MeshBody::new", rss0);
    let checker = SceneChecker::new(&body, std::slice::from_ref(&body)).expect("a checker");
    report("with a checker", rss0);
    std::hint::black_box(checker);
}
