//! `redundant-ik robot FILE`: what the core makes of a URDF, before it
//! runs: the chain from the base to the tip (each moving joint, its kind,
//! limits and largest rate), the links' volumes and how each was made, and
//! the warnings (a link without collision geometry, a mesh that cannot be
//! read). Meshes are read from the file's folder, or `--package-dir` for a
//! `package://` name.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::Args;

use redundant_ik::space::{Chain, SpacePreset};
use redundant_ik::urdf::volume::{self, Source, Volume};
use redundant_ik::urdf::{chain_urdf, JointKind, RobotSource, Urdf, UrdfChain, MAX_URDF_BYTES};

use super::emit;

/// The radius of a link's segment where it has no volume of its own (m).
pub const DEFAULT_RADIUS: f64 = 0.05;

/// Options of `redundant-ik robot`.
#[derive(Args, Debug)]
pub struct RobotArgs {
    /// The URDF file (plain URDF; a xacro file must be expanded first).
    #[arg(required_unless_present = "urdf_of")]
    pub file: Option<PathBuf>,
    /// Print an arm in space (panda, iiwa14) as URDF instead: its
    /// modified-DH rows as joints, its capsules as cylinders, its limits
    /// (what `robots/*.urdf` are).
    #[arg(long, conflicts_with = "file")]
    pub urdf_of: Option<String>,
    #[command(flatten)]
    pub chain: ChainArgs,
    /// Print JSON: `{ chain, volumes, warnings }`.
    #[arg(long)]
    pub json: bool,
}

/// `--urdf FILE` and its chain's options, for `simulate`, `figure` and
/// `atlas` (flattened into their scene options).
#[derive(Args, Debug, Clone)]
pub struct UrdfArgs {
    /// A robot's URDF instead of --arm (plain URDF; docs/urdf.md): the
    /// chain from its root (or --base) to its one leaf (or --tip), its
    /// links' volumes from their collision geometry. It starts at the
    /// middle of its joints' ranges (within +-pi) unless --theta0 is
    /// given, and its hand's line runs 0.15 m along y unless --target is.
    #[arg(long, conflicts_with_all = ["arm", "from"])]
    pub urdf: Option<PathBuf>,
    #[command(flatten)]
    pub chain: ChainArgs,
}

/// Which chain of a URDF, and where its meshes are.
#[derive(Args, Debug, Clone)]
pub struct ChainArgs {
    /// The chain's base link in the URDF (default: the tree's root).
    #[arg(long)]
    pub base: Option<String>,
    /// The chain's tip link in the URDF (default: the one leaf below the
    /// base; needed where the tree has several).
    #[arg(long)]
    pub tip: Option<String>,
    /// The folder `package://NAME/...` mesh names are read under, as
    /// `DIR/NAME/...` (default: the URDF's folder, and its parent).
    #[arg(long)]
    pub package_dir: Option<PathBuf>,
    /// MoveIt's SRDF for the robot: its <disable_collisions> pairs are
    /// not checked for self-collision (which it switches on).
    #[arg(long)]
    pub srdf: Option<PathBuf>,
}

impl ChainArgs {
    /// Refused where any of these options is given without `--urdf FILE`.
    pub fn need_urdf(&self, urdf: Option<&Path>) -> Result<(), String> {
        let given = [
            ("--base", self.base.is_some()),
            ("--tip", self.tip.is_some()),
            ("--package-dir", self.package_dir.is_some()),
            ("--srdf", self.srdf.is_some()),
        ];
        match given.iter().find(|(_, on)| *on) {
            Some((flag, _)) if urdf.is_none() => {
                Err(format!("{flag} goes with --urdf FILE (a robot's URDF)"))
            }
            _ => Ok(()),
        }
    }
}

/// The arm a spatial job runs: a preset, or a robot read from URDF (or
/// carried by a run file) that may be one.
pub struct Robot {
    /// The preset it is, if it is one.
    pub preset: Option<&'static SpacePreset>,
    /// What the outputs call it.
    pub label: String,
    /// Its name in file names (`panda`, or the URDF's robot name).
    pub key: String,
}

impl Robot {
    /// The preset `p`.
    pub fn preset(p: &'static SpacePreset) -> Self {
        Self {
            preset: Some(p),
            label: p.label.into(),
            key: p.key.into(),
        }
    }

    /// The robot whose chain is `chain`, called `name` unless it is a
    /// preset.
    pub fn of_chain(chain: &Chain, name: &str) -> Self {
        match SpacePreset::of(chain) {
            Some(p) => Self::preset(p),
            None => Self {
                preset: None,
                label: SpacePreset::label_of(chain, name),
                key: name.into(),
            },
        }
    }
}

/// A URDF file read (at most [`MAX_URDF_BYTES`]), its chain from the
/// options' base to their tip, and its links' volumes with the reader's
/// warnings.
pub struct Loaded {
    /// The file's text.
    pub text: String,
    /// The document.
    pub urdf: Urdf,
    /// Its chain.
    pub chain: UrdfChain,
    /// The links' volumes.
    pub volumes: Vec<Volume>,
    /// What the volumes' reader warns of.
    pub warnings: Vec<String>,
}

