//! Issue 26: a fuzz harness for the mesh readers on stable Rust (proptest).
//!
//! For every format (OFF, OBJ, PLY ASCII and binary, STL ASCII and binary)
//! the readers get random bytes, random bytes behind a plausible header, and
//! files written by the crate's own writers from random small meshes and
//! then mutated (bit flips, truncation, inserted or replaced tokens such as
//! huge counts, `nan`, `1e400` and negative indices, overwritten binary
//! words). Whatever the input:
//!
//! * the reader returns `Ok` or a typed content error, never panics;
//! * no single allocation exceeds [`alloc_limit`] of the input's length (a
//!   header claiming a billion vertices in a tiny file does not preallocate
//!   gigabytes: readers cap what they reserve from a claimed count);
//! * an `Ok` mesh has finite coordinates and faces of at least 3 vertices,
//!   every index in range;
//! * `load_polytope` on the same bytes written to a file gives `Ok` or a
//!   typed [`LoadError`].
//!
//! The case counts are small for CI (the whole file runs in a few seconds
//! in release); `DYMSUM_PROPTEST_CASES=5000` (or `PROPTEST_CASES`) runs
//! longer. Truncation at every byte of every format and the huge-header
//! regressions are plain tests.
//!
//! The one `unsafe` is the `GlobalAlloc` impl that measures allocations;
//! the library itself stays `#![forbid(unsafe_code)]`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;

use dymsum::polytope::MeshPolicy;
use dymsum::PolygonMesh;
use dymsum_io::formats::{read_mesh_bytes, read_obj_objects_bytes, write_mesh_bytes, Format};
use dymsum_io::formats::{FormatError, Location};
use dymsum_io::{load_polytope, load_polytope_bytes, LoadError};
use proptest::prelude::*;
use proptest::sample::Index;

// ---------------------------------------------------------------------------
// Allocation measurement

struct Measuring;

