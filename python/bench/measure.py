"""Measuring the peer benchmark's controllers: one run of the task
(`run_task`) and what it did (`outcome`), the timers (`timer_overhead_ns`,
`time_rates`), the packages' versions, the checks of the peers' models and
of NEO's damper rows against the scene (`check_models`,
`damper_rows_check`, `seg_clearance`), and the report's caveats
(`CAVEATS`)."""

from __future__ import annotations

import os
import platform
import time
from importlib import metadata
from pathlib import Path

import numpy as np

from neo_peer import damper_corrected
from task import Task

CAVEATS = [
    "Null-space term: ours `qp` and `numerical` by default minimise |qd - v|^2 with v the paper's "
    "area vector (lambda 4); mink has none (the minimum-norm rates); NEO's linear term is its "
    "manipulability gradient (neo.py's Y = 0.01, c = -jacobm, here of the translational "
    "manipulability). So the default rows follow different arm motions. The one program all three "
    "can state is the minimum-norm one: `ours qp lambda 0`, mink, and `neo corrected c=0` (the "
    "table's max_angle_difference_rad shows how closely they agree).",
    "Loop: plain Euler, theta += dt * rates, the rates at t_k = k dt, open loop (our feedback gain "
    "is 0), so each final error is mostly Euler drift (our RK4 `simulate` ends within 1.7e-5 m). "
    "mink's task is a pose error, not a velocity: its target each step is the hand's current pose "
    "moved by xdot dt (same rotation), so the position part of its SE(3) error is exactly "
    "xdot dt; setting it costs about 7 µs, counted in mink's step.",
    "mink's CollisionAvoidanceLimit bounds the step dq by gain (d - d_s) / dt (a displacement "
    "bound divided by dt), so matching our damper xi needs gain = xi dt^2 / (d_i - d_s) = 0.0089; "
    "the form's obvious reading, xi dt / (d_i - d_s) = 0.18, is a damper 20 times stiffer "
    "(shown as the untimed `mink gain xi dt/(di-ds)` row).",
    "Joint limits: ours and NEO use NEO's joint velocity damper (influence 0.9 rad, stop 0.05 rad, "
    "gain 1 rad/s). mink's ConfigurationLimit has the same slope (gain = dt xi_q / (rho_i - rho_s), "
    "min_distance_from_limits rho_s) but is on at every distance, not only within 0.9 rad; it "
    "binds nowhere in this task.",
    "Rate bounds: every controller gets our program's bounds min(rate_limit 1.5, the Panda's "
    "2.175/2.61) = 1.5 rad/s unless --peer-rates arm (the Panda's own, as neo.py's qdlim and the "
    "brief's VelocityLimit read). Only the shipped NEO damper's runs reach them.",
    "NEO's task is the world-frame linear velocity ([jacob0(q)[:3] | I3] [qd; s] = xdot); neo.py "
    "uses the end-effector frame's 6-D twist from p_servo, a slack weight 1/e and slack bounds of "
    "10; here the slack weight is Y w (our task-to-rate weight ratio) and the slack bounds 10 (never "
    "reached).",
    "NEO's step includes the robot's scene-graph update (_update_link_tf and update, which Swift's "
    "env.step does in neo.py) so that coal sees the capsules where the arm is. RTB 1.5's "
    "joint_velocity_damper rebuilds robot.qlim from every link twice per joint, about half of the "
    "step; `neo corrected fast` computes the same rows from limits read once (a lower bound on a "
    "careful NEO user's step).",
    "Models: the MJCF and the rtb.Robot are written from the scene's MDH rows (frames agree with "
    "ours to 4e-16 m over 20 random poses) with a capsule on each moving segment (MuJoCo's and "
    "coal's capsule-sphere distances agree with ours to 2e-16 m); spatialgeometry has no capsule, "
    "so the rtb capsules are a small CollisionShape subclass over coal.Capsule. The fixed base's "
    "capsule (0 to 0.333 m on z) is in the clearance measure but in no one's dampers.",
    "Clearance and hand error are read at the step poses only (every 0.05 s), for all alike.",
    "Timing: one process, GC off while timing, the order of the controllers rotated every round, "
    "medians over every step of every timed round; perf_counter_ns around each step (about 40 ns "
    "of timer in each sample, not subtracted). Ours is called through PyO3: the call, the argument "
    "copies and the new numpy array are inside its microseconds, and the Euler update "
    "(theta += dt * r) is about 0.7 µs of them. A shared 2-core machine: the spread is in p10/p90 "
    "and round_medians_us_min_max.",
    "Solvers: mink and NEO both through qpsolvers with daqp (dual active set, MIT), the same "
    "family as our Goldfarb-Idnani solver; --neo-solver quadprog (GPL-2.0+, not in the "
    "requirements) gives the same NEO numbers.",
]


