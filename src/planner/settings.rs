//! What changes a planner between steps: the method, the networks, the
//! target (a new line), the obstacles and the gains. Each setting is
//! checked first; a refused one changes nothing.

use super::methods::{DELTA, LAMBDA};
use super::{check_networks, rule_of, Method, Networks, Planned, Planner, Track};
use crate::arm::{Arm, JointLimits, RateLimits};
use crate::error::{coordinate, positive, Error, Result};
use crate::ik::DampingSchedule;
use crate::model::Scene as _;
use crate::obstacle::Obstacle;
use crate::scene::{self, Param};
use crate::space::{Chain, Sphere, MAX_SPHERES};

impl<A: Planned<M>, const M: usize> Planner<A, M> {
    /// Switches method; methods that use networks need them. The new
    /// method's rule is built here (its scratch space allocated once).
    pub fn set_method(&mut self, method: Method) -> Result<()> {
        check_networks(method, &self.networks, self.scene.arm())?;
        if method != self.method {
            self.ws.rule = rule_of(method, self.scene.arm().dof())?;
        }
        self.method = method;
        self.resample();
        Ok(())
    }

    /// Installs (or removes) the trained networks. Networks trained for
    /// another arm are refused ([`Error::NetworksForAnotherArm`]).
    pub fn set_networks(&mut self, networks: Option<Networks<A, M>>) -> Result<()> {
        check_networks(self.method, &networks, self.scene.arm())?;
        self.networks = networks;
        self.resample();
        Ok(())
    }

    /// Sets a parameter of the methods ([`Param`]); refused, changing
    /// nothing, when out of its bounds.
    pub fn set_param(&mut self, param: &'static Param, value: f64) -> Result<()> {
        self.scene.params_mut().set(param, value)?;
        self.resample();
        Ok(())
    }

    /// Sets `lambda`, the gain of the obstacle vector.
    pub fn set_lambda(&mut self, lambda: f64) -> Result<()> {
        self.set_param(&LAMBDA, lambda)
    }

    /// Sets the constant damping `delta` (eqs. 6, 17, 20). In Cases 1 and 3
    /// it damps the network's `Phi` through [`crate::ik::damp_phi`].
    pub fn set_delta(&mut self, delta: f64) -> Result<()> {
        self.set_param(&DELTA, delta)
    }

    /// Switches the damping schedule on (`Some`) or off (`None`).
    pub fn set_damping(&mut self, damping: Option<DampingSchedule>) -> Result<()> {
        if let Some(d) = &damping {
            d.validate()?;
        }
        *self.scene.damping_mut() = damping;
        self.resample();
        Ok(())
    }
}

impl Planner<Arm, 2> {
    /// Re-plans: a new straight line from the current end effector to `target`,
    /// starting now and lasting `duration` seconds (rounded up to whole steps).
    /// The scene's path becomes the line (a circle or a polyline gives way
    /// to the line to the dragged target).
    pub fn set_target(&mut self, target: [f64; 2], duration: f64) -> Result<()> {
        coordinate("target x", target[0])?;
        coordinate("target y", target[1])?;
        positive("line duration", duration)?;
        let steps = (duration / self.scene.dt - 1e-9).ceil().max(1.0);
        self.scene.target = target;
        self.scene.path = crate::scene::Path::Line;
        self.track = Track::straight(
            self.ws.pose.end_effector(),
            target,
            self.t,
            steps * self.scene.dt,
        );
        let (arm, pose) = (&self.scene.arm, &self.ws.pose);
        self.reachable = self.track.all_points(|p| arm.reaches(pose, p));
        // The damping schedule is switched on where a point of the path
        // (the target, for the line) lies outside the workspace.
        if DampingSchedule::switch_on_out_of_reach(&mut self.scene.damping, self.reachable) {
            self.auto_damping = true;
        }
        self.resample();
        Ok(())
    }

    /// Replaces the obstacles; takes effect at the next step.
    pub fn set_obstacles(&mut self, obstacles: Vec<Obstacle>) -> Result<()> {
        for ob in &obstacles {
            ob.validate(&self.scene.arm)?;
        }
        self.scene.obstacles = obstacles;
        self.resample();
        Ok(())
    }

