//! Issue 8 §5: nothing lost on a failed write, non-regular files refused,
//! OBJ bodies, stricter STL/PLY errors, model parameter limits.

use std::io::{self, Write};
use std::path::{Path, PathBuf};

use dymsum::polytope::MeshPolicy;
use dymsum::Rotation;
use dymsum_io::atomic::{read_regular_file, write_atomic, AtomicFile, FileError};
use dymsum_io::formats::{
    read_mesh, read_mesh_bytes, read_obj_objects_bytes, write_mesh, write_mesh_bytes, Format,
    FormatError,
};
use dymsum_io::{load_polytope, LoadError};
use dymsum_testkit::cube_mesh as cube;
use dymsum_testkit::files::names;

fn temp_dir(name: &str) -> PathBuf {
    dymsum_testkit::files::temp_dir("io-safety", name)
}

/// A writer that accepts `limit` bytes, then fails like a full disk.
struct FailAfter<'a> {
    inner: &'a mut dyn Write,
    left: usize,
}

impl Write for FailAfter<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.left == 0 {
            return Err(io::Error::new(
                io::ErrorKind::StorageFull,
                "no space left on device (injected)",
            ));
        }
        let n = buf.len().min(self.left);
        self.left -= n;
        self.inner.write(&buf[..n])
    }
    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

#[test]
fn injected_write_failure_keeps_the_earlier_file_and_leaves_no_temp() {
    let dir = temp_dir("inject");
    let path = dir.join("sum.off");
    write_mesh(&path, &cube()).unwrap();
    let good = std::fs::read(&path).unwrap();
    let big = write_mesh_bytes(&dymsum_io::models::model("gs2").unwrap(), Format::Off).unwrap();
    let mut tried = 0;
    for limit in (0..big.len()).step_by(97).chain([big.len() - 1]) {
        let err = write_atomic(&path, |w| {
            let mut f = FailAfter {
                inner: w,
                left: limit,
            };
            f.write_all(&big)
        })
        .unwrap_err();
        assert!(matches!(err, FileError::Write { .. }), "{err:?}");
        assert!(err.to_string().contains("sum.off"), "{err}");
        assert!(err.to_string().contains("no space left"), "{err}");
        assert_eq!(err.path(), path);
        assert_eq!(std::fs::read(&path).unwrap(), good, "limit {limit}");
        assert_eq!(names(&dir), ["sum.off"], "limit {limit}");
        tried += 1;
    }
    assert!(tried > 10);
    // Without the fault, the new content replaces the old one whole.
    write_atomic(&path, |w| w.write_all(&big)).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), big);
    assert_eq!(names(&dir), ["sum.off"]);
}

#[test]
fn atomic_file_dropped_without_commit_leaves_target_alone() {
    let dir = temp_dir("drop");
    let path = dir.join("run.csv");
    std::fs::write(&path, "old\n").unwrap();
    {
        let mut f = AtomicFile::create(&path).unwrap();
        writeln!(f, "new, partial").unwrap();
        assert_eq!(names(&dir).len(), 2); // the temporary file exists meanwhile
        assert!(names(&dir).iter().any(|n| n.starts_with(".run.tmp-")));
    }
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old\n");
    assert_eq!(names(&dir), ["run.csv"]);
    let mut f = AtomicFile::create(&path).unwrap();
    writeln!(f, "new").unwrap();
    f.commit().unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new\n");
    assert_eq!(names(&dir), ["run.csv"]);
}

#[test]
fn write_errors_name_the_file_once() {
    let dir = temp_dir("missing");
    let path = dir.join("no_such_dir").join("x.off");
    let err = write_mesh(&path, &cube()).unwrap_err();
    assert!(matches!(err, FormatError::Io { .. }), "{err:?}");
    let text = err.to_string();
    assert!(text.starts_with(&path.display().to_string()), "{text}");
    assert_eq!(text.matches("No such file").count(), 1, "{text}");
    // A directory as the target.
    let err = write_mesh(&dir.join("sub.off"), &cube());
    assert!(err.is_ok());
    std::fs::create_dir(dir.join("d.off")).unwrap();
    let err = write_mesh(&dir.join("d.off"), &cube()).unwrap_err();
    assert!(err.to_string().contains("d.off"), "{err}");
    assert!(dir.join("d.off").is_dir());
    assert_eq!(names(&dir), ["d.off", "sub.off"]);
}

