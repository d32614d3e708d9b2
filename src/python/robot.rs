//! `redundant_ik.Robot`: an arm the package can plan for, a planar arm or
//! a chain in space (a preset or a robot's URDF), and its kinematics as
//! numpy arrays. It names itself to the command line by the flags that
//! make it (`--arm panda`, `--urdf FILE --tip hand`), so a run, an atlas
//! or a controller of a robot is the tool's for those flags.

use std::path::{Path, PathBuf};

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use super::{core_error, error};
use crate::cli::robot::{urdf_scene, ChainArgs};
use crate::cli::{parse_arm, ArmChoice};
use crate::kinematics::Pose;
use crate::space::{Chain, PoseChain};
use crate::urdf::MAX_URDF_BYTES;
use crate::Arm;

/// The arm itself.
#[derive(Clone)]
enum Body {
    Plane(Arm),
    Space(Box<PoseChain>),
}

/// What made the robot: what pickling carries, and what its flags say.
#[derive(Clone)]
enum Made {
    /// A preset's name or a planar arm's `POST:L1,L2,...`.
    Arm(String),
    /// A URDF: the file it was read from (meshes are read beside it), its
    /// text, and the chain's options.
    Urdf {
        path: PathBuf,
        text: String,
        base: Option<String>,
        tip: Option<String>,
        /// MoveIt's SRDF: its file and its text.
        srdf: Option<(PathBuf, String)>,
        package_dir: Option<String>,
    },
}

/// An arm: a planar arm (a chain whose joint axes are parallel; the
/// paper's is `Robot.preset("paper")`) or a chain in space (the Franka
/// Panda, the KUKA iiwa 14, or any serial arm from its URDF).
///
/// `Robot.preset(name)`, `Robot.planar("POST:L1,L2,...")` and
/// `Robot.from_urdf(path_or_text, base=None, tip=None, srdf=None,
/// package_dir=None)` make one. Angles are in radians, lengths in metres.
/// A robot pickles (a URDF's text travels with it).
#[pyclass(module = "redundant_ik", frozen)]
pub struct Robot {
    body: Body,
    made: Made,
    name: String,
}

impl Robot {
    /// The command line's flags that name this robot.
    pub fn flags(&self) -> Vec<String> {
        match &self.made {
            Made::Arm(key) => vec!["--arm".into(), key.clone()],
            Made::Urdf {
                path,
                base,
                tip,
                srdf,
                package_dir,
                ..
            } => {
                let mut f = vec!["--urdf".to_string(), path.display().to_string()];
                let srdf = srdf.as_ref().map(|(p, _)| p.display().to_string());
                for (flag, v) in [
                    ("--base", base),
                    ("--tip", tip),
                    ("--srdf", &srdf),
                    ("--package-dir", package_dir),
                ] {
                    if let Some(v) = v {
                        f.push(flag.into());
                        f.push(v.clone());
                    }
                }
                f
            }
        }
    }

    fn dof(&self) -> usize {
        match &self.body {
            Body::Plane(a) => a.dof(),
            Body::Space(p) => p.chain.dof(),
        }
    }

    /// The joint angles as `n` finite numbers, or why not.
    fn angles(&self, theta: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
        super::controller::vector(theta, "theta", self.dof())
    }
}

/// The file of a URDF or an SRDF given as its text or as a path (`ext`),
/// and its text.
fn file_and_text(given: &str, ext: &str) -> PyResult<(PathBuf, String)> {
    if given.trim_start().starts_with('<') {
        Ok((text_file(given, ext)?, given.to_string()))
    } else {
        let path = PathBuf::from(given);
        let text = read_urdf(&path)?;
        Ok((path, text))
    }
}

/// A path (str or os.PathLike) or a document's text.
fn path_or_text(value: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    match value.extract::<PathBuf>() {
        Ok(p) => Ok(p.to_string_lossy().into_owned()),
        Err(_) => value.extract::<String>().map_err(|_| {
            error(format!(
                "{name}: expected a path (str or os.PathLike) or the file's text"
            ))
        }),
    }
}

