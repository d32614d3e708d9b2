"""The controller is the run's arithmetic: its rates rebuild the run's
RK4 step, and the kinematics are the tool's."""

import numpy as np
import pytest

import redundant_ik as rik
from conftest import DATA, cli


def rk4_first_step(c, theta0):
    """simulate's first step, from the controller's rates at its stages."""
    h = c.dt
    k1 = c.step(theta0, 0.0)
    k2 = c.step(theta0 + 0.5 * h * k1, 0.5 * h)
    k3 = c.step(theta0 + 0.5 * h * k2, 0.5 * h)
    k4 = c.step(theta0 + h * k3, h)
    return theta0 + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


CASES = [
    (dict(robot="paper", method="numerical"), dict(task=1, method="numerical")),
    (dict(robot="paper", method="qp", feedback=2), dict(task=1, method="qp", feedback=2)),
    (dict(robot="paper", method="case3"), dict(task=1, method="case3")),
    (dict(robot="panda", method="qp"), dict(arm="panda", method="qp")),
    (dict(robot="panda", method="priority", path="circle:0.45,0.1,0.5,0,0,1"),
     dict(arm="panda", method="priority", path="circle:0.45,0.1,0.5,0,0,1")),
    (dict(robot="panda", method="numerical", task="pose"), dict(arm="panda", method="numerical", task="pose")),
]


@pytest.mark.parametrize("controller,run", CASES)
def test_the_rates_rebuild_the_runs_first_rk4_step(controller, run):
    c = rik.Controller(**controller)
    r = rik.simulate(**run)
    np.testing.assert_array_equal(c.theta0, r.theta[0])
    np.testing.assert_allclose(rk4_first_step(c, r.theta[0]), r.theta[1], rtol=0, atol=1e-12)


def test_rates_for_the_lines_velocity_are_the_first_stage():
    c = rik.Controller("panda", method="qp")
    r = rik.simulate(arm="panda", method="qp")
    xdot = (np.array(r.scene["target"]) - r.hand[0]) / r.scene["tf"]
    np.testing.assert_allclose(c.rates(r.theta[0], xdot), c.step(r.theta[0], 0.0), rtol=0, atol=1e-12)
    np.testing.assert_allclose(c.reference(r.t[5]), r.reference[5], rtol=0, atol=1e-12)


def test_obstacles_move_between_calls():
    c = rik.Controller("panda", method="qp", obstacles=[(0.215, 0.21, 0.7, 0.06)])
    theta = c.theta0
    xdot = np.array([0.0, 0.06, 0.0])
    near = c.rates(theta, xdot)
    c.obstacles = [(2.0, 2.0, 2.0, 0.06)]
    far = c.rates(theta, xdot)
    assert not np.allclose(near, far)
    c.move_obstacle(0, (0.215, 0.21, 0.7))
    np.testing.assert_array_equal(c.rates(theta, xdot), near)
    assert c.obstacles == [[0.215, 0.21, 0.7, 0.06]]
    with pytest.raises(rik.Error, match="obstacles\\[0\\]"):
        c.obstacles = [(1.0, 2.0)]
    with pytest.raises(rik.Error):
        c.obstacles = [(0.0, 0.0, 0.1, 0.05)]  # on the base
    assert c.obstacles == [[0.215, 0.21, 0.7, 0.06]]


def test_the_forward_kinematics_are_the_tools():
    for name, arm in [("paper", "paper"), ("panda", "panda"), ("iiwa14", "iiwa14")]:
        robot = rik.Robot.preset(name)
        run = rik.Run(cli("simulate", "--arm", arm, "--json", "--tf", "1"))
        for k in (0, -1):
            f = robot.forward(run.theta[k])
            np.testing.assert_array_equal(f["hand"], run.hand[k])
            np.testing.assert_array_equal(f["points"][-len(run.points[k]):], run.points[k])


def test_the_jacobian_is_the_derivative_of_the_hand():
    rng = np.random.default_rng(7)
    for robot in [rik.Robot.preset("paper"), rik.Robot.preset("panda"),
                  rik.Robot.from_urdf(DATA / "urdf" / "slider_arm.urdf", tip="tool")]:
        lim = robot.joint_limits
        # Within the limits and +-pi (a continuous joint's are +-1e6 rad).
        lo, hi = (np.maximum(lim[:, 0], -np.pi), np.minimum(lim[:, 1], np.pi)) if lim is not None else (-2, 2)
        theta = rng.uniform(lo, hi, robot.n)
        J = robot.jacobian(theta)
        m = 2 if robot.kind == "planar" else 6
        assert J.shape == (m, robot.n)
        eps = 1e-6
        for i in range(robot.n):
            d = np.zeros(robot.n)
            d[i] = eps
            fp, fm = robot.forward(theta + d), robot.forward(theta - d)
            np.testing.assert_allclose(J[: len(fp["hand"]), i], (fp["hand"] - fm["hand"]) / (2 * eps), atol=1e-8)
            if m == 6:
                # The angular rows: dR R^T is the skew matrix of the column.
                dR = (fp["rotation"] - fm["rotation"]) / (2 * eps)
                W = dR @ robot.forward(theta)["rotation"].T
                np.testing.assert_allclose(J[3:, i], [W[2, 1], W[0, 2], W[1, 0]], atol=1e-8)


def test_a_user_loop_follows_the_line_past_the_sphere():
    c = rik.Controller("panda", method="qp")
    theta = c.theta0.copy()
    steps = int(round(c.tf / c.dt))
    for k in range(steps):
        theta = theta + c.dt * c.step(theta, k * c.dt)
    robot = rik.Robot.preset("panda")
    error = np.linalg.norm(robot.forward(theta)["hand"] - c.reference(c.tf))
    assert error < 5e-3
