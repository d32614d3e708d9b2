"""The mink peer: the scene's Panda written as MJCF (`mjcf`) and mink 1.3
mapped onto our program (`Mink`), behind the controllers' interface
(reset(), step(k), angles(); see ours.py)."""

from __future__ import annotations

import math
import sys

import numpy as np

from task import PEER_SOLVER, Task, fmt, rot_x_quat


def mjcf(task: Task) -> str:
    """The Panda of the scene as MJCF: one body per MDH frame (its pose in
    the parent `Rx(alpha) Tx(a) Tz(d)`, the hinge about its z), a capsule
    geom on each moving segment in the body that carries it, the hand a
    site at the flange, the sphere a world geom."""
    lines = [
        '<mujoco model="panda-mdh">',
        '  <compiler angle="radian" autolimits="true"/>',
        f'  <option timestep="{task.dt}"/>',
        "  <worldbody>",
    ]
    for j, c in enumerate(task.spheres):
        lines.append(
            f'    <geom name="obstacle{j}" type="sphere" pos="{fmt(c[:3])}" size="{fmt([c[3]])}"/>'
        )
    segs = {k: (A, B) for k, A, B in task.segments()}
    if not np.allclose(task.base, np.eye(4)):
        sys.exit("a placed base: the MJCF here assumes the identity")
    indent = "    "
    for i, (a, alpha, d, _) in enumerate(task.rows):
        k = i + 1
        pos = [a, -d * math.sin(alpha), d * math.cos(alpha)]
        q = rot_x_quat(alpha)
        lines.append(
            f'{indent}<body name="link{k}" pos="{fmt(pos)}" quat="{fmt(q)}">'
        )
        indent += "  "
        lo, hi = task.qlim[i]
        lines.append(f'{indent}<joint name="joint{k}" type="hinge" axis="0 0 1" range="{fmt([lo, hi])}"/>')
        # Kinematics only: a nominal inertia (MuJoCo needs one on a moving body).
        lines.append(f'{indent}<inertial pos="0 0 0" mass="1" diaginertia="0.01 0.01 0.01"/>')
        if k in segs:
            A, B = segs[k]
            lines.append(
                f'{indent}<geom name="seg{k}" type="capsule" size="{fmt([task.radius])}" '
                f'fromto="{fmt(list(A) + list(B))}"/>'
            )
    f = task.flange
    lines.append(f'{indent}<site name="hand" pos="{fmt(f)}"/>')
    for i in range(task.n, 0, -1):
        indent = indent[:-2]
        lines.append(f"{indent}</body>")
    lines += ["  </worldbody>", "</mujoco>"]
    return "\n".join(lines) + "\n"


class Mink:
    """mink 1.3 mapped onto our program.

    Ours, the slack eliminated and scaled by 2/w, in the step dq = qd dt:
    (1/w)|dq|^2 + |J dq - xdot dt|^2 (+ the criterion v; none here).
    mink: cost^2 |J dq - e|^2 + damping |dq|^2 with e the frame task's
    error: position_cost 1, orientation_cost 0, damping 1/w, and the target
    the hand's position plus xdot dt with its current orientation, so that
    e = xdot dt exactly (open loop, as our feedback gain 0).
    mink's variable is the step dq = qd dt (VelocityLimit: |dq| <= v_max
    dt). CollisionAvoidanceLimit (mink 1.3, as its code reads) bounds
    -n^T J dq <= gain (d - d_s) / dt: divided by dt though dq is a
    displacement, so in rates -n^T J qd <= gain (d - d_s) / dt^2. Ours is
    -n^T J qd <= xi (d - d_s) / (d_i - d_s): gain = xi dt^2 / (d_i - d_s)
    (0.0089 here; xi dt / (d_i - d_s), what the bound's form suggests, is
    a damper 1/dt = 20 times stiffer), detection distance d_i.
    ConfigurationLimit bounds dq <= gain (q_max - rho_s - q) with no dt:
    gain = xi_q dt / (rho_i - rho_s), min_distance_from_limits rho_s (on
    at every distance; ours only within rho_i).
    """

    def __init__(self, task: Task, rate_bounds, naive_gain=False):
        import mink
        import mujoco

        self.mink = mink
        self.task = task
        self.kind = "mink"
        self.label = "mink 1.3 (daqp)"
        self.xml = mjcf(task)
        model = mujoco.MjModel.from_xml_string(self.xml)
        self.model = model
        self.conf = mink.Configuration(model)
        self.frame = mink.FrameTask(
            frame_name="hand",
            frame_type="site",
            position_cost=1.0,
            orientation_cost=0.0,
            gain=1.0,
            lm_damping=0.0,
        )
        self.tasks = [self.frame]
        arm_geoms = [f"seg{k}" for k, _, _ in task.segments()]
        obstacles = [f"obstacle{j}" for j in range(len(task.spheres))]
        self.collision_gain = task.xi * task.dt**2 / (task.d_i - task.d_s)
        if naive_gain:
            self.collision_gain = task.xi * task.dt / (task.d_i - task.d_s)
            self.label += ", collision gain xi dt / (d_i - d_s)"
        self.limit_gain = task.xi_q * task.dt / (task.rho_i - task.rho_s)
        self.limits = [
            mink.ConfigurationLimit(model, gain=self.limit_gain, min_distance_from_limits=task.rho_s),
            mink.VelocityLimit(model, {f"joint{i + 1}": float(rate_bounds[i]) for i in range(task.n)}),
            mink.CollisionAvoidanceLimit(
                model,
                geom_pairs=[(arm_geoms, obstacles)],
                gain=self.collision_gain,
                minimum_distance_from_collisions=task.d_s,
                collision_detection_distance=task.d_i,
            ),
        ]
        self.pairs = len(self.limits[2].geom_id_pairs)
        self.damping = 1.0 / task.w
        self.dt = task.dt
        self.step_dx = task.xdot * task.dt
        self.failures = 0

    def reset(self):
        self.conf.update(q=self.task.theta0.copy())
        self.failures = 0

    def step(self, k):
        mink = self.mink
        T = self.conf.get_transform_frame_to_world("hand", "site")
        self.frame.set_target(mink.SE3.from_rotation_and_translation(T.rotation(), T.translation() + self.step_dx))
        try:
            vel = mink.solve_ik(
                self.conf, self.tasks, self.dt, PEER_SOLVER, damping=self.damping, limits=self.limits
            )
        except mink.NoSolutionFound:
            # Hold still, as NEO's step does when its solver finds none.
            self.failures += 1
            return
        self.conf.integrate_inplace(vel, self.dt)

    def angles(self):
        return np.array(self.conf.q, dtype=float)
