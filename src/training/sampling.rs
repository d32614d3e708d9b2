//! Training data from the numerical route (`docs/conventions.md`, "The
//! networks"): how the poses and obstacle points of [`Sampling`] are drawn.
//!
//! A box over theta that spans the tasks contains singular poses where `Phi`
//! is unbounded, so the data is drawn around the configurations the tasks
//! actually visit: the numerical route and the no-avoidance route are run
//! on a set of straight-line tasks with many obstacle positions drawn
//! uniformly from a region, every visited pose is kept, and samples are
//! visited poses plus Gaussian noise. Poses whose Jacobian's smallest
//! singular value is below a floor are rejected.
//!
//! The tasks are the paper's Task 1 and Task 2 for the paper's arm (with
//! the region around and between both canonical obstacles:
//! [`Sampling::default`]), and random straight-line tasks inside the arm's
//! reach for any other arm ([`Sampling::for_arm`], [`super::tasks`]).

use nalgebra::{DVector, Vector2};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::ik;
use crate::networks::Sampling;
use crate::nn::rng::Rng;
use crate::obstacle::{self, Obstacle};
use crate::planner::{Method, Planner};
use crate::scene::Scene;

/// The smoothing `eps` (m^2) of the sign of eq. (15) in the `reach`
/// recipe's `v` targets: 0.1, as measured before the recipe was written
/// (`docs/learning.md`); the paper's arm's triangles have `|D|` up to 4 m^2.
pub const REACH_SIGN_SMOOTHING: f64 = 0.1;

/// A pose visited by a planner run, with that run's obstacle point.
#[derive(Debug, Clone, PartialEq)]
pub struct Visited {
    /// Joint angles.
    pub theta: Vec<f64>,
    /// Obstacle centre of the run.
    pub obstacle: [f64; 2],
}

impl Sampling {
    /// How to sample for `arm`: the paper's sampling ([`Sampling::default`])
    /// for the paper's arm; for any other arm 60 random straight-line tasks
    /// with 6 obstacles each near the links' sweep (spread 0.08 of the
    /// reach; the region is [`super::tasks::obstacle_region`]), every `v`
    /// sample paired with its run's obstacle, the rest as the paper's, with
    /// the sigma floor scaled by the reach (0.2 m of the paper's 2.05 m).
    /// Uniform obstacles over the whole reach would mostly sit far from the
    /// arm, where the area criterion keeps turning the joints (the areas
    /// grow with distance), and would spread the poses over several turns.
    pub fn for_arm(arm: &Arm) -> Self {
        if arm.same_geometry(&Arm::paper()) {
            return Self::default();
        }
        let (obstacle_min, obstacle_max) = super::tasks::obstacle_region(arm);
        let paper_reach = Arm::paper().max_reach();
        Self {
            tasks: Vec::new(),
            random_tasks: 60,
            obstacles_per_task: 6,
            obstacle_min,
            obstacle_max,
            sigma_floor: 0.2 * arm.max_reach() / paper_reach,
            paired_obstacle_share: 1.0,
            obstacle_spread: 0.08 * arm.max_reach(),
            ..Self::default()
        }
    }

    /// The `reach` recipe's sampling for `arm` and `net`, meant to hold
    /// wherever a run of the arm may go (`docs/learning.md`):
    /// - `Phi`: poses uniform over the whole joint torus, those with
    ///   `sigma_min(J)` below 0.15 m (for the paper's 2.05 m reach; scaled
    ///   by the reach for other arms) rejected;
    /// - `v`: the poses of numerical runs of random straight-line tasks
    ///   (and, for the paper's arm, of its two tasks) with obstacles
    ///   uniform over the whole box of the reach (the atlas's region),
    ///   each paired with its run's obstacle; the sign of eq. (15)
    ///   smoothed by [`REACH_SIGN_SMOOTHING`].
    pub fn reach(arm: &Arm, net: crate::networks::NetKind) -> Self {
        let paper_reach = Arm::paper().max_reach();
        let r = arm.max_reach();
        let post = arm.post();
        let (obstacle_min, obstacle_max) = ([-r, (post - r).max(0.0)], [r, post + r]);
        let base = Self {
            obstacle_min,
            obstacle_max,
            methods: vec![Method::NUMERICAL],
            ..Self::default()
        };
        match net {
            crate::networks::NetKind::Phi => Self {
                tasks: Vec::new(),
                obstacles_per_task: 0,
                theta_noise: 0.0,
                sigma_floor: 0.15 * r / paper_reach,
                paired_obstacle_share: 0.0,
                obstacle_noise: 0.0,
                whole_torus: true,
                ..base
            },
            crate::networks::NetKind::V => Self {
                tasks: if arm.dof() == 3 && arm.same_geometry(&Arm::paper()) {
                    vec![1, 2]
                } else {
                    Vec::new()
                },
                random_tasks: 40,
                obstacles_per_task: 25,
                theta_noise: 0.08,
                sigma_floor: 0.0,
                paired_obstacle_share: 1.0,
                obstacle_noise: 0.03,
                sign_smoothing: REACH_SIGN_SMOOTHING,
                ..base
            },
        }
    }