/// Reads the URDF at `path` into its chain and volumes (meshes beside it
/// or under `--package-dir`); a refusal names the file.
pub fn load(path: &Path, options: &ChainArgs) -> Result<Loaded, String> {
    let text = super::read_at_most(path, MAX_URDF_BYTES, "a URDF")?;
    let at = |e: redundant_ik::Error| format!("{}: {e}", path.display());
    let urdf = Urdf::parse(&text).map_err(at)?;
    let chain =
        UrdfChain::new(&urdf, options.base.as_deref(), options.tip.as_deref()).map_err(at)?;
    let mesh = mesh_reader(path, options.package_dir.as_deref());
    let (volumes, warnings) = volume::volumes(&urdf, &chain, &mesh, DEFAULT_RADIUS);
    Ok(Loaded {
        text,
        urdf,
        chain,
        volumes,
        warnings,
    })
}

/// A mesh file's bytes for its URDF name: `package://NAME/REST` under
/// `--package-dir` (or the URDF's folder and its parent, as `NAME/REST`
/// and `REST`), `file://PATH`, or a path relative to the URDF's folder.
pub fn mesh_reader(urdf: &Path, package_dir: Option<&Path>) -> impl Fn(&str) -> Option<Vec<u8>> {
    let folder = urdf.parent().map(Path::to_path_buf).unwrap_or_default();
    let package = package_dir.map(Path::to_path_buf);
    move |name: &str| {
        let mut tries: Vec<PathBuf> = Vec::new();
        if let Some(rest) = name.strip_prefix("package://") {
            let (pkg, inner) = rest.split_once('/').unwrap_or((rest, ""));
            if let Some(dir) = &package {
                tries.push(dir.join(pkg).join(inner));
            }
            for dir in [Some(folder.as_path()), folder.parent()]
                .into_iter()
                .flatten()
            {
                tries.push(dir.join(pkg).join(inner));
                tries.push(dir.join(inner));
            }
        } else if let Some(path) = name.strip_prefix("file://") {
            tries.push(PathBuf::from(path));
        } else {
            tries.push(folder.join(name));
        }
        tries.iter().find_map(|p| {
            let size = std::fs::metadata(p).ok()?.len();
            (size <= redundant_ik::urdf::stl::MAX_STL_BYTES as u64)
                .then(|| std::fs::read(p).ok())
                .flatten()
        })
    }
}

/// The URDF of the arm in space `key`, as `robots/KEY.urdf` holds it.
pub fn preset_urdf(key: &str) -> Result<String, String> {
    let p = SpacePreset::named(key).map_err(|e| format!("--urdf-of: {e}"))?;
    let comment = format!(
        "{}: written from the preset's modified-DH rows, limits and capsules (src/space/preset.rs) by redundant-ik's robot command, its urdf-of option. Numbers: {}.",
        p.label, p.source
    );
    Ok(chain_urdf(p.key, &comment, &p.chain()))
}

/// Runs `redundant-ik robot`.
pub fn run(args: &RobotArgs) -> Result<(), String> {
    if let Some(key) = &args.urdf_of {
        return emit(&preset_urdf(key)?);
    }
    let Some(file) = &args.file else {
        return Err("robot: give a URDF file, or --urdf-of PRESET".into());
    };
    let Loaded {
        chain,
        volumes,
        warnings,
        ..
    } = load(file, &args.chain)?;
    if args.json {
        #[derive(serde::Serialize)]
        struct Out<'a> {
            chain: &'a UrdfChain,
            volumes: &'a [Volume],
            warnings: &'a [String],
        }
        let json = serde_json::to_string(&Out {
            chain: &chain,
            volumes: &volumes,
            warnings: &warnings,
        })
        .map_err(|e| e.to_string())?;
        return emit(&format!("{json}\n"));
    }
    emit(&describe(&chain, &volumes, &warnings))
}

/// The chain, its volumes and the warnings as text.
fn describe(chain: &UrdfChain, volumes: &[Volume], warnings: &[String]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "robot '{}': {} moving joints from '{}' to '{}'",
        chain.robot,
        chain.dof(),
        chain.base,
        chain.tip
    );
    for (k, j) in chain.joints.iter().enumerate() {
        let unit = match j.kind {
            JointKind::Revolute => ("rad", "rad/s"),
            JointKind::Prismatic => ("m", "m/s"),
        };
        let range = j.limits.map_or("no limits".to_string(), |[lo, hi]| {
            format!("{lo} to {hi} {}", unit.0)
        });
        let rate = j
            .velocity
            .map_or(String::new(), |v| format!(", at most {v} {}", unit.1));
        let [x, y, z] = j.axis;
        let _ = writeln!(
            out,
            "  {:>2} {:<24} {:<9} axis ({x}, {y}, {z})  {range}{rate}",
            k + 1,
            j.name,
            match j.kind {
                JointKind::Revolute => "revolute",
                JointKind::Prismatic => "prismatic",
            }
        );
    }
    let _ = writeln!(out, "{} volumes:", volumes.len());
    for v in volumes {
        let how = match &v.source {
            Source::Sphere => "sphere".to_string(),
            Source::Cylinder => "capsule around a cylinder".to_string(),
            Source::Box => "capsule around a box".to_string(),
            Source::Mesh(f) => format!("capsule around the mesh {f}"),
            Source::Segment => "segment to the next joint".to_string(),
        };
        let _ = writeln!(
            out,
            "  {:<24} moved by joint {:<2} radius {:.4} m, length {:.4} m: {how}",
            v.link,
            v.moved_by,
            v.radius,
            (0..3)
                .map(|k| (v.b[k] - v.a[k]).powi(2))
                .sum::<f64>()
                .sqrt()
        );
    }
    for w in warnings {
        let _ = writeln!(out, "warning: {w}");
    }
    out
}