thread_local! {
    /// The largest single allocation (or reallocation) this thread asked
    /// for since the last [`largest_allocation`] reset.
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

fn note(size: usize) {
    // `try_with`: the slot may already be gone while the thread exits.
    let _gone_at_thread_exit = LARGEST.try_with(|c| c.set(c.get().max(size)));
}

unsafe impl GlobalAlloc for Measuring {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note(new_size);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Measuring = Measuring;

/// Runs `f` and returns its result and the largest single allocation it
/// made on this thread.
fn largest_allocation<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let before = LARGEST.with(|c| c.replace(0));
    let r = f();
    let largest = LARGEST.with(|c| {
        let largest = c.get();
        c.set(before.max(largest));
        largest
    });
    (r, largest)
}

/// The most a reader may allocate at once for `len` input bytes: what the
/// content can need (a small multiple of its length) plus a fixed amount
/// for what readers reserve from a claimed count (capped at 2^16
/// elements, a few MiB). A header's count alone never raises it.
fn alloc_limit(len: usize) -> usize {
    (16 << 20) + 64 * len
}

// ---------------------------------------------------------------------------
// The invariants

/// Reads `bytes` as `format` and checks every invariant of the module docs.
fn check_read(bytes: &[u8], format: Format) -> Result<(), TestCaseError> {
    let (result, largest) = largest_allocation(|| read_mesh_bytes(bytes, format, "fuzz"));
    prop_assert!(
        largest <= alloc_limit(bytes.len()),
        "{format}: one allocation of {largest} bytes for {} input bytes",
        bytes.len()
    );
    match result {
        Ok(mesh) => check_mesh(&mesh, format)?,
        Err(e) => check_error(&e, format)?,
    }
    if format == Format::Obj {
        let (objects, largest) = largest_allocation(|| read_obj_objects_bytes(bytes, "fuzz"));
        prop_assert!(largest <= alloc_limit(bytes.len()));
        match objects {
            Ok(bodies) => {
                for (_, m) in &bodies {
                    // Point clouds (no faces) are bodies here.
                    check_mesh(m, format)?;
                }
            }
            Err(e) => check_error(&e, format)?,
        }
    }
    let (loaded, largest) = largest_allocation(|| {
        load_polytope_bytes(bytes, format, "fuzz", MeshPolicy::default()).map(|_| ())
    });
    // Hull building may allocate in proportion to the vertices, which the
    // input's length bounds.
    prop_assert!(largest <= alloc_limit(bytes.len()));
    if let Err(e) = loaded {
        check_load_error(&e)?;
    }
    Ok(())
}

fn check_mesh(mesh: &PolygonMesh, format: Format) -> Result<(), TestCaseError> {
    prop_assert!(!mesh.vertices.is_empty(), "{format}: Ok without vertices");
    for v in &mesh.vertices {
        prop_assert!(
            v.iter().all(|c| c.is_finite()),
            "{format}: non-finite vertex {v:?}"
        );
    }
    let n = mesh.vertices.len();
    for f in &mesh.faces {
        prop_assert!(f.len() >= 3, "{format}: face {f:?} of < 3 vertices");
        prop_assert!(
            f.iter().all(|&i| i < n),
            "{format}: face {f:?} out of range of {n} vertices"
        );
    }
    Ok(())
}

/// A content error: typed, labelled, displayable. Reading bytes never
/// gives the file-level or writing variants.
fn check_error(e: &FormatError, format: Format) -> Result<(), TestCaseError> {
    let text = e.to_string();
    prop_assert!(text.contains("fuzz"), "{format}: unlabelled error {text}");
    prop_assert!(
        !matches!(
            e,
            FormatError::Io { .. }
                | FormatError::NotRegularFile { .. }
                | FormatError::UnknownExtension { .. }
                | FormatError::InvalidMesh { .. }
        ),
        "{format}: unexpected error kind for bytes: {e:?}"
    );
    if let Some(Location::Line(l)) = e.location() {
        prop_assert!(*l >= 1, "{format}: line 0 in {text}");
    }
    Ok(())
}

fn check_load_error(e: &LoadError) -> Result<(), TestCaseError> {
    // Every variant renders; a file that exists is never "not found".
    let _ = (e.to_string(), e.origin(), e.cause(), e.for_operand("A"));
    prop_assert!(
        !matches!(e, LoadError::NotFound { .. } | LoadError::Model { .. }),
        "{e:?}"
    );
    Ok(())
}

// ---------------------------------------------------------------------------
// Generators

/// Finite coordinates, with the awkward ones well represented.
fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -10.0..10.0f64,
        1 => Just(0.0),
        1 => Just(-0.0),
        1 => Just(1e-300),
        1 => Just(5e-324),
        1 => Just(-f64::MIN_POSITIVE),
        1 => Just(1e30),
        1 => Just(-3.0e38),
        1 => Just(1e300),
        1 => Just(-f64::MAX),
        1 => (-1000i32..1000).prop_map(f64::from),
    ]
}

/// A small mesh the writers accept (STL after [`stl_range`]): 1 to 10 vertices, up to 8 faces of 3
/// to 6 (possibly repeated) vertices.
fn small_mesh() -> impl Strategy<Value = PolygonMesh> {
    prop::collection::vec(prop::array::uniform3(coordinate()), 1..=10).prop_flat_map(|vertices| {
        let n = vertices.len();
        let faces = prop::collection::vec(prop::collection::vec(0..n, 3..=6), 0..=8);
        (Just(vertices), faces).prop_map(|(v, f)| PolygonMesh::new(v, f))
    })
}

/// The mesh with coordinates clamped into `f32` range for STL (its
/// writer refuses larger ones), unchanged for the other formats.
fn stl_range(mut mesh: PolygonMesh, f: Format) -> PolygonMesh {
    if matches!(f, Format::Stl | Format::StlAscii) {
        for v in &mut mesh.vertices {
            for c in v {
                *c = c.clamp(-3.0e38, 3.0e38);
            }
        }
    }
    mesh
}