def run_task(ctrl, task: Task, timed: bool = True):
    """One run of the task: the step poses and each step's cost (ns)."""
    ctrl.reset()
    thetas = [np.array(ctrl.angles(), dtype=float)]
    ns = np.empty(task.steps, dtype=np.int64)
    clock = time.perf_counter_ns
    for k in range(task.steps):
        t0 = clock()
        ctrl.step(k)
        ns[k] = clock() - t0
        thetas.append(np.array(ctrl.angles(), dtype=float))
    return np.array(thetas), ns


def outcome(task: Task, thetas) -> dict:
    clear = [task.clearance(th) for th in thetas]
    rates = np.diff(thetas, axis=0) / task.dt
    hands = np.array([task.hand(th) for th in thetas])
    refs = np.array([task.reference(k * task.dt) for k in range(len(thetas))])
    return {
        "min_clearance_m": float(min(clear)),
        "steps_inside_stop_distance": int(sum(c < task.d_s - 1e-6 for c in clear)),
        "steps_in_collision": int(sum(c < 0 for c in clear)),
        "final_error_m": float(np.linalg.norm(hands[-1] - task.target)),
        "max_tracking_error_m": float(np.max(np.linalg.norm(hands - refs, axis=1))),
        "max_rate": float(np.max(np.abs(rates))),
        "final_theta": [float(x) for x in thetas[-1]],
        "joint_limit_margin": float(
            np.min(np.minimum(thetas - task.qlim[:, 0], task.qlim[:, 1] - thetas))
        ),
    }


def timer_overhead_ns(reps=20000) -> float:
    clock = time.perf_counter_ns
    d = np.empty(reps)
    for i in range(reps):
        t0 = clock()
        d[i] = clock() - t0
    return float(np.median(d))


def time_rates(ctrls, states, xdot, rounds, inner=5):
    """Controller.rates alone, on the task's states: per round the mean of
    `inner` passes over all states; the median over rounds (and the
    median of single calls, timed one by one)."""
    per_round = {name: [] for name in ctrls}
    single = {name: [] for name in ctrls}
    clock = time.perf_counter_ns
    names = list(ctrls)
    for r in range(rounds):
        for name in names[r % len(names):] + names[: r % len(names)]:
            c = ctrls[name]
            t0 = clock()
            for _ in range(inner):
                for th in states:
                    c.rates(th, xdot)
            per_round[name].append((clock() - t0) / (inner * len(states)))
            for th in states:
                t1 = clock()
                c.rates(th, xdot)
                single[name].append(clock() - t1)
    return {
        name: {
            "median_of_round_means_us": float(np.median(per_round[name]) / 1e3),
            "median_single_call_us": float(np.median(single[name]) / 1e3),
            "p90_single_call_us": float(np.percentile(single[name], 90) / 1e3),
            "calls": len(single[name]) + rounds * inner * len(states),
        }
        for name in names
    }


def versions():
    out = {"python": platform.python_version(), "machine": platform.machine(), "cpus": os.cpu_count()}
    try:
        import redundant_ik

        out["redundant_ik"] = f"{redundant_ik.__version__} ({Path(redundant_ik.__file__).parent})"
    except ImportError:
        out["redundant_ik"] = None
    for pkg in [
        "numpy",
        "mink",
        "mujoco",
        "daqp",
        "qpsolvers",
        "roboticstoolbox-python",
        "spatialmath-python",
        "spatialgeometry",
        "coal",
        "scipy",
    ]:
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            out[pkg] = None
    return out


