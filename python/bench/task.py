"""The peer benchmark's task: the Franka Panda scene as the tool states it
(`load_scene`), its numbers and the geometry every controller is judged by
(`Task`), and the small helpers the peers' models share (`capsule_pose`,
`fmt`, `rot_x_quat`); also the repository root and the peers' QP solver."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
PEER_SOLVER = "daqp"


def load_scene(path: str | None):
    """The Panda task's run file (a dict): from `path`, else from the
    package (`redundant_ik.simulate`), else from the command-line tool."""
    if path:
        return json.loads(Path(path).read_text()), f"file {path}"
    try:
        import redundant_ik

        run = redundant_ik.simulate(robot=redundant_ik.Robot.preset("panda"), method="qp")
        return json.loads(run.to_json()), "redundant_ik.simulate(robot=Robot.preset('panda'), method='qp')"
    except ImportError:
        pass
    for exe in (ROOT / "target/release/redundant-ik", ROOT / "target/debug/redundant-ik"):
        if exe.exists():
            out = subprocess.run(
                [str(exe), "simulate", "--arm", "panda", "--method", "qp", "--json"],
                check=True,
                capture_output=True,
                text=True,
            ).stdout
            return json.loads(out), f"{exe.relative_to(ROOT)} simulate --arm panda --method qp --json"
    sys.exit("no scene: redundant_ik is not importable and no redundant-ik binary was found (--scene PATH)")


class Task:
    """The scene's numbers, and the geometry every controller is judged by."""

    def __init__(self, run: dict):
        s = run["scene"]
        self.run_summary = run.get("summary", {})
        arm = s["arm"]
        self.rows = [(r["a"], r["alpha"], r["d"], r["offset"]) for r in arm["rows"]]
        self.n = len(self.rows)
        base_r, base_t = arm["base"]
        self.base = np.eye(4)
        self.base[:3, :3] = np.array(base_r)
        self.base[:3, 3] = base_t
        self.flange = np.array(arm["flange"], dtype=float)
        self.radius = float(arm["radius"])
        self.qlim = np.array(arm["joint_limits"], dtype=float)  # n x 2
        self.arm_rates = np.array(arm["rate_limits"], dtype=float)
        self.theta0 = np.array(s["theta0"], dtype=float)
        self.target = np.array(s["target"], dtype=float)
        self.spheres = np.array([list(o["centre"]) + [o["radius"]] for o in s["obstacles"]], dtype=float)
        self.dt = float(s["dt"])
        self.tf = float(s["tf"])
        self.steps = int(round(self.tf / self.dt))
        self.feedback = float(s.get("feedback_gain", 0.0))
        p = s["params"]
        self.params = p
        self.d_i = p["influence"]
        self.d_s = p["stop_distance"]
        self.xi = p["damper_gain"]
        self.w = p["slack_weight"]
        self.L = p["rate_limit"]
        self.rho_i = p["limit_influence"]
        self.rho_s = p["limit_stop"]
        self.xi_q = p["limit_gain"]
        # The bounds our program applies: min(L, the arm's own rate limit).
        self.rate_bounds = np.minimum(self.L, self.arm_rates)
        if any(abs(r[3]) > 0 for r in self.rows):
            sys.exit("a row with a joint offset: the peers' models here assume none")
        self.start = self.frames(self.theta0)[1][-1]
        self.xdot = (self.target - self.start) / self.tf
        self.forward = None  # the package's Robot.forward, when importable

    def reference(self, t: float) -> np.ndarray:
        return self.start + (self.target - self.start) * min(max(t / self.tf, 0.0), 1.0)

    def frames(self, theta):
        """Every MDH frame (4x4, base first) and the chain's points: the base
        origin, each frame's origin, the hand (numpy, for checks)."""
        T = self.base.copy()
        frames = [T.copy()]
        for (a, alpha, d, off), q in zip(self.rows, theta):
            ca, sa = math.cos(alpha), math.sin(alpha)
            ct, st = math.cos(q + off), math.sin(q + off)
            A = np.array(
                [
                    [ct, -st, 0.0, a],
                    [st * ca, ct * ca, -sa, -d * sa],
                    [st * sa, ct * sa, ca, d * ca],
                    [0.0, 0.0, 0.0, 1.0],
                ]
            )
            T = T @ A
            frames.append(T.copy())
        hand = T[:3, :3] @ self.flange + T[:3, 3]
        points = [f[:3, 3] for f in frames] + [hand]
        return frames, np.array(points)

    def points(self, theta) -> np.ndarray:
        if self.forward is not None:
            return np.asarray(self.forward(theta)["points"], dtype=float)
        return self.frames(theta)[1]

    def hand(self, theta) -> np.ndarray:
        return self.points(theta)[-1]

    def clearance(self, theta) -> float:
        """Smallest capsule-surface to sphere-surface distance over every
        segment between consecutive distinct points (the fixed base's
        included) and every sphere."""
        pts = self.points(theta)
        best = math.inf
        for A, B in zip(pts[:-1], pts[1:]):
            w = B - A
            ww = float(w @ w)
            if ww < 1e-24:
                continue
            for c in self.spheres:
                C, R = c[:3], c[3]
                s = min(max(float((C - A) @ w) / ww, 0.0), 1.0)
                best = min(best, float(np.linalg.norm(C - (A + s * w))) - self.radius - R)
        return best

    def segments(self):
        """(k, A_k, B_k): each moving capsule in the local frame of MDH frame
        k (the frame that carries it), A_k its origin, B_k frame k+1's
        origin or the hand; zero-length ones skipped. The fixed base's
        segment (frame 0) carries no joint and is left out of the peers'
        avoidance (our dampers see it as fixed too)."""
        out = []
        for k in range(1, self.n + 1):
            if k < self.n:
                a, alpha, d, _ = self.rows[k]
                B = np.array([a, -d * math.sin(alpha), d * math.cos(alpha)])
            else:
                B = self.flange.copy()
            if np.linalg.norm(B) > 1e-12:
                out.append((k, np.zeros(3), B))
        return out


def capsule_pose(A, B):
    """4x4 pose of a capsule on A-B: its origin at the middle, its z along B - A."""
    z = (B - A) / np.linalg.norm(B - A)
    x = np.cross([0.0, 0.0, 1.0], z) if abs(z[2]) < 0.9 else np.cross([1.0, 0.0, 0.0], z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    T = np.eye(4)
    T[:3, :3] = np.c_[x, y, z]
    T[:3, 3] = (A + B) / 2
    return T


def fmt(xs) -> str:
    """Numbers as MJCF text, each the shortest decimal that reads back to it."""
    return " ".join(repr(float(x)) for x in xs)


def rot_x_quat(alpha):
    return [math.cos(alpha / 2), math.sin(alpha / 2), 0.0, 0.0]