/// Tokens that stress a reader: huge and negative counts and indices,
/// non-finite and overflowing numbers, keywords of every format, structure
/// characters, odd bytes.
const TOKENS: &[&str] = &[
    "999999999",
    "18446744073709551615",
    "18446744073709551616",
    "4294967295",
    "4294967296",
    "2147483648",
    "-2147483649",
    "-1",
    "-999999999",
    "0",
    "1",
    "2",
    "3",
    "nan",
    "NaN",
    "-nan",
    "inf",
    "-inf",
    "infinity",
    "1e400",
    "-1e400",
    "1e-400",
    "1.5e308",
    "1e308",
    "-1.7976931348623157e308",
    "1e-320",
    "0x10",
    "1.",
    ".5",
    "+",
    "-",
    "e",
    "",
    " ",
    "\n",
    "\r\n",
    "\r",
    "\t",
    "#",
    "\\",
    "\\\n",
    "/",
    "//",
    "1//",
    "OFF",
    "COFF",
    "4OFF",
    "OFF BINARY",
    "ply",
    "format ascii 1.0",
    "format binary_big_endian 1.0",
    "element vertex 4294967295",
    "element face 999999999",
    "property list uchar int vertex_indices",
    "property list uint int vertex_indices",
    "property float x",
    "end_header",
    "solid",
    "endsolid",
    "facet normal 0 0 0",
    "outer loop",
    "vertex 0 0 0",
    "vertex nan 0 0",
    "endloop",
    "endfacet",
    "v",
    "v 1 2 3 0",
    "v 1e300 1e300 1e300 1e-300",
    "f",
    "f 1",
    "f 1 2",
    "f 0 1 2",
    "f -1 -2 -999",
    "f 999999999 1 2",
    "o",
    "g x",
    "curv",
    "0\n",
    "1 0\n",
    "2 0 1\n",
    "999999999 0 1 2\n",
    "\u{0}",
    "\u{feff}",
    "\u{a0}",
    "é",
    "\u{ff}",
];

/// Binary words written over a file's bytes: extreme counts and indices,
/// non-finite `f32`/`f64` bit patterns.
fn binary_word() -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        Just(u32::MAX.to_le_bytes().to_vec()),
        Just(u32::MAX.to_be_bytes().to_vec()),
        Just((-1i32).to_le_bytes().to_vec()),
        Just(i32::MIN.to_le_bytes().to_vec()),
        Just(0x7fff_ffffu32.to_le_bytes().to_vec()),
        Just(0u32.to_le_bytes().to_vec()),
        Just(vec![0u8]),
        Just(vec![1u8]),
        Just(vec![2u8]),
        Just(vec![255u8]),
        Just(f32::NAN.to_le_bytes().to_vec()),
        Just(f32::INFINITY.to_le_bytes().to_vec()),
        Just(f64::NAN.to_le_bytes().to_vec()),
        Just(f64::NEG_INFINITY.to_le_bytes().to_vec()),
        Just(f64::NAN.to_be_bytes().to_vec()),
        Just(f64::MAX.to_le_bytes().to_vec()),
        prop::collection::vec(any::<u8>(), 1..9),
    ]
}

