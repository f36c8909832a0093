//! Exact state checks of a [`SceneChecker`]: the body's tree walked at the
//! pose against the scene's, the exact triangle test, then containment by
//! the winding number (the contact rule in `scene::checker`'s docs).
//!
//! # Containment first
//!
//! Before the walk, the first [`POINTS_ASKED_FIRST`] points of the
//! containment test (a body component's vertex in a scene solid, a scene
//! component's corner in a body solid, in the test's order, counted before
//! its box filters, so that the first asking scans at most that many
//! however many the filters drop: a soup's thousands of components wait
//! for the walk) are asked; one inside decides a collision. Where one body lies
//! deep in the other, the walk meets many triangle pairs that are close
//! but do not cross before it reaches one that does, while a ray decides
//! at once: on the 16 seeded robot part pairs and the irb6640 visual
//! cylinder against the irb2400 link 1 (2 × 600 states each, interleaved,
//! best of three), the geometric means of the medians fell from 5.07 to
//! 4.39 µs, of the 99th percentiles from 64.3 to 51.7 µs, of the means
//! from 11.6 to 9.2 µs; on the cylinder pair's random states the 99th
//! percentile fell from 343 to 35 µs (docs/BENCHMARKS.md, "Containment
//! first").
//!
//! Since the inside grids, the first asking reads the grids alone
//! (`one_inside_by_grids`): a point read in a classified cell is decided
//! as before, and the first point no grid reads stops the asking as an
//! error of the first asking (never shown: the walk, then the whole
//! asking from the first point, follow, as for any error below), so no
//! segment, list or ray is made before the walk. Near contact those were
//! made twice (the first asking's, then the second's again from its own
//! first point), and a point deep in the other body lies in a classified
//! cell. On the Centauro knee against the TALOS arm link
//! (example-robot-data, 30 near and 30 random states with their
//! bisections) 629 M → 456 M and 591 M → 428 M instructions (−28%), the
//! near median from Python 38.0 → 22.1 µs (python-fcl 21.6); the `SEED=5`
//! sample of 16 pairs −0.75%; the cylinder pair's random 99th percentile
//! in Rust 40.8 → 49–50 µs, from Python 39 µs against fcl's 94
//! (docs/BENCHMARKS.md, "A new seeded sample"). Test
//! `the_first_asking_reads_the_grids_only`. An independent review
//! (2026-12-02, ninth stop) read every path of the grids-only asking:
//! each point is excluded by a box, read by a grid, or stops it with the
//! error (so an "outside" covers every point asked, and the second asking
//! resumes after them with the same numbering), the body's vertices are
//! read as `MeshBody::inside_solid` reads them, and the error reaches no
//! caller; its remark on a misplaced doc line is applied.
//!
//! Why the answer is the same. Before, the answer was `W ∨ C`: the walk
//! `W`, then the containment test `C`, which asks its points in a fixed
//! order and stops at the first inside. Each point's answer and `W` are
//! deterministic, and the caches the two share (posed vertices, node
//! boxes, by the query's epoch) hold the same values whichever runs
//! first. So asking `C`'s first points before `W` cannot change the
//! disjunction: a first "inside" is the old answer too (the walk meets, or
//! the same point comes first in the full test), a first "outside" is what
//! the full test would find again for those points, so it resumes after
//! them. Nor is a first "inside" a wrong collision where it differs from
//! the exact containment (the test's precondition, that the point lies on
//! none of the other body's triangles, which the walk used to establish):
//! the points asked are corners of triangles the bodies keep, the test
//! reads only kept triangles, and every kept one is in the walked trees,
//! so a point on one is a contact, which collides. An error of the first
//! asking (a point neither read from the grid nor decided by a ray, never
//! seen) is not final: the walk may still meet, and only when it does not
//! is the containment asked again from the first point, so an error is
//! returned exactly where the walk-then-containment order returns one (both
//! askings read the same grid; since the grid, at a subset of the states
//! that returned one before it).
//!
//! Since "Segments between points" (`body::winding`), a point may take
//! its windings along a segment from the point asked before it. Where no
//! point asked lies on a triangle, each answer is still the point's own
//! (the segment's count is exact, and a point no ray decides may now be
//! decided: errors at a subset again), so the argument above stands.
//! Where one does, the bodies touch and the state collides; a later
//! point's windings may then be off by that triangle's weight, and its
//! answer differ from its own ray's (an independent review saw it in
//! about 1% of its contact states' first askings). A wrong "inside" is
//! still a collision; a wrong "outside" or an error in the first asking
//! is not final, and the walk meets at that triangle. The full asking
//! comes only after a walk that met nothing, when no point lies on a
//! triangle, and the segments' last point is not carried from one asking
//! to the other.
//!
//! An independent review (2026-11-30) checked this argument and the code:
//! the numbering of points is the same in both askings (then counted after
//! the deterministic box filters; since the review, before them, which
//! depends on nothing but the order, the same in both), the shared caches are
//! written with identical values, `parity` is reset on every path, and no
//! new panic is reachable. Its randomized comparison, 24,000 poses of
//! bodies against one to three obstacles (boxes on a quarter grid, nested
//! shells, cavities, flipped and open boxes, double-sided squares, grid
//! soups; quarter, half and generic turns), found no disagreement with
//! the old order, nor between the split and the whole containment test
//! at every split point 0–20 (480,000 checks).
//!
//! # The roots first
//!
//! Before anything else, the walk's own first tests are made on the two
//! roots: the body's root box carried to the pose (grown by the posing's
//! rounding bound `pad`, so that it holds every posed vertex
//! `fl(M v + t)`) against the scene's root box; then, where the matrix is
//! near a rotation (`pose_skew`), the scene's root box carried back
//! against the body's (grown by `back_pad`, as in the walk) (both
//! `carry_unless_parted`); and, after the grids (*The order* below),
//! their oriented boxes (`oriented_roots_apart`; `solid::obb`,
//! certified). Where one parts them, the state is free. Why that is
//! exact: each test separates a convex set holding every point of the
//! posed body's hull (the hull of
//! the posed vertices; the carrying back is affine, so its argument holds
//! for every point of the hull, not only for triangles) from a convex set
//! holding the scene's. So no triangles meet (the walk would part this
//! pair first), no posed body vertex lies in a scene solid and no scene
//! corner lies in a posed body solid (a solid, the region of non-zero
//! winding number, lies in the hull of its triangles). The old order gave
//! `Ok(false)` there too, or, for a point whose own tests did not decide
//! (never seen: a point the oriented boxes place outside, or a scene
//! corner parted by the carried root boxes by less than the containment's
//! looser `back_pad`, which its filter lets through to a ray), the
//! undecided error: the answer is now the proved one. The boxes computed
//! stay in the query's caches, and the walk does not test the roots' pair
//! again (where the matrix is not near a rotation it then skips the
//! carried-back test there: a culling test skipped, never a pair
//! dropped). On robot part pairs, random free states whose roots are
//! parted (parry, which does not ask containment, answers them in 0.2 to
//! 0.3 µs) took about 3,000 to 4,000 instructions, the containment test's
//! filters and tree queries first (docs/BENCHMARKS.md, "The roots first").
//!
//! An independent review (2026-12-01) found the argument and the code
//! sound: the world box's rounding (about `20u (reach + |t|)` against
//! `pad = 128u (reach + |t|)`), the carrying back for points of the hull,
//! the oriented boxes (NaN or infinite slack proves nothing apart), empty
//! scenes, the caches at index 0 holding exactly the walk's values, and
//! the early-stopping list of scene corners and the short ranges of body
//! components asked directly (both below) ask the same points in the same
//! numbering. Its randomized comparison with the old order (6,000 states:
//! boxes, tetrahedra and 27-cube bodies; random and quarter turns; offsets
//! 1 to 3·10⁸; walls 0 to 10⁵ ulps past the extreme vertex, tight rooms,
//! slanted and diagonal scenes, 64-cube scenes; 2,813 with parted roots)
//! found no disagreement. Its remarks are applied: the carried-back test
//! is made only where the matrix is near a rotation (it had relied on
//! `Rotation`'s invariant alone), the carrying is computed only past the
//! first test and once a query, the error sentence above, the components'
//! section below, and the test's wording.
//!
//! *The order* (2026-12-02, thirteenth stop). The two box tests come
//! first (`carry_unless_parted`), then "One cell holds a body" (below),
//! then the oriented boxes (`oriented_roots_apart`), then the rest. Each
//! of these decides only what it proves, whatever ran before it (none
//! assumes another failed), so the order changes no answer, only the
//! cost; the walk still starts past the roots' pair, as all three ran
//! before it. The grids go before the oriented boxes because a state a
//! grid holds whole is typically one whose roots' oriented boxes overlap
//! (the small part near or inside the large one's box): there the
//! fifteen-axis test (about 500 instructions) parted nothing, while the
//! grid's gate (the other box at most two cells wide) costs a few
//! comparisons where it does not apply. On the middle states of four
//! pairs parry's BVH test answers fastest (docs/BENCHMARKS.md, "Three
//! timings"), 1,232 to 2,510 instructions a state became 835 to 1,736.
//! Where the oriented boxes would part the roots and a grid's gate
//! applies but the grid does not decide, the grid's work comes first: the
//! whole samples' random states are still cheaper (`SEED=5` −0.4%,
//! `SEED=79` −1.7%).
//!
//! An independent review (2026-12-02) found the order sound: nothing on
//! the grids' path reads the posed oriented boxes (`obb_cache` slot 0) or
//! assumes them overlapping, every answer on it is exact (an undecided
//! point falls through), the walk still runs only after all three tests,
//! and the slot holds the same value for it. Its randomized check (54,000
//! states: slanted slabs, two blocks and an open slab against a speck, a
//! flake and a cube, quarter and generic turns) matched the walk followed
//! by the containment test on every state, 10,779 of them with the
//! oriented boxes apart (10,651 decided by the grids' path, all free).
//!
//! # One cell holds a body
//! Past the roots' box tests (before their oriented boxes: "The order"
//! above), and before anything is asked, each body's inside
//! grid (`body::inside_grid`) may hold the other body whole: where the
//! other's box meets at most [`CELLS_MOST`] cells of it (it is at most
//! [`CELLS_ACROSS`] cells wide, else the grid is not asked), all
//! classified alike, the state's answer is that class, inside a solid
//! (collides) or outside every one (free). Two cases:
//!
//! 1. *The posed body's box in the scene's grid*, where every scene
//!    triangle is a solid's (a grid knows only its solids' triangles).
//!    The box is the walk's own first one (`carry_unless_parted`): the
//!    body's root box carried to the pose and grown by `pad`, so it holds
//!    every posed vertex, hence the posed triangles and the posed body's
//!    hull. The cells it meets meet no scene triangle (a classified cell
//!    meets no triangle of a solid, and the box lies in their union), so
//!    no posed body triangle meets a scene triangle; every point of the
//!    box, each posed body point among them, lies in one of them and has
//!    its answer, the same for all;
//!    and no scene corner lies in a posed body solid, which lies in the
//!    posed body's hull, in the box, where no scene triangle is. Outside:
//!    nothing meets and nothing is inside, free. Inside: every body
//!    vertex is in a scene solid, which the containment test's first body
//!    point asked would find (the scene's oriented box excludes no point
//!    of a solid): collides. The body's own triangles may be of any kind.
//! 2. *The scene's box carried back into the body's grid*, where every
//!    body triangle is a solid's and the matrix is near a rotation with
//!    `det M > 0.5` (the conditions of "The grid at a pose"). The box is
//!    the scene's root box carried back as "The corners together" carries
//!    the corners' box (`carried_back`), whose argument gives: for every
//!    point `p` of the scene's box, the box of half-width `e₁` about
//!    `B(p)` lies in it. Let `U` be the union of the closed cells it
//!    meets, all classified alike: no body triangle of the body's frame
//!    meets `U`, so each of its points lies more than `e₁` from every
//!    such `B(p)` (in the largest coordinate difference). Moving each vertex straight from
//!    `vᵢ` to `B(Pᵢ)` moves every triangle point by at most `e₁`, so none
//!    passes through `B(p)`: the winding numbers about `B(p)` are the body
//!    frame's, the class of the cell of `U` that holds it, and by the map
//!    `B` the posed body's about `p`. For the same reason no posed body
//!    triangle meets a scene point (its image under `B` is within `e₁` of
//!    a body-frame point, which lies more than `e₁` from `B(p)`), and no
//!    posed body point lies in the scene's box (its image is within `e₁`
//!    of a body-frame point, which is not in `U`, while every point of
//!    `B` of the box has its `e₁`-box in `U`), so none is inside a scene
//!    solid. Outside: free; inside: every scene point lies in a body
//!    solid, and the containment test's first scene corner asked would
//!    find it: collides. The scene's triangles may be of any kind.
//!
//! Case 1's box is the roots' own (`pad` is 64 units of rounding against
//! about 20 the posing makes; "The roots first", reviewed); no test fails
//! without it, as it matters only where cells are about an ulp wide.
//!
//! Either answer is the proved one, and the old order's where that
//! returned one (an error of an undecided point becomes the answer).
//! Several cells rather than one: each point of the box lies in one of
//! them and takes its answer, the same for all (`InsideGrid::classify_cells`);
//! a box in one cell straddles a plane too often to pay. Counted as
//! `ContainmentStats::bodies_by_grid`. Where a small closed part lies
//! in the open, or deep inside the other, this replaces the walk and the
//! containment test: the Centauro elbow against the Solo12 hip (random
//! states, Rust) took a median 1.40 µs, now 0.43–0.58 µs (parry's BVH
//! test 0.27–0.31 µs), the human abdomen against the TIAGo omni base 1.02
//! → 0.50 µs (docs/BENCHMARKS.md, "One cell holds a body"). Real meshes
//! with open parts on the relevant side skip it (the TALOS gripper base
//! has two surface components: its 1.6–1.7× parry is the walk's).
//!
//! An independent review (2026-12-02) found the argument and the code
//! sound: both cases' rounding (`e₁ ≤ 2 pad + 3 · 2⁻⁴⁰ reach`, `e₂` within
//! the `16u(|p| + |t|)` term at the box's largest corner, the sides'
//! rounding within the doubled growth), joined scenes (winding numbers
//! constant per source on a region without triangles), empty and
//! subnormal grids, NaN and infinite boxes, and `classify_cells` against
//! brute force on 800,000 boxes (on planes, an ulp off, partly outside,
//! `lo > hi`, NaN; 122,087 answered, all alike; every one of 11,121
//! face-adjacent classified pairs of one class). Its randomized comparison
//! with an oracle that reads no grid (`surfaces_touch`, then exact rays):
//! 300,960 states (shells with cavities, nested and touching solids, thin
//! slabs, four joined obstacles whose windings cancel, open sheets and
//! boxes; scales 10⁻¹⁰⁰ to 10¹⁰⁰, offsets to 10⁸, quarter, nudged and
//! generic turns, boxes on grid planes), 35,054 decided by a grid, no
//! disagreement. It found that dropping the solids' condition, or reading
//! only the first and last cells, gives wrong answers its harness and the
//! tests catch, and that without case 2's growth the two rounding tests
//! fail. Its wording remarks are applied.
//!
//! # No triangle by a body
//! Where the other body's box is at most [`CELLS_ACROSS`] cells of a
//! body's grid wide but the grid cannot answer (a cell there meets a
//! triangle, the box leaves the grid's extent or would read more than
//! [`CELLS_MOST`] cells, or the body has triangles of surfaces as well as
//! its solids', which no grid knows), or the other body is at most
//! [`SMALL_BESIDE`] as wide as the body (a body of surfaces alone has no
//! grid), the body's own tree is asked whether any of its
//! triangles may meet that box (`some_triangle_may_meet`: a triangle
//! whose box meets it and whose plane, a certified separating axis, does
//! not part them; all triangles, of solids and of surfaces). Where none
//! may, one point of the containment test decides the state:
//!
//! 1. *No scene triangle meets the posed body's box* (case 1's box, which
//!    holds the posed body's hull): no posed body triangle meets a scene
//!    triangle; no scene corner lies in a posed body solid (a corner of a
//!    scene triangle is outside the box, and a body solid inside it); and
//!    the box, convex, hence connected, meets no scene triangle, so every
//!    source's winding number is the same about each of its points, each
//!    posed body point among them. The containment test's first point
//!    decides: where the scene has a solid, the first body component's
//!    vertex (inside: it is in a scene solid, collides; outside: no body
//!    point is, free); where it has none, its first scene corner, which it
//!    lists only inside the box, so none is listed: free.
//! 2. *No body triangle of the body's frame meets the scene's box carried
//!    back* (case 2's box `b`, the matrix near a rotation with `det M >
//!    0.5`): case 2's argument with `b` for `U`. Each body triangle point
//!    lies more than `e₁` from every `B(p)` (else it would be in the
//!    `e₁`-box about `B(p)`, which lies in `b`), so the winding numbers
//!    about `B(p)` are the body frame's, and by the map `B` the posed
//!    body's about `p`; they are the same for every `p` of the scene's box,
//!    as `b`, convex, meets no body triangle; no posed body triangle meets
//!    a scene point, and no posed body point lies in the scene's box.
//!    The containment test's first scene corner (numbered after the body's
//!    points where the scene has a solid, else first:
//!    `first_scene_corner`) decides: inside, every scene point is in a
//!    body solid (collides); outside, none is (free).
//!
//! The point is asked as the containment test asks it (grid, segment from
//! a classified cell, or ray), on none of the other body's triangles, so
//! its answer is exact; where it is not decided (never seen) the state
//! is checked as any other. Counted as `ContainmentStats::bodies_by_region`.
//! The box tests are culling tests that prove a miss; a false "may meet"
//! only leaves the state to the walk. Where a small part lies in a mixed
//! cell of a large one modelled in other units (the Centauro BallHand, in
//! millimetres, about the TIAGo Pro suspension link, in metres; the
//! Centauro wheel 23 collision mesh about the G1 ankle roll link), this
//! replaces the walk and asks one corner where five were asked; a G1
//! finger link in the open shells of the TIAGo Pro omni base (which has
//! no solid, so no grid) is free at once (docs/BENCHMARKS.md, "No
//! triangle by a body"). Test: `a_body_no_triangle_comes_near_is_decided_by_one_point`
//! (every answer against the walk and the whole containment test; both
//! answers decided by one point in each case, with and without solids on
//! the small side, where the numbering of the scene's corners differs;
//! open large sides, with no grid; corners on a wall up to the rounding,
//! far from the origin) and `the_plane_test_parts_no_box_touching_a_huge_slanted_face`
//! (the plane test's slack).
//!
//! An independent review (2026-12-02, twelfth stop) found no fault: the
//! boxes are the ones the argument needs (case 1's is the roots' own,
//! cached; case 2's is case 2's `carried_back`, over every scene
//! triangle), `mag` bounds every point the plane test projects (a zero
//! or overflowing normal parts nothing), a box that is not finite may
//! meet, joined scenes keep each source's number, the point asked is the
//! containment test's own (case 1: component 0's vertex, the length-one
//! range skipping the components' filter; case 2: `first_scene_corner`),
//! and an undecided point leaves the state to the walk. Its randomized
//! comparison with an oracle that reads no grid and no tree (every
//! triangle pair exactly, each component's point by its own exact ray):
//! 3,123,200 states (coarse shells with cavities, nested and inward
//! shells, slanted and tetrahedral shells, open boxes with solids inside,
//! sheets, joined scenes of two or three obstacles; cubes, flakes, a soup
//! of 27 cubes, tiny shells; units 10⁻³ to 10³, sizes down to 10⁻⁷ of the
//! large side, offsets 10⁶ to 10⁸; exact, nudged and generic turns;
//! corners on faces, one ulp off, coplanar flakes), 482,883 decided by
//! the rule (both answers in both cases), no disagreement; a slanted face
//! of edge 10⁴ to 10⁸ by a tiny cube a few roundings into or off it,
//! 100,000 states, none wrong. Of its fourteen mutants the tests catch
//! the box tests skipped, each wrong point, surfaces ignored, the solids'
//! root for the scene's, and the unpadded boxes (case 2's growth by the
//! older rounding tests alone); its remarks are applied: the slack, which
//! no test pinned (one state in 6,000 of its slanted-face harness went
//! wrong without it), now fails the slanted-face test, the far-offset
//! and wall-contact states were added, and the wording above. The
//! quarter-width gate came after the review; a gate only decides where
//! the tree is asked, and the argument holds for any box.
//!
//! # No triangle against a leaf's box
//! A body triangle the walk reaches meets a scene leaf's triangles only
//! where its exact box (of its posed corners) meets the leaf's box and a
//! scene triangle's box; then the certified triangle test
//! (`kernel::separation::triangles_apart`, the scene triangle's normal
//! first) and the exact one decide. A certified test of the triangle
//! against the leaf's box (its normal and nine edge axes) was made between
//! the two: on robot parts near contact, past the oriented boxes, it
//! seldom parted what the boxes left (none of 1,808 pairs on a slow state
//! of the TIAGo wheel against the Centauro forearm, where the triangle
//! test parted every one on its first axes) and, when it could not, cost
//! every axis. Dropped: a culling test, so no answer changes. The state
//! checks' instructions (near-contact states and their bisections, 300
//! a pair): the wheel and forearm −28%, a PR2 forearm roll link against
//! the Centauro link 1 −17%, the PMB2 caster against the TIAGo Pro
//! suspension, where it parted most, −1.7%; 16 seeded pairs of
//! example-robot-data −7.8% (docs/BENCHMARKS.md, "Segments between points
//! and no triangle against a leaf's box").
//!
//! # The grid at a pose
//! A scene corner `p` is asked about the body's solids at the pose `(M, t)`
//! (`M` the rounded matrix, `det M > 0`, `MᵀM` within `2⁻⁴⁰` of the
//! identity, else the grid is not read). The answer wanted is the winding
//! numbers (per source) about `p` of the posed float vertices
//! `Pᵢ = fl(M vᵢ + t)`. The map `B(x) = Mᵀ(x − t)`, in exact arithmetic, is
//! affine and invertible, so it keeps whether each winding number is zero
//! (with positive determinant, each number itself): the answer is that of
//! the triangles on `B(Pᵢ)` about `B(p)`. Each `B(Pᵢ)` lies within `e₁` of
//! `vᵢ` per coordinate (`Mᵀ` times the posing's rounding, up to √3 times
//! it, which twice `pad` covers, and `MᵀM − I` times the body's size),
//! and the computed corner carried back,
//! `back = fl(Mᵀ(p − t))`, within `e₂` of `B(p)` (its rounding); the
//! corner filter's `back_pad` bounds `e₁ + e₂` (the comment at it). Move
//! each vertex straight from `vᵢ` to `B(Pᵢ)`: every point of every
//! triangle moves at most `e₁` per coordinate, so if no triangle of the
//! body's frame comes within `e₁ + e₂` of `back`, none of the moving ones
//! ever passes through `B(p)`, and the winding numbers about `B(p)` do not
//! change on the way: they are the body frame's. And `B(p)` lies within
//! `e₂` of `back`. So when the box of half-width `back_pad` about `back`
//! lies in a classified cell of the body's grid (which meets no triangle
//! of a solid, `body::inside_grid`), the cell's answer is the answer at
//! the pose, and `p` is on no triangle; otherwise the ray decides, as
//! before. On the Centauro pelvis against the G1 ankle roll link
//! (example-robot-data, 300 random states), where the rays through the
//! posed pelvis were 92% of the slow states, the instructions fell from
//! 95.5 to 18.3 million (docs/BENCHMARKS.md, "Inside grids").
//!
//! An independent review (2026-11-30, night) found the grid's argument,
//! the index arithmetic (200,000 `classify` calls against exact rationals,
//! points on planes, NaN, infinities, half-widths to 10³⁰⁸) and this
//! pose argument sound (the worst `(e₁ + e₂) / back_pad` over random
//! poses at every scale, in exact rationals: 5.7 · 10⁻⁵), and 144,311
//! state checks agreed with an oracle that reads no grid (placed bodies,
//! `surfaces_touch` and the ray; cavities, nested, touching and joined
//! solids, corners on grid planes and cell corners, scales 2⁻⁶⁰ to 2¹⁷).
//! It found one wrong answer, at subnormal sizes, mended: a region was
//! asked from its first cell's computed midpoint, which rounds outside a
//! cell of zero width at an odd multiple of the least subnormal (a cube 8
//! of them wide was called empty inside); the midpoint is now clamped to
//! the cell (`body::inside_grid`'s test
//! `a_region_is_asked_from_inside_its_first_cell_at_subnormal_sizes`).
//! Its wording remarks are applied.
//!
//! # The corners together
//! Where the grid is read at the pose at all (below: the matrix near a
//! rotation, `det M > 0.5`) and at least [`CORNERS_TOGETHER`] scene corners
//! are in the posed body's reach (the list cut at as many as the asking
//! may reach), the box `R` holding them (exact: their own coordinates'
//! least and greatest) is asked of the body's grid first, as a whole. Its
//! eight corners are carried back as a single corner is, and their box
//! grown by twice `back_pad` at their largest coordinates
//! (`carried_back`, shared with the next section, whose argument this
//! is): for each scene corner `p` in `R`, `B(p)` lies in `B(R)`, the hull
//! of the eight exact images, each within `e₂` of its computed one, so the
//! box of half-width `e₁` about `B(p)` lies in the computed corners' box
//! grown by `e₁ + e₂ ≤ back_pad`, and the growth by twice that covers the
//! sides' own rounding. When that grown box lies in one classified cell,
//! so does the box about each `B(p)`, and "The grid at a pose" gives each
//! corner the cell's answer, the exact one (asking a corner alone gives
//! the same wherever it decides; where its own box leaves the cell and
//! every ray is degenerate, it would have been an error): every corner
//! asked is outside (the test goes on as if none were asked), or every
//! one inside (a collision, if the asking includes one of them: test
//! `the_corners_together_answer_only_for_the_corners_asked`). Otherwise
//! each corner is asked as before. On a Cassie hip pitch link
//! (47 solids, 0.25 long) inside the box of a Centauro head base (268
//! long, in mm) the 47 corners are one question of the grid. Test:
//! `the_corners_together_read_no_cell_the_rounding_may_leave` (it fails
//! when the box is not grown). An independent review (2026-12-01, sixth
//! stop) checked the asked range's arithmetic against the corner loop's
//! numbering, the scratch left whole by the early return, the rounding
//! argument (`back_pad` grows with the coordinates, so its value at the
//! largest covers every corner), and that `InsideGrid::classify` computes
//! the same box as before, bit for bit; its two coverage remarks are
//! applied (the asked-range test above, and
//! `many_corners_by_a_face_read_one_culled_list`), and its wording ones.
//!
//! Past the grid, each corner is decided by a segment from the corner
//! decided before (`body::winding`, "Segments between points") or, for the
//! first, from a point one or two cells away in an outside cell, or in an
//! inside cell whose windings the grid kept ("A start outside" there;
//! tests `a_first_corner_starts_from_an_outside_cell`,
//! `a_first_corner_deep_in_a_solid_starts_from_an_inside_cell`).
//! The solid components a segment between two corners counts are those
//! whose posed boxes meet the segment's box; that box lies in the
//! corners' box, so they are among the components whose posed boxes meet
//! the corners' box, found and posed once per state, at the first such
//! segment (the same set, so the same windings). Posing every component's
//! box for every segment had been a quarter of the slowest head / hip
//! states. An independent review (2026-12-01, seventh stop) checked that
//! `known` only ever holds a corner of the list (read outside by the grid,
//! or decided), so every such segment's box lies in the corners' box, and
//! that the closed `meets` keeps the set and its order the same.
//!
//! # The body's components near the scene
//! The containment test asks one vertex of every body component whether
//! it lies in a scene solid (posing it, then the scene's oriented box or
//! grid or a ray). A body of many components (a visual mesh of hundreds
//! of shells) posed them all at every state: on the Centauro pelvis (945
//! components) against the G1 ankle link, 55% of a typical state check.
//! A body of 16 to 2¹⁶ components keeps a tree over those vertices in its
//! own frame (`MeshBody::component_points`), and only the components the
//! tree finds in the scene's solids' box carried back are asked, in the
//! same order.
//!
//! Why the answer is the same. Let `S` be the box of the scene's solid
//! components (the root of their tree) and `p̃` a component's vertex `v`
//! posed in floats. Carried back by `B(x) = Mᵀ(x − t)` (exact), `p̃ ∈ S`
//! puts `B(p̃)` in `B(S)`, the hull of its eight corners carried back,
//! each computed within `e₂` of the exact (as a scene corner above), and
//! `B(p̃)` lies within `e₁` of `v` ("The grid at a pose"): so `v` lies in
//! the box of the eight computed corners grown by `e₁ + e₂`, which
//! `back_pad` bounds (at the corners' largest coordinates); the box is
//! grown by twice that, for its sides' own rounding (`fl(lo − 2b) ≤ lo −
//! b`: a side's rounding is a few `u` of `|lo| ≲ 1.74 (|S| + |t|)`, far
//! below `b ≥ 32u (|S| + |t|)`; `10⁻³⁰⁰` covers subnormal sizes). Where a
//! corner's carrying overflows (scene coordinates near the largest float,
//! `t` near 10²⁹⁹), at most one side per axis does: that corner computes
//! to an infinity of the right sign, a NaN only where another corner
//! gives that side, and the box's `min`/`max` skip NaN. A component the
//! tree leaves out therefore has `p̃` outside `S`, so outside every scene
//! solid component's box: its grid cell (if any) says outside (a region
//! has the winding number of its points, zero there) and its ray has no
//! candidates, so it answered "outside" before (or was excluded by the
//! oriented box), never an error. The others are asked as before, in
//! increasing index, so the first "inside" or error is the same one, and
//! the numbering of "Containment first" is unchanged. Where the matrix
//! is not near a rotation (`pose_skew`), every component is asked.
//! Test: `the_components_near_the_scene_hold_every_vertex_posed_in_its_solids`
//! (a scene box with its corner exactly at a posed vertex, a few ulps
//! wide, far from the origin; it fails when the growth is dropped).
//! Typical pelvis states: 16.4 k → 10.7 k instructions
//! (docs/BENCHMARKS.md, "Motions' pair tests and many components").
//! A range of at most [`POINTS_ASKED_FIRST`] components (the first
//! asking) is asked directly, without the tree: the filter only leaves out
//! components that answer "outside", so the first "inside" or error is the
//! same, and the tree's query and sort cost more than posing a few
//! vertices. Likewise the scene's corners in the body's box are listed
//! only as far as the asking reaches (`AabbTree::for_each_meeting_while`,
//! the same order).
//!
//! An independent review (2026-12-01) found no flaw: it verified that a
//! vertex posed into `S` always lies in the carried region (the hull
//! argument per coordinate, `e₁` within `size · 2⁻³⁶` and `2 pad`, the
//! sides' rounding, subnormal sizes), that a left-out component answered
//! "outside" before (no ray candidates; a grid region of winding zero),
//! never an error (its point is finite by `check_range`), and the
//! numbering (empty scenes, `start ≥ len`, `end ≤ len`, `end = 0`). Its
//! remarks are applied: the overflow sentence and the sides' inequality
//! above, the wording of the filter's doc, and no tree query for an empty
//! range.
//!
//! [`MeshBody::inside_solid`]: crate::body::MeshBody

