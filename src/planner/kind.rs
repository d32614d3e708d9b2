//! What the planner needs of an arm model beyond its kinematics
//! ([`crate::model::Model`]): the methods' rules and constraints from the
//! registry, the scene's path as a track, whether a point is in reach, and
//! what a sample records of obstacles. Implemented by the planar arm
//! (`M = 2`) and the chain in space (`M = 3`); everything else of the
//! planner is written once.

use super::along::Circle;
use super::methods::{constraints, Builder, Entry};
use super::path::{Shape, Track};
use crate::arm::Arm;
use crate::clearance::Pair;
use crate::error::{Error, Result};
use crate::kinematics::Pose;
use crate::model::Model;
use crate::scene::{circle_plane, Path, PoseScene, Scene, SpacePath, SpaceScene, MAX_POINTS};
use crate::space::self_pairs::self_contact;
use crate::space::{norm, sub, CapsulePair, Chain, HandPose, PoseChain, SpacePose, Sphere};

/// What a sample records of the obstacles at a pose.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Contact {
    /// The smallest distance from an obstacle's centre to a moving link.
    pub distance: Option<f64>,
    /// The smallest clearance between a moving link and an obstacle.
    pub clearance: Option<f64>,
    /// Whether a link is inside an obstacle (or the ground, where the
    /// scene has one and the arm counts it).
    pub collision: bool,
    /// The smallest distance between two capsules of the chain that it
    /// checks for self-collision (none where it checks none).
    pub self_clearance: Option<f64>,
}

/// The scene type of one arm model: lets `Planner::new(scene, ...)` find
/// the arm and the task's dimension from the scene it is given.
pub trait SceneOf<A, const M: usize> {}

impl SceneOf<Arm, 2> for Scene {}
impl SceneOf<Chain, 3> for SpaceScene {}
impl SceneOf<PoseChain, 6> for PoseScene {}

/// An arm model the planner plans for.
pub trait Planned<const M: usize>: Model<M> {
    /// How `entry`'s rule is built for this model, if the method has one.
    fn rule(entry: &Entry) -> Option<Builder<Self, M>>;
    /// How `entry`'s constraint is built for this model.
    fn constraint(entry: &constraints::Entry) -> constraints::Build<Self, M>;
    /// The track of the scene's path for a hand at `start` at time `t0`,
    /// taking `duration`; refused where the path does not validate.
    fn track(scene: &Self::Scene, start: [f64; M], t0: f64, duration: f64) -> Result<Track<M>>;
    /// [`Planned::track`] into `track`, reusing its buffer (the scene and
    /// its path were validated when `track` was made).
    fn renew_track(
        scene: &Self::Scene,
        start: [f64; M],
        t0: f64,
        duration: f64,
        track: &mut Track<M>,
    );
    /// Whether the hand can be at `p` at all (the planar arm's annulus; a
    /// chain's reach about its first joint, an upper bound), at a pose of
    /// the arm's.
    fn reaches(&self, pose: &Self::Pose, p: [f64; M]) -> bool;
    /// What a sample records of the scene's obstacles at `pose`.
    fn contact(scene: &Self::Scene, pose: &Self::Pose) -> Contact;
    /// The path as a polyline from `start` to `end`, for drawing.
    fn outline(scene: &Self::Scene, start: [f64; M], end: [f64; M]) -> Vec<[f64; M]>;
}

impl Planned<2> for Arm {
    fn rule(entry: &Entry) -> Option<Builder<Self, 2>> {
        Some(entry.rule)
    }
    fn constraint(entry: &constraints::Entry) -> constraints::Build<Self, 2> {
        entry.build
    }
    fn track(scene: &Scene, start: [f64; 2], t0: f64, duration: f64) -> Result<Track<2>> {
        scene.path.validate(start)?;
        let end = scene.path.end(start, scene.target);
        Ok(Track::from_shape(
            plane_shape(&scene.path, start),
            <Arm as Model<2>>::geodesic,
            start,
            end,
            t0,
            duration,
        ))
    }
    fn renew_track(scene: &Scene, start: [f64; 2], t0: f64, duration: f64, track: &mut Track<2>) {
        let end = scene.path.end(start, scene.target);
        track.renew(plane_shape(&scene.path, start), start, end, t0, duration);
    }
    fn reaches(&self, _: &Pose, p: [f64; 2]) -> bool {
        self.can_reach(&nalgebra::Vector2::new(p[0], p[1]))
    }
    fn contact(scene: &Scene, pose: &Pose) -> Contact {
        let mut c = Contact::default();
        for ob in &scene.obstacles {
            let d = pose.clearance(ob.centre);
            c.collision |= d < ob.radius;
            c.distance = Some(c.distance.map_or(d, |m| m.min(d)));
            let k = d - ob.radius;
            c.clearance = Some(c.clearance.map_or(k, |m| m.min(k)));
        }
        if let Some(post) = scene.ground() {
            // The ground as an obstacle: a link below the floor or across
            // the post collides.
            let n = pose.dof();
            c.collision |= (0..n).any(|k| Pair::floor(pose, k).clearance < 0.0)
                || (1..n).any(|k| Pair::post(pose, k, post).clearance < 0.0);
        }
        c
    }
    fn outline(scene: &Scene, start: [f64; 2], end: [f64; 2]) -> Vec<[f64; 2]> {
        scene.path.outline(start, end, 96)
    }
}