/// One mutation of a file.
#[derive(Clone, Debug)]
enum Mutation {
    /// Flip one bit.
    Flip(Index, u8),
    /// Cut the file at a position.
    Truncate(Index),
    /// Insert a token (with spaces around it or not) at a position.
    Insert(Index, &'static str, bool),
    /// Replace the `n`-th whitespace-separated token.
    Replace(Index, &'static str),
    /// Overwrite bytes at a position with a binary word.
    Overwrite(Index, Vec<u8>),
    /// Delete a range of up to 16 bytes.
    Delete(Index, usize),
    /// Repeat a range of up to 64 bytes.
    Repeat(Index, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let token = prop::sample::select(TOKENS);
    prop_oneof![
        1 => (any::<Index>(), 0u8..8).prop_map(|(i, b)| Mutation::Flip(i, b)),
        1 => any::<Index>().prop_map(Mutation::Truncate),
        1 => (any::<Index>(), token.clone(), any::<bool>())
            .prop_map(|(i, t, s)| Mutation::Insert(i, t, s)),
        2 => (any::<Index>(), token).prop_map(|(i, t)| Mutation::Replace(i, t)),
        1 => (any::<Index>(), binary_word()).prop_map(|(i, w)| Mutation::Overwrite(i, w)),
        1 => (any::<Index>(), 1usize..16).prop_map(|(i, n)| Mutation::Delete(i, n)),
        1 => (any::<Index>(), 1usize..64).prop_map(|(i, n)| Mutation::Repeat(i, n)),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let pos = |i: &Index, len: usize| if len == 0 { 0 } else { i.index(len + 1) };
    match m {
        Mutation::Flip(i, b) => {
            if !bytes.is_empty() {
                let p = i.index(bytes.len());
                bytes[p] ^= 1 << b;
            }
        }
        Mutation::Truncate(i) => bytes.truncate(pos(i, bytes.len())),
        Mutation::Insert(i, t, spaced) => {
            let p = pos(i, bytes.len());
            let t = if *spaced {
                format!(" {t} ")
            } else {
                t.to_string()
            };
            bytes.splice(p..p, t.into_bytes());
        }
        Mutation::Replace(i, t) => {
            // Byte ranges of whitespace-separated tokens.
            let mut tokens = Vec::new();
            let mut start = None;
            for (k, b) in bytes.iter().enumerate() {
                match (b.is_ascii_whitespace(), start) {
                    (false, None) => start = Some(k),
                    (true, Some(s)) => {
                        tokens.push(s..k);
                        start = None;
                    }
                    _ => {}
                }
            }
            if let Some(s) = start {
                tokens.push(s..bytes.len());
            }
            if !tokens.is_empty() {
                let r = tokens[i.index(tokens.len())].clone();
                bytes.splice(r, t.bytes());
            }
        }
        Mutation::Overwrite(i, w) => {
            if bytes.len() >= w.len() {
                let p = i.index(bytes.len() - w.len() + 1);
                bytes[p..p + w.len()].copy_from_slice(w);
            }
        }
        Mutation::Delete(i, n) => {
            if !bytes.is_empty() {
                let p = i.index(bytes.len());
                let end = (p + n).min(bytes.len());
                bytes.drain(p..end);
            }
        }
        Mutation::Repeat(i, n) => {
            if !bytes.is_empty() {
                let p = i.index(bytes.len());
                let end = (p + n).min(bytes.len());
                let copy = bytes[p..end].to_vec();
                bytes.splice(end..end, copy);
            }
        }
    }
}

fn format() -> impl Strategy<Value = Format> {
    prop::sample::select(Format::ALL.to_vec())
}

/// The case count: `default`, or `DYMSUM_PROPTEST_CASES` /
/// `PROPTEST_CASES` for longer runs.
fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| dymsum_testkit::proptest_cases(default))
}

/// A plausible start for each format, so random bytes get past the magic.
const PREFIXES: &[(&str, Format)] = &[
    ("OFF\n", Format::Off),
    ("OFF\n3 1 0\n", Format::Off),
    ("COFF 4 2\n", Format::Off),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\n", Format::Obj),
    ("ply\nformat ascii 1.0\n", Format::Ply),
    (
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n",
        Format::Ply,
    ),
    (
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\n\
         property double y\nproperty double z\nelement face 1\n\
         property list uchar int vertex_indices\nend_header\n",
        Format::PlyBinary,
    ),
    (
        "ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty float x\n\
         property float y\nproperty float z\nelement face 1\n\
         property list uint uint vertex_indices\nend_header\n",
        Format::PlyBinary,
    ),
    (
        "solid x\nfacet normal 0 0 1\nouter loop\n",
        Format::StlAscii,
    ),
];

// ---------------------------------------------------------------------------
// Properties

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(128), ..ProptestConfig::default() })]

    /// (a) Random bytes in every format.
    #[test]
    fn random_bytes_never_panic_or_overallocate(
        bytes in prop::collection::vec(any::<u8>(), 0..1024),
    ) {
        for f in Format::ALL {
            check_read(&bytes, f)?;
        }
    }

    /// Random bytes (or random text tokens) behind a plausible header.
    #[test]
    fn random_payload_behind_a_header(
        which in 0..PREFIXES.len(),
        tail in prop_oneof![
            prop::collection::vec(any::<u8>(), 0..512),
            prop::collection::vec(prop::sample::select(TOKENS), 0..64)
                .prop_map(|t| t.join(" ").into_bytes()),
        ],
    ) {
        let (prefix, f) = PREFIXES[which];
        let mut bytes = prefix.as_bytes().to_vec();
        bytes.extend_from_slice(&tail);
        check_read(&bytes, f)?;
    }

    /// A binary STL: an 80-byte header, a count and random triangles (the
    /// count sometimes matching the length, sometimes huge).
    #[test]
    fn random_binary_stl(
        header in prop::collection::vec(any::<u8>(), 80),
        solid in any::<bool>(),
        count in prop_oneof![Just(None), any::<u32>().prop_map(Some)],
        body in prop::collection::vec(any::<u8>(), 0..400),
    ) {
        let mut bytes = header;
        if solid {
            bytes[..6].copy_from_slice(b"solid ");
        }
        let n = count.unwrap_or((body.len() / 50) as u32);
        bytes.extend_from_slice(&n.to_le_bytes());
        bytes.extend_from_slice(&body);
        check_read(&bytes, Format::Stl)?;
    }

    /// (b) Files written by the crate's writers from random meshes, read
    /// back whole (the same faces) and then mutated.
    #[test]
    fn written_then_mutated_files(
        mesh in small_mesh(),
        f in format(),
        mutations in prop::collection::vec(mutation(), 1..4),
    ) {
        let bytes = write_mesh_bytes(&stl_range(mesh.clone(), f), f)
            .expect("the generator makes writable meshes");
        let mesh = stl_range(mesh, f);
        // Unmutated, the file reads back with the same faces (STL
        // triangulates and merges, so only the triangle count).
        let back = read_mesh_bytes(&bytes, f, "fuzz");
        match f {
            Format::Stl | Format::StlAscii if mesh.faces.is_empty() => {
                prop_assert!(back.is_err());
            }
            Format::Stl | Format::StlAscii => {
                prop_assert_eq!(back.unwrap().faces.len(), mesh.triangle_count());
            }
            _ => prop_assert_eq!(&back.unwrap().faces, &mesh.faces),
        }
        let mut bytes = bytes;
        for m in &mutations {
            apply(&mut bytes, m);
            check_read(&bytes, f)?;
        }
    }
}

