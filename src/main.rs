//! `redundant-ik`: the command-line shell over the library (simulation,
//! figures, training, evaluation). All mathematics lives in the library.

#[cfg(not(target_family = "wasm"))]
mod cli;

#[cfg(not(target_family = "wasm"))]
fn main() {
    std::process::exit(cli::main());
}

/// The command-line tool is native only; the wasm build is the library.
#[cfg(target_family = "wasm")]
fn main() {}