#[test]
fn fifo_and_device_are_refused_without_blocking() {
    let dir = temp_dir("fifo");
    let fifo = dir.join("pipe.off");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    // Nobody writes to the FIFO: opening it for reading would block forever.
    let err = read_mesh(&fifo).unwrap_err();
    assert!(matches!(err, FormatError::NotRegularFile { .. }), "{err:?}");
    assert!(err.to_string().contains("pipe.off"), "{err}");
    let err = load_polytope(fifo.to_str().unwrap(), MeshPolicy::default()).unwrap_err();
    assert!(err.to_string().contains("not a regular file"), "{err}");

    // /dev/zero never ends: refused, not read until memory runs out.
    let zero = dir.join("x.stl");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let err = read_mesh(&zero).unwrap_err();
    assert!(matches!(err, FormatError::NotRegularFile { .. }), "{err:?}");
    let err = read_regular_file(Path::new("/dev/null")).unwrap_err();
    assert!(matches!(err, FileError::NotRegular { .. }), "{err:?}");
    let err = read_regular_file(&dir).unwrap_err();
    assert!(err.to_string().contains("directory"), "{err}");
    // A symbolic link to a regular file is read.
    let real = dir.join("real.off");
    write_mesh(&real, &cube()).unwrap();
    let link = dir.join("link.off");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    assert_eq!(read_mesh(&link).unwrap(), cube());
}

use dymsum_testkit::cube_obj;

#[test]
fn obj_groups_of_one_closed_mesh_are_one_body() {
    let text = cube_obj(0.0, 0, true);
    let bodies = read_obj_objects_bytes(text.as_bytes(), "groups.obj").unwrap();
    assert_eq!(bodies.len(), 1);
    assert_eq!(bodies[0].0, "side0");
    assert_eq!(bodies[0].1.faces.len(), 6);
    assert_eq!(bodies[0].1.vertices.len(), 8);
    // Loads as one convex body, like the same mesh without groups.
    let dir = temp_dir("groups");
    let path = dir.join("groups.obj");
    std::fs::write(&path, &text).unwrap();
    let l = load_polytope(path.to_str().unwrap(), MeshPolicy::strict()).unwrap();
    assert_eq!(l.polytope.face_count(), 6);
    assert_eq!(l.polytope.vertex_count(), 8);
}

#[test]
fn obj_object_with_vertices_only_is_a_point_cloud_body() {
    let mut text = "o box\n".to_string() + &cube_obj(0.0, 0, false);
    text += "o pts\nv 10 10 10\nv 11 10 10\nv 10 11 10\nv 10 10 11\n";
    let bodies = read_obj_objects_bytes(text.as_bytes(), "two.obj").unwrap();
    let got: Vec<(&str, usize, usize)> = bodies
        .iter()
        .map(|(n, m)| (n.as_str(), m.vertices.len(), m.faces.len()))
        .collect();
    assert_eq!(got, [("box", 8, 6), ("pts", 4, 0)]);
    assert_eq!(bodies[1].1.vertices[3], [10.0, 10.0, 11.0]);
    // One body asked for: refused with the bodies named, not half-read.
    let dir = temp_dir("two");
    let path = dir.join("two.obj");
    std::fs::write(&path, &text).unwrap();
    let err = load_polytope(path.to_str().unwrap(), MeshPolicy::default()).unwrap_err();
    assert!(matches!(err, LoadError::SeveralBodies { .. }), "{err:?}");
    assert!(err.to_string().contains("`box`, `pts`"), "{err}");
    // Two separate closed meshes (no shared vertices) stay two bodies.
    let two = "o a\n".to_string() + &cube_obj(0.0, 0, false) + "o b\n" + &cube_obj(5.0, 8, false);
    let bodies = read_obj_objects_bytes(two.as_bytes(), "ab.obj").unwrap();
    let got: Vec<(&str, usize, usize)> = bodies
        .iter()
        .map(|(n, m)| (n.as_str(), m.vertices.len(), m.faces.len()))
        .collect();
    assert_eq!(got, [("a", 8, 6), ("b", 8, 6)]);
}

