//! Issue 22 §1: `dymsum cobst --format npz|npz-mesh|halfspaces`. The map
//! container is read back by a minimal reader of stored ZIP entries and
//! NPY 1.0 arrays (written independently of `dymsum_io::npz`), and its
//! arrays equal the library's slices bit for bit. python/tests loads the
//! same container with `np.load(..., allow_pickle=False)`.

mod common;

use std::collections::BTreeMap;

use common::{assert_fails, model, ok, run, temp_dir};
use dymsum::query::orientations_about_axis;
use dymsum::{CObstacle, DVec3};

/// One NPY array: its dtype descriptor, shape and raw little-endian bytes.
#[derive(Debug)]
struct Npy {
    descr: String,
    shape: Vec<usize>,
    data: Vec<u8>,
}

impl Npy {
    fn f64s(&self) -> Vec<f64> {
        assert_eq!(self.descr, "<f8");
        self.data
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }
    fn i64s(&self) -> Vec<i64> {
        assert_eq!(self.descr, "<i8");
        self.data
            .chunks_exact(8)
            .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }
    fn strs(&self) -> Vec<String> {
        let width: usize = self.descr.strip_prefix("<U").unwrap().parse().unwrap();
        self.data
            .chunks_exact(4 * width)
            .map(|c| {
                c.chunks_exact(4)
                    .map(|b| u32::from_le_bytes(b.try_into().unwrap()))
                    .take_while(|&u| u != 0)
                    .map(|u| char::from_u32(u).unwrap())
                    .collect()
            })
            .collect()
    }
}

fn u16_at(b: &[u8], i: usize) -> usize {
    u16::from_le_bytes([b[i], b[i + 1]]) as usize
}
fn u32_at(b: &[u8], i: usize) -> usize {
    u32::from_le_bytes(b[i..i + 4].try_into().unwrap()) as usize
}

/// Reads every entry of a stored (uncompressed) `.npz`.
fn read_npz(path: &std::path::Path) -> BTreeMap<String, Npy> {
    let b = std::fs::read(path).unwrap();
    let mut out = BTreeMap::new();
    let mut i = 0;
    while u32_at(&b, i) == 0x0403_4b50 {
        assert_eq!(u16_at(&b, i + 8), 0, "entries are stored");
        let size = u32_at(&b, i + 18);
        assert_eq!(size, u32_at(&b, i + 22));
        let (n, extra) = (u16_at(&b, i + 26), u16_at(&b, i + 28));
        let name = std::str::from_utf8(&b[i + 30..i + 30 + n]).unwrap();
        let data = &b[i + 30 + n + extra..i + 30 + n + extra + size];
        assert_eq!(&data[..8], b"\x93NUMPY\x01\x00");
        let hlen = u16_at(data, 8);
        assert_eq!((10 + hlen) % 64, 0);
        let header = std::str::from_utf8(&data[10..10 + hlen]).unwrap();
        let field = |key: &str| {
            let at = header.find(key).unwrap() + key.len();
            header[at..].trim_start()
        };
        let descr = field("'descr':").split('\'').nth(1).unwrap().to_string();
        assert!(field("'fortran_order':").starts_with("False"));
        let shape_text = field("'shape':");
        let shape_text = &shape_text[1..shape_text.find(')').unwrap()];
        let shape = shape_text
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().unwrap())
            .collect();
        out.insert(
            name.strip_suffix(".npy").unwrap().to_string(),
            Npy {
                descr,
                shape,
                data: data[10 + hlen..].to_vec(),
            },
        );
        i += 30 + n + extra + size;
    }
    assert_eq!(u32_at(&b, i), 0x0201_4b50, "the central directory follows");
    out
}

#[test]
fn npz_halfspaces_equal_the_library_bit_for_bit() {
    let dir = temp_dir("map-hs");
    let out = dir.join("m");
    let text = ok(&[
        "cobst",
        "gs1+box:1,0.5,0.5",
        "box:2,1,1",
        "--axis",
        "1,2,3",
        "--slices",
        "10",
        "--out",
        out.to_str().unwrap(),
        "--format",
        "npz",
    ]);
    assert!(text.contains("map.npz"), "{text}");
    // Only the container: no index, no slices.
    let names: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["map.npz"]);
    let z = read_npz(&out.join("map.npz"));
    assert_eq!(z["format"].strs(), ["dymsum-cobstacle-map"]);
    assert_eq!(z["form"].strs(), ["halfspaces"]);
    assert_eq!(z["form"].shape, Vec::<usize>::new());
    assert_eq!(z["certified"].i64s(), [0]);
    assert_eq!(z["robot_pieces"].strs(), ["r0", "r1"]);
    assert_eq!(z["obstacle_pieces"].strs(), ["o0"]);
    assert_eq!(z["pairs"].shape, [2, 2]);
    assert_eq!(z["pairs"].i64s(), [0, 0, 1, 0]);
    let turns = orientations_about_axis(DVec3::new(1.0, 2.0, 3.0), 10).unwrap();
    assert_eq!(z["orientations_xyzw"].shape, [10, 4]);
    let q: Vec<f64> = turns.iter().flat_map(|r| r.xyzw()).collect();
    assert_eq!(z["orientations_xyzw"].f64s(), q);
    let (start, normals, offsets) = (
        z["plane_start"].i64s(),
        z["normals"].f64s(),
        z["offsets"].f64s(),
    );
    assert_eq!(start.len(), 21);
    assert_eq!(z["normals"].shape, [offsets.len(), 3]);
    let obstacle = model("box:2,1,1");
    for (p, robot) in [model("gs1"), model("box:1,0.5,0.5")].iter().enumerate() {
        let hs = CObstacle::new(robot, &obstacle)
            .unwrap()
            .halfspace_slices(&turns)
            .unwrap();
        for (k, h) in hs.iter().enumerate() {
            let s = p * 10 + k;
            let (a, b) = (start[s] as usize, start[s + 1] as usize);
            assert_eq!(&offsets[a..b], h.offsets(), "pair {p}, slice {k}");
            let n: Vec<f64> = h.normals().iter().flat_map(|n| n.to_array()).collect();
            assert_eq!(&normals[3 * a..3 * b], &n[..], "pair {p}, slice {k}");
        }
    }
    dymsum_testkit::files::remove_dir(&dir);
}

