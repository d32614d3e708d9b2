//! `redundant-ik train` (stub until the networks land).

/// Options of `redundant-ik train`.
#[derive(clap::Args, Debug)]
pub struct TrainArgs {}

/// Runs `redundant-ik train`.
pub fn run(_args: &TrainArgs) -> Result<(), String> {
    Err("training is not available yet".into())
}