/// A URDF's (or an SRDF's) text, from a file (at most [`MAX_URDF_BYTES`]).
fn read_urdf(path: &Path) -> PyResult<String> {
    let meta = std::fs::metadata(path)
        .map_err(|e| error(format!("cannot read {}: {e}", path.display())))?;
    if meta.len() > MAX_URDF_BYTES as u64 {
        return Err(error(format!(
            "{}: {} bytes, more than a URDF's {MAX_URDF_BYTES}",
            path.display(),
            meta.len()
        )));
    }
    std::fs::read_to_string(path).map_err(|e| error(format!("cannot read {}: {e}", path.display())))
}

/// A URDF (or an SRDF, `ext`) given as text, kept as a file under the
/// temporary folder named by its content's hash (what `--urdf` reads; the
/// same text is the same file, in this process and in one that unpickles
/// the robot).
fn text_file(text: &str, ext: &str) -> PyResult<PathBuf> {
    let dir = std::env::temp_dir().join("redundant-ik-urdf");
    std::fs::create_dir_all(&dir)
        .map_err(|e| error(format!("cannot write {}: {e}", dir.display())))?;
    let path = dir.join(format!("{}.{ext}", &crate::cli::robot::sha256(text)[..16]));
    if std::fs::read_to_string(&path).ok().as_deref() != Some(text) {
        std::fs::write(&path, text)
            .map_err(|e| error(format!("cannot write {}: {e}", path.display())))?;
    }
    Ok(path)
}

#[pymethods]
impl Robot {
    /// A shipped arm by name: the planar `paper` (the paper's 3-link arm),
    /// `four`, `five`, `iiwa-planar`; in space `panda` (Franka Panda) and
    /// `iiwa14` (KUKA LBR iiwa 14), each with its limits.
    #[staticmethod]
    fn preset(name: &str) -> PyResult<Self> {
        if crate::space::Named::find(name).is_none() {
            return Err(error(format!(
                "no preset '{name}': {} (Robot.planar takes POST:L1,L2,...)",
                crate::space::Named::choices()
            )));
        }
        Self::of_arm(name)
    }

    /// A planar arm `POST:L1,L2,...`: the post's height and the links'
    /// lengths in metres (2 to 32 links), e.g. `"0.5:0.6,0.85,0.6"`, the
    /// paper's.
    #[staticmethod]
    fn planar(text: &str) -> PyResult<Self> {
        match parse_arm(text).map_err(error)? {
            ArmChoice::Planar(_) => Self::of_arm(text),
            ArmChoice::Space(p) => Err(error(format!(
                "{} is an arm in space: Robot.preset('{}')",
                p.key, p.key
            ))),
        }
    }

    /// A serial arm from its URDF (a file's path, or the text itself): the
    /// chain from `base` (default: the tree's root) to `tip` (default: the
    /// one leaf), its links' volumes from their collision geometry (meshes
    /// read beside the file, or under `package_dir` for `package://`
    /// names). `srdf` (a path or the text): MoveIt's SRDF, whose disabled
    /// pairs are not checked for self-collision (which it switches on). Hostile or broken XML raises Error.
    #[staticmethod]
    #[pyo3(signature = (urdf, base=None, tip=None, srdf=None, package_dir=None))]
    fn from_urdf(
        py: Python<'_>,
        urdf: &Bound<'_, PyAny>,
        base: Option<String>,
        tip: Option<String>,
        srdf: Option<&Bound<'_, PyAny>>,
        package_dir: Option<PathBuf>,
    ) -> PyResult<Self> {
        let (path, text) = file_and_text(&path_or_text(urdf, "urdf")?, "urdf")?;
        let srdf = srdf
            .map(|s| file_and_text(&path_or_text(s, "srdf")?, "srdf"))
            .transpose()?;
        let made = Made::Urdf {
            path,
            text,
            base,
            tip,
            srdf,
            package_dir: package_dir.map(|p| p.display().to_string()),
        };
        py.detach(|| Self::of_urdf(made))
    }

    /// Joints (degrees of freedom).
    #[getter]
    fn n(&self) -> usize {
        self.dof()
    }