use std::borrow::Cow;

use glam::{DMat3, DVec3};

use super::checker::{cached, cells, triangle_box, SceneChecker, Scratch};

use crate::body::winding::{
    keep_triangles_meeting, segment_start, some_winds, Known, Listed, Placed,
};
use crate::kernel::rotation::Pose;
use crate::kernel::separation::{triangles_apart, PlaneAxis};
use crate::query::checker::Checker;
use crate::query::error::QueryError;
use crate::solid::aabb::{Aabb, AabbTree};
use crate::solid::intersect::triangles_meet;
use crate::solid::obb::pose_skew;

/// The most triangles the segments between scene corners read from a list
/// made once, instead of walking the tree each ("Segments between points"
/// in `body::winding`): where the corners spread wider, each walks.
const TRIANGLES_LISTED_MOST: usize = 64;

/// Past how many scene corners in reach the list's triangles proven to
/// miss the corners' box are dropped (`body::winding::keep_triangles_meeting`:
/// up to eight signs of its plane and twelve of its edges' shadows a
/// triangle once, against one or two a segment).
const CORNERS_TO_CULL_PLANES: usize = 8;

/// From how many scene corners in reach their box is first asked of the
/// body's grid as a whole (module docs, "The corners together").
const CORNERS_TOGETHER: usize = 4;

