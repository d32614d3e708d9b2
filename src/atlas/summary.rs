//! What an atlas says per method, and its JSON form.

use serde::ser::{SerializeMap, SerializeStruct};
use serde::{Serialize, Serializer};

use super::{Atlas, Cell, Class, Outcome};
use crate::planner::Method;

/// Successes among some cells.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Rate {
    /// Cells counted (where avoidance is possible).
    pub cells: usize,
    /// Of which `success`.
    pub successes: usize,
    /// `successes / cells` (`None` without cells).
    pub rate: Option<f64>,
}

impl Rate {
    fn of(cells: usize, successes: usize) -> Self {
        Self {
            cells,
            successes,
            rate: (cells > 0).then(|| successes as f64 / cells as f64),
        }
    }
}

/// A network method against the numerical route, cell by cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Agreement {
    /// Cells where both succeed.
    pub both: usize,
    /// Cells where the numerical route succeeds and this method does not.
    pub numerical_only: usize,
    /// Cells where this method succeeds and the numerical route does not.
    pub method_only: usize,
    /// Cells where neither succeeds.
    pub neither: usize,
}

/// The smallest clearance (closest approach of a link to the disc's edge,
/// m) of the successful runs: do they skim the obstacle or keep away?
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Clearance {
    /// The median over the successes.
    pub median: f64,
    /// The 5th percentile: how close the closest twentieth come.
    pub p5: f64,
}

impl Clearance {
    /// Of the given clearances (`None` without any).
    fn of(mut values: Vec<f64>) -> Option<Self> {
        if values.is_empty() {
            return None;
        }
        values.sort_by(f64::total_cmp);
        let at = |q: f64| {
            values[((q * (values.len() - 1) as f64).round() as usize).min(values.len() - 1)]
        };
        Some(Self {
            median: at(0.5),
            p5: at(0.05),
        })
    }
}

/// One method over the whole grid.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodSummary {
    /// The method.
    pub method: Method,
    /// Cells of each class, in the order of [`Class::ALL`].
    pub counts: [usize; Class::COUNT],
    /// Success over the cells where avoidance is possible (neither
    /// `start_overlap` nor `path_blocked`).
    pub avoidable: Rate,
    /// The same over those of them where avoidance matters: the arm
    /// without avoidance collides there ([`Cell::avoidance_needed`]).
    pub mattered: Rate,
    /// The same inside the `v` network's trained obstacle region.
    pub inside_trained_region: Option<Rate>,
    /// The same outside it.
    pub outside_trained_region: Option<Rate>,
    /// For the network methods, when the numerical route was mapped too.
    pub agreement: Option<Agreement>,
    /// The smallest clearance of its successful runs, median and 5th
    /// percentile (`None` without a success).
    pub clearance: Option<Clearance>,
}

impl MethodSummary {
    /// Cells of class `class`.
    pub fn count(&self, class: Class) -> usize {
        Class::ALL
            .iter()
            .position(|&c| c == class)
            .map_or(0, |k| self.counts[k])
    }

    /// Success rate over the cells where avoidance is possible.
    pub fn success_rate(&self) -> Option<f64> {
        self.avoidable.rate
    }
}

fn inside<const D: usize>(region: [f64; 4], c: &Cell<D>) -> bool {
    (region[0]..=region[1]).contains(&c.centre[0]) && (region[2]..=region[3]).contains(&c.centre[1])
}