proptest! {
    // Each case writes a file: fewer cases.
    #![proptest_config(ProptestConfig { cases: cases(48), ..ProptestConfig::default() })]

    /// `load_polytope` on mutated files of every extension: `Ok` or a
    /// typed error (never "not found" for a file that exists).
    #[test]
    fn load_polytope_on_mutated_files(
        mesh in small_mesh(),
        f in format(),
        mutations in prop::collection::vec(mutation(), 0..3),
    ) {
        let mut bytes = write_mesh_bytes(&stl_range(mesh, f), f).expect("writable mesh");
        for m in &mutations {
            apply(&mut bytes, m);
        }
        let dir = dymsum_testkit::files::temp_dir("io-fuzz", "load");
        let path = dir.join(format!("m.{}", f.extension()));
        std::fs::write(&path, &bytes).unwrap();
        let spec = path.to_str().unwrap().to_string();
        let (loaded, largest) =
            largest_allocation(|| load_polytope(&spec, MeshPolicy::default()).map(|_| ()));
        dymsum_testkit::files::remove_dir(&dir);
        prop_assert!(largest <= alloc_limit(bytes.len()) + (1 << 20));
        if let Err(e) = loaded {
            check_load_error(&e)?;
            prop_assert!(e.origin().contains("m."), "{}", e.origin());
        }
    }
}

// ---------------------------------------------------------------------------
// Exhaustive truncation and named regressions

/// A small closed mesh with awkward coordinates and a quad face, in every
/// format.
fn sample_files() -> Vec<(Format, Vec<u8>)> {
    let mesh = PolygonMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.5, -0.0, 1e-300],
            [0.0, 2.0, 5e-324],
            [0.25, 0.25, -3.0],
            [1e30, -1e30, 7.0],
        ],
        vec![
            vec![0, 2, 1],
            vec![0, 1, 3],
            vec![1, 2, 3],
            vec![2, 0, 3],
            vec![0, 1, 4, 2],
        ],
    );
    Format::ALL
        .into_iter()
        .map(|f| (f, write_mesh_bytes(&mesh, f).unwrap()))
        .collect()
}

/// Truncation at every byte (inside a keyword, a count, a number, a
/// binary word, a line ending) of a file of each format.
#[test]
fn truncation_at_every_position_is_an_error_or_a_valid_mesh() {
    for (f, bytes) in sample_files() {
        for cut in 0..bytes.len() {
            check_read(&bytes[..cut], f).unwrap_or_else(|e| panic!("{f} cut at {cut}: {e}"));
        }
    }
}