    /// `n` poses uniform over the joint torus (`[-pi, pi)` per joint),
    /// rejected while `sigma_min(J)` is below the floor, each with an
    /// obstacle point uniform in the region.
    pub fn torus(&self, arm: &Arm, n: usize, rng: &mut Rng) -> Result<Vec<Visited>> {
        use std::f64::consts::PI;
        let mut out = Vec::with_capacity(n);
        let mut tries = 0usize;
        while out.len() < n {
            tries += 1;
            self.give_up_after(tries, n, "every pose of the torus")?;
            let theta: Vec<f64> = (0..arm.dof()).map(|_| rng.range(-PI, PI)).collect();
            if self.below_floor(arm, &theta) {
                continue;
            }
            let obstacle = self.uniform_obstacle(rng);
            out.push(Visited { theta, obstacle });
        }
        Ok(out)
    }

    /// Every pose `arm` visits in the numerical runs: each paper task with
    /// its canonical obstacle, and each random task, with
    /// `obstacles_per_task` obstacles uniform in the region, in every method
    /// listed. Runs that fail (obstacle on the post, a singular pose) are
    /// skipped. The paper's tasks start from three joint angles, so they
    /// need a 3-link arm.
    pub fn visited(&self, arm: &Arm, rng: &mut Rng) -> Result<Vec<Visited>> {
        self.validate()?;
        let mut bases = Vec::with_capacity(self.tasks.len() + self.random_tasks);
        for &task in &self.tasks {
            let mut base = Scene::task(task)?;
            if arm.dof() != base.theta0.len() {
                return Err(Error::Training(format!(
                    "sampling: the paper's tasks start from {} joint angles; a {}-link arm needs random tasks (Sampling::for_arm)",
                    base.theta0.len(),
                    arm.dof()
                )));
            }
            base.arm = arm.clone();
            bases.push(base);
        }
        let paper_tasks = bases.len();
        for _ in 0..self.random_tasks {
            bases.push(super::tasks::random_task(arm, rng)?);
        }
        let mut out = Vec::new();
        for (k, base) in bases.into_iter().enumerate() {
            let canonical = base.obstacles.first().map(|o| o.centre);
            let mut obstacles: Vec<[f64; 2]> = canonical.into_iter().collect();
            let sweep = if k >= paper_tasks && self.obstacle_spread > 0.0 {
                Planner::run(base.clone(), Method::NO_AVOIDANCE, None).ok()
            } else {
                None
            };
            for _ in 0..self.obstacles_per_task {
                obstacles.push(match &sweep {
                    Some(run) => {
                        let joints = &run.steps[rng.below(run.steps.len())].joints;
                        let link = 1 + rng.below(joints.len() - 1);
                        let (a, b, s) = (joints[link - 1], joints[link], rng.uniform());
                        [
                            a[0] + s * (b[0] - a[0]) + self.obstacle_spread * rng.normal(),
                            a[1] + s * (b[1] - a[1]) + self.obstacle_spread * rng.normal(),
                        ]
                    }
                    None => self.uniform_obstacle(rng),
                });
            }
            for o in obstacles {
                let radius = base.obstacles.first().map_or(0.05, |ob| ob.radius);
                let mut scene = base.clone();
                scene.obstacles = vec![Obstacle::new(o[0], o[1], radius)];
                for &method in &self.methods {
                    let Ok(run) = Planner::run(scene.clone(), method, None) else {
                        continue;
                    };
                    out.extend(run.steps.into_iter().map(|s| Visited {
                        theta: s.theta,
                        obstacle: o,
                    }));
                }
            }
        }
        if out.is_empty() {
            return Err(Error::Training(
                "sampling: no planner run succeeded, so there are no poses to learn from".into(),
            ));
        }
        Ok(out)
    }

