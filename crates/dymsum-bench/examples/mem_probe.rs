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
//! docs/BENCHMARKS.md, "Builds one at a time"). Each line also gives the
//! heap's own count (a counting allocator): the bytes live and the most
//! live at once since the start, which page rounding and the allocator's
//! free lists do not blur (docs/BENCHMARKS.md, "Convex bodies' memory").
use dymsum::query::{MeshBody, SceneChecker};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicIsize, Ordering::Relaxed};

/// The system allocator, counting the bytes live and their peak.
struct Counting;

static LIVE: AtomicIsize = AtomicIsize::new(0);
static PEAK: AtomicIsize = AtomicIsize::new(0);

fn grow(by: isize) {
    let now = LIVE.fetch_add(by, Relaxed) + by;
    PEAK.fetch_max(now, Relaxed);
}

// Unsafe because `GlobalAlloc` is an unsafe trait (the only way to count
// the heap); no speed is at stake in this probe.
// SAFETY: every call forwards to `System` with the caller's arguments
// unchanged; the counters only observe the sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        grow(layout.size() as isize);
        // SAFETY: the caller's contract for `alloc`, passed on.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size() as isize, Relaxed);
        // SAFETY: the caller's contract for `dealloc`, passed on.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        grow(new_size as isize - layout.size() as isize);
        // SAFETY: the caller's contract for `realloc`, passed on.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

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

/// Prints the peak and the resident memory added since `rss0` (KiB), and
/// the heap's live and peak bytes added since `heap0` (KB).
fn report(what: &str, rss0: i64, heap0: isize) {
    let (rss, hwm) = status();
    println!(
        "{what}: peak +{} KiB, stays +{} KiB; heap peak +{} KB, live +{} KB",
        hwm - rss0,
        rss - rss0,
        (PEAK.load(Relaxed) - heap0) / 1000,
        (LIVE.load(Relaxed) - heap0) / 1000
    );
}

/// Starts a measurement: the peak resident memory and the heap's peak
/// reset; returns the resident and live heap memory now.
fn start() -> (i64, isize) {
    std::fs::write("/proc/self/clear_refs", "5").expect("the peak reset");
    let heap0 = LIVE.load(Relaxed);
    PEAK.store(heap0, Relaxed);
    (status().0, heap0)
}

fn main() {
    let f = std::env::args().nth(1).expect("a mesh file");
    let mesh = dymsum_io::formats::read_mesh(std::path::Path::new(&f)).expect("a mesh");
    if std::env::var("AS_PYTHON").is_ok_and(|v| v == "1") {
        // The input stays (Python's arrays); the copies the bindings
        // convert it into count, each made just before its build and
        // dropped after it.
        let (rss0, heap0) = start();
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
        report("bodies", rss0, heap0);
        let v = dymsum::query::Validator::new(&bodies[0], &bodies[1..]).expect("a validator");
        drop(bodies);
        report("validator", rss0, heap0);
        std::hint::black_box(v);
        return;
    }
    let (rss0, heap0) = start();
    let body = MeshBody::new(&mesh).expect("a body");
    report("MeshBody::new", rss0, heap0);
    let checker = SceneChecker::new(&body, std::slice::from_ref(&body)).expect("a checker");
    report("with a checker", rss0, heap0);
    std::hint::black_box(checker);
}
