//! `redundant-ik eval` (stub until the networks land).

/// Options of `redundant-ik eval`.
#[derive(clap::Args, Debug)]
pub struct EvalArgs {}

/// Runs `redundant-ik eval`.
pub fn run(_args: &EvalArgs) -> Result<(), String> {
    Err("evaluation is not available yet".into())
}
