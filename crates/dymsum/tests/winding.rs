//! What a mesh encloses (issue 33 §1): the points of non-zero winding number
//! of its enclosing triangles, whatever the mesh's topology. Each named case
//! below was a wrong answer before (a robot inside a solid called free, or
//! one floating in a cavity called colliding); each is judged by an oracle
//! written from the boxes the mesh was made of (closed-interval tests,
//! exact on these dyadic coordinates), independent of the code under test,
//! in both roles (the mesh as the obstacle and as the moving body).

use dymsum::query::{MeshBody, SceneChecker};
use dymsum::solid::soup::{clean_soup, ComponentKind};
use dymsum::{DVec3, PolygonMesh, Pose, Rotation};
use dymsum_testkit::{box_corners, proptest_cases, CUBE_QUADS};
use proptest::prelude::*;

/// An axis-aligned box `[lo, hi]` (closed).
#[derive(Clone, Copy, Debug)]
struct Cell {
    lo: [f64; 3],
    hi: [f64; 3],
}

impl Cell {
    fn new(lo: [f64; 3], hi: [f64; 3]) -> Cell {
        Cell { lo, hi }
    }

    /// Whether two closed boxes share a point.
    fn meets(&self, o: &Cell) -> bool {
        (0..3).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }

    /// Whether `o` lies in this box's interior (open box).
    fn holds_strictly(&self, o: &Cell) -> bool {
        (0..3).all(|k| self.lo[k] < o.lo[k] && o.hi[k] < self.hi[k])
    }

    fn around(c: [f64; 3], h: f64) -> Cell {
        Cell::new(c.map(|x| x - h), c.map(|x| x + h))
    }
}

fn corners(c: &Cell) -> Vec<[f64; 3]> {
    box_corners(c.lo, c.hi)
}

/// The twelve triangles of a box, vertices from `offset`, outward or
/// inward.
fn box_triangles(offset: usize, outward: bool) -> Vec<Vec<usize>> {
    CUBE_QUADS
        .iter()
        .flat_map(|q| {
            let q = q.map(|v| v + offset);
            let (a, b) = ([q[0], q[1], q[2]], [q[0], q[2], q[3]]);
            [a, b].map(|t| {
                if outward {
                    t.to_vec()
                } else {
                    vec![t[0], t[2], t[1]]
                }
            })
        })
        .collect()
}

/// Boxes written into one mesh, each closed and with its own corners
/// (identical coordinates are merged by the cleaning, so touching boxes
/// share vertices, edges and back-to-back faces); `outward[i]` false makes
/// box `i` an inward shell.
fn boxes_mesh(cells: &[Cell], outward: &[bool]) -> PolygonMesh {
    let mut m = PolygonMesh::new(Vec::new(), Vec::new());
    for (i, c) in cells.iter().enumerate() {
        let base = m.vertices.len();
        m.vertices.extend(corners(c));
        m.faces.extend(box_triangles(base, outward[i]));
    }
    m
}

fn cube(c: [f64; 3], h: f64) -> PolygonMesh {
    boxes_mesh(&[Cell::around([0.0; 3], h)], &[true])
        .vertices
        .iter()
        .map(|p| [p[0] + c[0], p[1] + c[1], p[2] + c[2]])
        .collect::<Vec<_>>()
        .pipe(|v| PolygonMesh::new(v, box_triangles(0, true)))
}

trait Pipe: Sized {
    fn pipe<T>(self, f: impl FnOnce(Self) -> T) -> T {
        f(self)
    }
}
impl<T> Pipe for T {}

fn body(m: &PolygonMesh) -> MeshBody {
    let b = MeshBody::new(m).unwrap();
    b.sanity_check().unwrap();
    b
}

fn at(c: [f64; 3]) -> Pose {
    Pose::new(Rotation::IDENTITY, DVec3::from(c))
}

/// Whether a cube of half-size `h` centred at `c` collides with `mesh`,
/// asked both ways round: the cube moving among the mesh as an obstacle,
/// and the mesh moving (by `−c`) around the cube at the origin. The two
/// must agree.
fn collides(mesh: &PolygonMesh, c: [f64; 3], h: f64) -> bool {
    let m = body(mesh);
    let probe = body(&cube([0.0; 3], h));
    let as_obstacle = SceneChecker::new(&probe, std::slice::from_ref(&m))
        .unwrap()
        .collides_at(at(c))
        .unwrap();
    let as_body = SceneChecker::new(&m, &[probe])
        .unwrap()
        .collides_at(at(c.map(|x| -x)))
        .unwrap();
    assert_eq!(
        as_obstacle, as_body,
        "the two roles disagree for a cube of half-size {h} at {c:?}"
    );
    as_obstacle
}

