//! An atlas read back from its JSON (what `redundant-ik atlas --json`
//! writes and the page downloads): the cells as written, the summaries
//! computed again from them, so a file cannot carry a summary its cells
//! do not support.

use std::collections::BTreeMap;

use serde::de::Error as _;
use serde::{Deserialize, Deserializer};

use super::{summary, Atlas, Cell, Grid, Outcome};
use crate::planner::Method;

#[derive(Deserialize)]
struct CellIn {
    x: f64,
    y: f64,
    outcomes: BTreeMap<String, Outcome>,
    #[serde(default)]
    avoidance_needed: Option<bool>,
}

#[derive(Deserialize)]
struct AtlasIn {
    task: Option<u32>,
    grid: Grid,
    radius: f64,
    lambda: f64,
    /// `modes` in atlases written before this name.
    #[serde(alias = "modes")]
    methods: Vec<Method>,
    trained_region: Option<[f64; 4]>,
    cells: Vec<CellIn>,
}

impl<'de> Deserialize<'de> for Atlas {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let a = AtlasIn::deserialize(d)?;
        a.grid.validate().map_err(D::Error::custom)?;
        if a.cells.len() != a.grid.cells() {
            return Err(D::Error::custom(format!(
                "an atlas of {} x {} cells lists {}",
                a.grid.n,
                a.grid.n,
                a.cells.len()
            )));
        }
        if a.methods.is_empty() {
            return Err(D::Error::custom("an atlas names no method"));
        }
        let mut cells = Vec::with_capacity(a.cells.len());
        for (k, mut c) in a.cells.into_iter().enumerate() {
            let outcomes = a
                .methods
                .iter()
                .map(|m| {
                    c.outcomes
                        .remove(m.name())
                        .ok_or_else(|| D::Error::custom(format!("cell {k} has no outcome for {m}")))
                })
                .collect::<Result<Vec<_>, _>>()?;
            cells.push(Cell {
                centre: [c.x, c.y],
                outcomes,
                avoidance_needed: c.avoidance_needed,
            });
        }
        let summary = summary::summarise(&a.methods, &cells, a.trained_region, a.radius);
        Ok(Atlas {
            task: a.task,
            grid: a.grid,
            radius: a.radius,
            lambda: a.lambda,
            methods: a.methods,
            cells,
            trained_region: a.trained_region,
            summary,
        })
    }
}