    /// `"planar"` or `"space"`.
    #[getter]
    fn kind(&self) -> &'static str {
        match self.body {
            Body::Plane(_) => "planar",
            Body::Space(_) => "space",
        }
    }

    /// Its name: the preset's, the planar arm's `POST:L1,...`, or the
    /// URDF's robot name.
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// Each joint's position range, an `n x 2` array `[lo, hi]` (rad, or
    /// m for a sliding joint), or None where it has none.
    #[getter]
    fn joint_limits<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let limits = match &self.body {
            Body::Plane(a) => a.joint_limits(),
            Body::Space(p) => p.chain.joint_limits(),
        };
        limits
            .map(|l| {
                let flat: Vec<f64> = l.ranges().iter().flatten().copied().collect();
                Ok(PyArray1::from_vec(py, flat)
                    .reshape([l.ranges().len(), 2])?
                    .into_any())
            })
            .transpose()
    }

    /// Each joint's largest rate (rad/s), an array of `n`, or None.
    #[getter]
    fn rate_limits<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        let limits = match &self.body {
            Body::Plane(a) => a.rate_limits(),
            Body::Space(p) => p.chain.rate_limits(),
        };
        limits.map(|l| PyArray1::from_slice(py, l.rates()))
    }

    /// The forward kinematics at `theta` (n angles), a dict of arrays:
    /// `hand` (the hand's position: 2 numbers in the plane, 3 in space),
    /// `points` (the chain's points from the base to the hand, one row
    /// each); in space also `rotation` (the hand's 3 x 3), `transform` (its
    /// 4 x 4 homogeneous transform) and `frames` (each joint's frame, `n x
    /// 3 x 3`, its axes as columns; the joint turns about its z).
    fn forward<'py>(
        &self,
        py: Python<'py>,
        theta: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let theta = self.angles(theta)?;
        let d = PyDict::new(py);
        match &self.body {
            Body::Plane(arm) => {
                let pose = Pose::new(arm, &theta).map_err(core_error)?;
                let pts: Vec<f64> = pose.joints().iter().flatten().copied().collect();
                d.set_item("hand", PyArray1::from_slice(py, &pose.end_effector()))?;
                d.set_item(
                    "points",
                    PyArray1::from_vec(py, pts).reshape([pose.joints().len(), 2])?,
                )?;
            }
            Body::Space(pc) => {
                let mut pose = pc.pose();
                pose.update(pc, &theta).map_err(core_error)?;
                let space = pose.space();
                let p = space.hand();
                let r = pose.rotation();
                let mut t = [0.0; 16];
                for i in 0..3 {
                    t[4 * i..4 * i + 3].copy_from_slice(&r[i]);
                    t[4 * i + 3] = p[i];
                }
                t[15] = 1.0;
                let n = space.dof();
                let mut frames = Vec::with_capacity(9 * n);
                for i in 0..n {
                    let f = space.frame(i);
                    // By rows: entry (row, col) is axis col's component row.
                    frames.extend((0..9).map(|k| f[k % 3][k / 3]));
                }
                let pts = space.points();
                let flat: Vec<f64> = pts.iter().flatten().copied().collect();
                d.set_item("hand", PyArray1::from_slice(py, &p))?;
                d.set_item(
                    "points",
                    PyArray1::from_vec(py, flat).reshape([pts.len(), 3])?,
                )?;
                let rot: Vec<f64> = r.iter().flatten().copied().collect();
                d.set_item("rotation", PyArray1::from_vec(py, rot).reshape([3, 3])?)?;
                d.set_item("transform", PyArray1::from_slice(py, &t).reshape([4, 4])?)?;
                d.set_item("frames", PyArray1::from_vec(py, frames).reshape([n, 3, 3])?)?;
            }
        }
        Ok(d)
    }

    /// The Jacobian at `theta`: `2 x n` for a planar arm (the hand's
    /// velocity per joint rate), `6 x n` in space (the hand's linear
    /// velocity, then its angular velocity, in the world frame: the
    /// geometric Jacobian).
    fn jacobian<'py>(
        &self,
        py: Python<'py>,
        theta: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let theta = self.angles(theta)?;
        let n = theta.len();
        // Column-major in the core; a C-ordered numpy array is row-major.
        let (m, cols) = match &self.body {
            Body::Plane(arm) => (
                2,
                Pose::new(arm, &theta)
                    .map_err(core_error)?
                    .jacobian()
                    .to_vec(),
            ),
            Body::Space(pc) => {
                let mut pose = pc.pose();
                pose.update(pc, &theta).map_err(core_error)?;
                (6, pose.jacobian().to_vec())
            }
        };
        let rows: Vec<f64> = (0..m)
            .flat_map(|r| (0..n).map(move |c| (r, c)))
            .map(|(r, c)| cols[m * c + r])
            .collect();
        Ok(PyArray1::from_vec(py, rows).reshape([m, n])?.into_any())
    }

    /// The flags of the command-line tool that name this robot.
    #[getter]
    fn _flags(&self) -> Vec<String> {
        self.flags()
    }

    fn __repr__(&self) -> String {
        format!("Robot('{}', {}, n={})", self.name, self.kind(), self.dof())
    }

    /// Pickles as what made it (a URDF's text travels with it).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let restore = py.import("redundant_ik")?.getattr("_restore_robot")?;
        let args = match &self.made {
            Made::Arm(key) => PyTuple::new(
                py,
                [
                    "arm".into_pyobject(py)?.into_any(),
                    key.into_pyobject(py)?.into_any(),
                ],
            )?,
            Made::Urdf {
                path,
                text,
                base,
                tip,
                srdf,
                package_dir,
            } => (
                "urdf",
                path.display().to_string(),
                text,
                base,
                tip,
                srdf.as_ref()
                    .map(|(p, t)| (p.display().to_string(), t.clone())),
                package_dir,
            )
                .into_pyobject(py)?,
        };
        PyTuple::new(py, [restore, args.into_any()])
    }

    /// What `__reduce__` gave back: `("arm", key)` or `("urdf", path,
    /// text, base, tip, srdf, package_dir)`, `srdf` its `(path, text)` (for
    /// each, the file where it still holds the text, else the text).
    #[staticmethod]
    #[pyo3(signature = (kind, *args))]
    fn _restore(py: Python<'_>, kind: &str, args: &Bound<'_, PyTuple>) -> PyResult<Self> {
        match kind {
            "arm" => Self::of_arm(&args.get_item(0)?.extract::<String>()?),
            "urdf" => {
                type State = (
                    String,
                    String,
                    Option<String>,
                    Option<String>,
                    Option<(String, String)>,
                    Option<String>,
                );
                let (path, text, base, tip, srdf, package_dir): State = args.extract()?;
                // The file where it still holds the text, else the text.
                let again =
                    |path: String, text: String, ext: &str| -> PyResult<(PathBuf, String)> {
                        let path = PathBuf::from(path);
                        if std::fs::read_to_string(&path).ok().as_deref() == Some(text.as_str()) {
                            Ok((path, text))
                        } else {
                            Ok((text_file(&text, ext)?, text))
                        }
                    };
                let (path, text) = again(path, text, "urdf")?;
                let srdf = srdf.map(|(p, t)| again(p, t, "srdf")).transpose()?;
                let made = Made::Urdf {
                    path,
                    text,
                    base,
                    tip,
                    srdf,
                    package_dir,
                };
                py.detach(|| Self::of_urdf(made))
            }
            _ => Err(error(format!("not a robot's state: '{kind}'"))),
        }
    }
}

