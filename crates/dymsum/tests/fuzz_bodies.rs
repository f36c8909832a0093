//! Bodies of triangles from arbitrary bytes (issue 34: fuzzing went no
//! further than the readers): the stable run in CI of what the cargo-fuzz
//! target `fuzz/fuzz_targets/bodies.rs` checks off CI
//! (`dymsum_testkit::fuzz_bodies::check`): cleaning and classifying a soup
//! on a coarse grid never panics, the body passes its sanity check, the
//! scene checker answers the same in both roles, collides whenever the
//! triangles touch, and otherwise exactly when a float generalised winding
//! number (solid angles, an oracle independent of the exact ray test) is
//! not zero.

use dymsum_testkit::{fuzz_bodies, proptest_cases};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(proptest_cases(256)))]
    #[test]
    fn soups_from_bytes_keep_every_property(data in prop::collection::vec(any::<u8>(), 0..200)) {
        fuzz_bodies::check(&data);
    }
}
