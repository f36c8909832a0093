#![no_main]
//! OFF reader: `cargo +nightly fuzz run read_off`.

use dymsum_io::formats::Format;
use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    common::check(data, Format::Off);
});
