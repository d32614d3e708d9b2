"""The NEO peer, from Robotics Toolbox for Python 1.5: a capsule collision
shape over coal (`capsule_class`), the scene's arm as an `rtb.Robot`
(`rtb_robot`), the link collision damper with the point's velocity taken
right (`damper_corrected`), and NEO itself (`Neo`), behind the
controllers' interface (reset(), step(k), angles(); see ours.py)."""

from __future__ import annotations

import sys

import numpy as np

from task import Task, capsule_pose


def capsule_class():
    """A spatialgeometry collision shape for a capsule (coal's), centred
    on its origin, its axis along z (spatialgeometry has none)."""
    import coal
    from spatialgeometry.geom.CollisionShape import CollisionShape
    from spatialgeometry.geom.Shape import aabb_corners

    class Capsule(CollisionShape):
        _repr_params = ("radius", "length")

        def __init__(self, radius, length, **kwargs):
            super().__init__(stype="cylinder", **kwargs)
            self.radius = float(radius)
            self.length = float(length)

        def _init_coal(self):
            self.co = coal.CollisionObject(coal.Capsule(self.radius, self.length))
            self._cinit = True

        def to_dict(self):
            shape = super().to_dict()
            shape["radius"] = self.radius
            shape["length"] = self.length
            return shape

        def _local_corners(self):
            r, h = self.radius, self.length / 2 + self.radius
            return aabb_corners([-r, -r, -h], [r, r, h])

    return Capsule


def rtb_robot(task: Task, rate_bounds):
    """The scene's arm as an `rtb.Robot`: a fixed base link, one link per
    MDH row with the ETS `Rx(alpha) tx(a) tz(d) Rz(q)` (`Rz` and `tz`
    commute, so each link's frame is the MDH frame), a flange link, and a
    capsule on each moving segment in the link that carries it."""
    import roboticstoolbox as rtb
    from roboticstoolbox import ET, ETS
    from spatialmath import SE3

    Capsule = capsule_class()
    segs = {k: (A, B) for k, A, B in task.segments()}
    base = rtb.Link(ETS(), name="base")
    links = [base]
    parent = base
    for i, (a, alpha, d, _) in enumerate(task.rows):
        k = i + 1
        ets = ETS()
        if alpha:
            ets = ets * ET.Rx(alpha)
        if a:
            ets = ets * ET.tx(a)
        if d:
            ets = ets * ET.tz(d)
        ets = ets * ET.Rz()
        collision = []
        if k in segs:
            A, B = segs[k]
            collision = [
                Capsule(task.radius, float(np.linalg.norm(B - A)), pose=SE3(capsule_pose(A, B), check=False))
            ]
        link = rtb.Link(ets, name=f"link{k}", parent=parent, qlim=task.qlim[i], collision=collision)
        links.append(link)
        parent = link
    links.append(rtb.Link(ETS(ET.tz(float(task.flange[2]))), name="flange", parent=parent))
    if np.linalg.norm(task.flange[:2]) > 0:
        sys.exit("a flange off the last z: the rtb model here assumes it on z")
    robot = rtb.Robot(links, name="panda-mdh")
    robot.qdlim = np.array(rate_bounds, dtype=float)
    return robot


def damper_corrected(robot, shape, q, di, ds, xi, start, end, mode="closest"):
    """Velocity-damper rows `A qd <= b` for `shape` against every collision
    shape of the links from `start` to `end`, as RTB's
    `link_collision_damper` forms them but with the point's velocity taken
    right: `n^T J_p`, `n` the unit normal from the link's closest point `p`
    toward the obstacle (world frame), `J_p` the world-frame translational
    Jacobian of the link-fixed point at `p` (`mode="closest"`); or, to
    tell the shipped row's two errors apart, of the shape's origin in the
    world frame (`mode="origin"`)."""
    links, _, _ = robot.get_path(start=start, end=end)
    rows = []
    bounds = []
    for link in links:
        for col in link.collision:
            d, p_link, p_obs = col.closest_point(shape, di)
            if d is None:
                continue
            normal = (p_obs - p_link) / d
            T_link = robot.fkine(q, end=link).A
            if mode == "closest":
                local = T_link[:3, :3].T @ (p_link - T_link[:3, 3])
            else:
                local = col.T[:3, 3]
            tool = np.eye(4)
            tool[:3, 3] = local
            J = robot.jacob0(q, end=link, tool=tool)[:3]
            row = np.zeros(robot.n)
            row[: J.shape[1]] = normal @ J
            rows.append(row)
            bounds.append(xi * (d - ds) / (di - ds) + normal @ shape.v[:3])
    if not rows:
        return None, None
    return np.array(rows), np.array(bounds)


