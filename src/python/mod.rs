//! The Python package's native module, `redundant_ik._core` (feature
//! `python`; docs/python.md): a thin shell over the library and the
//! command-line shell, as the page's `web` module is. The package's
//! Python half (python/redundant_ik) turns keywords into the command
//! line's flags and JSON into numpy arrays; what runs is the core's.
//!
//! - `cli`: a command of the tool (`simulate --json`, `atlas --json`,
//!   `train`, ...) in this process, the GIL released, Ctrl-C checked
//!   between an atlas's rows and a training's epochs;
//! - [`robot::Robot`]: an arm's kinematics (the hand, the frames, the
//!   Jacobian) as numpy arrays;
//! - [`controller::Controller`]: one rate evaluation of a method, for a
//!   loop of the user's own.
//!
//! Every refusal raises `redundant_ik.Error` (a `ValueError`) with the
//! core's message; nothing here panics on what Python passes.

// PyO3's macros expand to the C API's calls; the shell's own code has no
// unsafe block.
#![allow(unsafe_code)]

use pyo3::prelude::*;

pub mod controller;
pub mod robot;

pyo3::create_exception!(
    redundant_ik,
    Error,
    pyo3::exceptions::PyValueError,
    "What the core refused, with its message: a refused scene, a bad \
     argument, an unreadable URDF or weights file. A ValueError."
);

/// `Error(message)`.
pub(crate) fn error(message: impl Into<String>) -> PyErr {
    Error::new_err(message.into())
}

/// The core's error as `redundant_ik.Error`.
pub(crate) fn core_error(e: crate::Error) -> PyErr {
    error(e.to_string())
}

/// Whether Ctrl-C was pressed: checked (with the GIL, briefly) by the
/// tool's long loops through [`crate::cli::embed::set_interrupt_check`].
fn interrupted() -> bool {
    Python::attach(|py| match py.check_signals() {
        Ok(()) => false,
        Err(e) => {
            // Kept for the caller, which raises it once the loop stopped.
            e.restore(py);
            true
        }
    })
}

/// Runs a command of the command-line tool in this process and returns
/// what it prints (`args`: the command and its flags, as the tool takes
/// them, e.g. `["simulate", "--json", "--method", "qp"]`). The GIL is
/// released while it runs; Ctrl-C stops an atlas or a training between
/// rows or epochs (KeyboardInterrupt).
#[pyfunction]
fn cli(py: Python<'_>, args: Vec<String>) -> PyResult<String> {
    crate::cli::embed::set_interrupt_check(interrupted);
    let argv = std::iter::once("redundant-ik".to_string()).chain(args);
    let result = py.detach(move || crate::cli::embed::run_captured(argv));
    if let Some(e) = PyErr::take(py) {
        return Err(e);
    }
    result.map_err(error)
}

/// A command's options, `(id, flag, switch, repeated)` each: the flag
/// without its dashes and with `_` for `-`, the flag, whether it takes no
/// value, whether it may be given several times.
#[pyfunction]
fn options(command: &str) -> PyResult<Vec<(String, String, bool, bool)>> {
    let list = crate::cli::embed::options(command)
        .ok_or_else(|| error(format!("no command '{command}'")))?;
    Ok(list
        .into_iter()
        .map(|o| (o.id, o.flag, o.switch, o.repeated))
        .collect())
}

/// Every method as JSON: its name, label, description, group, the networks
/// it needs, whether it runs in space, its parameters with their bounds
/// and defaults.
#[pyfunction]
fn methods_json() -> String {
    let list: Vec<serde_json::Value> = crate::planner::methods::ALL
        .iter()
        .map(|m| {
            let mut v = serde_json::to_value(m.info()).unwrap_or_default();
            if let Some(o) = v.as_object_mut() {
                o.insert("in_space".into(), m.in_space().into());
                o.insert(
                    "params".into(),
                    serde_json::to_value(m.params()).unwrap_or_default(),
                );
            }
            v
        })
        .collect();
    serde_json::Value::Array(list).to_string()
}

/// The native half of the package `redundant_ik`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("Error", m.py().get_type::<Error>())?;
    m.add_function(wrap_pyfunction!(cli, m)?)?;
    m.add_function(wrap_pyfunction!(options, m)?)?;
    m.add_function(wrap_pyfunction!(methods_json, m)?)?;
    m.add_class::<robot::Robot>()?;
    m.add_class::<controller::Controller>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