/// Faces with 0, 1 or 2 vertices are `DegenerateFace` errors in every
/// format that stores polygons.
#[test]
fn faces_of_fewer_than_three_vertices_are_degenerate_face_errors() {
    let verts = "0 0 0\n1 0 0\n0 1 0\n";
    for (k, list) in [(0, ""), (1, " 0"), (2, " 0 1")] {
        let off = format!("OFF\n3 1 0\n{verts}{k}{list}\n");
        let obj_list: String = list
            .split_whitespace()
            .map(|i| format!(" {}", i.parse::<usize>().unwrap() + 1))
            .collect();
        let obj = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf{obj_list}\n");
        let ply = format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
             property double z\nelement face 1\nproperty list uchar int vertex_indices\n\
             end_header\n{verts}{k}{list}\n"
        );
        let mut ply_bin = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n\
property double x\nproperty double y\nproperty double z\nelement face 1\n\
property list uchar int vertex_indices\nend_header\n"
            .to_vec();
        for v in [[0.0f64, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            for c in v {
                ply_bin.extend_from_slice(&c.to_le_bytes());
            }
        }
        ply_bin.push(k as u8);
        for i in 0..k {
            ply_bin.extend_from_slice(&(i as i32).to_le_bytes());
        }
        for (f, bytes) in [
            (Format::Off, off.into_bytes()),
            (Format::Obj, obj.into_bytes()),
            (Format::Ply, ply.into_bytes()),
            (Format::PlyBinary, ply_bin),
        ] {
            let err = read_mesh_bytes(&bytes, f, "fuzz").unwrap_err();
            assert!(
                matches!(err, FormatError::DegenerateFace { len, .. } if len == k),
                "{f}, {k} vertices: {err}"
            );
        }
    }
}

/// Asserts that reading `bytes` as `format` fails and allocates at most
/// 16 MiB at once, whatever count its header claims.
fn assert_refused_without_preallocating(bytes: &[u8], format: Format) {
    let (r, largest) = largest_allocation(|| read_mesh_bytes(bytes, format, "fuzz").map(|_| ()));
    assert!(r.is_err(), "{format}: {:?}", String::from_utf8_lossy(bytes));
    assert!(
        largest <= 16 << 20,
        "{format}: one allocation of {largest} bytes for a {}-byte file",
        bytes.len()
    );
}

#[test]
fn regression_off_huge_vertex_count_does_not_preallocate() {
    for text in [
        "OFF\n999999999 1 0\n",
        "OFF\n999999999 1 0\n0 0 0\n",
        "OFF 18446744073709551615 1\n0 0 0\n",
        "OFF\n3 999999999\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        "OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n999999999 0 1 2\n",
        "OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n18446744073709551615 0 1 2\n",
    ] {
        assert_refused_without_preallocating(text.as_bytes(), Format::Off);
    }
}

#[test]
fn regression_ply_huge_element_and_list_counts_do_not_preallocate() {
    let vertex = "property double x\nproperty double y\nproperty double z\n";
    for (encoding, payload) in [
        ("ascii", "0 0 0\n"),
        ("binary_little_endian", "\0\0\0\0"),
        ("binary_big_endian", ""),
    ] {
        let text = format!(
            "ply\nformat {encoding} 1.0\nelement vertex 4000000000\n{vertex}end_header\n{payload}"
        );
        assert_refused_without_preallocating(text.as_bytes(), Format::Ply);
        let text = format!(
            "ply\nformat {encoding} 1.0\nelement vertex 1\n{vertex}element face 18446744073709551615\n\
             property list uchar int vertex_indices\nend_header\n{payload}"
        );
        assert_refused_without_preallocating(text.as_bytes(), Format::Ply);
    }
    // A list whose count claims 4 billion entries, ASCII and binary.
    let head = |enc: &str| {
        format!(
            "ply\nformat {enc} 1.0\nelement vertex 3\n{vertex}element face 1\n\
             property list uint int vertex_indices\nend_header\n"
        )
    };
    let ascii = format!("{}0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n", head("ascii"));
    assert_refused_without_preallocating(ascii.as_bytes(), Format::Ply);
    let mut binary = head("binary_little_endian").into_bytes();
    binary.extend_from_slice(&[0u8; 72]);
    binary.extend_from_slice(&4_000_000_000u32.to_le_bytes());
    binary.extend_from_slice(&[0u8; 12]);
    assert_refused_without_preallocating(&binary, Format::PlyBinary);
}

