#![no_main]
//! Bodies of triangles from bytes: `cargo +nightly fuzz run bodies`. The
//! properties are `dymsum_testkit::fuzz_bodies::check`'s (cleaning,
//! sanity, both roles, touching, the winding number against solid angles);
//! `crates/dymsum/tests/fuzz_bodies.rs` runs them in CI under proptest.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    dymsum_testkit::fuzz_bodies::check(data);
});
