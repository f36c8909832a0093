#![no_main]
//! OBJ reader, as one mesh and as separate bodies:
//! `cargo +nightly fuzz run read_obj`.

use dymsum_io::formats::{read_obj_objects_bytes, Format};
use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    common::check(data, Format::Obj);
    if let Ok(bodies) = read_obj_objects_bytes(data, "fuzz") {
        for (_, mesh) in &bodies {
            common::check_mesh(mesh);
        }
    }
});
