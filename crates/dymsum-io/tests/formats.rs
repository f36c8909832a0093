//! Round trips and error cases for the mesh file formats.
//!
//! Everything sits in `mod formats` so that `cargo test -p dymsum-io formats`
//! selects all of these tests.

// The awkward coordinate 123456789.123456789 is meant to have more digits
// than an f64 holds.
#[allow(clippy::excessive_precision)]
mod formats {

    use std::path::{Path, PathBuf};

    use dymsum::PolygonMesh;
    use dymsum_io::formats::{
        read_mesh, read_mesh_bytes, read_obj_objects, read_obj_objects_bytes, write_mesh,
        write_mesh_bytes, write_mesh_with, Format, FormatError, Location,
    };

    /// A tetrahedron with awkward coordinates, plus a pentagon face on extra
    /// vertices (faces need not be closed for the format layer).
    fn awkward() -> PolygonMesh {
        let vertices = vec![
            [0.1, 1e-300, -0.0],
            [123456789.123456789, 1e16 + 1.0, 0.0],
            [-0.0, 0.2 + 0.1, 1e300],
            [f64::MIN_POSITIVE, -f64::MAX, 5e-324],
            [1.0 / 3.0, -2.0 / 3.0, std::f64::consts::PI],
            [f64::EPSILON, 1e-7, -123.456e-89],
        ];
        let faces = vec![
            vec![0, 1, 2],
            vec![0, 3, 1],
            vec![1, 3, 2],
            vec![2, 3, 0],
            vec![0, 1, 2, 4, 5],
        ];
        PolygonMesh::new(vertices, faces)
    }

    fn assert_bit_exact(a: &PolygonMesh, b: &PolygonMesh) {
        assert_eq!(a.faces, b.faces);
        assert_eq!(a.vertices.len(), b.vertices.len());
        for (i, (u, v)) in a.vertices.iter().zip(&b.vertices).enumerate() {
            for k in 0..3 {
                assert_eq!(
                    u[k].to_bits(),
                    v[k].to_bits(),
                    "vertex {i} coordinate {k}: {} vs {}",
                    u[k],
                    v[k]
                );
            }
        }
    }

    fn round_trip(mesh: &PolygonMesh, format: Format) -> PolygonMesh {
        let bytes = write_mesh_bytes(mesh, format).unwrap();
        read_mesh_bytes(&bytes, format, "mem").unwrap()
    }

    fn tmp_dir() -> PathBuf {
        dymsum_testkit::files::temp_dir("io-formats", "files")
    }

    use dymsum_testkit::cube_mesh as cube;

    fn off(text: &str) -> Result<PolygonMesh, FormatError> {
        read_mesh_bytes(text.as_bytes(), Format::Off, "t.off")
    }

    fn obj(text: &str) -> Result<PolygonMesh, FormatError> {
        read_mesh_bytes(text.as_bytes(), Format::Obj, "t.obj")
    }

    fn ply(bytes: &[u8]) -> Result<PolygonMesh, FormatError> {
        read_mesh_bytes(bytes, Format::Ply, "t.ply")
    }

    fn stl(bytes: &[u8]) -> Result<PolygonMesh, FormatError> {
        read_mesh_bytes(bytes, Format::Stl, "t.stl")
    }

    // ---------------------------------------------------------------- round trips

    #[test]
    fn lossless_formats_round_trip_cube_bit_exact() {
        for format in [Format::Off, Format::Obj, Format::Ply, Format::PlyBinary] {
            assert_bit_exact(&round_trip(&cube(), format), &cube());
        }
    }

    #[test]
    fn lossless_formats_round_trip_awkward_coordinates_bit_exact() {
        for format in [Format::Off, Format::Obj, Format::Ply, Format::PlyBinary] {
            let back = round_trip(&awkward(), format);
            assert_bit_exact(&back, &awkward());
            // -0.0 survives as -0.0.
            assert!(back.vertices[0][2].is_sign_negative(), "{format}");
            assert!(back.vertices[2][0].is_sign_negative(), "{format}");
        }
    }