#[test]
fn binary_stl_with_bytes_beyond_its_count_is_an_error() {
    let bytes = write_mesh_bytes(&cube(), Format::Stl).unwrap();
    assert_eq!(bytes.len(), 84 + 50 * 12);
    assert!(read_mesh_bytes(&bytes, Format::Stl, "c.stl").is_ok());
    for extra in [1usize, 49, 50, 500] {
        let mut longer = bytes.clone();
        longer.extend(std::iter::repeat_n(0u8, extra));
        let err = read_mesh_bytes(&longer, Format::Stl, "c.stl").unwrap_err();
        let text = err.to_string();
        assert!(text.contains("declares 12 triangles"), "{text}");
        assert!(text.contains(&format!("({extra} more)")), "{text}");
    }
    // A count larger than the data: the existing count mismatch.
    let mut lying = bytes.clone();
    lying[80..84].copy_from_slice(&13u32.to_le_bytes());
    let err = read_mesh_bytes(&lying, Format::Stl, "c.stl").unwrap_err();
    assert!(matches!(err, FormatError::CountMismatch { .. }), "{err:?}");
}

#[test]
fn ply_errors_are_in_our_words_with_line_or_element() {
    let header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                  property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let cases: [(String, &str, &str); 5] = [
        (
            format!("{header}0 0 0\n1 0 nan\n0 1 0\n0 0 1\n3 0 1 2\n"),
            "line 11",
            "cannot read `1 0 nan` as the values of a `vertex` element",
        ),
        (
            format!("{header}0 0 0\n1 0 0\n0 1 0\n"),
            "line",
            "the file ends after 3 of the 4 `vertex` elements the header declares",
        ),
        (
            format!("{header}0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1\n"),
            "line 14",
            "the list count says 3 entries, but only 2 follow",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty floot x\nend_header\n".to_string(),
            "line 4",
            "cannot understand the header line `property floot x`",
        ),
        ("plx\n".to_string(), "line 1", "not a PLY file"),
    ];
    for (text, at, want) in &cases {
        let err = read_mesh_bytes(text.as_bytes(), Format::Ply, "t.ply").unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains(want), "{msg}");
        assert!(msg.contains(at), "{msg}");
        for internal in ["ParseError", "Couldn't", "String:", "\n"] {
            assert!(!msg.contains(internal), "{msg}");
        }
    }
    // Binary: the element is named.
    let bytes = write_mesh_bytes(&cube(), Format::PlyBinary).unwrap();
    let err = read_mesh_bytes(&bytes[..bytes.len() - 3], Format::Ply, "t.ply").unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("face #5"), "{msg}");
    assert!(msg.contains("`face` elements the header declares"), "{msg}");
}