#[test]
fn npz_meshes_and_json_halfspaces_equal_the_library() {
    let dir = temp_dir("map-mesh");
    let out = dir.join("m");
    ok(&[
        "cobst",
        "gs1",
        "box:2,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "6",
        "--out",
        out.to_str().unwrap(),
        "--format",
        "npz-mesh",
    ]);
    let z = read_npz(&out.join("map.npz"));
    assert_eq!(z["form"].strs(), ["mesh"]);
    let turns = orientations_about_axis(DVec3::Z, 6).unwrap();
    let slices =
        dymsum::query::cobstacle_slices(&model("gs1"), &model("box:2,1,1"), &turns).unwrap();
    let (vs, fs) = (z["vertex_start"].i64s(), z["face_start"].i64s());
    let (v, cs, c) = (
        z["vertices"].f64s(),
        z["corner_start"].i64s(),
        z["corners"].i64s(),
    );
    for (k, m) in slices.iter().enumerate() {
        let verts: Vec<f64> = m.vertices.iter().flatten().copied().collect();
        assert_eq!(
            &v[3 * vs[k] as usize..3 * vs[k + 1] as usize],
            &verts[..],
            "slice {k}"
        );
        let faces: Vec<Vec<usize>> = (fs[k]..fs[k + 1])
            .map(|f| {
                c[cs[f as usize] as usize..cs[f as usize + 1] as usize]
                    .iter()
                    .map(|&i| i as usize)
                    .collect()
            })
            .collect();
        assert_eq!(faces, m.faces, "slice {k}");
    }
    // --format halfspaces: one JSON per slice, the library's planes (to
    // within serde_json's parsing, an ulp), and index.json.
    let out2 = dir.join("j");
    ok(&[
        "cobst",
        "gs1",
        "box:2,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "6",
        "--out",
        out2.to_str().unwrap(),
        "--format",
        "halfspaces",
    ]);
    assert!(out2.join("index.json").is_file());
    let cobst = CObstacle::new(&model("gs1"), &model("box:2,1,1")).unwrap();
    for (k, h) in cobst.halfspace_slices(&turns).unwrap().iter().enumerate() {
        let j: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(out2.join(format!("slice_{k:05}.json"))).unwrap(),
        )
        .unwrap();
        let d: Vec<f64> = j["offsets"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_eq!(d.len(), h.len());
        for (x, y) in d.iter().zip(h.offsets()) {
            assert!((x - y).abs() <= 2.0 * f64::EPSILON * y.abs(), "{x} {y}");
        }
    }
    dymsum_testkit::files::remove_dir(&dir);
}

#[test]
fn certified_npz_holds_the_slabs_and_npz_mesh_is_refused() {
    let dir = temp_dir("map-cert");
    let out = dir.join("m");
    ok(&[
        "cobst",
        "gs1",
        "box:2,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "8",
        "--out",
        out.to_str().unwrap(),
        "--certified",
        "--format",
        "npz",
    ]);
    let z = read_npz(&out.join("map.npz"));
    assert_eq!(z["certified"].i64s(), [1]);
    // The closed turn: 9 orientations, 8 slabs.
    assert_eq!(z["orientations_xyzw"].shape, [9, 4]);
    assert_eq!(z["slices_per_pair"].i64s(), [8]);
    let slabs = dymsum::query::certified_slabs_about_axis(
        &model("gs1"),
        &model("box:2,1,1"),
        DVec3::Z,
        &dymsum::query::full_turn_angles(8),
    )
    .unwrap();
    let (start, offsets) = (z["plane_start"].i64s(), z["offsets"].f64s());
    for (k, s) in slabs.iter().enumerate() {
        assert_eq!(
            &offsets[start[k] as usize..start[k + 1] as usize],
            s.offsets(),
            "slab {k}"
        );
    }
    let o = run(&[
        "cobst",
        "gs1",
        "box:2,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "8",
        "--out",
        dir.join("n").to_str().unwrap(),
        "--certified",
        "--format",
        "npz-mesh",
    ]);
    assert_fails(&o, 1, "npz-mesh");
    assert!(
        !dir.join("n").exists(),
        "nothing written for a refused format"
    );
    // Cell slabs do not fit the container (slabs between orientations).
    let o = run(&[
        "cobst",
        "gs1",
        "box:2,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "8",
        "--out",
        dir.join("c").to_str().unwrap(),
        "--certified",
        "--cell-radius",
        "0.1",
        "--format",
        "npz",
    ]);
    assert_fails(&o, 1, "--cell-radius");
    assert!(
        !dir.join("c").exists(),
        "nothing written for a refused format"
    );
    dymsum_testkit::files::remove_dir(&dir);
}
