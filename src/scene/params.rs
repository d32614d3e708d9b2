//! The numbers a method reads from its scene, each declared once by the
//! method (or constraint) that reads it ([`Param`], next to its
//! `MethodInfo`), and their values in a scene ([`Params`]), checked against
//! those declarations. Everything that shows or takes a parameter (the
//! command line's flags and help, the `--from` guard, the page's sliders,
//! the address, a run's JSON and the checks) reads the declarations; the
//! list of every declared parameter is the methods'
//! ([`crate::planner::methods::params`]).

use std::fmt;

use serde::Serialize;

use crate::error::{finite, non_negative, within, Error, Result};

/// Largest `K dt` accepted for the closed-loop gain. The tracking error then
/// obeys `e' = -K e`, which classical RK4 integrates stably only for
/// `K dt < 2.785`; 2.5 leaves a margin for the arm's nonlinearity.
pub const MAX_GAIN_STEP: f64 = 2.5;

pub(crate) fn validate_gain(gain: f64, dt: f64) -> Result<()> {
    non_negative("feedback gain", gain)?;
    if gain * dt > MAX_GAIN_STEP {
        return Err(Error::UnstableGain {
            gain,
            dt,
            max_gain: MAX_GAIN_STEP / dt,
            max_step: MAX_GAIN_STEP,
        });
    }
    Ok(())
}

/// How a parameter's slider moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Scale {
    /// In steps of the value itself.
    Linear,
    /// In powers of ten (`log10` of the value): a weight that spans orders
    /// of magnitude.
    Log,
}

/// A number of the scene that a method reads, declared as a `static` in
/// the file of the method or constraint that reads it and listed in its
/// `MethodInfo::params`. Compared by identity (its address): two
/// declarations are two parameters, even with equal fields.
#[derive(Debug, Serialize)]
pub struct Param {
    /// The name in URLs and JSON (`lambda`, `influence`, ...).
    pub name: &'static str,
    /// The command line's flag (`--lambda`, `--influence`, ...).
    pub flag: &'static str,
    /// What a control is labelled.
    pub label: &'static str,
    /// What a message calls it (ASCII: `damping factor delta`).
    #[serde(skip)]
    pub what: &'static str,
    /// What it does, for the command line's help (the default is printed
    /// after it from [`Param::default`]); only the tool carries it.
    #[cfg(feature = "cli")]
    #[serde(skip)]
    pub help: &'static str,
    /// Its unit, if any.
    pub unit: &'static str,
    /// Smallest and largest value accepted.
    pub bounds: (f64, f64),
    /// Its value where a scene does not set it (the paper's, for the
    /// paper's own parameters).
    pub default: f64,
    /// The span and step of a slider for it, `(min, max, step)`, in the
    /// slider's [`Scale`].
    pub slider: (f64, f64, f64),
    /// How the slider moves.
    pub scale: Scale,
    /// Whether it counts something (a whole number).
    pub count: bool,
    /// A parameter it must stay strictly below (the stop distance below
    /// the influence distance); that one names this in [`Param::above`].
    #[serde(skip)]
    pub below: Option<&'static Param>,
    /// The parameter that must stay strictly below this one.
    #[serde(skip)]
    pub above: Option<&'static Param>,
}

impl PartialEq for Param {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
    }
}

impl Eq for Param {}

impl fmt::Display for Param {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name)
    }
}

impl Param {
    /// Checks a value against the bounds (and, for a count, that it is
    /// whole), changing nothing.
    pub fn check(&self, value: f64) -> Result<()> {
        finite(self.what, value)?;
        let (lo, hi) = self.bounds;
        if lo == 0.0 {
            // "must not be negative" says more than a range (and, for a
            // gain, why).
            non_negative(self.what, value)?;
        }
        within(self.what, value, lo, hi)?;
        if self.count && value.fract() != 0.0 {
            return Err(Error::OutOfRange {
                what: format!("{} (a whole number)", self.what),
                value,
                min: lo,
                max: hi,
            });
        }
        Ok(())
    }

    /// The command line's help: what it does and its default.
    #[cfg(feature = "cli")]
    pub fn help_text(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", ascii_unit(self.unit))
        };
        format!("{} [default: {}{unit}]", self.help, self.default)
    }
}

/// A unit as a terminal prints it (`m²` -> `m^2`).
#[cfg(feature = "cli")]
fn ascii_unit(unit: &str) -> String {
    unit.replace('²', "^2")
}

/// The values of the parameters a scene sets; every other declared
/// parameter has its [`Param::default`]. Only values that differ from the
/// default are kept, so two scenes that run alike compare equal.
///
/// Reading a value is a scan of at most a dozen addresses (no hashing, no
/// string compare, no allocation): what the methods do at every RK4 stage.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Params(Vec<(&'static Param, f64)>);

impl Params {
    /// The value of `p`: the one set, else its default.
    #[inline]
    pub fn get(&self, p: &'static Param) -> f64 {
        self.0
            .iter()
            .find(|(q, _)| std::ptr::eq(*q, p))
            .map_or(p.default, |(_, v)| *v)
    }

    /// The value of a count parameter.
    #[inline]
    pub fn count(&self, p: &'static Param) -> u32 {
        self.get(p) as u32
    }

    /// Sets `p`; refused, changing nothing, when out of its bounds or
    /// breaking its order with another parameter.
    pub fn set(&mut self, p: &'static Param, value: f64) -> Result<()> {
        p.check(value)?;
        let mut next = self.clone();
        next.put(p, value);
        next.check_order(p)?;
        *self = next;
        Ok(())
    }

    /// Sets several at once, then checks them together (a stop distance
    /// and an influence distance given together, whatever their order).
    pub fn set_all(&mut self, values: &[(&'static Param, f64)]) -> Result<()> {
        let mut next = self.clone();
        for &(p, v) in values {
            p.check(v)?;
            next.put(p, v);
        }
        for &(p, _) in values {
            next.check_order(p)?;
        }
        *self = next;
        Ok(())
    }

    fn put(&mut self, p: &'static Param, value: f64) {
        self.0.retain(|(q, _)| !std::ptr::eq(*q, p));
        if value != p.default {
            self.0.push((p, value));
        }
    }

    /// The order of `p` with the parameters it is declared below or above.
    fn check_order(&self, p: &'static Param) -> Result<()> {
        let (low, high) = match (p.below, p.above) {
            (Some(high), _) => (p, high),
            (None, Some(low)) => (low, p),
            (None, None) => return Ok(()),
        };
        let (lo, hi) = (self.get(low), self.get(high));
        if lo >= hi {
            return Err(Error::OutOfRange {
                what: format!("{} (below the {})", low.what, high.what),
                value: lo,
                min: low.bounds.0,
                max: hi,
            });
        }
        Ok(())
    }

    /// Checks every value set (a scene read from a file bypasses
    /// [`Params::set`]).
    pub fn validate(&self) -> Result<()> {
        for &(p, v) in &self.0 {
            p.check(v)?;
            self.check_order(p)?;
        }
        Ok(())
    }

    /// The values set, in the order they were set.
    pub fn iter(&self) -> impl Iterator<Item = (&'static Param, f64)> + '_ {
        self.0.iter().copied()
    }
}
