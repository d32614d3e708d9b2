//! `redundant_ik.Controller`: one method's joint rates for a loop of the
//! user's own (a Python loop, a ROS node), over the planner that
//! `simulate` would run with the same keywords. Each call copies its
//! arguments into the controller's own buffers, makes one kinematics pass
//! and one rate evaluation through the planner's workspace (no allocation
//! in the core), and returns a new array.

use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use super::{core_error, error};
use crate::cli::planner::{planner, AnyPlanner};
use crate::model::Scene as _;
use crate::obstacle::Obstacle;
use crate::space::Sphere;

/// `len` finite numbers from `value` (a 1-D float64 numpy array, or any
/// sequence of numbers), into `out`; what is wrong names the argument.
pub(crate) fn read_into(value: &Bound<'_, PyAny>, name: &str, out: &mut [f64]) -> PyResult<()> {
    let len = out.len();
    if let Ok(a) = value.cast::<PyArray1<f64>>() {
        let r = a
            .try_readonly()
            .map_err(|e| error(format!("{name}: {e}")))?;
        match r.as_slice() {
            Ok(s) if s.len() == len => out.copy_from_slice(s),
            Ok(s) => {
                return Err(error(format!(
                    "{name}: expected {len} numbers, got an array of {}",
                    s.len()
                )))
            }
            Err(_) => {
                for (o, x) in out.iter_mut().zip(r.as_array().iter()) {
                    *o = *x;
                }
                if r.len() != len {
                    return Err(error(format!(
                        "{name}: expected {len} numbers, got an array of {}",
                        r.len()
                    )));
                }
            }
        }
    } else if let Ok(a) = value.cast::<numpy::PyUntypedArray>() {
        return Err(error(format!(
            "{name}: expected a 1-D float64 array of {len} numbers, got an array of shape {:?} and dtype {}",
            a.shape(),
            a.dtype()
        )));
    } else {
        let v: Vec<f64> = value.extract().map_err(|_| {
            error(format!(
                "{name}: expected {len} numbers (a 1-D float64 array or a sequence), got {}",
                value
                    .get_type()
                    .name()
                    .map_or("?".into(), |n| n.to_string())
            ))
        })?;
        if v.len() != len {
            return Err(error(format!(
                "{name}: expected {len} numbers, got {}",
                v.len()
            )));
        }
        out.copy_from_slice(&v);
    }
    if let Some(i) = out.iter().position(|x| !x.is_finite()) {
        return Err(error(format!(
            "{name}[{i}] = {} is not a finite number",
            out[i]
        )));
    }
    Ok(())
}

/// [`read_into`] a new vector of `len` numbers.
pub(crate) fn vector(value: &Bound<'_, PyAny>, name: &str, len: usize) -> PyResult<Vec<f64>> {
    let mut v = vec![0.0; len];
    read_into(value, name, &mut v)?;
    Ok(v)
}

/// The joint rates of one method for a loop of your own: the planner that
/// `simulate` runs for the same keywords (the robot, the method, its
/// parameters, the obstacles, the path), evaluated where you ask.
///
/// `rates(theta, xdot)` gives the rates for a task velocity `xdot` of
/// your own; `step(theta, t)` those for the path's velocity at time `t`
/// (plus the feedback `K (X_ref(t) - X)` when `feedback` > 0). Obstacles
/// move between calls (`obstacles = [...]`, `move_obstacle`).
#[pyclass(module = "redundant_ik", subclass)]
pub struct Controller {
    planner: AnyPlanner,
    n: usize,
    m: usize,
    theta: Vec<f64>,
    xdot: [f64; 6],
    out: Vec<f64>,
}

impl Controller {
    fn rates_into(&mut self) -> crate::Result<()> {
        let (theta, out, x) = (&self.theta, &mut self.out, &self.xdot);
        match &mut self.planner {
            AnyPlanner::Plane(p) => p.theta_dot_into(theta, [x[0], x[1]], out),
            AnyPlanner::Space(p) => p.theta_dot_into(theta, [x[0], x[1], x[2]], out),
            AnyPlanner::Pose(p) => p.theta_dot_into(theta, *x, out),
        }
    }