#[test]
fn regression_stl_huge_triangle_count_does_not_preallocate() {
    for count in [u32::MAX, 1 << 31, 999_999_999, 2] {
        let mut bytes = vec![0u8; 80];
        bytes.extend_from_slice(&count.to_le_bytes());
        bytes.extend_from_slice(&[0u8; 50]);
        assert_refused_without_preallocating(&bytes, Format::Stl);
        bytes[..6].copy_from_slice(b"solid ");
        assert_refused_without_preallocating(&bytes, Format::Stl);
    }
}

#[test]
fn regression_obj_huge_and_negative_indices_are_bad_index_errors() {
    for face in [
        "f 999999999 1 2",
        "f 1 2 9223372036854775807",
        "f 1 2 -4",
        "f -9223372036854775808 1 2",
        "f 0 1 2",
    ] {
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{face}\n");
        let err = read_mesh_bytes(text.as_bytes(), Format::Obj, "fuzz").unwrap_err();
        assert!(matches!(err, FormatError::BadIndex { .. }), "{face}: {err}");
        assert_refused_without_preallocating(text.as_bytes(), Format::Obj);
    }
}

#[test]
fn regression_non_finite_and_overflowing_coordinates_are_non_finite_errors() {
    for c in ["nan", "NaN", "inf", "-inf", "1e400", "-1e400"] {
        let off = format!("OFF\n3 1\n0 0 {c}\n1 0 0\n0 1 0\n3 0 1 2\n");
        let obj = format!("v 0 0 {c}\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        let stl = format!(
            "solid\nfacet normal 0 0 0\nouter loop\nvertex 0 0 {c}\nvertex 1 0 0\n\
             vertex 0 1 0\nendloop\nendfacet\nendsolid\n"
        );
        for (f, text) in [
            (Format::Off, off),
            (Format::Obj, obj),
            (Format::StlAscii, stl),
        ] {
            let err = read_mesh_bytes(text.as_bytes(), f, "fuzz").unwrap_err();
            assert!(
                matches!(err, FormatError::NonFinite { .. }),
                "{f} {c}: {err}"
            );
        }
    }
    // Binary PLY and STL: NaN and infinity bit patterns.
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let mesh = PolygonMesh::new(
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![vec![0, 1, 2]],
        );
        let mut stl = write_mesh_bytes(&mesh, Format::Stl).unwrap();
        stl[84 + 12..84 + 16].copy_from_slice(&bad.to_le_bytes());
        let err = read_mesh_bytes(&stl, Format::Stl, "fuzz").unwrap_err();
        assert!(matches!(err, FormatError::NonFinite { .. }), "{err}");
        let mut ply = write_mesh_bytes(&mesh, Format::PlyBinary).unwrap();
        let data = ply.len() - (1 + 12) - 72;
        ply[data..data + 8].copy_from_slice(&f64::from(bad).to_le_bytes());
        let err = read_mesh_bytes(&ply, Format::PlyBinary, "fuzz").unwrap_err();
        assert!(matches!(err, FormatError::NonFinite { .. }), "{err}");
    }
}

/// The files above, read through `load_polytope` from disk with every
/// extension: a typed error naming the file.
#[test]
fn load_polytope_on_truncated_files_gives_typed_errors() {
    let dir = dymsum_testkit::files::temp_dir("io-fuzz", "truncated");
    for (f, bytes) in sample_files() {
        for cut in [0, 1, bytes.len() / 3, bytes.len() / 2, bytes.len() - 1] {
            let path = dir.join(format!("cut{cut}.{}", f.extension()));
            std::fs::write(&path, &bytes[..cut]).unwrap();
            match load_polytope(path.to_str().unwrap(), MeshPolicy::default()) {
                Ok(_) => {}
                Err(e) => {
                    check_load_error(&e).unwrap();
                    assert!(
                        e.origin().contains(Path::new(&path).to_str().unwrap()),
                        "{f} cut {cut}: {}",
                        e.origin()
                    );
                }
            }
        }
    }
    dymsum_testkit::files::remove_dir(&dir);
}

/// The measurement itself: a reservation from a claimed count is seen (so
/// the limits above are not vacuous).
#[test]
fn measuring_allocator_sees_a_large_reservation() {
    let (v, largest) = largest_allocation(|| Vec::<u64>::with_capacity(1 << 24));
    assert!(largest >= 8 << 24, "{largest}");
    drop(v);
    let (_, small) = largest_allocation(|| vec![0u8; 10]);
    assert!(small < 1024, "{small}");
}
