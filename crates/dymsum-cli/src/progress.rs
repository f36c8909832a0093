//! The one progress bar of the CLI: on stderr, and only when stderr is a
//! terminal (hidden in pipes, files and tests, so output stays clean).

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressStyle};

/// A progress bar over `len` items called `unit` (`"steps"`, `"slices"`,
/// `"pairs"`), labelled `what`; hidden when stderr is not a terminal.
/// Callers may update the label with `set_message`.
pub fn bar(len: u64, what: &str, unit: &str) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len);
    let template =
        format!("{{msg}} [{{elapsed_precise}}] {{wide_bar}} {{pos}}/{{len}} {unit} (eta {{eta}})");
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style);
    }
    bar.set_message(what.to_string());
    bar
}