    #[test]
    fn round_trip_through_files_by_extension() {
        let dir = tmp_dir();
        for ext in ["off", "OBJ", "ply", "Ply"] {
            let path = dir.join(format!("awkward.{ext}"));
            write_mesh(&path, &awkward()).unwrap();
            assert_bit_exact(&read_mesh(&path).unwrap(), &awkward());
        }
        let path = dir.join("bin.ply");
        write_mesh_with(&path, &awkward(), Format::PlyBinary).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(bytes.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
        assert_bit_exact(&read_mesh(&path).unwrap(), &awkward());
        // .ply written by extension is ASCII.
        let path = dir.join("ascii.ply");
        write_mesh(&path, &cube()).unwrap();
        assert!(std::fs::read(&path)
            .unwrap()
            .starts_with(b"ply\nformat ascii 1.0\n"));
    }

    #[test]
    fn stl_round_trip_cube_triangulated() {
        for format in [Format::Stl, Format::StlAscii] {
            let back = round_trip(&cube(), format);
            assert_eq!(
                back.vertices.len(),
                8,
                "{format}: merged into shared vertices"
            );
            assert_eq!(back.faces.len(), 12);
            assert!(back.faces.iter().all(|f| f.len() == 3));
            assert_eq!(back.edge_count(), 18, "closed triangulated cube");
            assert!((back.signed_volume() - 1.0).abs() < 1e-12);
            for v in &back.vertices {
                assert!(cube().vertices.contains(v));
            }
        }
        let dir = tmp_dir();
        let path = dir.join("cube.STL");
        write_mesh(&path, &cube()).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(bytes.len(), 84 + 50 * 12, "binary STL by default");
        assert_eq!(read_mesh(&path).unwrap().faces.len(), 12);
    }

    #[test]
    fn stl_round_trip_is_exact_up_to_f32() {
        // Vertices distinct in f32; 1e300 would overflow f32 so it is left out.
        let mesh = PolygonMesh::new(
            vec![
                [0.1, 1e-300, -0.0],
                [123456789.123456789, 1e16 + 1.0, 0.0],
                [-0.0, 0.3, 1e30],
                [1.0 / 3.0, -2.0 / 3.0, std::f64::consts::PI],
            ],
            vec![vec![0, 1, 2], vec![0, 3, 1], vec![1, 3, 2], vec![2, 3, 0]],
        );
        for format in [Format::Stl, Format::StlAscii] {
            let back = round_trip(&mesh, format);
            assert_eq!(back.faces, mesh.faces, "{format}");
            for (u, v) in mesh.vertices.iter().zip(&back.vertices) {
                for k in 0..3 {
                    assert_eq!((u[k] as f32).to_bits(), (v[k] as f32).to_bits(), "{format}");
                    assert_eq!(v[k], f64::from(u[k] as f32));
                }
            }
        }
    }

    #[test]
    fn stl_write_rejects_coordinates_beyond_f32() {
        let err = write_mesh_bytes(&awkward(), Format::Stl).unwrap_err();
        assert!(matches!(err, FormatError::InvalidMesh { .. }), "{err}");
    }

    #[test]
    fn stl_merges_minus_zero_with_zero() {
        let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n\
                facet normal 0 0 1\nouter loop\nvertex -0 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid t\n";
        let m = stl(text.as_bytes()).unwrap();
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.faces, vec![vec![0, 1, 2], vec![0, 2, 3]]);
    }

    #[test]
    fn binary_stl_whose_header_starts_with_solid() {
        let mut bytes = write_mesh_bytes(&cube(), Format::Stl).unwrap();
        bytes[..12].copy_from_slice(b"solid cube\n ");
        let m = stl(&bytes).unwrap();
        assert_eq!(m.faces.len(), 12);
        assert_eq!(m.vertices.len(), 8);
    }

