#!/usr/bin/env python3
"""Peer benchmark: our controller against mink and Robotics Toolbox's NEO.

A script kept in the repository, NOT a test: it needs an environment of
its own (`python/bench/run.sh` makes `target/bench-venv` from
`python/bench/requirements.txt`, installs `redundant_ik` and runs this).

One task, three controllers, one process. The task is the Franka Panda
preset's (`redundant-ik simulate --arm panda --method qp --json`, read
through the package, so every number is the tool's own): the hand moves
on the straight line from its start to the target in `tf` = 5 s, a
control step every `dt` = 0.05 s, past a sphere of radius 0.06 m at
(0.215, 0.21, 0.7); every link is a capsule of radius 0.06 m on the
segment between consecutive joint-frame origins. Each controller is
integrated by plain Euler, `theta += dt * rates`, 100 steps:

- ours: `redundant_ik.Controller(Robot.preset("panda"), method=...)`,
  `theta += dt * c.step(theta, t)` (`qp`, `numerical`, and `qp` with
  `lambda_=0`, the minimum-norm program the peers map onto exactly);
- mink 1.3: `FrameTask` (position only) on the hand's site, limits
  `ConfigurationLimit`, `VelocityLimit`, `CollisionAvoidanceLimit`
  (capsules against the sphere), `solve_ik` with daqp, then
  `configuration.integrate_inplace`; the MuJoCo model is an MJCF written
  here from the scene's own modified-DH rows and capsules;
- NEO (Haviland and Corke 2021) from Robotics Toolbox for Python 1.5, in
  the shape of its `examples/neo.py`: equality `[J | I] [qd; s] = xdot`,
  `joint_velocity_damper`, `link_collision_damper` per obstacle, the
  manipulability gradient as the linear term, joint-rate bounds,
  `qpsolvers.solve_qp` (daqp); the robot an `rtb.Robot` built here from
  the same rows with the same capsules (a coal capsule shape). Run with
  RTB's damper as shipped and with the corrected damper (below).

Measured per control step (the median over every step of every timed
round, after warm-up, the controllers alternated in rounds): ours
`Controller.step` plus the numpy Euler update; mink's target update,
`solve_ik` and `integrate_inplace`; NEO's whole step. Also
`Controller.rates` alone for `qp` and `numerical`. For every run: the
smallest capsule-to-sphere clearance over the step poses (the same
function for all: our `Robot.forward(theta)["points"]` segments, radius
0.06 m) and the final hand error to the target.

The damper correction. RTB 1.5's `Robot.link_collision_damper` builds each
row as `n^T J`, `n` the unit normal from the link's closest point to the
obstacle in the world frame, but `J = jacobe(q, end=link,
tool=shape.T)`: the Jacobian of the shape's *origin* (the capsule's
centre) expressed in the *shape's own frame*. The corrected row uses the
world-frame translational Jacobian of the link-fixed point at the closest
point itself: `J = jacob0(q, end=link, tool=T_link^-1 p)[:3]`, `p` the
closest point on the link in the world, `T_link` the link's world pose.

    python peers.py [--rounds 30] [--warmup 3] [--json PATH] [--quick]

Prints a table and, with `--json PATH`, writes it all as JSON.
"""

from __future__ import annotations

import argparse
import gc
import json
import sys
from pathlib import Path

import numpy as np