#[test]
fn every_model_parameter_beyond_its_limit_is_refused_with_the_limit() {
    use dymsum_io::models::{model, ModelError};
    let cases = [
        ("sphere:33", "from 1 to 32"),
        ("sphere:300", "from 1 to 32"),
        ("ellipsoid:1,2,3:33", "from 1 to 32"),
        ("cylinder:10001", "from 3 to 10000"),
        ("cylinder:1000000", "from 3 to 10000"),
        ("cone:10001", "from 3 to 10000"),
        ("capsule:1000:1000", "at most 5000"),
        ("capsule:8:1001", "from 1 to 1000"),
        ("capsule:100:51", "at most 5000"),
        ("capsule:10001:1", "from 3 to 10000"),
        ("random:1000001", "from 4 to 1000000"),
        ("box:1e151", "from 1e-150 to 1e150"),
        ("box:1e-151", "from 1e-150 to 1e150"),
        ("box:1,1,1e300", "got 1e300"),
        ("box:1,1,-1", "from 1e-150 to 1e150"),
        ("cylinder:8:1e200,1", "got 1e200"),
        ("capsule:8:2:1,1e-200", "0 or from 1e-150"),
    ];
    for (spec, want) in cases {
        let err = model(spec).unwrap_err();
        assert!(
            matches!(err, ModelError::BadParameter { .. }),
            "{spec}: {err:?}"
        );
        let text = err.to_string();
        assert!(text.contains(want), "{spec}: {text}");
        assert!(
            text.len() < 200,
            "{spec}: a number with hundreds of digits? {text}"
        );
    }
    // The limits themselves are accepted (the largest ones load in seconds;
    // loading is tested for the cheap ones only).
    for spec in [
        "sphere:32",
        "cylinder:10000",
        "capsule:100:50",
        "box:1e150",
        "box:1e-150",
        "random:1000000",
    ] {
        assert!(model(spec).is_ok(), "{spec}");
    }
    // (box:1e-150 and box:1e150 are refused as flat until the predicates
    // handle extreme scales: the kernel part of issue 8 §3.)
    for spec in ["sphere:8", "cylinder:1000", "capsule:50:20"] {
        assert!(load_polytope(spec, MeshPolicy::default()).is_ok(), "{spec}");
    }
    // "non-finite" only for non-finite values.
    let err = model("box:abc").unwrap_err().to_string();
    assert!(
        err.contains("must be a number") && !err.contains("finite"),
        "{err}"
    );
    let err = model("box:inf").unwrap_err().to_string();
    assert!(err.contains("must be finite"), "{err}");
}

#[test]
fn quaternions_that_overflow_or_underflow_when_squared_are_normalised() {
    let unit = Rotation::from_wxyz(1.0, 0.0, 0.0, 1.0).unwrap();
    for s in [1e200, 1e300, f64::MAX, 1e-200, 1e-300, 5e-324] {
        let r = Rotation::from_wxyz(s, 0.0, 0.0, s).unwrap_or_else(|| panic!("scale {s:e}"));
        let (a, b) = (r.wxyz(), unit.wxyz());
        for k in 0..4 {
            assert!(
                (a[k] - b[k]).abs() <= 2.0 * f64::EPSILON,
                "scale {s:e}: {a:?}"
            );
        }
    }
    // Powers of two are exact: bit-identical.
    for k in [-1074, -1000, -600, 600, 1000, 1023] {
        let s = 2f64.powi(k);
        let r = Rotation::from_wxyz(s, 0.0, 0.0, s).unwrap_or_else(|| panic!("2^{k}"));
        assert_eq!(r.wxyz(), unit.wxyz(), "2^{k}");
    }
    let r = Rotation::from_wxyz(1e200, 2e200, 0.0, -2e200).unwrap();
    let w = r.wxyz();
    assert!(
        (w[0] - 1.0 / 3.0).abs() < 1e-15 && (w[3] + 2.0 / 3.0).abs() < 1e-15,
        "{w:?}"
    );
    // Powers of two: scaling is exact, so a scaled quaternion is the same rotation bit for bit.
    let q = Rotation::from_wxyz(0.9, 0.2, 0.3, 0.1).unwrap();
    let q2 = Rotation::from_wxyz(
        0.9 * 2f64.powi(900),
        0.2 * 2f64.powi(900),
        0.3 * 2f64.powi(900),
        0.1 * 2f64.powi(900),
    )
    .unwrap();
    assert_eq!(q.wxyz(), q2.wxyz());
    assert!(Rotation::from_wxyz(0.0, 0.0, 0.0, 0.0).is_none());
    assert!(Rotation::from_wxyz(f64::INFINITY, 0.0, 0.0, 0.0).is_none());
    assert!(Rotation::from_wxyz(f64::NAN, 0.0, 0.0, 1.0).is_none());
}
