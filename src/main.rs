//! `redundant-ik`: the command-line shell over the library (simulation,
//! figures, training, evaluation). All mathematics lives in the library.

mod cli;

fn main() {
    std::process::exit(cli::main());
}