/// Each method's summary over `cells` (of obstacles with `D`
/// coordinates), the success inside and outside the `v` network's trained
/// `region` where one is given (its first two coordinates).
pub(crate) fn summarise<const D: usize>(
    methods: &[Method],
    cells: &[Cell<D>],
    region: Option<[f64; 4]>,
    radius: f64,
) -> Vec<MethodSummary> {
    let numerical = methods.iter().position(|&m| m == Method::NUMERICAL);
    let success = |o: &Outcome| o.class == Class::Success;
    methods
        .iter()
        .enumerate()
        .map(|(k, &method)| {
            let mut counts = [0; Class::COUNT];
            let (mut all, mut ins, mut outs) = ((0, 0), (0, 0), (0, 0));
            let mut mattered = (0, 0);
            let mut clearances = Vec::new();
            let mut agree = Agreement {
                both: 0,
                numerical_only: 0,
                method_only: 0,
                neither: 0,
            };
            for cell in cells {
                let o = &cell.outcomes[k];
                let class_index = Class::ALL.iter().position(|&c| c == o.class).unwrap_or(0);
                counts[class_index] += 1;
                if let (true, Some(d)) = (success(o), o.min_distance) {
                    clearances.push(d - radius);
                }
                if o.class.avoidable() {
                    let won = usize::from(success(o));
                    all = (all.0 + 1, all.1 + won);
                    if cell.avoidance_needed == Some(true) {
                        mattered = (mattered.0 + 1, mattered.1 + won);
                    }
                    if let Some(r) = region {
                        let bucket = if inside(r, cell) { &mut ins } else { &mut outs };
                        *bucket = (bucket.0 + 1, bucket.1 + won);
                    }
                }
                if let Some(n) = numerical {
                    match (success(&cell.outcomes[n]), success(o)) {
                        (true, true) => agree.both += 1,
                        (true, false) => agree.numerical_only += 1,
                        (false, true) => agree.method_only += 1,
                        (false, false) => agree.neither += 1,
                    }
                }
            }
            let learned = method.uses_networks();
            MethodSummary {
                method,
                counts,
                avoidable: Rate::of(all.0, all.1),
                mattered: Rate::of(mattered.0, mattered.1),
                inside_trained_region: region.map(|_| Rate::of(ins.0, ins.1)),
                outside_trained_region: region.map(|_| Rate::of(outs.0, outs.1)),
                agreement: (learned && numerical.is_some()).then_some(agree),
                clearance: Clearance::of(clearances),
            }
        })
        .collect()
}

// ---- JSON ----------------------------------------------------------------
//
// {"task", "grid": {"region", "n"}, "radius", "lambda", "methods",
//  "trained_region", "cells": [{"x", "y", "outcomes": {"<method>": outcome}}],
//  "summary": {"<method>": {"success_rate", "counts": {"<class>": n}, ...}}}

impl Serialize for Atlas {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("Atlas", 8)?;
        st.serialize_field("task", &self.task)?;
        st.serialize_field("grid", &self.grid)?;
        st.serialize_field("radius", &self.radius)?;
        st.serialize_field("lambda", &self.lambda)?;
        st.serialize_field("methods", &self.methods)?;
        st.serialize_field("trained_region", &self.trained_region)?;
        let cells: Vec<CellJson<'_>> = self
            .cells
            .iter()
            .map(|cell| CellJson {
                methods: &self.methods,
                cell,
            })
            .collect();
        st.serialize_field("cells", &cells)?;
        st.serialize_field("summary", &SummaryJson(&self.summary))?;
        st.end()
    }
}

struct CellJson<'a> {
    methods: &'a [Method],
    cell: &'a Cell,
}

impl Serialize for CellJson<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("Cell", 4)?;
        st.serialize_field("x", &self.cell.centre[0])?;
        st.serialize_field("y", &self.cell.centre[1])?;
        st.serialize_field("outcomes", &ByMethod(self.methods, &self.cell.outcomes))?;
        st.serialize_field("avoidance_needed", &self.cell.avoidance_needed)?;
        st.end()
    }
}

/// `{"<method>": value}` in the methods' order.
struct ByMethod<'a, T>(&'a [Method], &'a [T]);

impl<T: Serialize> Serialize for ByMethod<'_, T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (m, v) in self.0.iter().zip(self.1) {
            map.serialize_entry(m.name(), v)?;
        }
        map.end()
    }
}

struct SummaryJson<'a>(&'a [MethodSummary]);

impl Serialize for SummaryJson<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for m in self.0 {
            map.serialize_entry(m.method.name(), m)?;
        }
        map.end()
    }
}

impl Serialize for MethodSummary {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("MethodSummary", 8)?;
        st.serialize_field("success_rate", &self.success_rate())?;
        st.serialize_field("counts", &Counts(&self.counts))?;
        st.serialize_field("avoidable", &self.avoidable)?;
        st.serialize_field("mattered", &self.mattered)?;
        st.serialize_field("inside_trained_region", &self.inside_trained_region)?;
        st.serialize_field("outside_trained_region", &self.outside_trained_region)?;
        st.serialize_field("agreement", &self.agreement)?;
        st.serialize_field("clearance", &self.clearance)?;
        st.end()
    }
}

struct Counts<'a>(&'a [usize; Class::COUNT]);

impl Serialize for Counts<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(None)?;
        for (c, n) in Class::ALL.iter().zip(self.0) {
            // Self-collision only where it happened (a chain that checks
            // it; the class came after the others).
            if *c != Class::SelfCollision || *n > 0 {
                map.serialize_entry(c.name(), n)?;
            }
        }
        map.end()
    }
}
