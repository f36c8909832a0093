#![no_main]
//! Every reader (the first byte picks OFF, OBJ, PLY or STL) and
//! `load_polytope_bytes` on the rest: `cargo +nightly fuzz run read_any`.

use dymsum::polytope::MeshPolicy;
use dymsum_io::formats::Format;
use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let format = Format::ALL[usize::from(pick) % Format::ALL.len()];
    common::check(rest, format);
    let _ = dymsum_io::load_polytope_bytes(rest, format, "fuzz", MeshPolicy::default());
});