    // ------------------------------------------------------------------ OFF input

    #[test]
    fn off_variants_are_read() {
        let text = "# a comment\n\nOFF 4 2 5 # counts on the header line\n\
                0 0 0\n1 0 0\n0 1 0\n  0 0 1  \n\
                3 0 2 1 255 0 0\n# between faces\n4 0 1 2 3\n";
        let m = off(text).unwrap();
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.faces, vec![vec![0, 2, 1], vec![0, 1, 2, 3]]);
        // Header on its own line, counts without edge count, CRLF line endings.
        let m = off("OFF\r\n3 1\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n").unwrap();
        assert_eq!(m.faces, vec![vec![0, 1, 2]]);
        // No header keyword at all.
        let m = off("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(m.vertices[1], [1.0, 0.0, 0.0]);
        // COFF: colour values after each vertex are ignored.
        let m = off("COFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 1 0 0 1\n0 1 0 1 0 0 1\n3 0 1 2\n").unwrap();
        assert_eq!(m.vertices[2], [0.0, 1.0, 0.0]);
    }

    #[test]
    fn the_bundled_fogel_cube_reads() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/fogel/cube.off");
        let m = read_mesh(&path).unwrap();
        assert_eq!(m.vertices.len(), 8);
        assert_eq!(m.faces.len(), 6);
        assert!(m.faces.iter().all(|f| f.len() == 4));
    }

    #[test]
    fn every_bundled_model_reads_and_round_trips() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/fogel");
        let mut n = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().and_then(|e| e.to_str()) != Some("off") {
                continue;
            }
            let m = read_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(!m.faces.is_empty(), "{}", path.display());
            for format in [Format::Off, Format::Obj, Format::Ply, Format::PlyBinary] {
                assert_bit_exact(&round_trip(&m, format), &m);
            }
            n += 1;
        }
        assert!(n >= 10);
    }

    // ------------------------------------------------------------------ OBJ input

    #[test]
    fn obj_index_forms_and_negative_indices() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
                f 1/1/1 2/1/1 3/1/1\nf 1//1 2//1 3//1\nf 1/1 2/1 3/1\nf -3 -2 -1\n\
                v 0 0 1 \\\n  1\ns off\nusemtl x\nf -4 -3 -1\n";
        let m = obj(text).unwrap();
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.vertices[3], [0.0, 0.0, 1.0]);
        assert_eq!(
            m.faces,
            vec![
                vec![0, 1, 2],
                vec![0, 1, 2],
                vec![0, 1, 2],
                vec![0, 1, 2],
                vec![0, 1, 3]
            ]
        );
    }

    #[test]
    fn obj_two_objects_give_two_meshes() {
        let text = "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n\
                o second\nv 5 5 5\nv 6 5 5\nv 5 6 5\nv 5 5 6\nf 4 5 6\nf -4 -1 -3\n";
        let objects = read_obj_objects_bytes(text.as_bytes(), "two.obj").unwrap();
        assert_eq!(objects.len(), 2);
        assert_eq!(objects[0].0, "first");
        assert_eq!(objects[0].1.vertices.len(), 3);
        assert_eq!(objects[0].1.faces, vec![vec![0, 1, 2]]);
        assert_eq!(objects[1].0, "second");
        assert_eq!(
            objects[1].1.vertices,
            vec![
                [5.0, 5.0, 5.0],
                [6.0, 5.0, 5.0],
                [5.0, 6.0, 5.0],
                [5.0, 5.0, 6.0]
            ]
        );
        assert_eq!(objects[1].1.faces, vec![vec![0, 1, 2], vec![0, 3, 1]]);

        // Through a file, with groups and shared vertices declared up front.
        let path = tmp_dir().join("groups.obj");
        std::fs::write(
            &path,
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\ng a\nf 1 2 4\ng b c\nf 2 3 4\no empty\n",
        )
        .unwrap();
        // Groups that share vertices are faces of one body (issue 8): one
        // mesh, named after the group of its first face.
        let objects = read_obj_objects(&path).unwrap();
        let names: Vec<&str> = objects.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["default"]);
        assert_eq!(objects[0].1.vertices.len(), 4);
        assert_eq!(
            objects[0].1.faces,
            vec![vec![0, 1, 2], vec![0, 1, 3], vec![1, 2, 3]]
        );
        // The whole file as one mesh keeps global indices.
        assert_eq!(read_mesh(&path).unwrap().faces.len(), 3);
    }

    // ------------------------------------------------------------------ PLY input

    #[test]
    fn ply_float_uint_and_big_endian_inputs() {
        let ascii = b"ply\nformat ascii 1.0\ncomment hi\nelement vertex 3\nproperty float x\n\
property float y\nproperty float z\nproperty uchar red\nelement face 1\n\
property list uchar uint vertex_index\nend_header\n0 0 0 255\n1 0 0 255\n0 0.5 0 255\n3 0 1 2\n";
        let m = ply(ascii).unwrap();
        assert_eq!(m.vertices[2], [0.0, 0.5, 0.0]);
        assert_eq!(m.faces, vec![vec![0, 1, 2]]);

        let mut be = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\n\
property double y\nproperty double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        .to_vec();
        for v in [[0.1, 0.0, -0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f64]] {
            for c in v {
                be.extend_from_slice(&c.to_be_bytes());
            }
        }
        be.push(3);
        for i in [0i32, 1, 2] {
            be.extend_from_slice(&i.to_be_bytes());
        }
        let m = ply(&be).unwrap();
        assert_eq!(m.vertices[0][0].to_bits(), 0.1f64.to_bits());
        assert!(m.vertices[0][2].is_sign_negative());
        assert_eq!(m.faces, vec![vec![0, 1, 2]]);
    }

    // --------------------------------------------------------------------- errors

    #[test]
    fn off_bad_count() {
        // Declares 2 faces, gives 1.
        let err = off("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap_err();
        match err {
            FormatError::CountMismatch {
                at,
                what,
                declared,
                found,
                ..
            } => {
                assert_eq!((what, declared, found), ("faces", 2, 1));
                assert_eq!(at, Location::Line(7), "end of file");
            }
            e => panic!("{e}"),
        }
        // Declares 4 vertices but gives 3: the face line is read as a vertex.
        let err = off("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap_err();
        assert!(matches!(err, FormatError::Parse { .. }), "{err}");
        assert_eq!(err.line(), Some(6));
        assert!(err.to_string().contains("vertex count"), "{err}");
        // Too few vertices.
        let err = off("OFF\n4 1 0\n0 0 0\n1 0 0\n").unwrap_err();
        assert!(
            matches!(
                err,
                FormatError::CountMismatch {
                    what: "vertices",
                    declared: 4,
                    found: 2,
                    ..
                }
            ),
            "{err}"
        );
        // Extra face line.
        let err = off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n").unwrap_err();
        assert!(
            matches!(err, FormatError::CountMismatch { ref at, what: "faces", .. } if *at == Location::Line(7)),
            "{err}"
        );
        assert_eq!(err.line(), Some(7));
        // A face listing fewer indices than it declares.
        let err = off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n").unwrap_err();
        assert!(matches!(err, FormatError::Parse { .. }), "{err}");
        assert_eq!(err.line(), Some(6));
    }

    #[test]
    fn index_out_of_range() {
        let err = off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").unwrap_err();
        assert!(
            matches!(
                err,
                FormatError::BadIndex { ref at, index: 3, vertex_count: 3, .. } if *at == Location::Line(6)
            ),
            "{err}"
        );
        let err = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n").unwrap_err();
        assert!(
            matches!(
                err,
                FormatError::BadIndex {
                    index: 4,
                    vertex_count: 3,
                    ..
                }
            ),
            "{err}"
        );
        assert_eq!(err.line(), Some(5));
        let err = obj("v 0 0 0\nv 1 0 0\nf 1 2 0\n").unwrap_err();
        assert!(
            matches!(err, FormatError::BadIndex { index: 0, .. }),
            "{err}"
        );
        let err = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n").unwrap_err();
        assert!(
            matches!(err, FormatError::BadIndex { index: -4, .. }),
            "{err}"
        );
        assert_eq!(err.line(), Some(4));
        let ascii =
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
property double z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 -1\n";
        let err = ply(ascii).unwrap_err();
        assert!(
            matches!(err, FormatError::BadIndex { index: -1, .. }),
            "{err}"
        );
        assert_eq!(err.line(), Some(14));
    }

    #[test]
    fn degenerate_faces_are_rejected_with_their_line() {
        let err = off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n").unwrap_err();
        assert!(
            matches!(err, FormatError::DegenerateFace { len: 2, .. }),
            "{err}"
        );
        assert_eq!(err.line(), Some(6));
        let err = obj("v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err();
        assert!(
            matches!(err, FormatError::DegenerateFace { len: 2, .. }),
            "{err}"
        );
        assert_eq!(err.line(), Some(3));
    }

    #[test]
    fn nan_and_infinite_coordinates() {
        let err = off("OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n").unwrap_err();
        assert!(
            matches!(err, FormatError::NonFinite { ref at, ref value, .. } if *at == Location::Line(4) && value == "NaN"),
            "{err}"
        );
        let err = off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 1e400\n3 0 1 2\n").unwrap_err();
        assert!(matches!(err, FormatError::NonFinite { .. }), "{err}");
        assert_eq!(err.line(), Some(5));
        let err = obj("# x\nv 0 0 0\nv inf 0 0\n").unwrap_err();
        assert!(matches!(err, FormatError::NonFinite { .. }), "{err}");
        assert_eq!(err.line(), Some(3));
        let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 nan\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
        let err = stl(text.as_bytes()).unwrap_err();
        assert!(matches!(err, FormatError::NonFinite { .. }), "{err}");
        assert_eq!(err.line(), Some(5));
        // Binary PLY with a NaN double: located by element index.
        let mut bytes = write_mesh_bytes(&cube(), Format::PlyBinary).unwrap();
        let header_len = bytes
            .windows(11)
            .position(|w| w == b"end_header\n")
            .unwrap()
            + 11;
        let off = header_len + 24 * 5 + 8;
        bytes[off..off + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        let err = ply(&bytes).unwrap_err();
        assert!(
            matches!(
                err,
                FormatError::NonFinite { at: Location::Element { ref kind, index: 5 }, .. } if kind == "vertex"
            ),
            "{err}"
        );
        // Binary STL with an infinite coordinate.
        let mut bytes = write_mesh_bytes(&cube(), Format::Stl).unwrap();
        let off = 84 + 50 * 3 + 12;
        bytes[off..off + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
        let err = stl(&bytes).unwrap_err();
        assert!(
            matches!(
                err,
                FormatError::NonFinite {
                    at: Location::Element { index: 3, .. },
                    ..
                }
            ),
            "{err}"
        );
        // Writing a NaN is refused.
        let mut m = cube();
        m.vertices[2][1] = f64::NAN;
        for format in Format::ALL {
            assert!(matches!(
                write_mesh_bytes(&m, format),
                Err(FormatError::InvalidMesh { .. })
            ));
        }
    }

    #[test]
    fn truncated_binary_files() {
        let bytes = write_mesh_bytes(&cube(), Format::Stl).unwrap();
        let err = stl(&bytes[..84 + 50 * 7 + 20]).unwrap_err();
        match err {
            FormatError::CountMismatch {
                at,
                what,
                declared,
                found,
                ..
            } => {
                assert_eq!(what, "triangles");
                assert_eq!((declared, found), (12, 7));
                assert_eq!(at, Location::Byte(84 + 50 * 7));
            }
            e => panic!("{e}"),
        }
        let err = stl(&bytes[..50]).unwrap_err();
        assert!(
            matches!(
                err,
                FormatError::Parse {
                    at: Location::Byte(50),
                    ..
                }
            ),
            "{err}"
        );
        // A header claiming 4 billion triangles does not allocate them.
        let mut lying = bytes.clone();
        lying[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
        let err = stl(&lying).unwrap_err();
        assert!(
            matches!(err, FormatError::CountMismatch { declared, found: 12, .. } if declared == u32::MAX as usize),
            "{err}"
        );

        let bytes = write_mesh_bytes(&cube(), Format::PlyBinary).unwrap();
        let header_len = bytes
            .windows(11)
            .position(|w| w == b"end_header\n")
            .unwrap()
            + 11;
        let err = ply(&bytes[..header_len + 24 * 6 + 3]).unwrap_err();
        assert!(
            matches!(
                err,
                FormatError::Parse { at: Location::Element { ref kind, index: 6 }, .. } if kind == "vertex"
            ),
            "{err}"
        );
        let err = ply(&bytes[..bytes.len() - 2]).unwrap_err();
        assert!(
            matches!(
                err,
                FormatError::Parse { at: Location::Element { ref kind, index: 5 }, .. } if kind == "face"
            ),
            "{err}"
        );
    }

    #[test]
    fn huge_counts_in_headers_do_not_preallocate() {
        let err = off("OFF\n18446744073709551615 1 0\n0 0 0\n").unwrap_err();
        assert!(matches!(err, FormatError::CountMismatch { .. }), "{err}");
        let text =
            b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty double x\n\
property double y\nproperty double z\nend_header\n";
        assert!(ply(text).is_err());
        let text =
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
property double z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n0 1 0\n4000000000 1 2 3\n";
        assert!(ply(text).is_err());
    }

    #[test]
    fn unknown_extension_and_missing_file() {
        for p in ["mesh.xyz", "mesh", "off", "dir.off/mesh.txt"] {
            let err = read_mesh(Path::new(p)).unwrap_err();
            assert!(
                matches!(err, FormatError::UnknownExtension { .. }),
                "{p}: {err}"
            );
            let err = write_mesh(Path::new(p), &cube()).unwrap_err();
            assert!(
                matches!(err, FormatError::UnknownExtension { .. }),
                "{p}: {err}"
            );
        }
        assert!(matches!(
            Format::from_path(Path::new("A.PlY")),
            Ok(Format::Ply)
        ));
        assert!(matches!(
            Format::from_path(Path::new("a.Stl")),
            Ok(Format::Stl)
        ));
        let missing = tmp_dir().join("does-not-exist.off");
        let err = read_mesh(&missing).unwrap_err();
        match &err {
            FormatError::Io { path, source } => {
                assert_eq!(path, &missing);
                assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
            }
            e => panic!("{e}"),
        }
        assert!(err.to_string().contains("does-not-exist.off"));
        let err = read_obj_objects(&tmp_dir().join("nope.obj")).unwrap_err();
        assert!(matches!(err, FormatError::Io { .. }));
    }

    #[test]
    fn empty_inputs() {
        for format in Format::ALL {
            let err = read_mesh_bytes(b"", format, "empty").unwrap_err();
            assert!(matches!(err, FormatError::Empty { .. }), "{format}: {err}");
        }
        assert!(matches!(
            off("OFF\n0 0 0\n"),
            Err(FormatError::Empty { .. })
        ));
        assert!(matches!(obj("# nothing\n"), Err(FormatError::Empty { .. })));
        assert!(matches!(
            stl(b"solid x\nendsolid x\n"),
            Err(FormatError::Empty { .. })
        ));
    }

    #[test]
    fn unsupported_features() {
        let err = off("4OFF\n1 0 0\n0 0 0 0\n").unwrap_err();
        assert!(matches!(err, FormatError::Unsupported { .. }), "{err}");
        let err = off("OFF BINARY\n").unwrap_err();
        assert!(matches!(err, FormatError::Unsupported { .. }), "{err}");
        let err = obj("v 0 0 0\ncstype bspline\n").unwrap_err();
        assert!(matches!(err, FormatError::Unsupported { .. }), "{err}");
        assert_eq!(err.line(), Some(2));
        let err = ply(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n")
        .unwrap_err();
        assert!(matches!(err, FormatError::Unsupported { .. }), "{err}");
    }

    #[test]
    fn syntax_errors_name_the_line() {
        let err = off("OFF\n3 1 0\n0 0 0\n1 zero 0\n").unwrap_err();
        assert!(matches!(err, FormatError::Parse { .. }), "{err}");
        assert_eq!(err.line(), Some(4));
        assert!(err.to_string().starts_with("t.off: line 4: "), "{err}");
        let err = obj("v 0 0\n").unwrap_err();
        assert_eq!(err.line(), Some(1));
        let err = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n").unwrap_err();
        assert_eq!(err.line(), Some(4));
        let bad_ply =
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
property float z\nend_header\n0 0 nan\n";
        let err = ply(bad_ply).unwrap_err();
        assert!(matches!(err, FormatError::Parse { .. }), "{err}");
        assert_eq!(err.line(), Some(8));
        let err = ply(b"ply\nformat ascii 1.0\nelemnt vertex 1\n").unwrap_err();
        assert_eq!(err.line(), Some(3), "{err}");
        let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n";
        let err = stl(text.as_bytes()).unwrap_err();
        assert_eq!(err.line(), Some(6), "{err}");
    }

    #[test]
    fn garbage_never_panics() {
        // A deterministic pseudo-random byte soup, plus mangled valid files.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut inputs: Vec<Vec<u8>> = Vec::new();
        for len in [0usize, 1, 5, 83, 84, 85, 134, 1000] {
            inputs.push((0..len).map(|_| next() as u8).collect());
        }
        for format in Format::ALL {
            let good = write_mesh_bytes(&cube(), format).unwrap();
            for cut in [1, 3, 10, good.len() / 2, good.len() - 1] {
                inputs.push(good[..cut].to_vec());
            }
            for _ in 0..20 {
                let mut m = good.clone();
                for _ in 0..4 {
                    let i = (next() as usize) % m.len();
                    m[i] = next() as u8;
                }
                inputs.push(m);
            }
        }
        // Whatever the bytes, the reader answers: a mesh whose faces index
        // its own vertices, or an error with a message.
        let well_formed = |m: &PolygonMesh| m.faces.iter().flatten().all(|&v| v < m.vertices.len());
        for input in &inputs {
            for format in Format::ALL {
                match read_mesh_bytes(input, format, "garbage") {
                    Ok(m) => assert!(well_formed(&m), "{format:?}: face index out of range"),
                    Err(e) => assert!(!e.to_string().is_empty()),
                }
            }
            match read_obj_objects_bytes(input, "garbage") {
                Ok(objects) => assert!(objects.iter().all(|(_, m)| well_formed(m))),
                Err(e) => assert!(!e.to_string().is_empty()),
            }
        }
    }

    #[test]
    fn format_names_parse_back() {
        for f in Format::ALL {
            assert_eq!(f.name().parse::<Format>().unwrap(), f);
        }
        assert_eq!("PLY_binary".parse::<Format>().unwrap(), Format::PlyBinary);
        assert!("3ds".parse::<Format>().is_err());
        assert!(Format::Off.is_lossless() && !Format::Stl.is_lossless());
    }
}