/// How many cells wide along each axis a body's box may be for
/// "One cell holds a body" to ask a grid about it (module docs).
const CELLS_ACROSS: f64 = 2.0;

/// How many cells a body's box may meet in all for "One cell holds a
/// body" to read them (module docs).
const CELLS_MOST: usize = 27;

/// How much narrower than a body (its root box's widest side) the other
/// body's box must be for "No triangle by a body" to ask the body's tree
/// where its grid was not asked (module docs): a cost decision only.
const SMALL_BESIDE: f64 = 0.25;

/// How many points a state check asks about containment before it walks
/// the trees (module docs, "Containment first"): enough for the few
/// components of a robot part; a soup's thousands wait for the walk.
const POINTS_ASKED_FIRST: usize = 8;

impl SceneChecker {
    /// Whether the body at `pose` touches or overlaps the scene (exact;
    /// module docs).
    ///
    /// # Errors
    /// [`QueryError::OutOfRange`] when a posed coordinate is not finite, or
    /// (never seen) when a containment is neither read from the grid nor
    /// decided by a ray.
    pub fn collides_at(&self, pose: Pose) -> Result<bool, QueryError> {
        let mut s = self.scratch();
        let out = self.collides_with(pose, &mut s);
        self.give_back(s);
        out
    }

    /// [`SceneChecker::collides_at`] for many poses, in parallel, in order
    /// ([`Checker::collides_many`]; callable without the trait in scope).
    ///
    /// # Errors
    /// The first error of [`SceneChecker::collides_at`].
    pub fn collides_many(&self, poses: &[Pose]) -> Result<Vec<bool>, QueryError> {
        Checker::collides_many(self, poses)
    }

    pub(super) fn collides_with(&self, pose: Pose, s: &mut Scratch) -> Result<bool, QueryError> {
        self.check_range(&pose)?;
        s.at.start(self.body.vertices.len());
        self.fit_node_cache(s);
        // Module docs, "The roots first".
        let Some(c) = self.carry_unless_parted(&pose, s) else {
            return Ok(false);
        };
        // Module docs, "One cell holds a body".
        if let Some(inside) = self.one_cell_holds_a_body(pose, &c, s) {
            return Ok(inside);
        }
        // Module docs, "The roots first": their oriented boxes, after the
        // grids (which decide for the many states they hold whole).
        if self.oriented_roots_apart(&c, s) {
            return Ok(false);
        }
        // Module docs, "Containment first".
        let first = 0..POINTS_ASKED_FIRST;
        let (skip, found) = match self.one_inside_by_grids(pose, s, first.clone()) {
            Ok(found) => (first.end, found),
            Err(_) => (0, false),
        };
        Ok(found
            || self.surfaces_meet_lazily(pose, &c, s, true)
            || self.one_inside_the_other(pose, s, skip..usize::MAX)?)
    }

    /// Whether one classified cell of a body's grid holds the other body
    /// whole (module docs, "One cell holds a body"): the posed body's box
    /// in a cell of the scene's grid, where every scene triangle is a
    /// solid's; or the scene's box carried back in a cell of the body's,
    /// where every body triangle is a solid's and the matrix is near a
    /// rotation. `Some(answer)` where one does: the cell's (inside a solid
    /// or outside every one) is the state's. Where the cells differ or a
    /// grid cannot be read, and no triangle of that body may meet the
    /// other's box, one point's answer (module docs, "No triangle by a
    /// body"). `None` where none of these decides.
    fn one_cell_holds_a_body(&self, pose: Pose, c: &Carry, s: &mut Scratch) -> Option<bool> {
        let (body, scene) = (&self.body, &self.scene);
        let grid = scene.inside_grid();
        // The box `carry_unless_parted` left at index 0 for this query.
        let world = cached(cells(&mut s.node_cache), s.at.epoch, 0, || {
            body.tree().bounds()[0].transformed(&c.m, c.t, c.pad)
        });
        let in_cells = grid.spans_at_most(world.size(), CELLS_ACROSS);
        if in_cells && scene.solid_components.len() == scene.components.len() {
            let answer = grid.classify_cells(world.lo.into(), world.hi.into(), CELLS_MOST);
            if answer.is_some() {
                s.tally.bodies_by_grid += 1;
                return answer;
            }
        }
        // Module docs, "No triangle by a body": the first body point.
        if (in_cells || world.size() <= SMALL_BESIDE * scene.tree().root().size())
            && !some_triangle_may_meet(scene.tree(), |j| self.scene_triangle(j), &world)
        {
            return self.one_point_decides(pose, s, 0);
        }
        if c.oriented && c.m.determinant() > 0.5 {
            let grid = body.inside_grid();
            let root = scene.tree().root();
            // Turned, the box is up to √3 times as wide along an axis.
            let in_cells = grid.spans_at_most(root.size() * 1.75, CELLS_ACROSS);
            if in_cells || root.size() * 1.75 <= SMALL_BESIDE * body.tree().root().size() {
                let size = body.reach + c.t.abs().max_element();
                let back = carried_back(&root, &c.mi, c.t, size, c.pad);
                if in_cells && body.solid_components.len() == body.components.len() {
                    let answer = grid.classify_cells(back.lo.into(), back.hi.into(), CELLS_MOST);
                    if answer.is_some() {
                        s.tally.bodies_by_grid += 1;
                        return answer;
                    }
                }
                // Module docs, "No triangle by a body": the first scene
                // corner.
                let unposed = |i: usize| body.triangles[i].map(|v| body.vertices[v as usize]);
                if !some_triangle_may_meet(body.tree(), unposed, &back) {
                    return self.one_point_decides(pose, s, self.first_scene_corner());
                }
            }
        }
        None
    }

    /// The number the containment test gives its first scene corner
    /// (`inside_either` counts its scene corners from it): after the
    /// body's points, which it asks only where the scene has a solid.
    fn first_scene_corner(&self) -> usize {
        if self.scene.solid_components.is_empty() {
            0
        } else {
            self.body.components.len()
        }
    }

    /// The containment test's point numbered `k` alone (module docs, "No
    /// triangle by a body"): `Some(inside)`, or `None` where it is not
    /// decided (never seen; the state is then checked as any other).
    fn one_point_decides(&self, pose: Pose, s: &mut Scratch, k: usize) -> Option<bool> {
        let inside = self
            .inside_either_with_parity(pose, s, k..k + 1, false)
            .ok()?;
        s.tally.bodies_by_region += 1;
        Some(inside)
    }

    /// The pose's matrix and translation, the posing's rounding bound,
    /// and the carrying of scene boxes back into the body's frame: the
    /// inverse pose and its pad (`surfaces_meet_lazily`'s comments).
    pub(super) fn carry(&self, pose: &Pose) -> Carry {
        let m = pose.rotation.matrix();
        let t = pose.translation;
        let size = self.body.reach + t.abs().max_element();
        // The scene's boxes carried back into the body's frame: `Mᵀ` undoes
        // `M` up to its distance from a rotation (at most 2⁻⁴⁷ an entry
        // after snapping), far inside `2⁻⁴⁰` of the sizes involved.
        let (mi, ti) = (m.transpose(), -(m.transpose() * t));
        let back_pad = size * (1.0 / (1u64 << 40) as f64);
        // Carrying a scene box back also rounds in the box's own
        // coordinates (its centre and half-size, then the sums): grow it by
        // a bound on that too, taken once for the whole scene (its box's
        // largest coordinate bounds every box's).
        let root = self.scene.tree().root();
        let mag = root
            .lo
            .iter()
            .chain(root.hi.iter())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let back_pad = back_pad + 16.0 * f64::EPSILON * (2.0 * mag + t.abs().max_element());
        Carry {
            m,
            t,
            pad: self.pad(pose),
            mi,
            ti,
            back_pad,
            oriented: pose_skew(&m).is_some(),
        }
    }

    /// The pose's [`SceneChecker::carry`], or `None` where the walk's first
    /// test parts the two roots at the pose by their boxes: the body's root
    /// box carried to the pose misses the scene's, or (the matrix near a
    /// rotation) the scene's carried back misses the body's. Then nothing
    /// meets and nothing lies inside the other (module docs, "The roots
    /// first"; their oriented boxes are `oriented_roots_apart`'s, asked
    /// later). The boxes are left in the query's caches for the walk; the
    /// carrying is computed only past the first test.
    fn carry_unless_parted(&self, pose: &Pose, s: &mut Scratch) -> Option<Carry> {
        let (bounds, scene) = (self.body.tree().bounds(), self.scene.tree());
        if bounds.is_empty() || scene.bounds().is_empty() {
            return None;
        }
        let epoch = s.at.epoch;
        let scene_root = scene.root();
        let world = cached(cells(&mut s.node_cache), epoch, 0, || {
            bounds[0].transformed(&pose.rotation.matrix(), pose.translation, self.pad(pose))
        });
        if !world.within(&scene_root, 0.0) {
            return None;
        }
        let c = self.carry(pose);
        if c.oriented {
            let back = cached(cells(&mut s.scene_cache), epoch, 0, || {
                scene_root.transformed(&c.mi, c.ti, c.back_pad)
            });
            if !back.within(&bounds[0], 0.0) {
                return None;
            }
        }
        Some(c)
    }

    /// Whether the roots' oriented boxes are apart at the pose (`c`, where
    /// the matrix is near a rotation): the last of the walk's first tests
    /// ("The roots first"), left in the query's cache for the walk.
    fn oriented_roots_apart(&self, c: &Carry, s: &mut Scratch) -> bool {
        if !c.oriented {
            return false;
        }
        let (a, b) = (&self.body.obbs()[0], &self.scene.obbs()[0]);
        let posed = cached(cells(&mut s.obb_cache), s.at.epoch, 0, || {
            a.posed(&c.m, c.t)
        });
        b.apart(&posed, a.h, a.fuzz, c.pad)
    }

    /// Whether some body triangle at `pose` (`c`, its
    /// [`SceneChecker::carry`]) meets some scene triangle (with
    /// `roots_meet`, the caller has found that the walk's first test does
    /// not part the roots: `carry_unless_parted` and
    /// `oriented_roots_apart`): the
    /// body's tree is walked with its body-frame boxes carried to the pose
    /// (each grown by a bound on the rounding of the points it holds, so
    /// no touching pair is dropped), and only the corners of the triangles
    /// reached are posed.
    pub(super) fn surfaces_meet_lazily(
        &self,
        pose: Pose,
        c: &Carry,
        s: &mut Scratch,
        roots_meet: bool,
    ) -> bool {
        let Carry {
            m,
            t,
            pad,
            mi,
            ti,
            back_pad,
            oriented,
        } = *c;
        let back = |o: &Aabb| o.transformed(&mi, ti, back_pad);
        let bounds = self.body.tree().bounds();
        let mut cache = std::mem::take(&mut s.node_cache);
        let cache_cells = cells(&mut cache);
        let epoch = s.at.epoch;
        let world = |n: usize| cached(cache_cells, epoch, n, || bounds[n].transformed(&m, t, pad));
        let scene = self.scene.tree();
        let mut stack = std::mem::take(&mut s.stack);
        // The body's triangles at the pose, each corner posed once per
        // query: a pair of triangles is kept only when the exact box of the
        // posed triangle meets the scene triangle's box, then when no axis
        // proves them apart in floats (`kernel::separation`, certified),
        // and decided by the exact test.
        let lazy = std::cell::RefCell::new((&mut s.at, &mut s.tris));
        let posed = |i: usize| {
            let (at, tris) = &mut *lazy.borrow_mut();
            tris.get(at, &self.body, &pose, i)
        };
        let mut scene_cache = std::mem::take(&mut s.scene_cache);
        let scene_cache_cells = cells(&mut scene_cache);
        let back_node = |k: usize, o: &Aabb| cached(scene_cache_cells, epoch, k, || back(o));
        // Then the oriented boxes (`solid::obb`: certified), when the
        // pose's matrix is close enough to a rotation for their test
        // (`oriented`).
        let mut obb_cache = std::mem::take(&mut s.obb_cache);
        let obb_cache_cells = cells(&mut obb_cache);
        let (body_obbs, scene_obbs) = (self.body.obbs(), self.scene.obbs());
        let obb_apart = |n: usize, k: usize| {
            let a = &body_obbs[n];
            let posed = cached(obb_cache_cells, epoch, n, || a.posed(&m, t));
            scene_obbs[k].apart(&posed, a.h, a.fuzz, pad)
        };
        // A leaf of two or more triangles at an angle (or a thin wall's
        // two sides) is boxed thick while each triangle is flat: where a
        // leaf's box and an inner node's could not be parted, each of the
        // leaf's triangles is tried with its own flat box (`solid::obb`,
        // "Triangles' own boxes"). A body triangle's box is fitted to its
        // posed corners, the very floats the exact test reads: no rounding
        // of the pose to cover. The scene's boxes hold for every query
        // (stamp 1), the body's for this one.
        let body_tree = self.body.tree();
        let mut scene_boxes = std::mem::take(&mut s.scene_triangle_boxes);
        let scene_boxes_cells = cells(&mut scene_boxes);
        let mut body_boxes = std::mem::take(&mut s.body_triangle_boxes);
        let body_boxes_cells = cells(&mut body_boxes);
        let leaf_triangles_apart = |n: usize, k: usize| {
            let (a, b) = (&body_obbs[n], &scene_obbs[k]);
            // Only a leaf thicker than the other node is wide is worth it:
            // against a wider node the triangles' boxes part what the
            // leaf's could not about as seldom as it did (tried at every
            // such pair, the ROS-Industrial pairs' state checks took 8–19%
            // more instructions; docs/BENCHMARKS.md, "Triangles' own
            // boxes").
            if b.h.min_element() > a.h.max_element() {
                match scene.leaf_items(k) {
                    Some(items)
                        if oriented && items.len() >= 2 && body_tree.leaf_items(n).is_none() =>
                    {
                        let posed = cached(obb_cache_cells, epoch, n, || a.posed(&m, t));
                        items.iter().all(|&j| {
                            let j = j as usize;
                            triangle_box(scene_boxes_cells, j, 1, || self.scene_triangle(j))
                                .apart(&posed, a.h, a.fuzz, pad)
                        })
                    }
                    _ => false,
                }
            } else if a.h.min_element() > b.h.max_element() {
                match body_tree.leaf_items(n) {
                    Some(items) if items.len() >= 2 && scene.leaf_items(k).is_none() => {
                        items.iter().all(|&i| {
                            let i = i as usize;
                            let own = triangle_box(body_boxes_cells, i, epoch, || posed(i).0);
                            b.apart(&own.unposed(), own.h, own.fuzz, 0.0)
                        })
                    }
                    _ => false,
                }
            } else {
                false
            }
        };
        let hit = body_tree.for_each_pair(
            |n, k, o| {
                // The roots' pair was tested already where `roots_meet`.
                ((roots_meet && n == 0 && k == 0)
                    || (world(n).within(o, 0.0)
                        && back_node(k, o).within(&bounds[n], 0.0)
                        && !(oriented && obb_apart(n, k))))
                    && !leaf_triangles_apart(n, k)
            },
            |n| bounds[n].size(),
            // A body triangle against a scene leaf's box, and against each
            // of its triangles' boxes: boxes alone (module docs, "No
            // triangle against a leaf's box").
            |i, o| posed(i).1.meets(o),
            |i, o| posed(i).1.meets(o),
            scene,
            scene.boxes(),
            scene.bounds(),
            &mut stack,
            |i, j| {
                let (tri, u) = (posed(i).0, self.scene_triangle(j));
                !triangles_apart(&tri, &u) && triangles_meet(&tri, &u)
            },
        );
        s.stack = stack;
        s.node_cache = cache;
        s.scene_cache = scene_cache;
        s.obb_cache = obb_cache;
        s.scene_triangle_boxes = scene_boxes;
        s.body_triangle_boxes = body_boxes;
        hit
    }

