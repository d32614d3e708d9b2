//! The methods' parameters as command-line flags, one per declared
//! parameter ([`redundant_ik::planner::params::all`]): the flag, its help
//! and its default come from the declaration, so a parameter a method
//! declares is a flag of `simulate`, `figure` and `atlas` with nothing
//! written here. And which flags a command line gave ([`Given`]), for the
//! `--from` guard.

use clap::{parser::ValueSource, Arg, ArgMatches, Args, Command, FromArgMatches};
use redundant_ik::planner::params;
use redundant_ik::scene::Param;

/// The parameters given on the command line, in the order of the list.
#[derive(Debug, Clone, Default)]
pub struct ParamArgs {
    /// Each parameter given, with its value (checked when applied).
    pub values: Vec<(&'static Param, f64)>,
}

impl FromArgMatches for ParamArgs {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut out = Self::default();
        out.update_from_arg_matches(m)?;
        Ok(out)
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        for &p in params::all() {
            if let Some(&v) = m.get_one::<f64>(p.name) {
                self.values.retain(|(q, _)| !std::ptr::eq(*q, p));
                self.values.push((p, v));
            }
        }
        Ok(())
    }
}

impl Args for ParamArgs {
    fn augment_args(cmd: Command) -> Command {
        params::all().iter().fold(cmd, |cmd, p| {
            cmd.arg(
                Arg::new(p.name)
                    .long(p.flag.trim_start_matches("--"))
                    .value_name(if p.count { "N" } else { "X" })
                    .value_parser(clap::value_parser!(f64))
                    .allow_hyphen_values(true)
                    .help(p.help_text()),
            )
        })
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

/// The ids of the arguments a command line gave itself (not defaults).
#[derive(Debug, Clone, Default)]
pub struct Given(pub Vec<String>);

impl Given {
    /// Whether argument `id` was given.
    pub fn has(&self, id: &str) -> bool {
        self.0.iter().any(|g| g == id)
    }

    /// The flags (`--name`) of the arguments of `A` that were given, but
    /// for those `skip` rejects, in `A`'s order.
    pub fn flags_of<A: Args>(&self, skip: impl Fn(&clap::Id) -> bool) -> Vec<String> {
        A::augment_args(Command::new("args"))
            .get_arguments()
            .filter(|a| !skip(a.get_id()) && self.has(a.get_id().as_str()))
            .map(|a| format!("--{}", a.get_long().unwrap_or(a.get_id().as_str())))
            .collect()
    }
}

impl FromArgMatches for Given {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let ids = m
            .ids()
            .filter(|id| m.value_source(id.as_str()) == Some(ValueSource::CommandLine))
            .map(|id| id.as_str().to_string())
            .collect();
        Ok(Given(ids))
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl Args for Given {
    fn augment_args(cmd: Command) -> Command {
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        cmd
    }
}
