//! `dymsum sum` of non-convex bodies (issue 21): unions of convex pieces
//! (OBJ objects, `+`), closed meshes of convex components, a non-convex mesh
//! refused without `--decomposition` and taken apart by V-HACD with it.
//! Every written mesh is re-read and validated.

mod common;

use std::path::Path;

use common::{assert_fails, ok, temp_dir};
use dymsum::nonconvex::check_closed_mesh;

const FACES: [[usize; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

fn corners(lo: [f64; 3], hi: [f64; 3]) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
        .collect()
}

/// The L (3×1×1 and 1×3×1 boxes at the origin) as an OBJ of two objects.
fn l_obj(dir: &Path) -> String {
    let mut s = String::new();
    for (k, (name, hi)) in [("long", [3., 1., 1.]), ("short", [1., 3., 1.])]
        .iter()
        .enumerate()
    {
        s += &format!("o {name}\n");
        for p in corners([0.; 3], *hi) {
            s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
        }
        for f in FACES {
            s += &format!(
                "f {} {} {} {}\n",
                f[0] + 1 + 8 * k,
                f[1] + 1 + 8 * k,
                f[2] + 1 + 8 * k,
                f[3] + 1 + 8 * k
            );
        }
    }
    let path = dir.join("L.obj");
    std::fs::write(&path, s).unwrap();
    path.to_str().unwrap().to_string()
}

/// An OFF of boxes as separate (overlapping) shells.
fn boxes_off(dir: &Path, name: &str, boxes: &[([f64; 3], [f64; 3])]) -> String {
    let mut v = Vec::new();
    let mut f = Vec::new();
    for (lo, hi) in boxes {
        let o = v.len();
        v.extend(corners(*lo, *hi));
        f.extend(FACES.iter().map(|q| q.map(|i| i + o)));
    }
    let mut s = format!("OFF\n{} {} 0\n", v.len(), f.len());
    for p in &v {
        s += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for q in &f {
        s += &format!("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
    }
    let path = dir.join(name);
    std::fs::write(&path, s).unwrap();
    path.to_str().unwrap().to_string()
}

/// The extruded L outline: one closed, non-convex mesh.
fn l_mesh_off(dir: &Path) -> String {
    let o = [[0., 0.], [3., 0.], [3., 1.], [1., 1.], [1., 3.], [0., 3.]];
    let mut s = "OFF\n12 14 0\n".to_string();
    for z in [0., 1.] {
        for p in o {
            s += &format!("{} {} {z}\n", p[0], p[1]);
        }
    }
    for t in [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]] {
        s += &format!(
            "3 {} {} {}\n3 {} {} {}\n",
            t[0],
            t[2],
            t[1],
            t[0] + 6,
            t[1] + 6,
            t[2] + 6
        );
    }
    for i in 0..6 {
        let j = (i + 1) % 6;
        s += &format!("4 {i} {j} {} {}\n", j + 6, i + 6);
    }
    let path = dir.join("Lmesh.off");
    std::fs::write(&path, s).unwrap();
    path.to_str().unwrap().to_string()
}

fn read_valid(path: &Path) -> dymsum::nonconvex::ClosedMeshInfo {
    let mesh = dymsum_io::formats::read_mesh(path).unwrap();
    check_closed_mesh(&mesh).unwrap()
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text.trim()).unwrap()
}

#[test]
fn l_obj_plus_a_half_cube_is_one_valid_solid_of_volume_12_375() {
    let dir = temp_dir("l_cube");
    let l = l_obj(&dir);
    for (k, o) in [[0., 0., 0.], [10., 0., 0.], [0., 0., 5.], [-3., -3., 0.]]
        .iter()
        .enumerate()
    {
        let cube = boxes_off(&dir, &format!("cube{k}.off"), &[(*o, o.map(|x| x + 0.5))]);
        let out = dir.join(format!("sum{k}.off"));
        let s = json(&ok(&[
            "sum",
            &l,
            &cube,
            "-o",
            out.to_str().unwrap(),
            "--json",
        ]));
        assert_eq!(s["pieces"], serde_json::json!([2, 1]));
        assert_eq!(s["decomposition"]["p"]["method"], "given");
        assert_eq!(s["shells"], 1);
        let info = read_valid(&out);
        assert!(
            (info.volume - 12.375).abs() < 1e-9,
            "{o:?}: {}",
            info.volume
        );
        assert_eq!((info.shells, info.genus), (1, 0));
    }
}

#[test]
fn l_obj_plus_a_ring_off_and_the_ring_keeps_its_hole() {
    let dir = temp_dir("l_ring");
    let l = l_obj(&dir);
    let ring = boxes_off(
        &dir,
        "ring.off",
        &[
            ([0., 0., 0.], [3., 1., 1.]),
            ([0., 2., 0.], [3., 3., 1.]),
            ([0., 0.5, 0.], [1., 2.5, 1.]),
            ([2., 0.5, 0.], [3., 2.5, 1.]),
        ],
    );
    let out = dir.join("out.off");
    let line = ok(&["sum", &l, &ring, "-o", out.to_str().unwrap()]);
    assert!(line.contains("2 pieces ⊕ 4 pieces, 8 pair sums"), "{line}");
    assert!(line.contains("Q 4 convex components (exact)"), "{line}");
    read_valid(&out);
    // The ring plus a small cube: genus 1 kept.
    let cube = boxes_off(&dir, "small.off", &[([0.; 3], [0.25; 3])]);
    let out = dir.join("ring_cube.off");
    let s = json(&ok(&[
        "sum",
        &ring,
        &cube,
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(s["genus"], 1);
    let info = read_valid(&out);
    assert_eq!((info.shells, info.genus), (1, 1));
    // Also as `+`-joined pieces, and to standard output.
    let joined = format!(
        "{}+{}",
        dir.join("small.off").display(),
        dir.join("cube_b.off").display()
    );
    boxes_off(&dir, "cube_b.off", &[([2.; 3], [3.; 3])]);
    let text = ok(&["sum", &l, &joined, "-o", "-"]);
    assert!(text.starts_with("OFF"), "{text}");
}

#[test]
fn a_non_convex_mesh_needs_a_decomposition() {
    let dir = temp_dir("l_mesh");
    let l = l_mesh_off(&dir);
    let out = dir.join("out.off");
    let o = common::run(&["sum", &l, "cube", "-o", out.to_str().unwrap()]);
    assert_fails(&o, 1, "needs a convex decomposition");
    assert_fails(&o, 1, "--decomposition vhacd");
    assert!(!out.exists());
    let s = json(&ok(&[
        "sum",
        &l,
        "cube",
        "-o",
        out.to_str().unwrap(),
        "--decomposition",
        "vhacd",
        "--json",
    ]));
    assert_eq!(s["decomposition"]["p"]["method"], "vhacd");
    assert_eq!(s["decomposition"]["p"]["exact"], false);
    let err = s["decomposition"]["p"]["volume_error"].as_f64().unwrap();
    assert!((0.0..0.25).contains(&err), "{s}");
    read_valid(&out);
}

#[test]
fn an_open_mesh_is_still_refused_as_before() {
    let dir = temp_dir("open");
    let out = dir.join("out.off");
    let o = common::run(&[
        "sum",
        &common::fixture("cube_open.off"),
        "cube",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_fails(&o, 1, "open mesh");
    // The problem first, the fix last (issue 29), word for word.
    assert_eq!(
        common::stderr(&o).trim_end(),
        format!(
            "error: P (file {}): open mesh: edge (4, 7) borders only one face; fix: close the \
             mesh (every edge must border exactly two faces), or give the body's convex pieces as \
             files joined with `+` or as OBJ objects",
            common::fixture("cube_open.off")
        )
    );
}

#[test]
fn animate_a_union_writes_merged_valid_frames() {
    let dir = temp_dir("animate");
    let l = l_obj(&dir);
    let ring = boxes_off(
        &dir,
        "ring.off",
        &[
            ([0., 0., 0.], [3., 1., 1.]),
            ([0., 2., 0.], [3., 3., 1.]),
            ([0., 0.5, 0.], [1., 2.5, 1.]),
            ([2., 0.5, 0.], [3., 2.5, 1.]),
        ],
    );
    let frames = dir.join("frames");
    let csv = dir.join("a.csv");
    let text = ok(&[
        "animate",
        &l,
        &ring,
        "--steps-per-rev",
        "100",
        "--steps",
        "20",
        "--frames-dir",
        frames.to_str().unwrap(),
        "--every",
        "10",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(
        text.contains("8 piece pairs, each updated by DYMSUM"),
        "{text}"
    );
    assert!(text.contains("(verified against walk)"), "{text}");
    assert_eq!(std::fs::read_to_string(&csv).unwrap().lines().count(), 21);
    for step in [10, 20] {
        let info = read_valid(&frames.join(format!("step_{step:06}.off")));
        assert_eq!(info.shells, 1);
    }
}

#[test]
fn cobst_merge_writes_one_valid_mesh_per_slice_equal_to_the_library_union() {
    use dymsum::query::orientations_about_axis;
    use dymsum::{ConvexUnion, DVec3, Polytope};
    let dir = temp_dir("cobst-merge");
    let l = l_obj(&dir);
    let out = dir.join("slices");
    let text = ok(&[
        "cobst",
        &l,
        "box:1,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "6",
        "--out",
        out.to_str().unwrap(),
        "--merge",
    ]);
    assert!(text.contains("6 slices (2 piece pairs)"), "{text}");
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("index.json")).unwrap()).unwrap();
    let box_at = |lo: [f64; 3], hi: [f64; 3]| Polytope::from_points(&corners(lo, hi)).unwrap();
    let robot = ConvexUnion::new(vec![
        box_at([0.; 3], [3., 1., 1.]),
        box_at([0.; 3], [1., 3., 1.]),
    ])
    .unwrap();
    let obstacle = ConvexUnion::new(vec![box_at([-0.5; 3], [0.5; 3])]).unwrap();
    let turns = orientations_about_axis(DVec3::Z, 6).unwrap();
    let expected = robot.cobstacle_union_slices(&obstacle, &turns).unwrap();
    for (k, slice) in expected.iter().enumerate() {
        let entry = &index[k];
        assert_eq!(entry["file"], format!("slice_{k:05}.off"));
        assert!(entry.get("files").is_none());
        let info = read_valid(&out.join(format!("slice_{k:05}.off")));
        assert_eq!(info.shells, 1);
        assert!((info.volume - slice.info().mesh.volume).abs() <= 1e-9 * info.volume);
    }
    // Only with --format off, and never with --certified.
    let o = common::run(&[
        "cobst",
        &l,
        "box:1,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "6",
        "--out",
        dir.join("npz").to_str().unwrap(),
        "--merge",
        "--format",
        "npz",
    ]);
    assert_fails(&o, 1, "--merge writes one mesh per slice");
}

#[test]
fn query_cobst_and_motion_take_meshes_of_convex_shells_and_announce_a_decomposition() {
    let dir = temp_dir("bodies");
    let ring = boxes_off(
        &dir,
        "ring.off",
        &[
            ([0., 0., 0.], [3., 1., 1.]),
            ([0., 2., 0.], [3., 3., 1.]),
            ([0., 0.5, 0.], [1., 2.5, 1.]),
            ([2., 0.5, 0.], [3., 2.5, 1.]),
        ],
    );
    // The unit box in the ring's hole: apart, 0.5 from the inner walls.
    let text = ok(&[
        "query",
        &ring,
        "box:0.5,0.5,0.5",
        "--pose-xyz-wxyz",
        "-1.5,-1.5,-0.5,1,0,0,0",
    ]);
    assert!(text.contains("apart, distance 0.250000000"), "{text}");
    let out = dir.join("slices");
    let text = ok(&[
        "cobst",
        &ring,
        "box:0.5,0.5,0.5",
        "--axis",
        "0,0,1",
        "--slices",
        "3",
        "--out",
        out.to_str().unwrap(),
        "--merge",
    ]);
    assert!(text.contains("3 slices (4 piece pairs)"), "{text}");
    for k in 0..3 {
        // A 0.5 box turned about z fits the 1×1 hole: every slice keeps it.
        assert_eq!(read_valid(&out.join(format!("slice_{k:05}.off"))).genus, 1);
    }
    let text = ok(&[
        "motion",
        &ring,
        "box:0.5,0.5,0.5",
        "--from-xyz-wxyz",
        "-1.5,-1.5,-0.5,1,0,0,0",
        "--to-xyz-wxyz",
        "-1.5,-1.2,-0.5,1,0,0,0",
    ]);
    assert!(text.contains("free"), "{text}");
    // A mesh that needs a decomposition: refused, or taken apart by V-HACD
    // with a note on standard error.
    let l = l_mesh_off(&dir);
    let o = common::run(&["query", &l, "box", "--pose-xyz-wxyz", "5,5,5,1,0,0,0"]);
    assert_fails(&o, 1, "--decomposition vhacd");
    let o = common::run(&[
        "query",
        &l,
        "box",
        "--pose-xyz-wxyz",
        "5,5,5,1,0,0,0",
        "--decomposition",
        "vhacd",
    ]);
    assert!(o.status.success());
    assert!(
        common::stderr(&o).contains("taken apart by vhacd"),
        "{}",
        common::stderr(&o)
    );
}

/// An OFF file of a polygon mesh.
fn write_off(dir: &Path, name: &str, v: &[[f64; 3]], f: &[Vec<usize>]) -> String {
    let mut s = format!("OFF\n{} {} 0\n", v.len(), f.len());
    for p in v {
        s += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for q in f {
        s += &q.len().to_string();
        for i in q {
            s += &format!(" {i}");
        }
        s += "\n";
    }
    let path = dir.join(name);
    std::fs::write(&path, s).unwrap();
    path.to_str().unwrap().to_string()
}

/// A prism over a curl that crosses itself (winding number 2 in places):
/// closed, oriented, manifold, of positive volume.
fn curl_prism() -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
    let ring = [
        [0., 0.],
        [4., 0.],
        [4., 3.],
        [1., 3.],
        [1., 1.],
        [3., 1.],
        [3., 2.],
        [2., 2.],
        [2., -1.],
        [0., -1.],
    ];
    let n = ring.len();
    let mut v = Vec::new();
    for z in [0., 1.] {
        v.extend(ring.iter().map(|p| [p[0], p[1], z]));
    }
    let mut f: Vec<Vec<usize>> = Vec::new();
    for k in 1..n - 1 {
        f.push(vec![0, k + 1, k]);
        f.push(vec![n, n + k, n + k + 1]);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        f.push(vec![i, j, n + j]);
        f.push(vec![i, n + j, n + i]);
    }
    (v, f)
}

/// Issue 26 §3: a closed mesh crossing itself was summed under
/// `--decomposition vhacd` (2 of 3). Now refused by the exact solid check,
/// before the decomposition and before its shells are taken, with the
/// problem first and the fix last; nothing is written.
#[test]
fn self_intersecting_meshes_are_refused_before_vhacd() {
    let dir = temp_dir("self_crossing");
    let (v, f) = curl_prism();
    let curl = write_off(&dir, "curl.off", &v, &f);
    let out = dir.join("out.off");
    for extra in [&["--decomposition", "vhacd"][..], &[][..]] {
        let mut args = vec!["sum", &curl, "cube", "-o", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        let o = common::run(&args);
        assert_fails(&o, 1, "not a solid: faces ");
        assert_fails(
            &o,
            1,
            " cross (they meet other than along a shared edge or vertex); fix: ",
        );
        assert!(common::stderr(&o).trim_end().ends_with("as OBJ objects"));
        assert!(!out.exists());
    }
    // The same for query, cobst and motion (one loader).
    let o = common::run(&[
        "query",
        "cube",
        &curl,
        "--pose-xyz-wxyz",
        "0,0,0,1,0,0,0",
        "--decomposition",
        "vhacd",
    ]);
    assert_fails(&o, 1, "not a solid: faces ");
}

/// Issue 26 §2 and §3: faces listed twice, and a closed zero-volume sheet
/// (two triangles back to back) beside a cube, are refused in a mesh of
/// convex shells too.
#[test]
fn duplicate_faces_and_zero_volume_sheets_are_refused() {
    let dir = temp_dir("sheets");
    let mut v = corners([0.; 3], [1.; 3]);
    let mut f: Vec<Vec<usize>> = FACES.iter().map(|q| q.to_vec()).collect();
    let twice: Vec<Vec<usize>> = f.iter().chain(f.iter()).cloned().collect();
    let cubes = write_off(&dir, "twice.off", &v, &twice);
    let out = dir.join("out.off");
    let out = out.to_str().unwrap();
    let o = common::run(&["sum", &cubes, "cube", "-o", out, "--decomposition", "vhacd"]);
    assert_fails(&o, 1, "not a solid: faces 0 and 6 have the same corners");
    v.extend([[2., 0., 0.], [3., 0., 0.], [2., 1., 0.]]);
    f.push(vec![8, 9, 10]);
    f.push(vec![8, 10, 9]);
    let sheet = write_off(&dir, "sheet.off", &v, &f);
    let o = common::run(&["sum", &sheet, "cube", "-o", out]);
    assert_fails(&o, 1, "not a solid: faces 6 and 7 have the same corners");
}

/// Issue 29: `info` and `render` take one convex body; a body of several
/// pieces is refused with the problem first and the fix last, naming the
/// subcommands that take unions (was: "mesh is not a topological sphere:
/// Euler characteristic V - E + F = 4, expected 2"). Pinned word for word.
#[test]
fn info_and_render_refuse_a_body_of_pieces_naming_the_subcommands_that_take_it() {
    let dir = temp_dir("one-body-only");
    let two = boxes_off(
        &dir,
        "two.off",
        &[([0.0; 3], [1.0; 3]), ([3.0, 0.0, 0.0], [4.0, 1.0, 1.0])],
    );
    let fix = "to use the pieces, run `dymsum sum`, `query`, `motion` or `cobst`, which take \
               unions (pieces joined with `+`, OBJ objects, or a mesh of convex shells), or give \
               one piece";
    let o = common::run(&["info", &two]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        common::stderr(&o).trim_end(),
        format!(
            "error: input (two.off): a body of 2 convex pieces, and `dymsum info` takes one \
             convex body; {fix}"
        )
    );
    let svg = dir.join("x.svg");
    let o = common::run(&["render", &two, "box", "-o", svg.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        common::stderr(&o).trim_end(),
        format!(
            "error: P (two.off): a body of 2 convex pieces, and `dymsum render` takes one \
             convex body; {fix}"
        )
    );
    // The same body is taken by `sum` as a union.
    let out = dir.join("sum.off");
    let text = ok(&["sum", &two, "box", "-o", out.to_str().unwrap(), "--json"]);
    assert_eq!(json(&text)["pieces"][0], 2, "{text}");
    std::fs::remove_dir_all(&dir).ok();
}