    /// Moves obstacle `index` to `centre`, keeping its radius; takes effect
    /// at the next step. Allocation-free (what an atlas of thousands of runs
    /// needs). Refused, leaving everything as it was, if the disc would
    /// overlap the base post or `index` names no obstacle.
    pub fn move_obstacle(&mut self, index: usize, centre: [f64; 2]) -> Result<()> {
        let count = self.scene.obstacles.len();
        let Some(ob) = self.scene.obstacles.get(index) else {
            return Err(Error::OutOfRange {
                what: "obstacle index".into(),
                value: index as f64,
                min: 0.0,
                max: count as f64 - 1.0,
            });
        };
        let moved = Obstacle {
            centre,
            radius: ob.radius,
        };
        moved.validate(&self.scene.arm)?;
        self.scene.obstacles[index] = moved;
        self.resample();
        Ok(())
    }

    /// Gives the arm other joint limits (position and rate; `None`:
    /// unlimited), keeping the rest of the scene. Refused, changing nothing,
    /// when their count does not match the links or the start pose lies
    /// outside them.
    pub fn set_arm_limits(
        &mut self,
        joint: Option<JointLimits>,
        rate: Option<RateLimits>,
    ) -> Result<()> {
        let arm = self.scene.arm.clone().with_limits(joint, rate)?;
        arm.check_within_limits("start pose theta0", &self.scene.theta0)?;
        self.scene.arm = arm;
        Ok(())
    }

    /// Sets how the methods of eq. (5) use the arm's joint limits (the
    /// paper's `W` of eq. 7: [`scene::JointWeighting`]).
    pub fn set_weighting(&mut self, weighting: scene::JointWeighting) {
        self.scene.weighting = weighting;
        self.resample();
    }

    /// Makes the floor `y = 0` and the post obstacles (or not) for the
    /// methods that read link-obstacle pairs ([`scene::Scene::floor`]).
    pub fn set_floor(&mut self, floor: bool) {
        self.scene.floor = floor;
        self.resample();
    }

    /// Sets the closed-loop gain `K` (0 = open loop, as in the paper).
    pub fn set_feedback_gain(&mut self, gain: f64) -> Result<()> {
        scene::validate_gain(gain, self.scene.dt)?;
        self.scene.feedback_gain = gain;
        Ok(())
    }
}

/// The arms in space whose scene holds spheres: a chain whose task is
/// its hand's position or its pose.
impl<A, const M: usize> Planner<A, M>
where
    A: super::Planned<M, Scene = scene::Scene<A, scene::SpacePath, M, 3>> + AsRef<Chain>,
    A::Pose: AsRef<crate::space::SpacePose>,
{
    /// Puts sphere `index` at `sphere` (or adds it, for `index` equal to
    /// the number of spheres); it takes effect at the next step, and the
    /// current sample is measured again. Allocation-free but for an added
    /// sphere (the scene's list grows). Refused, changing nothing, where the
    /// sphere does not validate (on the base, not finite), `index` is past
    /// the end or the scene has [`MAX_SPHERES`] already.
    pub fn set_sphere(&mut self, index: usize, sphere: Sphere) -> Result<()> {
        let count = self.scene.obstacles.len();
        if index > count {
            return Err(Error::OutOfRange {
                what: "sphere index".into(),
                value: index as f64,
                min: 0.0,
                max: count as f64,
            });
        }
        sphere.validate_at(self.scene.arm.as_ref(), self.ws.pose.as_ref())?;
        if index == count {
            if count >= MAX_SPHERES {
                return Err(Error::DimensionMismatch {
                    what: "spheres (at most)".into(),
                    expected: MAX_SPHERES,
                    found: count + 1,
                });
            }
            self.scene.obstacles.push(sphere);
        } else {
            self.scene.obstacles[index] = sphere;
        }
        self.resample();
        Ok(())
    }

    /// Replaces the spheres by `spheres` (at most [`MAX_SPHERES`]); takes
    /// effect at the next step. Refused, changing nothing, where one does
    /// not validate (on the base, not finite) or there are too many.
    pub fn set_spheres(&mut self, spheres: Vec<Sphere>) -> Result<()> {
        if spheres.len() > MAX_SPHERES {
            return Err(Error::DimensionMismatch {
                what: "spheres (at most)".into(),
                expected: MAX_SPHERES,
                found: spheres.len(),
            });
        }
        for s in &spheres {
            s.validate_at(self.scene.arm.as_ref(), self.ws.pose.as_ref())?;
        }
        self.scene.obstacles = spheres;
        self.resample();
        Ok(())
    }
}