    fn step_into(&mut self, t: f64) -> crate::Result<()> {
        let (theta, out) = (&self.theta, &mut self.out);
        match &mut self.planner {
            AnyPlanner::Plane(p) => p.rates_at(theta, t, out),
            AnyPlanner::Space(p) => p.rates_at(theta, t, out),
            AnyPlanner::Pose(p) => p.rates_at(theta, t, out),
        }
    }
}

#[pymethods]
impl Controller {
    /// A controller from `simulate`'s flags (the package's `Controller`
    /// builds them from its keywords).
    #[new]
    fn new(py: Python<'_>, args: Vec<String>) -> PyResult<Self> {
        let argv = std::iter::once("simulate".to_string()).chain(args);
        let planner = py.detach(move || planner(argv)).map_err(error)?;
        let (n, m) = match &planner {
            AnyPlanner::Plane(p) => (p.theta().len(), 2),
            AnyPlanner::Space(p) => (p.theta().len(), 3),
            AnyPlanner::Pose(p) => (p.theta().len(), 6),
        };
        Ok(Self {
            planner,
            n,
            m,
            theta: vec![0.0; n],
            xdot: [0.0; 6],
            out: vec![0.0; n],
        })
    }

    /// The joint rates (rad/s, `n`) at the angles `theta` (`n`) for the
    /// task velocity `xdot` (`m`: the hand's velocity, 2 numbers in the
    /// plane, 3 in space; 6 for the pose task, linear then angular) with
    /// the controller's method.
    fn rates<'py>(
        &mut self,
        py: Python<'py>,
        theta: &Bound<'py, PyAny>,
        xdot: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        read_into(theta, "theta", &mut self.theta)?;
        read_into(xdot, "xdot", &mut self.xdot[..self.m])?;
        self.rates_into().map_err(core_error)?;
        Ok(PyArray1::from_slice(py, &self.out))
    }

    /// The joint rates (rad/s, `n`) at the angles `theta` and time `t`
    /// (s) along the path: its task velocity at `t` (a line's constant
    /// rate while it runs, zero after) plus `K (X_ref(t) - X(theta))` when
    /// the feedback gain `K` > 0. What each stage of `simulate`'s RK4 step
    /// evaluates.
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        theta: &Bound<'py, PyAny>,
        t: f64,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        read_into(theta, "theta", &mut self.theta)?;
        if !t.is_finite() {
            return Err(error(format!("t = {t} is not a finite time")));
        }
        self.step_into(t).map_err(core_error)?;
        Ok(PyArray1::from_slice(py, &self.out))
    }

    /// The path's point at time `t`, `X_ref(t)` (`m` numbers).
    fn reference<'py>(&self, py: Python<'py>, t: f64) -> Bound<'py, PyArray1<f64>> {
        match &self.planner {
            AnyPlanner::Plane(p) => PyArray1::from_slice(py, &p.track().reference(t)),
            AnyPlanner::Space(p) => PyArray1::from_slice(py, &p.track().reference(t)),
            AnyPlanner::Pose(p) => PyArray1::from_slice(py, &p.track().reference(t)),
        }
    }

    /// Joints.
    #[getter]
    fn n(&self) -> usize {
        self.n
    }

    /// The task's dimension: 2 (the hand in the plane), 3 (its position
    /// in space) or 6 (its pose).
    #[getter]
    fn m(&self) -> usize {
        self.m
    }

    /// The method's name.
    #[getter]
    fn method(&self) -> &'static str {
        match &self.planner {
            AnyPlanner::Plane(p) => p.method().name(),
            AnyPlanner::Space(p) => p.method().name(),
            AnyPlanner::Pose(p) => p.method().name(),
        }
    }

    /// The scene's start angles `theta0` (rad).
    #[getter]
    fn theta0<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        match &self.planner {
            AnyPlanner::Plane(p) => PyArray1::from_slice(py, p.scene().theta0()),
            AnyPlanner::Space(p) => PyArray1::from_slice(py, p.scene().theta0()),
            AnyPlanner::Pose(p) => PyArray1::from_slice(py, p.scene().theta0()),
        }
    }

    /// The scene's step `dt` and final time `tf` (s): the path takes `tf`.
    #[getter]
    fn dt(&self) -> f64 {
        match &self.planner {
            AnyPlanner::Plane(p) => p.scene().dt(),
            AnyPlanner::Space(p) => p.scene().dt(),
            AnyPlanner::Pose(p) => p.scene().dt(),
        }
    }

    /// The scene's final time `tf` (s).
    #[getter]
    fn tf(&self) -> f64 {
        match &self.planner {
            AnyPlanner::Plane(p) => p.scene().tf(),
            AnyPlanner::Space(p) => p.scene().tf(),
            AnyPlanner::Pose(p) => p.scene().tf(),
        }
    }

    /// The obstacles, one row each: `(x, y, r)` in the plane, `(x, y, z,
    /// r)` in space. Set a list of such rows to replace them; refused,
    /// changing nothing, where one does not fit (not finite, on the base).
    #[getter]
    fn obstacles(&self) -> Vec<Vec<f64>> {
        match &self.planner {
            AnyPlanner::Plane(p) => p
                .scene()
                .obstacles
                .iter()
                .map(|o| vec![o.centre[0], o.centre[1], o.radius])
                .collect(),
            AnyPlanner::Space(p) => spheres(&p.scene().obstacles),
            AnyPlanner::Pose(p) => spheres(&p.scene().obstacles),
        }
    }

    #[setter]
    fn set_obstacles(&mut self, rows: Vec<Vec<f64>>) -> PyResult<()> {
        let width = if self.m == 2 { 3 } else { 4 };
        if let Some((i, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != width) {
            return Err(error(format!(
                "obstacles[{i}]: expected {width} numbers ({}), got {}",
                if width == 3 { "x, y, r" } else { "x, y, z, r" },
                r.len()
            )));
        }
        match &mut self.planner {
            AnyPlanner::Plane(p) => p.set_obstacles(
                rows.iter()
                    .map(|r| Obstacle {
                        centre: [r[0], r[1]],
                        radius: r[2],
                    })
                    .collect(),
            ),
            AnyPlanner::Space(p) => p.set_spheres(to_spheres(&rows)?),
            AnyPlanner::Pose(p) => p.set_spheres(to_spheres(&rows)?),
        }
        .map_err(core_error)
    }

    /// Moves obstacle `index` to `centre` (2 numbers in the plane, 3 in
    /// space), keeping its radius.
    fn move_obstacle(&mut self, index: usize, centre: &Bound<'_, PyAny>) -> PyResult<()> {
        let dim = if self.m == 2 { 2 } else { 3 };
        let c = vector(centre, "centre", dim)?;
        match &mut self.planner {
            AnyPlanner::Plane(p) => p.move_obstacle(index, [c[0], c[1]]),
            AnyPlanner::Space(p) => move_sphere(p.scene().obstacles.get(index), index, &c)
                .and_then(|s| p.set_sphere(index, s)),
            AnyPlanner::Pose(p) => move_sphere(p.scene().obstacles.get(index), index, &c)
                .and_then(|s| p.set_sphere(index, s)),
        }
        .map_err(core_error)
    }

    fn __repr__(&self) -> String {
        format!(
            "Controller(method='{}', n={}, m={}, obstacles={})",
            self.method(),
            self.n,
            self.m,
            self.obstacles().len()
        )
    }
}

fn spheres(s: &[Sphere]) -> Vec<Vec<f64>> {
    s.iter()
        .map(|s| vec![s.centre[0], s.centre[1], s.centre[2], s.radius])
        .collect()
}

fn to_spheres(rows: &[Vec<f64>]) -> PyResult<Vec<Sphere>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    Sphere::from_flat(&flat).map_err(core_error)
}

fn move_sphere(s: Option<&Sphere>, index: usize, c: &[f64]) -> crate::Result<Sphere> {
    let s = s.ok_or_else(|| crate::Error::OutOfRange {
        what: "obstacle index".into(),
        value: index as f64,
        min: 0.0,
        max: 0.0,
    })?;
    Ok(Sphere {
        centre: [c[0], c[1], c[2]],
        radius: s.radius,
    })
}
