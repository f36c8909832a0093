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
/// # Errors
/// None: it always returns `Ok`.
///
/// # Panics
/// If writing to `out` fails: `clap_complete::generate` panics on a write
/// error.
pub fn run(
    a: &CompletionsArgs,
    command: &mut clap::Command,
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    clap_complete::generate(a.shell, command, "dymsum", out);
    Ok(())
}
