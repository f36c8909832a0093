//! Prints the markdown tables of `docs/BENCHMARKS.md` from criterion's
//! output (`new/estimates.json` `median.point_estimate` of every bench).
//!
//! `cargo run -p dymsum-bench --bin bench_table [-- CRITERION_DIR]`
//!
//! `CRITERION_DIR` defaults to `$CARGO_TARGET_DIR/criterion`, else the
//! workspace's `target/criterion`.

use std::path::PathBuf;
use std::process::ExitCode;

fn main() -> ExitCode {
    let dir = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(dymsum_bench::default_criterion_dir);
    match dymsum_bench::collect_results(&dir) {
        Ok(results) if !results.is_empty() => {
            print!("{}", dymsum_bench::markdown_report(&results));
            ExitCode::SUCCESS
        }
        Ok(_) => {
            eprintln!("no criterion results under {}", dir.display());
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("cannot read {}: {e}", dir.display());
            ExitCode::FAILURE
        }
    }
}
