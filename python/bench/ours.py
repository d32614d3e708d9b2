"""Our controller in the peer benchmark: `redundant_ik.Controller` behind
the interface every controller here has: reset() to the start pose,
step(k) one control step, angles() the current angles (not timed)."""

from __future__ import annotations

import numpy as np

from task import Task


class Ours:
    def __init__(self, task: Task, method: str, label: str, **params):
        import redundant_ik

        self.task = task
        self.label = label
        self.kind = "ours"
        self.robot = redundant_ik.Robot.preset("panda")
        self.c = redundant_ik.Controller(self.robot, method=method, **params)
        self.keywords = dict(method=method, **params)
        self.dt = self.c.dt
        self.times = [k * self.dt for k in range(task.steps)]
        self.theta = task.theta0.copy()

    def reset(self):
        self.theta = np.array(self.c.theta0, dtype=float)

    def step(self, k):
        # The user's loop: plain Euler.
        self.theta += self.dt * self.c.step(self.theta, self.times[k])

    def angles(self):
        return self.theta
