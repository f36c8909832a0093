//! The `dymsum` binary: see `dymsum --help` and the README.

fn main() -> std::process::ExitCode {
    dymsum_cli::main()
}