    /// A body component inside a scene solid, or a scene component inside
    /// a body solid, asking only the points whose index, counted from 0 in
    /// the test's order before its box filters, is in `asked`: exact when
    /// no triangles meet; "inside" is a collision in any case (module
    /// docs, "Containment first").
    pub(super) fn one_inside_the_other(
        &self,
        pose: Pose,
        s: &mut Scratch,
        asked: std::ops::Range<usize>,
    ) -> Result<bool, QueryError> {
        self.inside_either_with_parity(pose, s, asked, false)
    }

    /// [`SceneChecker::one_inside_the_other`] as far as the grids decide
    /// (module docs, "Containment first"): an error (never shown) at the
    /// first point asked that no grid reads.
    fn one_inside_by_grids(
        &self,
        pose: Pose,
        s: &mut Scratch,
        asked: std::ops::Range<usize>,
    ) -> Result<bool, QueryError> {
        self.inside_either_with_parity(pose, s, asked, true)
    }

    /// [`SceneChecker::inside_either`] with the scratch's parity buffer
    /// lent to it (the two askings above).
    fn inside_either_with_parity(
        &self,
        pose: Pose,
        s: &mut Scratch,
        asked: std::ops::Range<usize>,
        grids_only: bool,
    ) -> Result<bool, QueryError> {
        let mut parity = std::mem::take(&mut s.parity);
        let out = self.inside_either(pose, s, &mut parity, asked, grids_only);
        s.parity = parity;
        out
    }

    /// Lists in `near`, in increasing order, the body's components whose
    /// vertex, posed at `pose`, may lie in the box of the scene's solid
    /// components (module docs, "The body's components near the scene"):
    /// every other one's posed vertex is outside that box. `false` (and `near`
    /// not read) where the body has no tree over its components' vertices
    /// or the pose's matrix is not near a rotation.
    fn components_near_the_scene(&self, pose: &Pose, near: &mut Vec<usize>) -> bool {
        let Some(points) = self.body.component_points() else {
            return false;
        };
        let m = pose.rotation.matrix();
        if pose_skew(&m).is_none() {
            return false;
        }
        let (t, pad) = (pose.translation, self.pad(pose));
        let size = self.body.reach + t.abs().max_element();
        let region = carried_back(&self.scene.solid_tree.root(), &m.transpose(), t, size, pad);
        near.clear();
        points.for_each_meeting(&region, |c| near.push(c));
        near.sort_unstable();
        true
    }

    pub(super) fn inside_either(
        &self,
        pose: Pose,
        s: &mut Scratch,
        parity: &mut Vec<u8>,
        asked: std::ops::Range<usize>,
        grids_only: bool,
    ) -> Result<bool, QueryError> {
        // The points, counted in order before the box filters (so that an
        // asking of a few scans only a few, however many the filters
        // drop): the one counted `number` has index `number − 1`, asked
        // when in `asked`. The body's points come first where the scene
        // has a solid; `number` counts on from the last of them.
        let mut number = self.first_scene_corner();
        if !self.scene.solid_components.is_empty() {
            let scene_box = self.scene.obbs().first();
            let components = &self.body.components;
            // The last point decided and its windings (module docs,
            // "Segments between points").
            let mut known = None;
            let mut ask = |c: usize| {
                let p = s.at.get(&self.body.vertices, &pose, components[c].1);
                // Outside the scene's oriented box: inside nothing of it.
                if scene_box.is_some_and(|o| o.excludes(p, 0.0)) {
                    return None;
                }
                if grids_only {
                    let read = self.scene.inside_grid().classify(p, 0.0);
                    s.tally.by_grid += u64::from(read.is_some());
                    return match read {
                        Some(true) => Some(Ok(true)),
                        Some(false) => None,
                        None => Some(Err(not_read())),
                    };
                }
                match self.scene.inside_solid(p, &mut known, parity, &mut s.tally) {
                    Some(true) => Some(Ok(true)),
                    Some(false) => None,
                    None => Some(Err(undecided(p))),
                }
            };
            // The components' indices asked, in order (module docs, "The
            // body's components near the scene"): those of `asked` whose
            // vertex may lie in the scene's solids' box, when the body's
            // tree over them and the pose allow the filter; else all.
            let range = asked.start.min(components.len())..asked.end.min(components.len());
            let mut near = std::mem::take(&mut s.asked);
            // A short range is asked directly: the tree's query and sort
            // cost more than posing those few vertices.
            let filtered = range.len() > POINTS_ASKED_FIRST
                && self.components_near_the_scene(&pose, &mut near);
            let count = if filtered { near.len() } else { range.len() };
            // One loop for both (one copy of `ask` in the code).
            let out = (0..count).find_map(|i| {
                let c = if filtered { near[i] } else { range.start + i };
                range.contains(&c).then(|| ask(c)).flatten()
            });
            s.asked = near;
            if let Some(out) = out {
                return out;
            }
            if asked.end <= components.len() {
                return Ok(false);
            }
        }
        if self.body.solid_components.is_empty() {
            return Ok(false);
        }
        // The scene components with a corner in the body's box at the pose.
        let m = pose.rotation.matrix();
        let pad = self.pad(&pose);
        let reach = self
            .body
            .tree()
            .root()
            .transformed(&m, pose.translation, pad);
        // Only as many corners as the asking may reach (its first ones, in
        // the tree's order, are those of the whole list).
        let wanted = asked.end.saturating_sub(number);
        let mut corners = std::mem::take(&mut s.asked);
        corners.clear();
        self.scene_corners.for_each_meeting_while(&reach, |k| {
            corners.push(k);
            corners.len() < wanted
        });
        if corners.is_empty() {
            s.asked = corners;
            return Ok(false);
        }
        // The body at the pose, posed only where the rays reach: its
        // vertices lazily, its node and component boxes carried from its
        // own frame and grown by the rounding bound (holding the posed
        // points), its triangles' boxes exact from their posed corners.
        let (t, pad) = (pose.translation, self.pad(&pose));
        let mi = m.transpose();
        let filter = pose_skew(&m).is_some();
        // The body's grid answers for a corner carried back (module docs,
        // "The grid at a pose"), the matrix near a rotation.
        let grid = (filter && m.determinant() > 0.5).then(|| self.body.inside_grid());
        let size = self.body.reach + t.abs().max_element();
        let corner = |k: usize| self.scene.vertices[self.scene.components[k].1 as usize];
        // The box holding the corners: asked of the grid as a whole, and
        // holding every segment between two of them.
        let region = Aabb::of(corners.iter().map(|&k| corner(k).to_array()));
        // All the corners at once, where their box, carried back, lies in
        // one classified cell (module docs, "The corners together").
        if let Some(g) = grid.filter(|_| corners.len() >= CORNERS_TOGETHER) {
            let back = carried_back(&region, &mi, t, size, pad);
            if let Some(inside) = g.classify_box(back.lo.into(), back.hi.into()) {
                // The corners numbered `number + 1 ..= number + len`: those
                // in `asked` are asked.
                let from = number.max(asked.start);
                let to = (number + corners.len()).min(asked.end);
                s.tally.by_grid += to.saturating_sub(from) as u64;
                s.asked = corners;
                return Ok(inside && from < to);
            }
        }
        let bounds = self.body.tree().bounds();
        let mut cache = std::mem::take(&mut s.node_cache);
        let cache_cells = cells(&mut cache);
        let epoch = s.at.epoch;
        let at = std::cell::RefCell::new(&mut s.at);
        let vertex = |v: u32| at.borrow_mut().get(&self.body.vertices, &pose, v);
        let node_box =
            |n: usize| cached(cache_cells, epoch, n, || bounds[n].transformed(&m, t, pad));
        let item_box = |i: usize| Aabb::of(self.body.triangles[i].map(|v| vertex(v).to_array()));
        let component_box = |c: usize| self.body.component_boxes[c].transformed(&m, t, pad);
        let placed = Placed {
            body: &self.body,
            vertex,
            node_box,
            item_box,
            component_box,
        };
        // The last corner decided and its windings (module docs, "Segments
        // between points").
        let mut known: Option<Known> = None;
        // A scene corner carried back into the body's frame, known there
        // up to `back_pad` per coordinate: a point of the posed body's
        // hull carried back lies within it of the body-frame hull (the
        // posing's rounding `pad`, three times the matrix's distance from
        // a rotation (`pose_skew`, at most 2⁻⁴⁰ an entry, else this
        // filter is off) times the body's size, this product's own
        // rounding, and an absolute 10⁻³⁰⁰ for subnormal sizes), so a
        // corner the body-frame boxes exclude by more is in none of the
        // body's solids.
        let body_box = self.body.obbs().first();
        let mut candidates = Vec::new();
        // The body's triangles whose boxes meet the box of the corners
        // listed, listed once at the first segment (module docs of
        // `body::winding`, "Segments between points"): every segment runs
        // between two of those corners, inside that box.
        let mut listed: Option<Option<Vec<Listed>>> = None;
        // The solid components whose boxes meet the corners' box, with
        // their boxes at the pose, found at the first segment between two
        // corners.
        let mut near_region: Option<Vec<(u32, Aabb)>> = None;
        // The list's triangles its cull placed by exact signs.
        let mut culled_exactly = 0;
        let mut out = Ok(false);
        for &k in &corners {
            number += 1;
            if number > asked.end {
                break;
            }
            if number <= asked.start {
                continue;
            }
            let p = corner(k);
            let back = mi * (p - t);
            let back_pad = back_pad(size, pad, p, t);
            if filter && body_box.is_some_and(|o| o.excludes(back, back_pad)) {
                continue;
            }
            if let Some(inside) = grid.and_then(|g| g.classify(back, back_pad)) {
                s.tally.by_grid += 1;
                if inside {
                    out = Ok(true);
                    break;
                }
                known = Some(Known::outside(p));
                continue;
            }
            if grids_only {
                out = Err(not_read());
                break;
            }
            // From the last corner decided where the segment is the
            // shorter way (the posed body's box bounds the ray's), else by
            // a ray.
            // Where no corner decided before is near, a start in a cell
            // of the body's grid by this corner's whose windings it knows
            // (outside, or inside and kept; module docs of
            // `body::winding`, "A start outside"), read at the pose as a
            // corner is; its segment may leave the corners'
            // box, which their list holds for segments between corners
            // only, so it walks the tree instead.
            let from = segment_start(
                known.as_ref(),
                p,
                &(placed.node_box)(0),
                grid.map_or(0.0, |g| g.cell_width()),
                |q| grid.and_then(|g| g.windings_at(mi * (q - t), self::back_pad(size, pad, q, t))),
            );
            let seeded = matches!(from, Some(Cow::Owned(_)));
            let along = from.as_ref().and_then(|k| {
                let segment = Aabb::of([k.at.to_array(), p.to_array()]);
                candidates.clear();
                if seeded {
                    candidates.extend(
                        self.body
                            .solid_components
                            .iter()
                            .filter(|&&c| (placed.component_box)(c as usize).meets(&segment)),
                    );
                } else {
                    // Between two corners: the segment lies in the corners'
                    // box, so a component whose box meets it meets that box;
                    // those are found and posed once.
                    let near = near_region.get_or_insert_with(|| {
                        let posed = |&c: &u32| (c, (placed.component_box)(c as usize));
                        let solids = self.body.solid_components.iter().map(posed);
                        solids.filter(|(_, b)| b.meets(&region)).collect()
                    });
                    candidates.extend(near.iter().filter(|(_, b)| b.meets(&segment)).map(|e| e.0));
                }
                let list = (!seeded).then(|| {
                    listed.get_or_insert_with(|| {
                        let mut list = placed.triangles_meeting(&region, TRIANGLES_LISTED_MOST);
                        // Where many segments will read it, the triangles
                        // proven to miss the corners' box are dropped.
                        if corners.len() > CORNERS_TO_CULL_PLANES {
                            if let Some(list) = &mut list {
                                culled_exactly = keep_triangles_meeting(list, &region);
                            }
                        }
                        list
                    })
                });
                let list = list.and_then(|list| list.as_deref());
                placed.windings_along(&candidates, k, p, list, parity)
            });
            let windings = match s.tally.count(from.is_some(), along) {
                Some(w) => Some(w),
                None => {
                    candidates.clear();
                    candidates.extend(self.body.solid_components.iter().filter(|&&c| {
                        let near_back = || {
                            let at = back.to_array();
                            let point = Aabb { lo: at, hi: at };
                            self.body.component_boxes[c as usize].within(&point, back_pad)
                        };
                        (placed.component_box)(c as usize).holds(p.to_array())
                            && (!filter || near_back())
                    }));
                    placed.windings_by_ray(&candidates, p, parity)
                }
            };
            match windings {
                Some(windings) => {
                    let inside = some_winds(&windings);
                    known = Some(Known { at: p, windings });
                    if inside {
                        out = Ok(true);
                        break;
                    }
                }
                None => {
                    out = Err(undecided(p));
                    break;
                }
            }
        }
        s.tally.plane_cull_fallbacks += culled_exactly;
        s.asked = corners;
        s.node_cache = cache;
        out
    }
}

