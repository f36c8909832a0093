//! Review (B): `SceneChecker::new` joins the obstacles into one `MeshBody`
//! (query/scene/checker.rs, `MeshBody::join`), and `inside_solid`
//! (now body/winding.rs) sums the signed crossings of *all* candidate
//! solid components into one winding number. A mesh may keep a shell
//! inward (LIMITS.md: "a shell consistent as given keeps its orientation";
//! only a negative total volume turns the mesh): its region has winding
//! number −1, which by the rule is inside that mesh. Where another
//! obstacle encloses the same region (+1), the joined sum is 0: a robot
//! lying inside *both* obstacles is called free by the scene, though each
//! obstacle alone says it collides.

use dymsum::query::{MeshBody, SceneChecker};
use dymsum::{DVec3, PolygonMesh, Pose, Rotation};

/// Outward quads of the unit cube's corners `i` (bit k: coordinate k high).
const OUT: [[usize; 4]; 6] = [
    [0, 4, 6, 2],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 2, 3, 1],
    [4, 5, 7, 6],
];

/// Appends the box `[lo, hi]³` to a mesh, outward or inward.
fn push_box(m: &mut PolygonMesh, lo: f64, hi: f64, outward: bool) {
    let base = m.vertices.len();
    for i in 0..8 {
        let pick = |k: usize| if i >> k & 1 == 0 { lo } else { hi };
        m.vertices.push([pick(0), pick(1), pick(2)]);
    }
    for f in OUT {
        let mut f: Vec<usize> = f.iter().map(|v| v + base).collect();
        if !outward {
            f.reverse();
        }
        m.faces.push(f);
    }
}

fn mesh(boxes: &[(f64, f64, bool)]) -> MeshBody {
    let mut m = PolygonMesh::new(Vec::new(), Vec::new());
    for &(lo, hi, out) in boxes {
        push_box(&mut m, lo, hi, out);
    }
    MeshBody::new(&m).unwrap()
}

#[test]
fn a_robot_inside_two_obstacles_collides() {
    // Obstacle A: a big box, and apart from it a small box exported
    // inward (its winding number −1: inside A by the rule; A's total
    // volume is positive, so A is not turned).
    let a = mesh(&[(0.0, 10.0, true), (20.0, 21.0, false)]);
    assert!(!a.report().inverted);
    // Obstacle B: a solid box around the same place.
    let b = mesh(&[(19.0, 22.0, true)]);
    // The robot: a small box, placed at the centre of the small box.
    let robot = mesh(&[(-0.1, 0.1, true)]);
    let pose = Pose::new(Rotation::IDENTITY, DVec3::splat(20.5));
    let alone_a = SceneChecker::new(&robot, std::slice::from_ref(&a)).unwrap();
    let alone_b = SceneChecker::new(&robot, std::slice::from_ref(&b)).unwrap();
    assert!(alone_a.collides_at(pose).unwrap(), "inside A (winding −1)");
    assert!(alone_b.collides_at(pose).unwrap(), "inside B (winding +1)");
    let both = SceneChecker::new(&robot, &[a, b]).unwrap();
    assert!(
        both.collides_at(pose).unwrap(),
        "inside both obstacles, yet the joined scene calls it free"
    );
}
