//! The invariants every target checks (as in
//! crates/dymsum-io/tests/fuzz_readers.rs): a reader returns `Ok` with
//! finite coordinates and faces of at least 3 in-range indices, or a
//! typed content error; it never panics.

use dymsum::PolygonMesh;
use dymsum_io::formats::{read_mesh_bytes, Format, FormatError};

pub fn check(bytes: &[u8], format: Format) {
    match read_mesh_bytes(bytes, format, "fuzz") {
        Ok(mesh) => check_mesh(&mesh),
        Err(e) => {
            let _ = e.to_string();
            assert!(
                !matches!(
                    e,
                    FormatError::Io { .. }
                        | FormatError::NotRegularFile { .. }
                        | FormatError::UnknownExtension { .. }
                        | FormatError::InvalidMesh { .. }
                ),
                "{e:?}"
            );
        }
    }
}

pub fn check_mesh(mesh: &PolygonMesh) {
    let n = mesh.vertices.len();
    assert!(mesh.vertices.iter().flatten().all(|c| c.is_finite()));
    for f in &mesh.faces {
        assert!(f.len() >= 3 && f.iter().all(|&i| i < n), "{f:?} of {n}");
    }
}
