#![no_main]
//! Pairs of triangles from bytes: `cargo +nightly fuzz run triangles`. The
//! properties are `dymsum_testkit::fuzz_triangles::check`'s
//! (`dymsum::solid::triangles_meet` against the Minkowski-difference
//! oracle, symmetric, independent of corner order and of an exact change
//! of frame); `crates/dymsum/tests/fuzz_triangles.rs` runs them in CI under
//! proptest.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    dymsum_testkit::fuzz_triangles::check(data);
});