impl Track<2> {
    /// The track of a planar `path` for a hand at `start` at time `t0`,
    /// taking `duration` seconds (`target` is the line's end). The path
    /// must have been validated ([`Path::validate`]).
    pub fn new(path: &Path, start: [f64; 2], target: [f64; 2], t0: f64, duration: f64) -> Self {
        let end = path.end(start, target);
        Track::from_shape(
            plane_shape(path, start),
            <Arm as Model<2>>::geodesic,
            start,
            end,
            t0,
            duration,
        )
    }
}

/// The shape of a planar path for a hand at `start`.
fn plane_shape(path: &Path, start: [f64; 2]) -> Shape<'_, 2> {
    match path {
        Path::Line => Shape::Line,
        Path::Circle { centre, laps } => Shape::Circle(Circle::planar(*centre, start, *laps)),
        Path::Points(p) => Shape::Points(p),
    }
}

impl Planned<3> for Chain {
    fn rule(entry: &Entry) -> Option<Builder<Self, 3>> {
        entry.space
    }
    fn constraint(entry: &constraints::Entry) -> constraints::Build<Self, 3> {
        entry.space
    }
    fn track(scene: &SpaceScene, start: [f64; 3], t0: f64, duration: f64) -> Result<Track<3>> {
        scene.path.validate(start)?;
        let end = scene.path.end(start, scene.target);
        Ok(Track::from_shape(
            space_shape(&scene.path, start)?,
            <Chain as Model<3>>::geodesic,
            start,
            end,
            t0,
            duration,
        ))
    }
    fn renew_track(
        scene: &SpaceScene,
        start: [f64; 3],
        t0: f64,
        duration: f64,
        track: &mut Track<3>,
    ) {
        let end = scene.path.end(start, scene.target);
        // The path validated with this start when the track was made.
        if let Ok(shape) = space_shape(&scene.path, start) {
            track.renew(shape, start, end, t0, duration);
        }
    }
    fn reaches(&self, pose: &SpacePose, p: [f64; 3]) -> bool {
        norm(sub(p, pose.joint_origin(0))) <= self.reach()
    }
    fn contact(scene: &SpaceScene, pose: &SpacePose) -> Contact {
        chain_contact(&scene.arm, &scene.obstacles, pose)
    }
    fn outline(scene: &SpaceScene, start: [f64; 3], end: [f64; 3]) -> Vec<[f64; 3]> {
        scene.path.outline(start, end, 96)
    }
}

/// A chain's contact with spheres: the capsules' clearance from them;
/// the floor is a constraint of the methods that keep a clearance, not
/// counted as a collision.
fn chain_contact(chain: &Chain, spheres: &[Sphere], pose: &SpacePose) -> Contact {
    let mut c = Contact::default();
    for (k, s) in chain.segments().iter().enumerate() {
        if s.moved_by == 0 {
            continue;
        }
        for (j, sp) in spheres.iter().enumerate() {
            let pair = CapsulePair::at(chain, pose, k, j, sp);
            let axis = pair.distance + s.radius + sp.radius;
            c.distance = Some(c.distance.map_or(axis, |m| m.min(axis)));
            c.clearance = Some(c.clearance.map_or(pair.distance, |m| m.min(pair.distance)));
        }
    }
    c.collision = c.clearance.is_some_and(|k| k < 0.0);
    for &[a, b] in chain.self_pairs() {
        let d = self_contact(chain, pose, a, b).distance;
        c.self_clearance = Some(c.self_clearance.map_or(d, |m| m.min(d)));
    }
    c
}

