//! The exact triangle–triangle test, `dymsum::solid::triangles_meet` (the
//! scene checker's; issue 34: nothing fuzzed it), against an independent
//! oracle: the origin in the hull of the Minkowski difference, decided by
//! Carathéodory's theorem in integer arithmetic
//! (`dymsum_testkit::fuzz_triangles::check`). Pairs on a small grid rich
//! in shared corners and edges, coplanar overlaps, edges on faces, corners
//! on triangles, flat triangles and shifted copies, each also in a random
//! exact frame (scales from subnormal to `2^959`, shifts up to `2^31`). The
//! cargo-fuzz target `fuzz/fuzz_targets/triangles.rs` runs the same
//! check off CI.

use dymsum_testkit::{fuzz_triangles, proptest_cases};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(proptest_cases(2048)))]
    #[test]
    fn triangle_pairs_from_bytes_meet_as_the_oracle_says(
        data in prop::collection::vec(any::<u8>(), 0..40)
    ) {
        fuzz_triangles::check(&data);
    }
}
