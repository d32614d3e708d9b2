//! An atlas read back from its JSON (what `redundant-ik atlas --json`
//! writes and the page downloads): the cells as written, the summaries
//! computed again from them, so a file cannot carry a summary its cells
//! do not support. The slice atlas of an arm in space reads back too
//! (its cells checked against its grid and plane), which the page's
//! workers draw as its maps.

use std::collections::BTreeMap;

use serde::de::Error as _;
use serde::{Deserialize, Deserializer};

use super::space::{Plane, SliceAtlas};
use super::{summary, Atlas, Cell, Grid, Outcome};
use crate::planner::Method;

/// Why an atlas's grid, cell count and methods do not make an atlas, if
/// they do not.
fn shape(grid: &Grid, cells: usize, methods: &[Method]) -> Result<(), String> {
    grid.validate().map_err(|e| e.to_string())?;
    if cells != grid.cells() {
        return Err(format!(
            "an atlas of {} x {} cells lists {cells}",
            grid.n, grid.n
        ));
    }
    if methods.is_empty() {
        return Err("an atlas names no method".into());
    }
    Ok(())
}

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
        shape(&a.grid, a.cells.len(), &a.methods).map_err(D::Error::custom)?;
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

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SliceCellIn {
    centre: [f64; 3],
    outcomes: Vec<Outcome>,
    #[serde(default)]
    avoidance_needed: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SliceIn {
    arm: Option<String>,
    plane: Plane,
    grid: Grid,
    radius: f64,
    methods: Vec<Method>,
    cells: Vec<SliceCellIn>,
}

impl<'de> Deserialize<'de> for SliceAtlas {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let a = SliceIn::deserialize(d)?;
        shape(&a.grid, a.cells.len(), &a.methods).map_err(D::Error::custom)?;
        let arm = match a.arm.as_deref() {
            None => None,
            Some(key) => Some(
                crate::space::SpacePreset::by_key(key)
                    .ok_or_else(|| D::Error::custom(format!("unknown arm in space '{key}'")))?
                    .key,
            ),
        };
        let mut cells = Vec::with_capacity(a.cells.len());
        for (k, c) in a.cells.into_iter().enumerate() {
            let (i, j) = (k % a.grid.n, k / a.grid.n);
            let at = a.plane.point(a.grid.x(i), a.grid.y(j));
            if (0..3).any(|q| (c.centre[q] - at[q]).abs() > 1e-9) {
                return Err(D::Error::custom(format!(
                    "cell {k} is not at its grid point on the slice {}",
                    a.plane
                )));
            }
            if c.outcomes.len() != a.methods.len() {
                return Err(D::Error::custom(format!(
                    "cell {k} has {} outcomes for {} methods",
                    c.outcomes.len(),
                    a.methods.len()
                )));
            }
            cells.push(Cell {
                centre: c.centre,
                outcomes: c.outcomes,
                avoidance_needed: c.avoidance_needed,
            });
        }
        Ok(SliceAtlas {
            arm,
            plane: a.plane,
            grid: a.grid,
            radius: a.radius,
            methods: a.methods,
            cells,
        })
    }
}