impl Robot {
    fn of_arm(key: &str) -> PyResult<Self> {
        let body = match parse_arm(key).map_err(error)? {
            ArmChoice::Planar(arm) => Body::Plane(arm),
            ArmChoice::Space(p) => Body::Space(Box::new(
                PoseChain::new(p.chain(), 1.0).map_err(core_error)?,
            )),
        };
        Ok(Self {
            body,
            made: Made::Arm(key.trim().to_string()),
            name: key.trim().to_string(),
        })
    }

    fn of_urdf(made: Made) -> PyResult<Self> {
        let Made::Urdf {
            path,
            base,
            tip,
            srdf,
            package_dir,
            ..
        } = &made
        else {
            return Err(error("not a URDF"));
        };
        let options = ChainArgs {
            base: base.clone(),
            tip: tip.clone(),
            package_dir: package_dir.as_ref().map(PathBuf::from),
            srdf: srdf.as_ref().map(|(p, _)| p.clone()),
        };
        let robot = urdf_scene(path, &options, None).map_err(error)?;
        let chain: Chain = robot.scene.arm;
        let name = robot.robot.key.clone();
        Ok(Self {
            body: Body::Space(Box::new(PoseChain::new(chain, 1.0).map_err(core_error)?)),
            made,
            name,
        })
    }
}