/// The oracle for unions of solid boxes: the probe meets one of them.
fn meets_union(cells: &[Cell], probe: &Cell) -> bool {
    cells.iter().any(|c| c.meets(probe))
}

fn kinds(m: &PolygonMesh) -> (usize, usize) {
    let r = body(m).report();
    (r.solids, r.surfaces)
}

#[test]
fn boxes_sharing_a_face_enclose() {
    let cells = [
        Cell::new([0.0; 3], [1.0; 3]),
        Cell::new([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
    ];
    let m = boxes_mesh(&cells, &[true, true]);
    assert_eq!(kinds(&m), (1, 1)); // the shared face is a surface inside
    for c in [[0.5, 0.5, 0.5], [1.5, 0.5, 0.5], [1.0, 0.5, 0.5]] {
        assert!(collides(&m, c, 0.1), "inside at {c:?}");
    }
    assert!(!collides(&m, [2.5, 0.5, 0.5], 0.1));
}

#[test]
fn boxes_sharing_an_edge_or_a_corner_enclose() {
    for other in [
        Cell::new([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]),
        Cell::new([1.0; 3], [2.0; 3]),
    ] {
        let cells = [Cell::new([0.0; 3], [1.0; 3]), other];
        let m = boxes_mesh(&cells, &[true, true]);
        assert_eq!(kinds(&m).1, 0, "no surface");
        for c in [[0.5; 3], [1.5, 1.5, 0.5]] {
            let probe = Cell::around(c, 0.1);
            assert_eq!(collides(&m, c, 0.1), meets_union(&cells, &probe), "{c:?}");
        }
    }
}

#[test]
fn a_chain_of_three_boxes_encloses() {
    let cells = [
        Cell::new([0.0; 3], [1.0; 3]),
        Cell::new([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
        Cell::new([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]),
    ];
    let m = boxes_mesh(&cells, &[true; 3]);
    for x in [0.5, 1.5, 2.5] {
        assert!(collides(&m, [x, 0.5, 0.5], 0.2));
    }
    assert!(!collides(&m, [1.5, 1.5, 0.5], 0.2));
}

#[test]
fn a_cavity_is_outside() {
    // A hollow box: the outer shell outward, the inner one inward.
    let outer = Cell::new([0.0; 3], [4.0; 3]);
    let cavity = Cell::new([1.0; 3], [3.0; 3]);
    let m = boxes_mesh(&[outer, cavity], &[true, false]);
    let soup = clean_soup(&m).unwrap();
    assert!(!soup.inverted);
    assert_eq!(soup.flipped, 0, "the inner shell keeps its orientation");
    let oracle = |c: [f64; 3], h: f64| {
        let p = Cell::around(c, h);
        outer.meets(&p) && !cavity.holds_strictly(&p)
    };
    for (c, h) in [
        ([2.0; 3], 0.25),          // floating in the cavity
        ([1.25, 2.0, 2.0], 0.25),  // touching the inner wall
        ([1.25, 2.0, 2.0], 0.125), // beside it
        ([0.5, 2.0, 2.0], 0.25),   // in the wall
        ([5.0, 5.0, 5.0], 0.25),   // outside
        ([2.0, 2.0, 2.0], 1.0),    // filling the cavity exactly: touches
        ([2.0, 2.0, 2.0], 0.9375), // nearly filling it
    ] {
        assert_eq!(collides(&m, c, h), oracle(c, h), "{c:?} {h}");
    }
}

#[test]
fn a_box_in_a_cavity_touching_the_inner_wall() {
    let outer = Cell::new([0.0; 3], [4.0; 3]);
    let cavity = Cell::new([1.0; 3], [3.0; 3]);
    let inner = Cell::new([1.0, 1.5, 1.5], [1.5, 2.5, 2.5]);
    let m = boxes_mesh(&[outer, cavity, inner], &[true, false, true]);
    let oracle = |c: [f64; 3], h: f64| {
        let p = Cell::around(c, h);
        (outer.meets(&p) && !cavity.holds_strictly(&p)) || inner.meets(&p)
    };
    for (c, h) in [
        ([1.25, 2.0, 2.0], 0.125),
        ([2.5, 2.0, 2.0], 0.25),
        ([1.75, 2.0, 2.0], 0.25),
        ([1.75, 2.0, 2.0], 0.125),
    ] {
        assert_eq!(collides(&m, c, h), oracle(c, h), "{c:?} {h}");
    }
}

/// A box `[0, 2] × [0, 1] × [0, 1]` whose top face is fanned about a
/// vertex `(1, 0, 1)` on its front edge, which the front face does not
/// have (a T-junction), optionally closed by the zero-area triangle CAD
/// exporters write there.
fn t_junction_box(fill: bool) -> PolygonMesh {
    let mut v = corners(&Cell::new([0.0; 3], [2.0, 1.0, 1.0]));
    v.push([1.0, 0.0, 1.0]);
    let mut faces: Vec<Vec<usize>> = CUBE_QUADS
        .iter()
        .filter(|q| **q != [4, 5, 7, 6])
        .map(|q| q.to_vec())
        .collect();
    faces.extend([vec![4, 8, 6], vec![8, 7, 6], vec![8, 5, 7]]);
    if fill {
        faces.push(vec![4, 5, 8]);
    }
    PolygonMesh::new(v, faces)
}

#[test]
fn t_junctions_enclose_with_or_without_their_fill() {
    for fill in [false, true] {
        let m = t_junction_box(fill);
        let soup = clean_soup(&m).unwrap();
        assert_eq!(soup.solids(), 1, "fill {fill}");
        assert_eq!(soup.split_edges, 1, "fill {fill}");
        assert_eq!(soup.dropped_zero_area, usize::from(fill));
        assert!(collides(&m, [1.0, 0.5, 0.5], 0.25), "fill {fill}");
        assert!(!collides(&m, [3.0, 0.5, 0.5], 0.25));
    }
}

#[test]
fn a_fin_on_a_closed_box_is_a_surface_beside_a_solid_box() {
    let mut m = boxes_mesh(&[Cell::new([0.0; 3], [1.0; 3])], &[true]);
    // Corners 4 = (0, 0, 1) and 5 = (1, 0, 1): the top front edge.
    m.vertices.push([0.5, -1.0, 1.5]);
    m.faces.push(vec![4, 5, 8]);
    let soup = clean_soup(&m).unwrap();
    let kinds: Vec<ComponentKind> = soup.components.iter().map(|c| c.kind).collect();
    assert_eq!(kinds, [ComponentKind::Solid, ComponentKind::Surface]);
    assert_eq!(soup.set_aside, 1);
    assert!(collides(&m, [0.5; 3], 0.25));
    assert!(!collides(&m, [0.5, -0.5, 2.0], 0.1));
}

#[test]
fn inward_closed_input_is_turned_and_reported() {
    let cells = [
        Cell::new([0.0; 3], [1.0; 3]),
        Cell::new([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
    ];
    let m = boxes_mesh(&cells, &[false, false]);
    let soup = clean_soup(&m).unwrap();
    assert!(soup.inverted);
    assert!(body(&m).report().inverted);
    assert!(collides(&m, [0.5; 3], 0.25));
    assert!(collides(&m, [1.5, 0.5, 0.5], 0.25));
}

#[test]
fn a_closed_mesh_crossing_itself_encloses_by_its_winding_number() {
    // A unit box whose top corner (1, 1, 1) is pulled through the bottom
    // face: a closed cycle that crosses itself. Near the corner (0, 0, 0)
    // the surface is the box's, winding number 1.
    let mut m = boxes_mesh(&[Cell::new([0.0; 3], [1.0; 3])], &[true]);
    m.vertices[7] = [0.5, 0.5, -2.0];
    assert_eq!(kinds(&m), (1, 0));
    assert!(collides(&m, [0.125, 0.125, 0.25], 0.0625));
}

#[test]
fn a_double_sided_closed_box_still_encloses() {
    let mut m = boxes_mesh(&[Cell::new([0.0; 3], [1.0; 3])], &[true]);
    let backs: Vec<Vec<usize>> = m.faces.iter().map(|f| vec![f[0], f[2], f[1]]).collect();
    m.faces.extend(backs);
    assert_eq!(kinds(&m), (1, 0));
    assert!(collides(&m, [0.5; 3], 0.25));
}

/// Random unions of boxes on a coarse grid (many shared faces, edges and
/// corners; overlaps too), some written as grid cells and some as larger
/// boxes (T-junctions where a large face meets several small ones), probed
/// by cubes on a finer grid, some touching faces exactly.
fn grid_union() -> impl Strategy<Value = Vec<Cell>> {
    prop::collection::vec(
        (prop::array::uniform3(0u8..4), prop::array::uniform3(1u8..3)),
        1..6,
    )
    .prop_map(|boxes| {
        boxes
            .into_iter()
            .map(|(lo, size)| {
                let lo = lo.map(f64::from);
                Cell::new(lo, std::array::from_fn(|k| lo[k] + f64::from(size[k])))
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(proptest_cases(48)))]
    #[test]
    fn unions_of_grid_boxes_enclose_exactly_their_union(
        cells in grid_union(),
        probes in prop::collection::vec((prop::array::uniform3(-2i32..48), any::<bool>()), 12),
    ) {
        let m = boxes_mesh(&cells, &vec![true; cells.len()]);
        let soup = clean_soup(&m).unwrap();
        prop_assert!(!soup.inverted);
        for (g, touching) in probes {
            // Centres on an eighth grid; half-size 1/16 reaches the
            // integer planes from centres at k/8 + 1/16 exactly, 1/32
            // never does.
            let c = g.map(|x| f64::from(x) / 8.0 + 1.0 / 16.0);
            let h = if touching { 1.0 / 16.0 } else { 1.0 / 32.0 };
            let expected = meets_union(&cells, &Cell::around(c, h));
            prop_assert_eq!(collides(&m, c, h), expected, "{:?} {} in {:?}", c, h, cells);
        }
    }
}

#[test]
fn sums_refuse_what_only_the_winding_number_gives_a_meaning() {
    // Sums and decompositions need solids in the strict sense
    // (`check_solid_mesh`) and refuse these with a typed error, never
    // reinterpreting them.
    let welded_touching = clean_soup(&boxes_mesh(
        &[
            Cell::new([0.0; 3], [1.0; 3]),
            Cell::new([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
        ],
        &[true, true],
    ))
    .unwrap()
    .mesh;
    let cavity = boxes_mesh(
        &[Cell::new([0.0; 3], [4.0; 3]), Cell::new([1.0; 3], [3.0; 3])],
        &[true, false],
    );
    let mut crossing = boxes_mesh(&[Cell::new([0.0; 3], [1.0; 3])], &[true]);
    crossing.vertices[7] = [0.5, 0.5, -2.0];
    for (name, m) in [
        ("welded touching boxes", welded_touching),
        ("a cavity", cavity),
        ("a T-junction", t_junction_box(false)),
        ("a mesh crossing itself", crossing),
    ] {
        assert!(dymsum::check_solid_mesh(&m).is_err(), "{name}");
    }
}

#[test]
fn a_box_inside_another_sharing_faces_the_same_way_round_encloses() {
    // Found by the grid-union proptest: a face two coincident solids share
    // the same way round was dropped as a duplicate, which opened both.
    let cells = [
        Cell::new([0.0, 0.0, 1.0], [1.0, 2.0, 2.0]),
        Cell::new([0.0, 0.0, 1.0], [2.0, 2.0, 2.0]),
    ];
    let m = boxes_mesh(&cells, &[true, true]);
    let soup = clean_soup(&m).unwrap();
    assert!(soup.weights.contains(&2), "the shared faces count twice");
    for c in [[0.0625, 0.0625, 1.0625], [0.5, 1.0, 1.5], [1.5, 1.0, 1.5]] {
        assert!(collides(&m, c, 1.0 / 32.0), "{c:?}");
    }
}

#[test]
fn a_t_junction_body_keeps_its_inside_when_turned() {
    // The moving body has the T-junction: posed, its vertex on the edge is
    // rounded off the edge, so the cleaning splits the long edge's triangle
    // there (the enclosing part closed edge for edge in any pose).
    let m = t_junction_box(false);
    let soup = clean_soup(&m).unwrap();
    let n = soup.mesh.faces.len();
    assert!(
        n > 13,
        "the front face is split at the T-junction: {n} triangles"
    );
    let tri = body(&m);
    let probe = body(&cube([0.0; 3], 0.0625));
    let checker = SceneChecker::new(&tri, &[probe]).unwrap();
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..300 {
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let axis = DVec3::new(next(), next(), next());
        let angle = 3.0 * next();
        let r = Rotation::from_axis_angle(axis, angle).unwrap();
        // Posed so that the box's centre (1, 0.5, 0.5) lands on the probe.
        let t = -(r.matrix() * DVec3::new(1.0, 0.5, 0.5)) + DVec3::splat(1e-3 * next());
        assert!(
            checker.collides_at(Pose::new(r, t)).unwrap(),
            "{axis} {angle}"
        );
    }
}