impl Planned<6> for PoseChain {
    fn rule(entry: &Entry) -> Option<Builder<Self, 6>> {
        entry.pose
    }
    fn constraint(entry: &constraints::Entry) -> constraints::Build<Self, 6> {
        entry.pose
    }
    /// The straight line, the orientation along its shortest rotation; a
    /// circle or a polyline of the hand's position with the start
    /// orientation kept.
    fn track(scene: &PoseScene, start: [f64; 6], t0: f64, duration: f64) -> Result<Track<6>> {
        if scene.path != SpacePath::Line {
            scene.validate()?;
        }
        let mut buf = [[0.0; 6]; MAX_POINTS];
        let shape = pose_shape(&scene.path, start, &mut buf)?;
        Ok(Track::from_shape(
            shape,
            Self::geodesic,
            start,
            pose_end(scene, start),
            t0,
            duration,
        ))
    }
    fn renew_track(
        scene: &PoseScene,
        start: [f64; 6],
        t0: f64,
        duration: f64,
        track: &mut Track<6>,
    ) {
        let mut buf = [[0.0; 6]; MAX_POINTS];
        // The path validated with this start when the track was made.
        if let Ok(shape) = pose_shape(&scene.path, start, &mut buf) {
            track.renew(shape, start, pose_end(scene, start), t0, duration);
        }
    }
    fn reaches(&self, pose: &HandPose, p: [f64; 6]) -> bool {
        self.chain.reaches(pose.space(), [p[0], p[1], p[2]])
    }
    fn contact(scene: &PoseScene, pose: &HandPose) -> Contact {
        chain_contact(&scene.arm.chain, &scene.obstacles, pose.space())
    }
    /// The hand's path: 33 poses along the line, or the circle's or the
    /// polyline's points with the start orientation.
    fn outline(scene: &PoseScene, start: [f64; 6], end: [f64; 6]) -> Vec<[f64; 6]> {
        if scene.path == SpacePath::Line {
            return (0..=32)
                .map(|k| Self::geodesic(start, end, f64::from(k) / 32.0).0)
                .collect();
        }
        let (p, q) = ([start[0], start[1], start[2]], [end[0], end[1], end[2]]);
        scene
            .path
            .outline(p, q, 96)
            .into_iter()
            .map(|x| lift(x, start))
            .collect()
    }
}

/// The point `p` of the hand's position with `pose`'s orientation.
fn lift(p: [f64; 3], pose: [f64; 6]) -> [f64; 6] {
    [p[0], p[1], p[2], pose[3], pose[4], pose[5]]
}

/// Where a pose scene's path ends for a hand at `start`: the target, on
/// the line; else the position path's end with the start orientation.
fn pose_end(scene: &PoseScene, start: [f64; 6]) -> [f64; 6] {
    if scene.path == SpacePath::Line {
        return scene.target;
    }
    let [x, y, z, ..] = scene.target;
    let end = scene.path.end([start[0], start[1], start[2]], [x, y, z]);
    lift(end, start)
}

/// The shape of a pose scene's path for a hand at `start`: the line, or
/// the position's circle or polyline lifted into the pose's coordinates
/// with the start orientation (the polyline's points in `buf`, no
/// allocation).
fn pose_shape<'a>(
    path: &'a SpacePath,
    start: [f64; 6],
    buf: &'a mut [[f64; 6]; MAX_POINTS],
) -> Result<Shape<'a, 6>> {
    let p = [start[0], start[1], start[2]];
    Ok(match space_shape(path, p)? {
        Shape::Line => Shape::Line,
        Shape::Points(points) => {
            let n = points.len().min(MAX_POINTS);
            for (b, &q) in buf.iter_mut().zip(&points[..n]) {
                *b = lift(q, start);
            }
            Shape::Points(&buf[..n])
        }
        Shape::Circle(c) => {
            let [u, w] = c.axes;
            Shape::Circle(Circle {
                centre: lift(c.centre, start),
                axes: [lift(u, [0.0; 6]), lift(w, [0.0; 6])],
                radius: c.radius,
                phase: c.phase,
                sweep: c.sweep,
            })
        }
    })
}

/// The shape of a spatial path for a hand at `start`.
fn space_shape(path: &SpacePath, start: [f64; 3]) -> Result<Shape<'_, 3>> {
    Ok(match path {
        SpacePath::Line => Shape::Line,
        SpacePath::Points(p) => Shape::Points(p),
        SpacePath::Circle {
            centre,
            normal,
            laps,
        } => {
            let (axes, radius) =
                circle_plane(*centre, *normal, start).map_err(|why| Error::Syntax {
                    what: "path",
                    text: path.to_string(),
                    expected: why.into(),
                })?;
            Shape::Circle(Circle {
                centre: *centre,
                axes,
                radius,
                phase: 0.0,
                sweep: std::f64::consts::TAU * f64::from(*laps),
            })
        }
    })
}