def check_models(task: Task, mink_ctrl, neo_ctrl, seed=1, poses=20) -> dict:
    """The peers' models against the scene's kinematics: the hand and
    each joint frame's origin over random poses within the limits, and
    each capsule's clearance to the sphere (mink's MuJoCo distance, RTB's
    coal distance) against ours."""
    import mujoco

    rng = np.random.default_rng(seed)
    out = {"poses": poses}
    qs = [task.theta0] + [rng.uniform(task.qlim[:, 0], task.qlim[:, 1]) for _ in range(poses - 1)]
    pkg_err = 0.0
    mj_err = 0.0
    rtb_err = 0.0
    mj_dist_err = 0.0
    rtb_dist_err = 0.0
    for q in qs:
        frames, pts = task.frames(q)
        if task.forward is not None:
            pkg_err = max(pkg_err, float(np.max(np.abs(np.asarray(task.forward(q)["points"]) - pts))))
        if mink_ctrl is not None:
            m = mink_ctrl.model
            data = mink_ctrl.conf.data
            mink_ctrl.conf.update(q=q.copy())
            hand = data.site("hand").xpos
            mj_err = max(mj_err, float(np.max(np.abs(hand - pts[-1]))))
            for k in range(1, task.n + 1):
                mj_err = max(mj_err, float(np.max(np.abs(data.body(f"link{k}").xpos - pts[k]))))
            for gid_a, gid_b in mink_ctrl.limits[2].geom_id_pairs:
                fromto = np.zeros(6)
                dist = mujoco.mj_geomDistance(m, data, gid_a, gid_b, 10.0, fromto)
                name = m.geom(gid_a).name if m.geom(gid_a).name.startswith("seg") else m.geom(gid_b).name
                k = int(name[3:])
                mj_dist_err = max(mj_dist_err, abs(dist - seg_clearance(task, pts, k)))
        if neo_ctrl is not None:
            r = neo_ctrl.robot
            T = r.fkine_all(q)
            # fkine_all: the robot's base first, then each link by its number.
            for k in range(1, task.n + 1):
                rtb_err = max(rtb_err, float(np.max(np.abs(T[r.links[k].number].t - pts[k]))))
            rtb_err = max(rtb_err, float(np.max(np.abs(r.fkine(q).t - pts[-1]))))
            r.q = q.copy()
            r._update_link_tf(q)
            r.update()
            for k, link in enumerate(r.links):
                for col in link.collision:
                    d, _, _ = col.closest_point(neo_ctrl.obstacles[0], 10.0)
                    rtb_dist_err = max(rtb_dist_err, abs(d - seg_clearance(task, pts, k)))
    out["package_points_vs_mdh_m"] = pkg_err if task.forward is not None else None
    out["mujoco_frames_vs_mdh_m"] = mj_err
    out["rtb_frames_vs_mdh_m"] = rtb_err
    out["mujoco_capsule_distance_vs_ours_m"] = mj_dist_err
    out["rtb_coal_capsule_distance_vs_ours_m"] = rtb_dist_err
    return out


def damper_rows_check(task: Task, neo, q, h=1e-6) -> dict:
    """At the pose `q`: each damper row `A` (A qd <= b, A = the approach
    speed per joint rate) of RTB's shipped damper, of the world-frame
    row at the shape's origin and of the corrected one, against the true
    one, minus the central-difference gradient of that capsule's
    clearance to the sphere. Rows in the order of the links."""
    r = neo.robot
    sphere = neo.obstacles[0]
    r.q = np.array(q, dtype=float)
    r._update_link_tf(r.q)
    r.update()
    shipped, _ = r.link_collision_damper(sphere, r.q, task.d_i, task.d_s, task.xi, end=neo.end_link, start=neo.start_link)
    origin, _ = damper_corrected(r, sphere, r.q, task.d_i, task.d_s, task.xi, neo.start_link, neo.end_link, "origin")
    closest, _ = damper_corrected(r, sphere, r.q, task.d_i, task.d_s, task.xi, neo.start_link, neo.end_link, "closest")
    pts = task.frames(q)[1]
    rows = []
    for k, link in enumerate(r.links):
        for col in link.collision:
            d, _, _ = col.closest_point(sphere, task.d_i)
            if d is None:
                continue
            g = np.zeros(task.n)
            for i in range(task.n):
                e = np.zeros(task.n)
                e[i] = h
                g[i] = (
                    seg_clearance(task, task.frames(q + e)[1], k) - seg_clearance(task, task.frames(q - e)[1], k)
                ) / (2 * h)
            rows.append((k, seg_clearance(task, pts, k), -g))
    out = {"pose": [float(x) for x in q], "rows": []}
    if shipped is None or closest is None or len(rows) != len(shipped):
        out["error"] = "the dampers' rows and the capsules within reach do not match"
        return out
    for j, (k, c, truth) in enumerate(rows):
        scale = float(np.linalg.norm(truth))
        out["rows"].append(
            {
                "capsule_of_frame": k,
                "clearance_m": c,
                "true_row": [float(x) for x in truth],
                "shipped_row": [float(x) for x in shipped[j]],
                "shipped_error_rel": float(np.linalg.norm(shipped[j] - truth) / scale),
                "origin_world_error_rel": float(np.linalg.norm(origin[j] - truth) / scale),
                "corrected_error_rel": float(np.linalg.norm(closest[j] - truth) / scale),
            }
        )
    return out


def seg_clearance(task: Task, pts, k: int) -> float:
    """Clearance of the capsule carried by frame k (from point k to the
    next distinct point) to the first sphere."""
    A = pts[k]
    j = k + 1
    while np.linalg.norm(pts[j] - A) < 1e-12:
        j += 1
    B = pts[j]
    w = B - A
    C, R = task.spheres[0][:3], task.spheres[0][3]
    s = min(max(float((C - A) @ w) / float(w @ w), 0.0), 1.0)
    return float(np.linalg.norm(C - (A + s * w))) - task.radius - R