# The pieces, sibling modules (this folder is on sys.path when the script
# runs): the task, the controllers, the measuring.
from measure import (
    CAVEATS,
    check_models,
    damper_rows_check,
    outcome,
    run_task,
    time_rates,
    timer_overhead_ns,
    versions,
)
from mink_peer import Mink
from neo_peer import Neo
from ours import Ours
from task import PEER_SOLVER, Task, load_scene


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=30, help="timed rounds (each: every controller's 100 steps)")
    ap.add_argument("--warmup", type=int, default=3, help="untimed rounds first")
    ap.add_argument("--rates-rounds", type=int, default=200, help="rounds for Controller.rates alone")
    ap.add_argument("--quick", action="store_true", help="2 rounds, 1 warm-up, 20 rates rounds (development)")
    ap.add_argument("--json", metavar="PATH", help="write the results as JSON")
    ap.add_argument("--scene", metavar="PATH", help="a run file of `simulate --arm panda --method qp --json`")
    ap.add_argument(
        "--peer-rates",
        choices=["ours", "arm"],
        default="ours",
        help="peers' joint-rate bounds: ours (min(rate_limit, the arm's), what our QP applies) or the arm's own",
    )
    ap.add_argument("--neo-solver", default=PEER_SOLVER, help="qpsolvers backend for NEO (default daqp)")
    ap.add_argument("--no-ours", action="store_true", help="peers only (no redundant_ik)")
    args = ap.parse_args()
    if args.quick:
        args.rounds, args.warmup, args.rates_rounds = 2, 1, 20

    run, source = load_scene(args.scene)
    task = Task(run)
    have_ours = False
    if not args.no_ours:
        try:
            import redundant_ik

            task.forward = redundant_ik.Robot.preset("panda").forward
            have_ours = True
        except ImportError as e:
            print(f"note: redundant_ik not importable ({e}): peers only", file=sys.stderr)
    rate_bounds = task.rate_bounds if args.peer_rates == "ours" else task.arm_rates

    # The controllers.
    timed = {}
    if have_ours:
        timed["ours qp"] = Ours(task, "qp", "ours: Controller(panda, method='qp')")
        timed["ours numerical"] = Ours(task, "numerical", "ours: Controller(panda, method='numerical')")
        timed["ours qp lambda 0"] = Ours(task, "qp", "ours: Controller(panda, method='qp', lambda_=0)", lambda_=0)
    mink_ctrl = Mink(task, rate_bounds)
    timed["mink"] = mink_ctrl
    timed["neo shipped"] = Neo(task, rate_bounds, "shipped", True, args.neo_solver)
    timed["neo corrected"] = Neo(task, rate_bounds, "corrected", True, args.neo_solver)
    # NEO without RTB's slowest avoidable cost (its joint damper reads the
    # limits anew every call): the same program, a lower bound on NEO's step.
    timed["neo corrected fast"] = Neo(task, rate_bounds, "corrected", True, args.neo_solver, cached_limits=True)
    # Outcome only (not timed): the damper's two errors apart, and the
    # minimum-norm NEO (no manipulability term), our lambda-0 program.
    extra = {
        "mink gain xi dt/(di-ds)": Mink(task, rate_bounds, naive_gain=True),
        "neo origin-world": Neo(task, rate_bounds, "origin-world", True, args.neo_solver),
        "neo shipped c=0": Neo(task, rate_bounds, "shipped", False, args.neo_solver),
        "neo corrected c=0": Neo(task, rate_bounds, "corrected", False, args.neo_solver),
        "neo origin-world c=0": Neo(task, rate_bounds, "origin-world", False, args.neo_solver),
    }

    # Our controller against the scene (the same task, the same numbers).
    consistency = {"scene_source": source}
    if have_ours:
        c = timed["ours qp"].c
        consistency["theta0_diff"] = float(np.max(np.abs(np.asarray(c.theta0) - task.theta0)))
        consistency["dt_tf"] = [c.dt, c.tf]
        consistency["obstacles"] = c.obstacles
        consistency["reference_diff_m"] = float(
            max(np.max(np.abs(np.asarray(c.reference(t)) - task.reference(t))) for t in np.linspace(0, task.tf, 11))
        )
        zero = c.step(task.theta0, 0.0) - c.rates(task.theta0, task.xdot)
        consistency["step_vs_rates_at_t0"] = float(np.max(np.abs(zero)))
    models = check_models(task, mink_ctrl, timed["neo shipped"])

    # Outcomes: one run each (every run of a controller is the same run).
    results = {}
    for name, ctrl in list(timed.items()) + list(extra.items()):
        thetas, _ = run_task(ctrl, task)
        res = outcome(task, thetas)
        res["label"] = ctrl.label
        if hasattr(ctrl, "failures"):
            res["qp_failures"] = ctrl.failures
        res["timed"] = name in timed
        results[name] = res
        results[name]["_thetas"] = thetas

    # Cost per step: warm-up, then rounds, the order rotated every round.
    names = list(timed)
    step_ns = {name: [] for name in names}
    overhead = timer_overhead_ns()
    gc_was = gc.isenabled()
    gc.disable()
    try:
        for r in range(args.warmup + args.rounds):
            order = names[r % len(names):] + names[: r % len(names)]
            for name in order:
                thetas, ns = run_task(timed[name], task)
                if r >= args.warmup:
                    step_ns[name].append(ns)
                    # Every round is the same run.
                    if not np.allclose(thetas, results[name]["_thetas"], atol=1e-12, rtol=0):
                        results[name]["nondeterministic"] = True
    finally:
        if gc_was:
            gc.enable()
    for name in names:
        ns = np.concatenate(step_ns[name])
        results[name]["step_median_us"] = float(np.median(ns) / 1e3)
        results[name]["step_p10_us"] = float(np.percentile(ns, 10) / 1e3)
        results[name]["step_p90_us"] = float(np.percentile(ns, 90) / 1e3)
        results[name]["step_mean_us"] = float(np.mean(ns) / 1e3)
        results[name]["steps_timed"] = int(ns.size)
        # The median of each round's median: how stable the number is.
        per_round = [np.median(x) / 1e3 for x in step_ns[name]]
        results[name]["round_medians_us_min_max"] = [float(min(per_round)), float(max(per_round))]

    rates_alone = None
    if have_ours:
        import redundant_ik

        robot = redundant_ik.Robot.preset("panda")
        ctrls = {
            "qp": redundant_ik.Controller(robot, method="qp"),
            "numerical": redundant_ik.Controller(robot, method="numerical"),
        }
        states = [np.ascontiguousarray(th) for th in results["ours qp"]["_thetas"][:-1]]
        for _ in range(3):
            for c in ctrls.values():
                for th in states:
                    c.rates(th, task.xdot)
        gc.disable()
        try:
            rates_alone = time_rates(ctrls, states, np.ascontiguousarray(task.xdot), args.rates_rounds)
        finally:
            if gc_was:
                gc.enable()
        rates_alone["states"] = "the 100 step poses of the qp run, xdot the path's velocity"
        rates_alone["goals_us"] = {"qp": 3.0, "numerical": 1.5}

    # The same program, the same rates? Our lambda-0 QP against the peers
    # mapped onto it, pose by pose.
    agreement = {}
    if have_ours:
        ref = results["ours qp lambda 0"]["_thetas"]
        for peer in ("mink", "neo corrected c=0", "neo corrected", "neo shipped c=0"):
            agreement[f"{peer} vs ours qp lambda 0"] = float(np.max(np.abs(results[peer]["_thetas"] - ref)))
    # The shipped damper's rows against the truth, where the corrected NEO
    # comes nearest the sphere.
    th = results["neo corrected"]["_thetas"]
    nearest = th[int(np.argmin([task.clearance(x) for x in th]))]
    rows_check = damper_rows_check(task, extra["neo shipped c=0"], nearest)

    for res in results.values():
        res.pop("_thetas", None)

    ratios = {}
    if have_ours:
        for ours_name in ("ours qp", "ours numerical"):
            for peer in ("mink", "neo shipped", "neo corrected", "neo corrected fast"):
                ratios[f"{peer} / {ours_name}"] = results[peer]["step_median_us"] / results[ours_name]["step_median_us"]

    damper = {
        "shipped_min_clearance_m": results["neo shipped"]["min_clearance_m"],
        "corrected_min_clearance_m": results["neo corrected"]["min_clearance_m"],
        "origin_world_min_clearance_m": results["neo origin-world"]["min_clearance_m"],
        "shipped_c0_min_clearance_m": results["neo shipped c=0"]["min_clearance_m"],
        "corrected_c0_min_clearance_m": results["neo corrected c=0"]["min_clearance_m"],
        "origin_world_c0_min_clearance_m": results["neo origin-world c=0"]["min_clearance_m"],
        "stop_distance_m": task.d_s,
        "correction": (
            "RTB 1.5 Robot.link_collision_damper forms each row as n^T J with n the world-frame unit "
            "normal from the link's closest point toward the obstacle but J = jacobe(q, end=link, "
            "tool=shape.T): the velocity of the shape's origin expressed in the shape's frame. Corrected: "
            "J = jacob0(q, end=link, tool=transl(T_link^-1 p))[:3], the world-frame translational "
            "Jacobian of the link-fixed point at the closest point p. 'origin-world' is the middle "
            "step: the world frame, but still at the shape's origin."
        ),
    }

    report = {
        "task": {
            "arm": "panda",
            "scene_source": source,
            "theta0": task.theta0.tolist(),
            "target": task.target.tolist(),
            "start": task.start.tolist(),
            "obstacles": task.spheres.tolist(),
            "capsule_radius": task.radius,
            "dt": task.dt,
            "tf": task.tf,
            "steps": task.steps,
            "loop": "plain Euler: theta += dt * rates, 100 steps, t_k = k dt",
            "simulate_summary_rk4": task.run_summary,
            "params": {k: task.params[k] for k in (
                "influence", "stop_distance", "damper_gain", "slack_weight", "rate_limit",
                "limit_influence", "limit_stop", "limit_gain", "lambda", "delta")},
            "peer_rate_bounds": list(map(float, rate_bounds)),
        },
        "mapping": {
            "mink": {
                "task": "FrameTask('hand', 'site', position_cost=1, orientation_cost=0, gain=1, lm_damping=0); "
                "target = hand's current pose translated by xdot dt (open loop)",
                "damping": mink_ctrl.damping,
                "CollisionAvoidanceLimit": {
                    "gain": mink_ctrl.collision_gain,
                    "gain_formula": "xi dt^2 / (d_i - d_s): mink bounds the step dq by gain (d - d_s) / dt",
                    "minimum_distance_from_collisions": task.d_s,
                    "collision_detection_distance": task.d_i,
                    "pairs": mink_ctrl.pairs,
                },
                "ConfigurationLimit": {"gain": mink_ctrl.limit_gain, "min_distance_from_limits": task.rho_s},
                "VelocityLimit": list(map(float, rate_bounds)),
                "solver": PEER_SOLVER,
                "mjcf": mink_ctrl.xml,
            },
            "neo": {
                "Y": Neo.Y,
                "slack_weight": Neo.Y * task.w,
                "equality": "[jacob0(q)[:3] | I3] [qd; s] = xdot",
                "joint_velocity_damper": {"ps": task.rho_s, "pi": task.rho_i, "gain": task.xi_q},
                "link_collision_damper": {"di": task.d_i, "ds": task.d_s, "xi": task.xi},
                "linear_term": "-jacobm(q, axes='trans') (or 0)",
                "bounds": "rates as mink's; slack +-10 (neo.py)",
                "solver": args.neo_solver,
            },
        },
        "consistency": consistency,
        "model_checks": models,
        "timer_overhead_ns": overhead,
        "results": results,
        "rates_alone": rates_alone,
        "ratios": ratios,
        "neo_damper": damper,
        "neo_damper_rows": rows_check,
        "max_angle_difference_rad": agreement,
        "rounds": args.rounds,
        "warmup": args.warmup,
        "versions": versions(),
        "caveats": CAVEATS,
    }

    print_table(report, have_ours)
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(report, indent=1) + "\n")
        print(f"\nwritten: {args.json}")
    bad = [k for k, v in models.items() if k.endswith("_m") and v is not None and v > 1e-9]
    if bad:
        sys.exit(f"the peers' models are not the scene's arm: {', '.join(bad)}")