/// The capsule pairs `srdf` disables for a chain read from URDF whose
/// volumes are `volumes`; the SRDF's link names that no volume has are
/// reported on stderr.
pub fn srdf_pairs(srdf: &Path, volumes: &[volume::Volume]) -> Result<Vec<[usize; 2]>, String> {
    let text = super::read_at_most(srdf, MAX_URDF_BYTES, "an SRDF")?;
    let links = redundant_ik::urdf::srdf::disabled_links(&text)
        .map_err(|e| format!("{}: {e}", srdf.display()))?;
    let (pairs, unknown) = redundant_ik::urdf::srdf::disabled_pairs(volumes, &links);
    if !unknown.is_empty() {
        eprintln!(
            "note: {} names links the chain has no volume of ({}): their pairs are not the chain's",
            srdf.display(),
            unknown.join(", ")
        );
    }
    Ok(pairs)
}

/// `chain` with self-collision checked (`--self-collision`, or an SRDF's
/// `disabled` pairs): every pair of capsules but the adjacent ones, the
/// disabled ones and those touching at the zero pose or at `theta0`.
pub fn with_self_collision(
    chain: Chain,
    disabled: &[[usize; 2]],
    theta0: &[f64],
) -> Result<Chain, String> {
    let zero = vec![0.0; chain.dof()];
    chain
        .with_self_collision(disabled, &[&zero, theta0])
        .map_err(|e| e.to_string())
}

/// A robot read from URDF: what it is called, its own scene, its links'
/// volumes (for an SRDF) and its source (what a run file records).
pub struct UrdfRobot {
    /// Its name and key.
    pub robot: Robot,
    /// Its own scene.
    pub scene: redundant_ik::scene::SpaceScene,
    /// The links' volumes, in the chain's order.
    pub volumes: Vec<Volume>,
    /// The file's text, base, tip and SHA-256.
    pub source: RobotSource,
}

/// The hexadecimal SHA-256 of `text`.
pub fn sha256(text: &str) -> String {
    use sha2::Digest as _;
    sha2::Sha256::digest(text.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Refused where a run file's robot carries a URDF whose SHA-256 is not
/// the one it records (a file changed by hand, or cut), or that does not
/// describe `chain`, the chain its scene runs.
pub fn check_source(source: Option<&RobotSource>, chain: &Chain) -> Result<(), String> {
    let Some(source) = source else {
        return Ok(());
    };
    if let (Some(text), Some(hash)) = (&source.urdf, &source.sha256) {
        if &sha256(text) != hash {
            return Err(
                "the run file's URDF does not have the SHA-256 it records: the file was changed"
                    .into(),
            );
        }
    }
    source.check(chain).map_err(|e| e.to_string())
}

/// `scene`'s target moved to the end of the robot's own line from where
/// its start pose puts the hand (after `--theta0`); refused where the
/// scene then does not validate.
pub fn own_line_from_start(scene: &mut redundant_ik::scene::SpaceScene) -> Result<(), String> {
    scene.target = redundant_ik::scene::own_line_end(scene.start());
    scene.validate().map_err(|e| e.to_string())
}

/// The robot of the URDF at `path` (its chain as `chain` picks it, the
/// limits of `joint_limits` where given) and its own scene
/// ([`SpaceScene::own`](redundant_ik::scene::SpaceScene::own)). The
/// reader's warnings go to stderr.
pub fn urdf_scene(
    path: &Path,
    options: &ChainArgs,
    joint_limits: Option<redundant_ik::arm::JointLimits>,
) -> Result<UrdfRobot, String> {
    let Loaded {
        text,
        urdf,
        chain: uc,
        volumes,
        warnings,
    } = load(path, options)?;
    let chain = uc
        .to_chain(&volumes, joint_limits)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    let name = if urdf.name.is_empty() {
        "robot"
    } else {
        &urdf.name
    };
    let robot = Robot::of_chain(&chain, name);
    let source = match robot.preset {
        Some(p) => RobotSource::shipped(p.key),
        None => RobotSource {
            name: name.to_string(),
            sha256: Some(sha256(&text)),
            urdf: Some(text),
            base: options.base.clone(),
            tip: options.tip.clone(),
        },
    };
    let scene = redundant_ik::scene::SpaceScene::own(chain).map_err(|e| e.to_string())?;
    Ok(UrdfRobot {
        robot,
        scene,
        volumes,
        source,
    })
}