class Neo:
    """NEO in the shape of RTB's examples/neo.py, on our task.

    neo.py: min 1/2 [qd; s]^T Q [qd; s] + c^T [qd; s], Q = diag(Y I, (1/e) I),
    [J_e | I] [qd; s] = v (p_servo), joint_velocity_damper(ps 0.05, pi 0.9),
    link_collision_damper(obstacle, q, 0.3, 0.05, 1.0) per obstacle,
    c = [-jacobm; 0], bounds qdlim and 10 on the slack, Y = 0.01.
    Here: the task is the hand's position, so [J0_p | I3] [qd; s] = xdot
    (world frame); Q = diag(Y I, Y w I) with Y = 0.01 (neo.py's) and w our
    slack weight (our ratio of the task's weight to the rates'); the
    dampers with our numbers (d_i, d_s, xi; rho_i, rho_s, xi_q); c the
    translational manipulability's gradient (neo.py's linear term) or 0
    (the minimum-norm program, our `lambda 0`); bounds our rate bounds.
    """

    Y = 0.01

    def __init__(self, task: Task, rate_bounds, damper: str, manip: bool, solver: str, cached_limits=False):
        import qpsolvers
        import spatialgeometry as sg
        from spatialmath import SE3

        self.qp = qpsolvers
        self.task = task
        self.kind = "neo"
        self.damper = damper
        self.manip = manip
        self.solver = solver
        self.cached_limits = cached_limits
        self.label = f"NEO rtb 1.5 ({damper} damper, {'manipulability' if manip else 'c = 0'}, {solver})"
        if cached_limits:
            self.label += ", joint damper from cached limits"
        self.robot = rtb_robot(task, rate_bounds)
        self.obstacles = []
        for c in task.spheres:
            s = sg.Sphere(radius=float(c[3]), pose=SE3(*c[:3]))
            s.update()
            self.obstacles.append(s)
        n = task.n
        self.n = n
        self.Q = np.eye(n + 3) * self.Y
        self.Q[n:, n:] = self.Y * task.w * np.eye(3)
        self.Aeq_slack = np.eye(3)
        self.beq = task.xdot.copy()
        self.lb = -np.r_[rate_bounds, 10 * np.ones(3)]
        self.ub = np.r_[rate_bounds, 10 * np.ones(3)]
        self.start_link = self.robot.links[0]
        self.end_link = self.robot.links[-1]
        self.dt = task.dt
        self.failures = 0
        self.max_rows = 0
        self.q = task.theta0.copy()
        self.qmin = task.qlim[:, 0].copy()
        self.qmax = task.qlim[:, 1].copy()

    def joint_damper(self, q):
        """RTB's joint_velocity_damper's rows (the same formula, the upper
        limit's row winning where both are near), from limits read once:
        RTB's rebuilds `robot.qlim` from every link twice per joint."""
        t = self.task
        n = self.n
        A = np.zeros((n, n))
        b = np.zeros(n)
        lo = q - self.qmin
        hi = self.qmax - q
        near_lo = lo <= t.rho_i
        near_hi = hi <= t.rho_i
        idx = np.arange(n)
        A[idx[near_lo], idx[near_lo]] = -1.0
        b[near_lo] = t.xi_q * (lo[near_lo] - t.rho_s) / (t.rho_i - t.rho_s)
        A[idx[near_hi], idx[near_hi]] = 1.0
        b[near_hi] = t.xi_q * (hi[near_hi] - t.rho_s) / (t.rho_i - t.rho_s)
        return A, b

    def reset(self):
        self.robot.q = self.task.theta0.copy()
        self.failures = 0

    def step(self, k):
        r = self.robot
        n = self.n
        q = r.q
        t = self.task
        # What Swift's env.step does after integrating: the links' and
        # their shapes' world poses for the new q.
        r._update_link_tf(q)
        r.update()
        J = r.jacob0(q)[:3]
        Aeq = np.c_[J, self.Aeq_slack]
        Ain = np.zeros((n + 3, n + 3))
        bin = np.zeros(n + 3)
        if self.cached_limits:
            Ain[:n, :n], bin[:n] = self.joint_damper(q)
        else:
            Ain[:n, :n], bin[:n] = r.joint_velocity_damper(q, t.rho_s, t.rho_i, n, t.xi_q)
        for obstacle in self.obstacles:
            if self.damper == "shipped":
                c_Ain, c_bin = r.link_collision_damper(
                    obstacle, q, t.d_i, t.d_s, t.xi, end=self.end_link, start=self.start_link
                )
            else:
                c_Ain, c_bin = damper_corrected(
                    r, obstacle, q, t.d_i, t.d_s, t.xi, self.start_link, self.end_link,
                    mode="closest" if self.damper == "corrected" else "origin",
                )
            if c_Ain is not None and c_bin is not None:
                c_Ain = np.c_[c_Ain, np.zeros((c_Ain.shape[0], 3))]
                Ain = np.r_[Ain, c_Ain]
                bin = np.r_[bin, c_bin]
        if self.manip:
            c = np.r_[-r.jacobm(q, axes="trans").reshape((n,)), np.zeros(3)]
        else:
            c = np.zeros(n + 3)
        qd = self.qp.solve_qp(self.Q, c, Ain, bin, Aeq, self.beq, lb=self.lb, ub=self.ub, solver=self.solver)
        if qd is None:
            # Infeasible (or the solver gave up): hold still.
            self.failures += 1
            return
        r.q = q + qd[:n] * self.dt

    def angles(self):
        return np.array(self.robot.q, dtype=float)
