//! `dymsum completions SHELL`: a completion script for the shell, generated
//! from the command-line definition (so it never drifts from the flags).
//!
//! ```sh
//! dymsum completions bash > ~/.local/share/bash-completion/completions/dymsum
//! dymsum completions zsh > "${fpath[1]}/_dymsum"
//! dymsum completions fish > ~/.config/fish/completions/dymsum.fish
//! ```

use std::io::Write;

use clap::Args;
use clap_complete::Shell;

/// Arguments of `dymsum completions`.
#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// The shell to generate for.
    #[arg(value_enum, value_name = "SHELL")]
    pub shell: Shell,
}

/// Runs `dymsum completions`.
///
/// The script is generated in memory first (`clap_complete::generate`
/// panics on a write error), then written.
///
/// # Errors
/// If writing to `out` fails (e.g. a closed pipe or a full disk).
pub fn run(
    a: &CompletionsArgs,
    command: &mut clap::Command,
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(a.shell, command, "dymsum", &mut script);
    out.write_all(&script)?;
    out.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    /// A writer whose every write fails, like a closed pipe.
    struct Closed;

    impl Write for Closed {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::ErrorKind::BrokenPipe.into())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Err(std::io::ErrorKind::BrokenPipe.into())
        }
    }

    #[test]
    fn a_failed_write_is_an_error_not_a_panic() {
        let a = CompletionsArgs { shell: Shell::Bash };
        let err = run(&a, &mut crate::cli::Cli::command(), &mut Closed).unwrap_err();
        let io = err.downcast_ref::<std::io::Error>().expect("an I/O error");
        assert_eq!(io.kind(), std::io::ErrorKind::BrokenPipe);
        let mut script = Vec::new();
        run(&a, &mut crate::cli::Cli::command(), &mut script).unwrap();
        assert!(String::from_utf8(script).unwrap().contains("dymsum"));
    }
}