/// A pose's values for the walk ([`SceneChecker::carry`]).
#[derive(Clone, Copy)]
pub(super) struct Carry {
    m: DMat3,
    t: DVec3,
    pad: f64,
    mi: DMat3,
    ti: DVec3,
    back_pad: f64,
    oriented: bool,
}

/// Whether some triangle of `tree` (item `i` the triangle `corners(i)`)
/// may meet the closed box `b`: its box meets `b` and its plane, a
/// certified separating axis (`kernel::separation::PlaneAxis`), does not
/// part them. `false` proves that every one misses `b`; a box that is not
/// finite proves nothing.
fn some_triangle_may_meet(
    tree: &AabbTree,
    corners: impl Fn(usize) -> [DVec3; 3],
    b: &Aabb,
) -> bool {
    let (lo, hi) = (DVec3::from(b.lo), DVec3::from(b.hi));
    if !(lo.is_finite() && hi.is_finite()) {
        return true;
    }
    let mut met = false;
    tree.for_each_meeting_while(b, |i| {
        let t = corners(i);
        let mag = t.iter().fold(lo.abs().max(hi.abs()), |m, p| m.max(p.abs()));
        met = !PlaneAxis::new(&t, mag).parts(lo, hi);
        !met
    });
    met
}

/// The box `b` of the scene's frame carried back into the body's at a pose
/// (`mi` the rounded matrix's transpose, `t` its translation; `size` and
/// `pad` as for [`back_pad`]): its eight corners carried back as the scene's
/// corners are (`inside_either`), each within `back_pad` (at the corners'
/// largest coordinates) of where the body's frame has the points of `b`
/// posed points carried back exactly, and grown by twice that, for its
/// sides' own rounding (module docs, "The body's components near the
/// scene").
///
/// The corners' box is found without carrying the eight corners one by
/// one, and is the same float box: a corner's carried coordinate `i` is
/// `fl(fl(x + y) + z)` with `x = fl(mᵢ₀ fl(c₀ − t₀))` and likewise `y`,
/// `z` (glam's product, column by column, no fused steps), each term taking
/// one of two values as the corner takes `b`'s low or high side on that
/// axis. Rounding is monotone, so the sum is nondecreasing in each term,
/// and its least over the eight corners is the sum of the three least
/// terms, its greatest that of the greatest: six differences and eighteen
/// products instead of eight corners' (test
/// `carried_back_is_the_eight_corners_box_bit_for_bit`). This holds where
/// no term is NaN (`b − t` does not overflow: the callers' boxes are
/// non-empty and finite, their poses within `check_range`'s bounds), and
/// up to the sign of a zero before the growth, which the growth (at
/// least `2·10⁻³⁰⁰`) removes. An independent review (2026-12-02) confirmed
/// the argument, glam's order (`mul_vec3`, no fused steps), the guards of
/// the three callers, and that the test fails when the sum's order or a
/// term's choice is changed.
fn carried_back(b: &Aabb, mi: &DMat3, t: DVec3, size: f64, pad: f64) -> Aabb {
    let cols = [mi.x_axis, mi.y_axis, mi.z_axis];
    // Column `axis`'s least and greatest terms over the box's two sides.
    let terms = |axis: usize| {
        let low = cols[axis] * (b.lo[axis] - t[axis]);
        let high = cols[axis] * (b.hi[axis] - t[axis]);
        (low.min(high), low.max(high))
    };
    let ((l0, h0), (l1, h1), (l2, h2)) = (terms(0), terms(1), terms(2));
    // Summed as glam's product sums them: x, then + y, then + z.
    let (lo, hi) = ((l0 + l1) + l2, (h0 + h1) + h2);
    let largest = DVec3::from(b.lo).abs().max(DVec3::from(b.hi).abs());
    let grow = DVec3::splat(2.0 * back_pad(size, pad, largest, t));
    Aabb {
        lo: (lo - grow).to_array(),
        hi: (hi + grow).to_array(),
    }
}

/// How far a point `p` of the scene carried back into the body's frame at
/// a pose `(M, t)` (`fl(Mᵀ (p − t))`, `M` within `2⁻⁴⁰` an entry of a
/// rotation), and the body's float-posed vertices carried back alike, may
/// lie from where the body's frame has them (`size` the body's reach plus
/// `|t|`, `pad` the posing's rounding bound; the comment at its use in
/// `inside_either`, and the module docs, "The grid at a pose").
fn back_pad(size: f64, pad: f64, p: DVec3, t: DVec3) -> f64 {
    size * (1.0 / (1u64 << 36) as f64)
        + 2.0 * pad
        + 16.0 * f64::EPSILON * (p.abs().max_element() + t.abs().max_element())
        + 1e-300
}

/// The first asking's stop at a point no grid reads (module docs,
/// "Containment first"; never returned: the walk, then the whole asking,
/// follow).
fn not_read() -> QueryError {
    QueryError::OutOfRange(String::new())
}

