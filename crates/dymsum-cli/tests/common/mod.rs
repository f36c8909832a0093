//! Helpers shared by the CLI integration tests: running the `dymsum`
//! binary, fresh temp directories, fixtures and reading the output.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use dymsum::polytope::MeshPolicy;
use dymsum::Polytope;

/// The binary under test.
pub const BIN: &str = env!("CARGO_BIN_EXE_dymsum");

/// A fresh empty directory under the system temp dir, named after the test
/// suite, the process, a counter and `name`.
pub fn temp_dir(name: &str) -> PathBuf {
    dymsum_testkit::files::temp_dir(env!("CARGO_CRATE_NAME"), name)
}

/// The path of `tests/fixtures/NAME`.
pub fn fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

/// Runs `dymsum ARGS`, in `cwd` if given.
pub fn run_in(cwd: Option<&Path>, args: &[&str]) -> Output {
    let mut cmd = Command::new(BIN);
    cmd.args(args);
    if let Some(dir) = cwd {
        cmd.current_dir(dir);
    }
    cmd.output().expect("the dymsum binary runs")
}

/// Runs `dymsum ARGS`.
pub fn run(args: &[&str]) -> Output {
    run_in(None, args)
}

/// The output's stdout as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The output's stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `dymsum ARGS`, asserts success and returns stdout.
pub fn ok(args: &[&str]) -> String {
    let o = run(args);
    assert!(
        o.status.success(),
        "dymsum {args:?} failed: {}\n{}",
        stderr(&o),
        stdout(&o)
    );
    stdout(&o)
}

/// A built-in model or a mesh file, as a polytope.
pub fn model(spec: &str) -> Polytope {
    dymsum_io::load_polytope(spec, MeshPolicy::default())
        .unwrap()
        .polytope
}

/// Asserts that a run failed with exit `code` and that its stderr names
/// `needle`; the message shows the whole stderr otherwise.
#[track_caller]
pub fn assert_fails(o: &Output, code: i32, needle: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(code), "stderr: {err}");
    assert!(err.contains(needle), "stderr lacks `{needle}`: {err}");
}
