//! The tool run inside another program (the Python package): a command
//! line parsed and run in this process, its standard output returned as
//! text ([`run_captured`]); the options a command takes ([`options`]);
//! and a check of the caller's Ctrl-C between the rows of an atlas and
//! the epochs of a training ([`interrupted`]).

use clap::{CommandFactory, Parser};

use super::{dispatch, Cli};

/// What the long loops (an atlas's rows, a training's epochs) ask
/// between steps: whether the user asked to stop (the Python package's
/// Ctrl-C). Unset in the tool, whose Ctrl-C ends the process.
static INTERRUPT: std::sync::OnceLock<fn() -> bool> = std::sync::OnceLock::new();

/// Sets what [`interrupted`] asks (once; later calls keep the first).
pub fn set_interrupt_check(check: fn() -> bool) {
    let _ = INTERRUPT.set(check);
}

/// Whether the user asked a long loop to stop; its caller then returns
/// [`INTERRUPTED`] as its error.
pub fn interrupted() -> bool {
    INTERRUPT.get().is_some_and(|check| check())
}

/// The error of a loop stopped by [`interrupted`].
pub const INTERRUPTED: &str = "interrupted";

thread_local! {
    /// Where [`emit`] writes on this thread while [`run_captured`] runs.
    static CAPTURE: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
}

/// Runs the command line `args` (the program's name first, as
/// `std::env::args` gives it) in this process and returns what it would
/// print on standard output, or the message it would print as an error
/// (an argument clap refuses, a refused scene, ...). What the Python
/// package calls: `redundant_ik.simulate(...)` is `simulate --json` with
/// the flags its keywords name. `--help` returns the help text.
pub fn run_captured<I, T>(args: I) -> Result<String, String>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            return match e.kind() {
                ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => Ok(e.render().to_string()),
                _ => Err(clap_message(e)),
            };
        }
    };
    CAPTURE.with(|c| *c.borrow_mut() = Some(String::new()));
    let result = dispatch(&cli);
    let out = CAPTURE.with(|c| c.borrow_mut().take()).unwrap_or_default();
    result.map(|()| out)
}

/// clap's message for a refused command line, without its usage lines
/// (one line, as `main` prints the tool's own errors).
pub(super) fn clap_message(e: clap::Error) -> String {
    let text = e.render().to_string();
    text.trim_start_matches("error: ")
        .lines()
        .take_while(|l| !l.starts_with("Usage:"))
        .filter(|l| !l.trim().is_empty())
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(" ")
}

/// A command's option, as a caller that builds command lines (the Python
/// package's keywords) needs it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OptionInfo {
    /// Its id: the flag without its dashes, `_` for `-` (`joint_limits`).
    pub id: String,
    /// The flag (`--joint-limits`).
    pub flag: String,
    /// Whether it is a switch (no value).
    pub switch: bool,
    /// Whether it may be given several times (`--obstacle`).
    pub repeated: bool,
}

/// The options of a subcommand (`simulate`: `task`, `arm`, `lambda`,
/// ...), or `None` for no such command.
pub fn options(command: &str) -> Option<Vec<OptionInfo>> {
    use clap::ArgAction;
    let cli = Cli::command();
    let sub = cli.find_subcommand(command)?;
    Some(
        sub.get_arguments()
            .filter_map(|a| {
                let long = a.get_long()?;
                Some(OptionInfo {
                    id: long.replace('-', "_"),
                    flag: format!("--{long}"),
                    switch: matches!(a.get_action(), ArgAction::SetTrue),
                    repeated: matches!(a.get_action(), ArgAction::Append),
                })
            })
            .collect(),
    )
}

/// Appends `text` to this thread's capture, if [`run_captured`] is
/// running; whether it did.
pub(super) fn capture(text: &str) -> bool {
    CAPTURE.with(|c| match c.borrow_mut().as_mut() {
        Some(out) => {
            out.push_str(text);
            true
        }
        None => false,
    })
}