/// The error of a point whose containment is neither read from the grid nor
/// decided by a ray (never seen).
fn undecided(p: DVec3) -> QueryError {
    QueryError::OutOfRange(format!(
        "whether the point {:?} lies inside a solid could not be decided: every ray from it \
         passes through an edge or lies in a face's plane",
        p.to_array()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::winding::ContainmentStats;
    use crate::body::MeshBody;
    use crate::kernel::rotation::Rotation;
    use crate::mesh::PolygonMesh;

    /// The eight corners carried back one by one and joined, as
    /// `carried_back` computed its box before it summed the least and
    /// greatest terms instead: the reference it must equal bit for bit.
    fn carried_back_by_corners(b: &Aabb, mi: &DMat3, t: DVec3, size: f64, pad: f64) -> Aabb {
        let mut region = Aabb::EMPTY;
        let mut largest = DVec3::ZERO;
        for k in 0..8 {
            let pick = |axis: usize| {
                if k >> axis & 1 == 0 {
                    b.lo[axis]
                } else {
                    b.hi[axis]
                }
            };
            let corner = DVec3::new(pick(0), pick(1), pick(2));
            largest = largest.max(corner.abs());
            let back = (*mi * (corner - t)).to_array();
            region = region.join(&Aabb { lo: back, hi: back });
        }
        let grow = 2.0 * back_pad(size, pad, largest, t);
        Aabb {
            lo: region.lo.map(|x| x - grow),
            hi: region.hi.map(|x| x + grow),
        }
    }

    /// `carried_back` sums the least and the greatest of each column's two
    /// terms (its docs: rounding is monotone): the same float box as the
    /// eight corners', on turns and on arbitrary matrices with negative,
    /// zero and tiny entries, boxes flat on an axis, a point, boxes
    /// straddling zero and far from the origin, translations up to 10⁹.
    #[test]
    fn carried_back_is_the_eight_corners_box_bit_for_bit() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for k in 0..50_000 {
            let scale = [1e-9, 1e-3, 1.0, 1e3, 1e9][k % 5];
            let mi = if k % 3 == 0 {
                DMat3::from_cols_array(&std::array::from_fn(|i| match (k / 3 + i) % 7 {
                    0 => 0.0,
                    1 => -0.0,
                    2 => 1e-300,
                    _ => rng.random_range(-2.0..2.0),
                }))
            } else {
                random_turn(&mut rng).matrix().transpose()
            };
            let mut coordinate = || rng.random_range(-1.0..1.0) * scale;
            let off = DVec3::new(coordinate(), coordinate(), coordinate()) * [0.0, 1.0, 1e3][k % 3];
            let (p, q) = (
                DVec3::new(coordinate(), coordinate(), coordinate()) + off,
                DVec3::new(coordinate(), coordinate(), coordinate()) + off,
            );
            let (mut lo, mut hi) = (p.min(q).to_array(), p.max(q).to_array());
            // Flat on the axes `k % 4` names (all three: a point).
            for axis in 0..3 {
                if k % 4 == 3 || k % 4 == axis + 1 && k % 8 < 4 {
                    hi[axis] = lo[axis];
                }
            }
            if k % 11 == 0 {
                lo[0] = -0.0;
                hi[0] = 0.0;
            }
            let b = Aabb { lo, hi };
            let t = DVec3::new(coordinate(), coordinate(), coordinate()) * [1.0, 1e3, 1e-6][k % 3];
            let (size, pad) = (scale * 3.0, scale * 1e-15);
            let (got, want) = (
                carried_back(&b, &mi, t, size, pad),
                carried_back_by_corners(&b, &mi, t, size, pad),
            );
            for axis in 0..3 {
                assert_eq!(
                    got.lo[axis].to_bits(),
                    want.lo[axis].to_bits(),
                    "{k}: lo {axis}"
                );
                assert_eq!(
                    got.hi[axis].to_bits(),
                    want.hi[axis].to_bits(),
                    "{k}: hi {axis}"
                );
            }
        }
    }

    /// The per-query caches (posed vertices, triangles, node boxes) are
    /// stamped with a query counter that wraps after 2³² queries; a
    /// triangle posed in the counter's last cycle must not pass for this
    /// cycle's. A vertical triangle whose box crosses a flat one's: it
    /// crosses the flat triangle at the first pose, misses it at the
    /// second (boxes still meeting).
    #[test]
    fn caches_survive_the_query_counter_wrapping() {
        let flat = PolygonMesh::new(
            vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]],
            vec![vec![0, 1, 2]],
        );
        let upright = PolygonMesh::new(
            vec![[1.5, 1.5, -1.0], [1.5, 1.5, 1.0], [1.6, 1.4, 0.0]],
            vec![vec![0, 1, 2]],
        );
        let checker = SceneChecker::new(
            &MeshBody::new(&upright).unwrap(),
            &[MeshBody::new(&flat).unwrap()],
        )
        .unwrap();
        let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, x, 0.0));
        let mut s = checker.scratch();
        assert!(checker.collides_with(at(-1.0), &mut s).unwrap());
        assert!(!checker.collides_with(at(0.0), &mut s).unwrap());
        // The next query wraps the counter back to the first one's stamp.
        s.at.epoch = u32::MAX;
        assert!(checker.collides_with(at(-1.0), &mut s).unwrap());
        s.at.epoch = u32::MAX;
        assert!(!checker.collides_with(at(0.0), &mut s).unwrap());
        assert!(!checker.collides_at(at(0.0)).unwrap());
    }

    /// A rotation drawn as the tests here draw one: a normalised
    /// quaternion of four uniform coordinates in `[-1, 1)`.
    fn random_turn(rng: &mut impl rand::Rng) -> Rotation {
        Rotation::from_quat(
            glam::DQuat::from_xyzw(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize(),
        )
    }

    /// A pose far from the origin (about 10⁶, where the rounding of posing
    /// and of carrying back is about 10⁻¹⁰): on even rounds a quarter turn
    /// nudged by up to 10⁻⁸ rad (the box of points carried back is then
    /// about as thin as they are), on odd rounds a generic turn.
    fn far_pose_where_rounding_decides(rng: &mut impl rand::Rng, round: usize) -> Pose {
        let turn = if round % 2 == 0 {
            let quarter = |axis: DVec3, k: u32| {
                Rotation::from_axis_angle(axis, f64::from(k) * std::f64::consts::FRAC_PI_2).unwrap()
            };
            let nudge = Rotation::from_axis_angle(
                DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                ),
                rng.random_range(0.0..1e-8),
            )
            .unwrap();
            quarter(DVec3::Z, rng.random_range(0..4))
                .then(&quarter(DVec3::X, rng.random_range(0..4)))
                .then(&nudge)
        } else {
            random_turn(rng)
        };
        Pose::new(
            turn,
            DVec3::new(1.0e6, -2.0e6, 3.0e6) * rng.random_range(0.5..1.0),
        )
    }

    /// The answer as the walk followed by the whole containment test gave
    /// it, before "Containment first", "The roots first" and "One cell
    /// holds a body": the oracle those orders are compared with.
    fn walk_then_containment(checker: &SceneChecker, pose: Pose) -> bool {
        let mut s = checker.scratch();
        checker.check_range(&pose).unwrap();
        s.at.start(checker.body.vertices.len());
        checker.fit_node_cache(&mut s);
        let out = checker.surfaces_meet_lazily(pose, &checker.carry(&pose), &mut s, false)
            || checker
                .one_inside_the_other(pose, &mut s, 0..usize::MAX)
                .unwrap();
        checker.give_back(s);
        out
    }

    /// A box 9 wide (each face cut into 4 × 4 quads) with a cavity whose
    /// face nearest the origin lies at `x = face`.
    fn shell(face: f64) -> MeshBody {
        use crate::body::inside_grid::tests::push_box;
        let mut m = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut m, [0.0; 3], [9.0; 3], true, 4);
        push_box(&mut m, [face, 2.0, 2.0], [6.0, 7.0, 7.0], false, 1);
        MeshBody::new(&m).unwrap()
    }

    /// `body` posed at `pose` (its vertices as the checker poses them), and
    /// whether a mesh of the scene's frame touches its surface (exact).
    fn posed_and_touching(
        body: &MeshBody,
        pose: Pose,
    ) -> (MeshBody, impl Fn(&PolygonMesh) -> bool) {
        let posed = body.placed(pose).unwrap();
        let posed_mesh = PolygonMesh::new(
            posed.vertices().iter().map(|v| v.to_array()).collect(),
            posed
                .triangles()
                .iter()
                .map(|t| t.map(|v| v as usize).to_vec())
                .collect(),
        );
        let still = Pose::new(Rotation::IDENTITY, DVec3::ZERO);
        let touch = move |other: &PolygonMesh| {
            crate::query::scene::surfaces_touch(&posed_mesh, still, other, still).unwrap()
        };
        (posed, touch)
    }

    /// The body's grid read at a pose (module docs, "The grid at a pose")
    /// answers only where the corner's whole box of rounding lies in a
    /// classified cell. A body far from the origin (its corners carried
    /// back to within about 10⁻⁹), whose cavity's face lies 10⁻¹¹ beyond a
    /// cell's plane, against triangles in the cavity parallel to that face
    /// and within 2 · 10⁻¹⁰ of it on either side: every answer is the exact
    /// one, the posed body's own ray and the surfaces' test.
    #[test]
    fn the_grid_at_a_pose_reads_no_cell_the_rounding_may_leave() {
        use rand::{Rng, SeedableRng};
        // The planes depend on the box and the triangle count alone.
        let plane = shell(2.5).inside_grid().planes()[0][2];
        assert!((2.0..3.0).contains(&plane));
        let face = plane + 1e-11;
        let body = shell(face);
        assert_eq!(body.inside_grid().planes()[0][2], plane);
        let cell = body
            .inside_grid()
            .classify(DVec3::new(plane - 1e-12, 3.0, 3.0), 0.0);
        assert_eq!(cell, Some(true), "the cell before the face is classified");
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let (mut answers, mut colliding) = (0, 0);
        for _ in 0..400 {
            let turn = random_turn(&mut rng);
            let t = DVec3::new(1.0e6, -2.0e6, 3.0e6) * rng.random_range(0.5..1.0);
            let pose = Pose::new(turn, t);
            let x = face + rng.random_range(-2e-10..2e-10);
            let corners = [[x, 3.0, 3.1], [x, 3.5, 3.0], [x, 3.2, 3.6]]
                .map(|v| pose.apply(DVec3::from(v)).to_array());
            let triangle = PolygonMesh::new(corners.to_vec(), vec![vec![0, 1, 2]]);
            let checker = SceneChecker::new(&body, &[MeshBody::new(&triangle).unwrap()]).unwrap();
            let (posed, touch) = posed_and_touching(&body, pose);
            let exact = touch(&triangle)
                || posed
                    .inside_by_ray(DVec3::from(corners[0]), &mut Vec::new())
                    .unwrap();
            assert_eq!(checker.collides_at(pose).unwrap(), exact, "{pose:?} at {x}");
            answers += 1;
            colliding += usize::from(exact);
        }
        // Both sides of the face were met.
        assert!(
            colliding > 50 && answers - colliding > 50,
            "{colliding} of {answers}"
        );
    }

    /// `count` cubes `size` wide by the plane `x = face` of a body's frame,
    /// posed at `pose`: each beyond the plane (`x` above it) but, with
    /// chance `wall`, before it, `depth` from it, `y` and `z` drawn from
    /// `across`; the mesh and its corners, posed.
    #[allow(clippy::too_many_arguments)]
    fn specks_by_a_face(
        rng: &mut impl rand::Rng,
        pose: Pose,
        count: usize,
        face: f64,
        wall: f64,
        depth: std::ops::Range<f64>,
        across: std::ops::Range<f64>,
        size: f64,
    ) -> (PolygonMesh, Vec<DVec3>) {
        use crate::body::inside_grid::tests::push_box;
        let mut specks = PolygonMesh::new(Vec::new(), Vec::new());
        let mut corners = Vec::new();
        for _ in 0..count {
            let side = if rng.random_bool(wall) { -1.0 } else { 1.0 };
            let lo = [
                face + side * rng.random_range(depth.clone()),
                rng.random_range(across.clone()),
                rng.random_range(across.clone()),
            ];
            let from = specks.vertices.len();
            push_box(&mut specks, lo, lo.map(|x| x + size), true, 1);
            for v in &mut specks.vertices[from..] {
                *v = pose.apply(DVec3::from(*v)).to_array();
            }
            corners.extend(specks.vertices[from..].iter().map(|&v| DVec3::from(v)));
        }
        (specks, corners)
    }

    /// Whether some of `corners` lies in `body`'s solids at `pose`: each
    /// corner's own ray through the posed body (the oracle).
    fn inside_by_rays(body: &MeshBody, pose: Pose, corners: &[DVec3]) -> bool {
        let posed = body.placed(pose).unwrap();
        corners
            .iter()
            .any(|&c| posed.inside_by_ray(c, &mut Vec::new()).unwrap())
    }

    /// 150 rounds of `specks(rng, pose)` (the specks and their corners) by
    /// `body` at random turns: every answer is the exact one
    /// ([`inside_by_rays`]), more than 20 collide and more than 20 do not,
    /// and no corner takes a ray (each is decided by a segment).
    fn first_corners_take_no_ray(
        body: &MeshBody,
        seed: u64,
        mut specks: impl FnMut(&mut rand_chacha::ChaCha8Rng, Pose) -> (PolygonMesh, Vec<DVec3>),
    ) {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let (mut colliding, mut rounds) = (0, 0);
        let mut stats = ContainmentStats::default();
        for _ in 0..150 {
            let pose = Pose::new(random_turn(&mut rng), DVec3::new(-4.0, 30.0, 7.0));
            let (specks, corners) = specks(&mut rng, pose);
            let checker = SceneChecker::new(body, &[MeshBody::new(&specks).unwrap()]).unwrap();
            let exact = inside_by_rays(body, pose, &corners);
            assert_eq!(checker.collides_at(pose).unwrap(), exact, "{pose:?}");
            colliding += usize::from(exact);
            rounds += 1;
            stats.add(&checker.containment_stats());
        }
        assert!(
            colliding > 20 && rounds - colliding > 20,
            "{colliding} of {rounds}"
        );
        assert_eq!((stats.by_ray, stats.segment_fallbacks), (0, 0), "{stats:?}");
        assert!(stats.by_segment >= rounds as u64, "{stats:?}");
    }

    /// A first corner starts from an outside cell (module docs of
    /// `body::winding`, "A start outside"): specks by the cavity's face of a
    /// shell (the face's cell meets it, so the grid cannot read them, and
    /// the way out of the shell is longer than two cells), on either side
    /// of it, at random turns and offsets. Every answer is the exact one
    /// (each corner's own ray through the posed body), and no corner takes
    /// a ray: the first is decided by the segment from a point of an
    /// outside cell, the next ones by segments from the corner before.
    #[test]
    fn a_first_corner_starts_from_an_outside_cell() {
        use crate::body::inside_grid::tests::push_box;
        use rand::Rng;
        let mut m = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut m, [0.0; 3], [90.0; 3], true, 8);
        push_box(&mut m, [25.0, 20.0, 20.0], [70.0, 70.0, 70.0], false, 8);
        let body = MeshBody::new(&m).unwrap();
        let width = body.inside_grid().cell_width();
        assert!(width < 12.0, "cells {width} wide");
        first_corners_take_no_ray(&body, 11, |rng, pose| {
            let count = rng.random_range(1..4);
            specks_by_a_face(rng, pose, count, 25.0, 0.3, 0.01..0.5, 30.0..60.0, 1e-2)
        });
    }

    /// A first corner with no outside cell near starts from an inside one
    /// (module docs of `body::winding`, "A start outside"; of
    /// `body::inside_grid`, "Windings kept"): specks by the face of a
    /// cavity smaller than a cell deep in a solid box (every cell within
    /// two of them meets the cavity or lies inside), in the cavity or in
    /// the solid, at random turns. Every answer is the exact one (each
    /// corner's own ray through the posed body), and no corner takes a
    /// ray. Fails when the grid gives no windings for inside cells.
    #[test]
    fn a_first_corner_deep_in_a_solid_starts_from_an_inside_cell() {
        use crate::body::inside_grid::tests::push_box;
        let mut m = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut m, [0.0; 3], [90.0; 3], true, 8);
        push_box(&mut m, [40.0; 3], [46.0; 3], false, 1);
        let body = MeshBody::new(&m).unwrap();
        let width = body.inside_grid().cell_width();
        assert!(width > 6.0 && width < 12.0, "cells {width} wide");
        first_corners_take_no_ray(&body, 12, |rng, pose| {
            specks_by_a_face(rng, pose, 2, 40.0, 0.4, 0.01..0.5, 41.0..45.0, 1e-2)
        });
    }

    /// The corners together answer only for the corners the asking
    /// includes: five scene cubes deep in a body's solid (one classified
    /// cell) are inside when asked, and not when the asking starts past
    /// them (the checker's second asking, after the first asked them).
    #[test]
    fn the_corners_together_answer_only_for_the_corners_asked() {
        use crate::body::inside_grid::tests::push_box;
        let mut m = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut m, [0.0; 3], [9.0; 3], true, 4);
        let body = MeshBody::new(&m).unwrap();
        let mut specks = PolygonMesh::new(Vec::new(), Vec::new());
        for i in 0..5 {
            let lo = [4.4 + 0.02 * f64::from(i), 4.4, 4.4];
            push_box(&mut specks, lo, lo.map(|x| x + 1e-3), true, 1);
        }
        let checker = SceneChecker::new(&body, &[MeshBody::new(&specks).unwrap()]).unwrap();
        let pose = Pose::new(Rotation::IDENTITY, DVec3::ZERO);
        let ask = |asked: std::ops::Range<usize>| {
            let mut s = checker.scratch();
            s.at.start(checker.body.vertices.len());
            checker.fit_node_cache(&mut s);
            let out = checker.one_inside_the_other(pose, &mut s, asked).unwrap();
            checker.give_back(s);
            out
        };
        // The body's one component, then the five corners, numbered 1 to 6.
        assert!(ask(0..usize::MAX));
        assert!(ask(5..6));
        assert!(!ask(6..usize::MAX));
        assert!(!ask(0..1));
        let stats = checker.containment_stats();
        assert_eq!((stats.by_segment, stats.by_ray), (0, 0), "{stats:?}");
    }

    /// Many scene corners by a cavity's face, in cells that meet it: past
    /// eight in reach, the segments between them read one list of the
    /// body's triangles near them, without those whose planes clear the
    /// corners' box (`body::winding`, "Segments between points"). Twelve
    /// small cubes on either side of the face, 2 to 50 thousandths from
    /// it, at random turns: every answer is the exact one (each corner's
    /// own ray through the posed body). Fails when the list is culled for
    /// the box of the first two corners only.
    #[test]
    fn many_corners_by_a_face_read_one_culled_list() {
        use rand::{Rng, SeedableRng};
        let body = shell(2.5);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut colliding, mut segments) = (0, 0);
        for round in 0..200 {
            let pose = Pose::new(random_turn(&mut rng), DVec3::new(3.0, -1.0, 2.0));
            // Mostly in the cavity, a few in the wall (each side in turn
            // the first asked, whichever order the tree gives).
            let wall = rng.random_range(0.0..0.3);
            let (specks, corners) =
                specks_by_a_face(&mut rng, pose, 12, 2.5, wall, 0.002..0.05, 3.0..5.0, 1e-3);
            let scene = MeshBody::new(&specks).unwrap();
            let checker = SceneChecker::new(&body, &[scene]).unwrap();
            let exact = inside_by_rays(&body, pose, &corners);
            assert_eq!(checker.collides_at(pose).unwrap(), exact, "round {round}");
            colliding += usize::from(exact);
            segments += checker.containment_stats().by_segment;
        }
        assert!(
            colliding > 40 && colliding < 160 && segments > 500,
            "{colliding} colliding, {segments} segments"
        );
    }

    /// The first asking reads the grids alone (module docs, "Containment
    /// first"): specks deep in a solid box are read inside, specks deep in
    /// a shell's cavity outside, both by the grid; specks by the cavity's
    /// face, in cells that meet it, stop the asking unanswered; no segment
    /// or ray is cast. The checker's answers are the exact ones. Fails
    /// when the first asking decides a point past the grids.
    #[test]
    fn the_first_asking_reads_the_grids_only() {
        use crate::body::inside_grid::tests::push_box;
        let mut solid = PolygonMesh::new(Vec::new(), Vec::new());
        push_box(&mut solid, [0.0; 3], [9.0; 3], true, 4);
        let (solid, shell) = (MeshBody::new(&solid).unwrap(), shell(2.5));
        let pose = Pose::new(Rotation::IDENTITY, DVec3::ZERO);
        for (body, x, first, exact) in [
            (&solid, 4.2, Some(true), true),
            (&shell, 4.2, Some(false), false),
            (&shell, 2.51, None, false),
        ] {
            let mut specks = PolygonMesh::new(Vec::new(), Vec::new());
            for i in 0..3 {
                let lo = [x, 4.0 + 0.1 * f64::from(i), 4.5];
                push_box(&mut specks, lo, lo.map(|c| c + 1e-3), true, 1);
            }
            let checker = SceneChecker::new(body, &[MeshBody::new(&specks).unwrap()]).unwrap();
            let mut s = checker.scratch();
            s.at.start(checker.body.vertices.len());
            checker.fit_node_cache(&mut s);
            let read = checker.one_inside_by_grids(pose, &mut s, 0..POINTS_ASKED_FIRST);
            assert_eq!(read.ok(), first, "{x}");
            let tally = s.tally;
            checker.give_back(s);
            assert_eq!((tally.by_segment, tally.by_ray), (0, 0), "{x}: {tally:?}");
            assert!(first.is_none() || tally.by_grid > 0, "{x}: {tally:?}");
            assert_eq!(checker.collides_at(pose).unwrap(), exact, "{x}");
        }
    }

    /// One checker, its states one after another: twelve specks by a
    /// shell's cavity face, the body moved to and fro along the face's
    /// normal so that the face crosses them (a state's containment test
    /// must read nothing decided at the state before); every answer is
    /// the exact one (the surfaces' test, then each corner's own ray
    /// through the posed body). Fails when a state starts its segments
    /// from the point the state before decided last.
    #[test]
    fn specks_a_moving_face_crosses_are_answered_state_by_state() {
        use rand::{Rng, SeedableRng};
        let body = shell(2.5);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(8);
        let (mut colliding, mut answers) = (0, 0);
        for round in 0..30 {
            let turn = random_turn(&mut rng);
            let base = Pose::new(turn, DVec3::new(3.0, -1.0, 2.0));
            let (specks, corners) =
                specks_by_a_face(&mut rng, base, 12, 2.5, 0.0, 0.002..0.05, 3.0..5.0, 1e-3);
            let checker = SceneChecker::new(&body, &[MeshBody::new(&specks).unwrap()]).unwrap();
            for _ in 0..20 {
                let shift = turn.apply(DVec3::X) * rng.random_range(-0.06..0.06);
                let pose = Pose::new(turn, base.translation + shift);
                let (_, touching) = posed_and_touching(&body, pose);
                let exact = touching(&specks) || inside_by_rays(&body, pose, &corners);
                assert_eq!(checker.collides_at(pose).unwrap(), exact, "round {round}");
                colliding += usize::from(exact);
                answers += 1;
            }
        }
        assert!(
            colliding > answers / 5 && colliding < answers * 4 / 5,
            "{colliding} of {answers} colliding"
        );
    }

    /// The corners read together (module docs, "The corners together")
    /// only where their box's rounding stays in a classified cell: the
    /// shell of `the_grid_at_a_pose_reads_no_cell_the_rounding_may_leave`
    /// far from the origin, against a cluster of six triangles 10⁻³ wide
    /// parallel to the cavity's face, either all well inside a cell (deep
    /// in the wall, or in the cavity) or all on one side of the face within
    /// 2 · 10⁻¹⁰ of it:
    /// every answer is the exact one (the surfaces' test, then each
    /// corner's own ray through the posed body). The cluster alone is read
    /// whole ("One cell holds a body", the same rounding); with a far
    /// triangle added, its corners are read together.
    #[test]
    fn the_corners_together_read_no_cell_the_rounding_may_leave() {
        use rand::{Rng, SeedableRng};
        let plane = shell(2.5).inside_grid().planes()[0][2];
        let face = plane + 1e-11;
        let body = shell(face);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(6);
        let (mut answers, mut colliding, mut read, mut read_whole) = (0, 0, 0, 0);
        for round in 0..600 {
            // Quarter turns nudged by up to 10⁻⁸ rad (the box of the corners
            // carried back is then about as thin as they are: the rounding
            // decides) and generic turns.
            let pose = far_pose_where_rounding_decides(&mut rng, round);
            // Deep in the wall's cell before the face, or in a cavity's
            // cell; else all on one side of the face, within 2 · 10⁻¹⁰.
            let deep = [1.9, 4.5][round / 2 % 2];
            let side = [-1.0, 1.0][round / 2 % 2];
            let mut corners = Vec::new();
            let mut faces = Vec::new();
            for i in 0..6 {
                let x = if round % 3 == 2 {
                    deep + rng.random_range(-0.1..0.1)
                } else {
                    face + side * rng.random_range(1e-12..2e-10)
                };
                let (y, z) = (3.0 + 1e-3 * i as f64, 3.0 + 5e-4 * i as f64);
                for v in [[x, y, z + 1e-3], [x, y + 5e-4, z], [x, y + 5e-4, z + 8e-4]] {
                    corners.push(pose.apply(DVec3::from(v)).to_array());
                }
                faces.push(vec![3 * i, 3 * i + 1, 3 * i + 2]);
            }
            let cluster = PolygonMesh::new(corners.clone(), faces.clone());
            let (posed, touch) = posed_and_touching(&body, pose);
            let exact = touch(&cluster)
                || (0..6).any(|i| {
                    posed
                        .inside_by_ray(DVec3::from(corners[3 * i]), &mut Vec::new())
                        .unwrap()
                });
            // The cluster alone: its box, carried back, is read whole
            // ("One cell holds a body") where it lies in classified cells.
            let checker = SceneChecker::new(&body, &[MeshBody::new(&cluster).unwrap()]).unwrap();
            assert_eq!(checker.collides_at(pose).unwrap(), exact, "{pose:?}");
            let stats = checker.containment_stats();
            read_whole += usize::from(stats.bodies_by_grid > 0);
            // With a triangle far beyond the body's reach, the scene's box
            // is too wide for that: the corners are read together.
            let mut far = corners.clone();
            for v in [[1e3, 0.0, 0.0], [1e3, 1.0, 0.0], [1e3, 0.0, 1.0]] {
                far.push(pose.apply(DVec3::from(v)).to_array());
            }
            let mut far_faces = faces;
            far_faces.push(vec![18, 19, 20]);
            let scene = MeshBody::new(&PolygonMesh::new(far, far_faces)).unwrap();
            let checker = SceneChecker::new(&body, &[scene]).unwrap();
            assert_eq!(checker.collides_at(pose).unwrap(), exact, "{pose:?}");
            let stats = checker.containment_stats();
            assert_eq!(stats.bodies_by_grid, 0);
            read += usize::from(stats.by_ray + stats.by_segment == 0 && stats.by_grid > 0);
            answers += 1;
            colliding += usize::from(exact);
        }
        assert!(
            colliding > 50 && answers - colliding > 50 && read > 50 && read_whole > 50,
            "{colliding} colliding, {read} read from the grid alone, {read_whole} whole, of {answers}"
        );
    }

    /// "One cell holds a body" (module docs) where the rounding decides:
    /// the shell far from the origin, its cavity's face 10⁻¹¹ before a
    /// cell's plane (so the cavity's cell beyond that plane is classified
    /// outside), against a cluster of six triangles 5 · 10⁻⁴ wide in the
    /// cavity whose nearest corners lie within 2 · 10⁻¹⁰ of the face,
    /// before it or beyond it (crossing the face, into the wall), or deep
    /// in that cell. The scene's box carried back is off by about 10⁻¹⁰
    /// there: every answer is the exact one (the surfaces' test, then each
    /// corner's own ray), and the grid decided many.
    #[test]
    fn a_scene_read_whole_is_never_one_the_rounding_may_move_off_a_face() {
        use rand::{Rng, SeedableRng};
        let planes = shell(2.5).inside_grid().planes()[0].clone();
        // The first plane in the cavity (from 2.5 to 6).
        let plane = *planes.iter().find(|&&x| x > 3.0).unwrap();
        let face = plane - 1e-11;
        let body = shell(face);
        assert_eq!(body.inside_grid().planes()[0], planes);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(13);
        let (mut colliding, mut free, mut whole) = (0, 0, 0);
        for round in 0..600 {
            let pose = far_pose_where_rounding_decides(&mut rng, round);
            let mut corners = Vec::new();
            let mut faces = Vec::new();
            // Crossing the face, or all before it within 2 · 10⁻¹⁰, or deep
            // in the cavity's cell beyond the plane.
            let (from, to) = [(-2e-10, 0.0), (1e-12, 2e-10), (1e-4, 1e-3)][round % 3];
            for i in 0..6 {
                let near = face + rng.random_range(from..to);
                let (y, z) = (3.0 + 1e-5 * i as f64, 3.0 + 5e-6 * i as f64);
                for v in [
                    [near, y, z],
                    [face + 3e-4, y + 5e-4, z],
                    [face + 3e-4, y, z + 5e-4],
                ] {
                    corners.push(pose.apply(DVec3::from(v)).to_array());
                }
                faces.push(vec![3 * i, 3 * i + 1, 3 * i + 2]);
            }
            let cluster = PolygonMesh::new(corners.clone(), faces);
            let (posed, touch) = posed_and_touching(&body, pose);
            let exact = touch(&cluster)
                || (0..18).any(|i| {
                    posed
                        .inside_by_ray(DVec3::from(corners[i]), &mut Vec::new())
                        .unwrap_or(true)
                });
            let checker = SceneChecker::new(&body, &[MeshBody::new(&cluster).unwrap()]).unwrap();
            assert_eq!(
                checker.collides_at(pose).unwrap(),
                exact,
                "{round}: {pose:?}"
            );
            whole += usize::from(checker.containment_stats().bodies_by_grid > 0);
            colliding += usize::from(exact);
            free += usize::from(!exact);
        }
        assert!(
            colliding > 50 && free > 50 && whole > 50,
            "{colliding} colliding, {free} free, {whole} read whole"
        );
    }

    /// The closed box from `lo` to `hi`, its corners exactly those
    /// coordinates.
    fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> PolygonMesh {
        let mut mesh = crate::robot::shapes::box_mesh(DVec3::ONE);
        for v in &mut mesh.vertices {
            *v = std::array::from_fn(|k| if v[k] < 0.0 { lo[k] } else { hi[k] });
        }
        mesh
    }

    /// The closed box `[lo, hi]` with each face split into `k × k` quads
    /// (welded, outward): enough triangles for a fine inside grid.
    fn split_cuboid(lo: [f64; 3], hi: [f64; 3], k: usize) -> PolygonMesh {
        let mut index = std::collections::HashMap::new();
        let mut vertices = Vec::new();
        let mut at = |q: [usize; 3]| {
            *index.entry(q).or_insert_with(|| {
                vertices.push(std::array::from_fn(|d| {
                    lo[d] + (hi[d] - lo[d]) * q[d] as f64 / k as f64
                }));
                vertices.len() - 1
            })
        };
        let mut faces = Vec::new();
        for a in 0..3 {
            let (b, c) = ((a + 1) % 3, (a + 2) % 3);
            for side in [0, k] {
                for u in 0..k {
                    for v in 0..k {
                        let mut quad: Vec<usize> = [(u, v), (u + 1, v), (u + 1, v + 1), (u, v + 1)]
                            .iter()
                            .map(|&(x, y)| {
                                let mut q = [0; 3];
                                (q[a], q[b], q[c]) = (side, x, y);
                                at(q)
                            })
                            .collect();
                        if side == 0 {
                            quad.reverse();
                        }
                        faces.push(quad);
                    }
                }
            }
        }
        PolygonMesh::new(vertices, faces)
    }

    /// Two split boxes with a gap of 4 between them (x from −8 to −2 and
    /// from 2 to 8), and optionally an open square sheet in the gap's
    /// middle plane `x = 0`.
    fn two_blocks(sheet: bool) -> PolygonMesh {
        let blocks = [
            split_cuboid([-8.0; 3], [-2.0, 8.0, 8.0], 8),
            split_cuboid([2.0, -8.0, -8.0], [8.0; 3], 8),
        ];
        let sheet = sheet.then(|| {
            PolygonMesh::new(
                vec![
                    [0.0, -3.0, -3.0],
                    [0.0, 3.0, -3.0],
                    [0.0, 3.0, 3.0],
                    [0.0, -3.0, 3.0],
                ],
                vec![vec![0, 1, 2, 3]],
            )
        });
        let parts: Vec<(PolygonMesh, [f64; 3])> = blocks
            .into_iter()
            .chain(sheet)
            .map(|m| (m, [0.0; 3]))
            .collect();
        joined(&parts, 1.0)
    }

    /// The exact quarter turn about z.
    fn quarter_about_z() -> Rotation {
        Rotation::from_quat(glam::DQuat::from_xyzw(
            0.0,
            0.0,
            0.5f64.sqrt(),
            0.5f64.sqrt(),
        ))
    }

    /// "One cell holds a body" (module docs): a small cube (and an open
    /// triangle) among two large blocks, and the blocks as the body about
    /// a small cube, at random poses over the blocks, their gap and their
    /// walls (generic turns and quarter turns): every answer is the walk
    /// followed by the containment test's, and the grid decided states in
    /// both cases, inside and outside. A sheet in the gap, open, is in no
    /// grid: with it, neither case is tried, and a cube across it collides.
    #[test]
    fn one_cell_holding_a_body_answers_as_the_walk_then_containment() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(97);
        let blocks = MeshBody::new(&two_blocks(false)).unwrap();
        let speck = MeshBody::new(&cuboid([-0.1; 3], [0.1; 3])).unwrap();
        let flake = MeshBody::new(&PolygonMesh::new(
            vec![[0.0, 0.0, 0.0], [0.2, 0.0, 0.0], [0.0, 0.2, 0.05]],
            vec![vec![0, 1, 2]],
        ))
        .unwrap();
        let by_cells = |checker: &SceneChecker, pose: Pose| {
            let mut s = checker.scratch();
            checker.check_range(&pose).unwrap();
            s.at.start(checker.body.vertices.len());
            checker.fit_node_cache(&mut s);
            let out = checker
                .carry_unless_parted(&pose, &mut s)
                .and_then(|c| checker.one_cell_holds_a_body(pose, &c, &mut s));
            checker.give_back(s);
            out
        };
        let quarter = quarter_about_z();
        for (case, checker) in [
            (
                1,
                SceneChecker::new(&speck, std::slice::from_ref(&blocks)).unwrap(),
            ),
            (
                1,
                SceneChecker::new(&flake, std::slice::from_ref(&blocks)).unwrap(),
            ),
            (
                2,
                SceneChecker::new(&blocks, std::slice::from_ref(&speck)).unwrap(),
            ),
        ] {
            let mut decided = [0usize; 2];
            for k in 0..3_000 {
                let rotation = if k % 3 == 0 {
                    quarter
                } else {
                    random_turn(&mut rng)
                };
                let t = DVec3::new(
                    rng.random_range(-9.0..9.0),
                    rng.random_range(-9.0..9.0),
                    rng.random_range(-9.0..9.0),
                );
                // Case 2 moves the blocks about the speck at the origin.
                let pose = Pose::new(rotation, if case == 1 { t } else { rotation.apply(-t) });
                let now = checker.collides_at(pose).unwrap();
                assert_eq!(
                    now,
                    walk_then_containment(&checker, pose),
                    "case {case}, {k}: {pose:?}"
                );
                if let Some(inside) = by_cells(&checker, pose) {
                    assert_eq!(inside, now, "case {case}, {k}");
                    decided[usize::from(inside)] += 1;
                }
            }
            assert!(
                decided[0] > 100 && decided[1] > 100,
                "case {case}: {decided:?}"
            );
            // Counted once by `collides_at` and once by `by_cells` (by the
            // grid, or where a cell is mixed by "No triangle by a body").
            let stats = checker.containment_stats();
            assert_eq!(
                (stats.bodies_by_grid + stats.bodies_by_region) as usize,
                2 * (decided[0] + decided[1]),
                "case {case}"
            );
        }
        // The sheet across the gap: the speck on it collides, and no grid
        // decides (the scene's, or the body's, has a surface component).
        let sheeted = MeshBody::new(&two_blocks(true)).unwrap();
        let on_sheet = Pose::new(Rotation::IDENTITY, DVec3::new(0.05, 0.5, 0.5));
        let checker = SceneChecker::new(&speck, std::slice::from_ref(&sheeted)).unwrap();
        assert!(checker.collides_at(on_sheet).unwrap());
        assert_eq!(by_cells(&checker, on_sheet), None);
        let checker = SceneChecker::new(&sheeted, std::slice::from_ref(&speck)).unwrap();
        let back = Pose::new(Rotation::IDENTITY, -on_sheet.translation);
        assert!(checker.collides_at(back).unwrap());
        assert_eq!(by_cells(&checker, back), None);
    }

    /// Joined meshes, each moved by `offset` and scaled by `scale`.
    fn joined(parts: &[(PolygonMesh, [f64; 3])], scale: f64) -> PolygonMesh {
        let mut mesh = PolygonMesh::new(Vec::new(), Vec::new());
        for (part, offset) in parts {
            let base = mesh.vertices.len();
            mesh.vertices.extend(
                part.vertices
                    .iter()
                    .map(|v| std::array::from_fn(|k| (v[k] + offset[k]) * scale)),
            );
            mesh.faces.extend(
                part.faces
                    .iter()
                    .map(|f| f.iter().map(|&v| v + base).collect()),
            );
        }
        mesh
    }

    /// "No triangle by a body" (module docs): small bodies of several
    /// components (closed cubes and an open triangle; open triangles alone)
    /// by the walls of two
    /// large blocks (with and without an open sheet between them, so with
    /// the grid's reading tried first or not at all; open, so with no grid;
    /// the blocks also in units a thousand times smaller), the blocks as the body and as the
    /// scene, at generic and quarter turns: every answer is the walk
    /// followed by the containment test's, and one point decided states
    /// of both answers in every case.
    #[test]
    fn a_body_no_triangle_comes_near_is_decided_by_one_point() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(101);
        let flake = PolygonMesh::new(
            vec![[0.0, 0.0, 0.0], [0.2, 0.0, 0.0], [0.0, 0.2, 0.05]],
            vec![vec![0, 1, 2]],
        );
        let cube = || cuboid([-0.1; 3], [0.1; 3]);
        let specks = MeshBody::new(&joined(
            &[
                (cube(), [0.0; 3]),
                (cube(), [0.35, 0.0, 0.0]),
                (cube(), [0.0, 0.3, 0.2]),
                (flake.clone(), [-0.3, -0.2, 0.1]),
            ],
            1.0,
        ))
        .unwrap();
        // Surfaces alone: the containment test then numbers the scene's
        // corners from the first (a body of them asks no point of its own).
        let flakes = MeshBody::new(&joined(
            &[
                (flake.clone(), [0.0; 3]),
                (flake.clone(), [0.3, 0.1, 0.0]),
                (flake, [0.0, -0.3, 0.2]),
            ],
            1.0,
        ))
        .unwrap();
        let quarter = quarter_about_z();
        // Also far from the origin, where the posing rounds most.
        for (scale, offset) in [(1.0, 0.0), (1e3, 0.0), (1.0, 1e6)] {
            // Closed blocks, with the sheet, and open at the top (surfaces
            // alone: no grid, so the tree is asked for a small body alone).
            for (sheet, open) in [(false, false), (true, false), (false, true)] {
                let mut mesh = two_blocks(sheet);
                if open {
                    let vertices = mesh.vertices.clone();
                    mesh.faces
                        .retain(|f| f.iter().any(|&v| vertices[v][2] < 8.0));
                }
                let blocks = MeshBody::new(&joined(&[(mesh, [offset; 3])], scale)).unwrap();
                assert_eq!(blocks.solid_components.is_empty(), open);
                for (case, small) in [(1, &specks), (1, &flakes), (2, &specks), (2, &flakes)] {
                    let checker = if case == 1 {
                        SceneChecker::new(small, std::slice::from_ref(&blocks)).unwrap()
                    } else {
                        SceneChecker::new(&blocks, std::slice::from_ref(small)).unwrap()
                    };
                    let solids = small.solid_components.len();
                    let mut decided = [0usize; 2];
                    for k in 0..2_000 {
                        let rotation = if k % 3 == 0 {
                            quarter
                        } else {
                            random_turn(&mut rng)
                        };
                        // By a wall of a block (x = ±2 or ±8), or anywhere.
                        let wall = [-8.0, -2.0, 2.0, 8.0][k % 4] + rng.random_range(-0.8..0.8);
                        let x = if k % 5 == 0 {
                            rng.random_range(-9.0..9.0)
                        } else {
                            wall
                        };
                        let mut t =
                            DVec3::new(x, rng.random_range(-9.0..9.0), rng.random_range(-9.0..9.0))
                                * scale;
                        if k % 6 == 3 {
                            // A quarter turn: the small body's extreme corner
                            // on a gap's wall (x = ±2), up to the rounding.
                            let m = rotation.matrix();
                            let m = if case == 1 { m } else { m.transpose() };
                            let xs = small.vertices.iter().map(|&v| (m * v).x);
                            let (lo, hi) =
                                xs.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
                            t.x = if k % 12 == 3 {
                                2.0 * scale - hi
                            } else {
                                -2.0 * scale - lo
                            };
                            t.y = t.y.clamp(-6.0 * scale, 6.0 * scale);
                            t.z = t.z.clamp(-6.0 * scale, 6.0 * scale);
                        }
                        let t = t + DVec3::splat(offset * scale);
                        // Case 2 moves the blocks about the specks.
                        let pose =
                            Pose::new(rotation, if case == 1 { t } else { rotation.apply(-t) });
                        let before = checker.containment_stats().bodies_by_region;
                        let now = checker.collides_at(pose).unwrap();
                        let what = format!(
                            "scale {scale}, offset {offset}, sheet {sheet}, open {open}, case {case}, {solids} solids, {k}: {pose:?}"
                        );
                        assert_eq!(now, walk_then_containment(&checker, pose), "{what}");
                        if checker.containment_stats().bodies_by_region > before {
                            decided[usize::from(now)] += 1;
                        }
                    }
                    // Open blocks hold nothing inside: free answers alone.
                    assert!(
                        decided[0] > 50 && (open || decided[1] > 50),
                        "scale {scale}, offset {offset}, sheet {sheet}, open {open}, case {case}, {solids} solids: {decided:?}"
                    );
                }
            }
        }
    }

    /// "No triangle by a body" (module docs): the plane test's slack. A
    /// tiny box touches, at one corner, the centre of a huge slanted face
    /// through the origin (integer corners near 10⁷ with `p₂ = −p₀ − p₁`,
    /// so the face's plane holds the origin exactly); the rounded plane
    /// values of the face's corners are far from zero, so without the
    /// slack the plane would often part the box from the face. Every
    /// state collides (contact), as the walk finds.
    #[test]
    fn the_plane_test_parts_no_box_touching_a_huge_slanted_face() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(103);
        let integer = |rng: &mut rand_chacha::ChaCha8Rng| {
            DVec3::new(
                rng.random_range(-10_000_000i64..10_000_000) as f64,
                rng.random_range(-10_000_000i64..10_000_000) as f64,
                rng.random_range(-10_000_000i64..10_000_000) as f64,
            )
        };
        for k in 0..400 {
            let (p0, p1) = (integer(&mut rng), integer(&mut rng));
            let p2 = -p0 - p1;
            let n = (p1 - p0).cross(p2 - p0);
            if n.length() < 1e12 {
                continue;
            }
            // The apex on the face's negative side, the box on its positive.
            let apex = -n.normalize() * 1e7;
            let scene = MeshBody::new(&PolygonMesh::new(
                [p0, p1, p2, apex].map(|p| p.to_array()).to_vec(),
                vec![vec![0, 1, 2], vec![0, 3, 1], vec![1, 3, 2], vec![2, 3, 0]],
            ))
            .unwrap();
            assert_eq!(scene.solid_components.len(), 1);
            let s = 1e-3;
            let lo: [f64; 3] = std::array::from_fn(|a| if n[a] >= 0.0 { 0.0 } else { -s });
            let body = MeshBody::new(&cuboid(lo, lo.map(|x| x + s))).unwrap();
            let checker = SceneChecker::new(&body, &[scene]).unwrap();
            let rest = Pose::new(Rotation::IDENTITY, DVec3::ZERO);
            assert!(checker.collides_at(rest).unwrap(), "{k}: {p0} {p1}");
            assert!(walk_then_containment(&checker, rest), "{k}");
        }
    }

    /// Containment asked first (module docs) answers as the walk followed
    /// by the containment did, on boxes touching face to face, edge to
    /// face and corner to face (a ray then starts on a triangle of the
    /// other body), nested, crossing and apart, at exact quarter turns and
    /// a generic turn; and it decides the nested ones before any walk.
    #[test]
    fn containment_first_answers_as_the_walk_then_containment() {
        let body = MeshBody::new(&cuboid([-0.5; 3], [0.5; 3])).unwrap();
        let room = MeshBody::new(&cuboid([-4.0, -4.0, -4.0], [4.0, 4.0, 4.0])).unwrap();
        let plate = MeshBody::new(&cuboid([6.0, -2.0, -2.0], [6.25, 2.0, 2.0])).unwrap();
        let checker = SceneChecker::new(&body, &[room, plate]).unwrap();
        let before = |pose: Pose| walk_then_containment(&checker, pose);
        let turns = [
            Rotation::IDENTITY,
            quarter_about_z(),
            Rotation::from_quat(glam::DQuat::from_xyzw(0.1, -0.3, 0.2, 0.9).normalize()),
        ];
        let mut seen = [0usize; 2];
        for rotation in turns {
            // Steps of 1/8 from deep inside the room through its wall
            // (the body's faces on it from inside at x = 3.5, from outside
            // at 4.5), the gap, the plate (touching at 5.5 and 6.75) and
            // beyond.
            for step in 0..=64 {
                let x = step as f64 / 8.0;
                for yz in [0.0, 0.5, 3.5, 4.5] {
                    let pose = Pose::new(rotation, DVec3::new(x, yz, -yz));
                    let now = checker.collides_at(pose).unwrap();
                    assert_eq!(now, before(pose), "{pose:?}");
                    seen[usize::from(now)] += 1;
                }
            }
        }
        assert!(seen[0] > 20 && seen[1] > 20, "{seen:?}");
        // Nested: the first points asked decide, no walk needed.
        let deep = Pose::new(Rotation::IDENTITY, DVec3::new(1.0, 0.0, 0.0));
        let mut s = checker.scratch();
        s.at.start(checker.body.vertices.len());
        checker.fit_node_cache(&mut s);
        assert!(!checker.surfaces_meet_lazily(deep, &checker.carry(&deep), &mut s, false));
        assert!(checker
            .one_inside_the_other(deep, &mut s, 0..POINTS_ASKED_FIRST)
            .unwrap());
        // Face to face from outside: the body's corners lie on the room's
        // wall, and a ray from one starts on a wall triangle.
        let touching = Pose::new(Rotation::IDENTITY, DVec3::new(4.5, 0.0, 0.0));
        assert!(checker.collides_at(touching).unwrap());
        assert!(!checker
            .collides_at(Pose::new(Rotation::IDENTITY, DVec3::new(4.625, 0.0, 0.0)))
            .unwrap());
    }

    /// A body of `n³` small cubes on a grid of spacing `gap` about the
    /// origin: `n³` solid components.
    fn cubes(n: usize, gap: f64) -> PolygonMesh {
        let mut vertices = Vec::new();
        let mut faces = Vec::new();
        let half = (n as f64 - 1.0) * gap / 2.0;
        for k in 0..n * n * n {
            let at = DVec3::new((k % n) as f64, (k / n % n) as f64, (k / n / n) as f64) * gap
                - DVec3::splat(half);
            let cube = cuboid((at - 0.25).to_array(), (at + 0.25).to_array());
            let base = vertices.len();
            vertices.extend(cube.vertices);
            faces.extend(
                cube.faces
                    .into_iter()
                    .map(|f| f.into_iter().map(|v| v + base).collect()),
            );
        }
        PolygonMesh::new(vertices, faces)
    }

    /// The body's components near the scene (module docs): every
    /// component whose float-posed vertex lies in the box of the scene's
    /// solids is listed. The scene's box is built with its corner exactly
    /// at one posed vertex and as little as a few ulps wide, at generic
    /// turns, far from the origin and near it (the rounding of the carried
    /// box decides those); and the answers of `collides_at` are those of
    /// asking every component in turn, on cubes crossing a room's wall and
    /// a plate.
    #[test]
    fn the_components_near_the_scene_hold_every_vertex_posed_in_its_solids() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(71);
        let body = MeshBody::new(&cubes(3, 1.0)).unwrap();
        assert!(body.component_points().is_some());
        let mut near = Vec::new();
        let mut listed_at_a_corner = 0;
        for k in 0..400 {
            let rotation = random_turn(&mut rng);
            let far = [1.0, 1e3, 1e6][k % 3];
            let t = DVec3::new(rng.random_range(-1.0..1.0), 0.3, -0.7) * far;
            let pose = Pose::new(rotation, t);
            // The posed vertex of a random component, as the test poses it.
            let c = rng.random_range(0..body.components.len());
            let checker = SceneChecker::new(&body, std::slice::from_ref(&body)).unwrap();
            let mut s = checker.scratch();
            s.at.start(body.vertices.len());
            let p = s.at.get(&body.vertices, &pose, body.components[c].1);
            checker.give_back(s);
            // A scene solid with its lowest corner exactly there, a few
            // ulps wide (so the carried box is as small as the rounding).
            let wide = far * [1e-14, 1e-12, 1.0][k % 7 % 3];
            let scene = MeshBody::new(&cuboid(p.to_array(), (p + wide).to_array())).unwrap();
            assert_eq!(scene.solid_tree.root().lo, p.to_array());
            let checker = SceneChecker::new(&body, &[scene]).unwrap();
            assert!(checker.components_near_the_scene(&pose, &mut near));
            assert!(near.contains(&c), "{k} {pose:?}");
            assert!(near.windows(2).all(|w| w[0] < w[1]));
            listed_at_a_corner += 1;
        }
        assert_eq!(listed_at_a_corner, 400);
        // The answers, against asking every component in turn.
        let room = MeshBody::new(&cuboid([-4.0; 3], [4.0; 3])).unwrap();
        let plate = MeshBody::new(&cuboid([6.0, -2.0, -2.0], [6.25, 2.0, 2.0])).unwrap();
        let checker = SceneChecker::new(&body, &[room, plate]).unwrap();
        let every_component = |pose: Pose| {
            let mut s = checker.scratch();
            s.at.start(checker.body.vertices.len());
            checker.fit_node_cache(&mut s);
            let mut parity = Vec::new();
            let inside = checker.body.components.iter().any(|&(_, v)| {
                let p = s.at.get(&checker.body.vertices, &pose, v);
                checker
                    .scene
                    .inside_solid(p, &mut None, &mut parity, &mut Default::default())
                    .unwrap()
            });
            let corners = checker.body.components.len()..usize::MAX;
            let out = inside
                || checker.surfaces_meet_lazily(pose, &checker.carry(&pose), &mut s, false)
                || checker.one_inside_the_other(pose, &mut s, corners).unwrap();
            checker.give_back(s);
            out
        };
        let mut seen = [0usize; 2];
        for k in 0..600 {
            let rotation = Rotation::from_quat(
                glam::DQuat::from_xyzw(0.1, -0.3, 0.2 + k as f64 * 0.01, 0.9).normalize(),
            );
            let pose = Pose::new(rotation, DVec3::new(k as f64 / 64.0, 0.25, -0.5));
            let now = checker.collides_at(pose).unwrap();
            assert_eq!(now, every_component(pose), "{pose:?}");
            seen[usize::from(now)] += 1;
        }
        assert!(seen[0] > 50 && seen[1] > 50, "{seen:?}");
    }

    /// The roots' test before everything (module docs, "The roots first")
    /// parts no pair that touches: a body (a box and a tetrahedron) turned
    /// about random axes and by quarter turns, far from the origin, and a
    /// scene box whose face lies exactly at the body's farthest posed vertex
    /// (touching: a collision; the exact hulls touch, the computed boxes
    /// overlap by their pads), or one float beyond it (free: nothing
    /// touches), or beyond the body's box at any turn (free, and the
    /// roots' test parts it).
    /// It fails when the posed root box is not grown by the posing's
    /// rounding bound, or the scene's carried back not by its own.
    #[test]
    fn the_roots_test_parts_no_touching_pair() {
        use rand::{Rng, SeedableRng};
        let tetrahedron = PolygonMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [3.0, 0.1, 0.2],
                [0.3, 1.7, 0.1],
                [0.2, 0.3, 2.3],
            ],
            vec![vec![0, 2, 1], vec![0, 1, 3], vec![0, 3, 2], vec![1, 2, 3]],
        );
        let bodies = [cuboid([-0.5, -0.25, -1.0], [0.75, 0.5, 1.0]), tetrahedron];
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(35);
        let mut touching = 0;
        for trial in 0..600 {
            let mesh = &bodies[trial % 2];
            let body = MeshBody::new(mesh).unwrap();
            let axis = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            // Every third trial an exact quarter turn (the carried boxes
            // are then tight, and only the translation rounds).
            let quarter = trial % 3 == 0;
            let axis = if quarter {
                DVec3::AXES[trial / 3 % 3]
            } else {
                axis
            };
            let angle = if quarter {
                std::f64::consts::FRAC_PI_2 * (1 + trial / 9 % 3) as f64
            } else {
                rng.random_range(0.0..std::f64::consts::TAU)
            };
            let far = [1.0, 1e3, 1e6, 3e8][trial % 4];
            let t = DVec3::new(far + 0.123_456_7, -far * 0.7, far * 0.3 + 0.1);
            let Some(rotation) = Rotation::from_axis_angle(axis, angle) else {
                continue;
            };
            let pose = Pose::new(rotation, t);
            let posed: Vec<DVec3> = mesh
                .vertices
                .iter()
                .map(|&v| pose.apply(DVec3::from(v)))
                .collect();
            let top = posed
                .iter()
                .copied()
                .fold(posed[0], |a, b| if b.x > a.x { b } else { a });
            for (face, collides) in [(top.x, true), (f64::from_bits(top.x.to_bits() + 1), false)] {
                let wall = cuboid(
                    [face, top.y - 5.0, top.z - 5.0],
                    [face + 10.0, top.y + 5.0, top.z + 5.0],
                );
                let checker = SceneChecker::new(&body, &[MeshBody::new(&wall).unwrap()]).unwrap();
                assert_eq!(
                    checker.collides_at(pose).unwrap(),
                    collides,
                    "trial {trial}, the wall at {face}"
                );
                touching += usize::from(collides);
            }
            let wall = cuboid(
                [top.x + 8.0, top.y - 5.0, top.z - 5.0],
                [top.x + 18.0, top.y + 5.0, top.z + 5.0],
            );
            let checker = SceneChecker::new(&body, &[MeshBody::new(&wall).unwrap()]).unwrap();
            let mut s = checker.scratch();
            s.at.start(checker.body.vertices.len());
            checker.fit_node_cache(&mut s);
            assert!(
                checker.carry_unless_parted(&pose, &mut s).is_none(),
                "trial {trial}"
            );
            assert!(!checker.collides_at(pose).unwrap(), "trial {trial}");
        }
        assert!(touching > 500, "{touching}");
    }
}
