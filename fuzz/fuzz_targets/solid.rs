#![no_main]
//! Grid solids changed in one known way, from bytes:
//! `cargo +nightly fuzz run solid`. The properties are
//! `dymsum_testkit::fuzz_solid::check`'s (`check_solid_mesh` and
//! `check_closed_mesh` answer as the change makes certain and as the
//! integer oracle judges, alike in an exact change of frame);
//! `crates/dymsum/tests/fuzz_solid.rs` runs them in CI under proptest.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    dymsum_testkit::fuzz_solid::check(data);
});