    /// `n` training points: a visited pose picked at random plus noise,
    /// rejected while `J`'s smallest singular value is below the floor; the
    /// obstacle point paired with the run or uniform in the region.
    pub fn draw(
        &self,
        arm: &Arm,
        pool: &[Visited],
        n: usize,
        rng: &mut Rng,
    ) -> Result<Vec<Visited>> {
        if pool.is_empty() {
            return Err(Error::Training("sampling: empty pose pool".into()));
        }
        if pool.iter().any(|v| v.theta.len() != arm.dof()) {
            return Err(Error::Training(format!(
                "sampling: the pose pool is not for a {}-link arm",
                arm.dof()
            )));
        }
        let mut out = Vec::with_capacity(n);
        let mut tries = 0usize;
        while out.len() < n {
            tries += 1;
            self.give_up_after(tries, n, "every pose")?;
            let v = &pool[rng.below(pool.len())];
            let theta: Vec<f64> = v
                .theta
                .iter()
                .map(|t| t + self.theta_noise * rng.normal())
                .collect();
            if self.below_floor(arm, &theta) {
                continue;
            }
            let obstacle = if rng.uniform() < self.paired_obstacle_share {
                [
                    (v.obstacle[0] + self.obstacle_noise * rng.normal())
                        .clamp(self.obstacle_min[0], self.obstacle_max[0]),
                    (v.obstacle[1] + self.obstacle_noise * rng.normal())
                        .clamp(self.obstacle_min[1], self.obstacle_max[1]),
                ]
            } else {
                self.uniform_obstacle(rng)
            };
            out.push(Visited { theta, obstacle });
        }
        Ok(out)
    }

    /// An obstacle point uniform in the region.
    fn uniform_obstacle(&self, rng: &mut Rng) -> [f64; 2] {
        [
            rng.range(self.obstacle_min[0], self.obstacle_max[0]),
            rng.range(self.obstacle_min[1], self.obstacle_max[1]),
        ]
    }

    /// Whether `J`'s smallest singular value at the pose is below the floor
    /// (the samples' rejection rule).
    fn below_floor(&self, arm: &Arm, theta: &[f64]) -> bool {
        let j = arm.jacobian(&DVector::from_column_slice(theta));
        ik::smallest_singular_value(&j) < self.sigma_floor
    }

    /// The end of a rejection loop that has made `tries` proposals for `n`
    /// samples: an error after `100 n + 1000`, when the floor rejects
    /// nearly `what` it draws from.
    fn give_up_after(&self, tries: usize, n: usize, what: &str) -> Result<()> {
        if tries > 100 * n + 1000 {
            return Err(Error::Training(format!(
                "sampling: sigma floor {} rejects nearly {what}",
                self.sigma_floor
            )));
        }
        Ok(())
    }
}

/// `Phi(theta)` at `delta = 0` as a row-major `n x 2` array (eq. 19).
pub fn phi_target(arm: &Arm, theta: &[f64]) -> Result<Vec<f64>> {
    let p = ik::phi(&arm.jacobian(&DVector::from_column_slice(theta)), 0.0)?;
    let mut out = Vec::with_capacity(2 * p.nrows());
    for i in 0..p.nrows() {
        out.push(p[(i, 0)]);
        out.push(p[(i, 1)]);
    }
    Ok(out)
}

/// The area gradient `g(theta, O)` (`v = lambda / 4 g`, eqs. 14-15), its
/// sign smoothed by `eps` ([`obstacle::smoothed_sign`]; 0 is the paper's).
pub fn v_target(arm: &Arm, theta: &[f64], o: [f64; 2], eps: f64) -> Vec<f64> {
    obstacle::area_gradient_smoothed(
        arm,
        &DVector::from_column_slice(theta),
        &Vector2::new(o[0], o[1]),
        eps,
    )
    .iter()
    .copied()
    .collect()
}