def print_table(rep, have_ours):
    t = rep["task"]
    print(
        f"Franka Panda, hand along a line to {t['target']} in {t['tf']} s, dt {t['dt']} s, "
        f"{t['steps']} Euler steps; sphere {t['obstacles']}; capsules r {t['capsule_radius']} m"
    )
    print(f"scene: {t['scene_source']}")
    print(f"timed rounds {rep['rounds']} (after {rep['warmup']} warm-up), timer overhead {rep['timer_overhead_ns']:.0f} ns (not subtracted)")
    print()
    hdr = f"{'controller':<22} {'median µs/step':>14} {'p10':>9} {'p90':>9} {'min clearance':>14} {'final error':>12} {'max |qd|':>9}"
    print(hdr)
    print("-" * len(hdr))
    for name, r in rep["results"].items():
        if r.get("timed"):
            cost = f"{r['step_median_us']:>14.2f} {r['step_p10_us']:>9.2f} {r['step_p90_us']:>9.2f}"
        else:
            cost = f"{'(not timed)':>14} {'':>9} {'':>9}"
        fail = f"  QP failures {r['qp_failures']}" if r.get("qp_failures") else ""
        print(
            f"{name:<22} {cost} {r['min_clearance_m']:>13.4f}m {r['final_error_m']:>11.2e}m {r['max_rate']:>8.3f}{fail}"
        )
    if rep["rates_alone"]:
        print()
        print("Controller.rates alone (the qp run's 100 poses):")
        for m in ("qp", "numerical"):
            x = rep["rates_alone"][m]
            print(
                f"  {m:<10} {x['median_of_round_means_us']:.3f} µs per call (median of round means), "
                f"single calls median {x['median_single_call_us']:.3f} µs, p90 {x['p90_single_call_us']:.3f} µs; "
                f"goal {rep['rates_alone']['goals_us'][m]} µs"
            )
    if rep["ratios"]:
        print()
        print("ratios of median cost per step:")
        for k, v in rep["ratios"].items():
            print(f"  {k:<32} {v:8.1f}x")
    d = rep["neo_damper"]
    print()
    print(
        f"NEO damper: shipped {d['shipped_min_clearance_m']:.4f} m, world frame at the shape's origin "
        f"{d['origin_world_min_clearance_m']:.4f} m, corrected {d['corrected_min_clearance_m']:.4f} m "
        f"(c = 0: {d['shipped_c0_min_clearance_m']:.4f} / {d['origin_world_c0_min_clearance_m']:.4f} / "
        f"{d['corrected_c0_min_clearance_m']:.4f} m); stop distance {d['stop_distance_m']} m"
    )
    for row in rep["neo_damper_rows"].get("rows", []):
        print(
            f"  damper row of the capsule on frame {row['capsule_of_frame']} (clearance {row['clearance_m']:.4f} m) "
            f"vs the clearance's gradient: shipped off by {100 * row['shipped_error_rel']:.0f}%, "
            f"world frame at the origin {100 * row['origin_world_error_rel']:.1f}%, "
            f"corrected {100 * row['corrected_error_rel']:.1e}%"
        )
    if rep["max_angle_difference_rad"]:
        print("largest angle difference over the run (rad):")
        for k, v in rep["max_angle_difference_rad"].items():
            print(f"  {k:<36} {v:.2e}")
    m = rep["model_checks"]
    print(
        f"model checks over {m['poses']} poses: MuJoCo frames {m['mujoco_frames_vs_mdh_m']:.1e} m, "
        f"rtb frames {m['rtb_frames_vs_mdh_m']:.1e} m, package points {m['package_points_vs_mdh_m'] or 0:.1e} m, "
        f"MuJoCo capsule distance {m['mujoco_capsule_distance_vs_ours_m']:.1e} m, "
        f"coal capsule distance {m['rtb_coal_capsule_distance_vs_ours_m']:.1e} m"
    )
    print()
    print("caveats:")
    for c in rep["caveats"]:
        print(f"- {c}")


if __name__ == "__main__":
    main()
