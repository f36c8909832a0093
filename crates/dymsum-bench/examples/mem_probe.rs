//! The memory a mesh body's build needs (issue 35), in this process:
//! `cargo run --release -p dymsum-bench --example mem_probe -- FILE`
//! reads the mesh, resets the peak resident memory
//! (`/proc/self/clear_refs`, Linux), then prints the peak and the resident
//! memory added by `MeshBody::new`, then by a `SceneChecker` of the body
//! against itself (its trees). With `AS_PYTHON=1`, what Python's
//! `MotionChecker((v, f), [(v, f)])` builds instead: two copies of the
//! mesh, each converted (copied) just before it goes through the ladder,
//! one at a time, then the validator; with `SIDE_BY_SIDE=1` as well, both
//! copied first and built on two threads (as Python built them before:
//! docs/BENCHMARKS.md, "Builds one at a time").
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
        // The input stays (Python's arrays); the copies the bindings
        // convert it into count, each made just before its build and
        // dropped after it.
        std::fs::write("/proc/self/clear_refs", "5").expect("the peak reset");
        let (rss0, _) = status();
        let build = |m: &dymsum::PolygonMesh| {
            dymsum::query::Body::from_mesh_with(m, &Default::default())
                .expect("a body")
                .0
        };
        let bodies: Vec<dymsum::query::Body> =
            if std::env::var("SIDE_BY_SIDE").is_ok_and(|v| v == "1") {
                let (first, second) = (mesh.clone(), mesh.clone());
                std::thread::scope(|s| {
                    let other = s.spawn(move || build(&second));
                    let first = build(&first);
                    vec![first, other.join().expect("the second build")]
                })
            } else {
                (0..2).map(|_| build(&mesh.clone())).collect()
            };
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
