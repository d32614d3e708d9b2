"""Robots, runs and atlases pickle, so a sweep can run on Dask or Ray."""

import pickle

import numpy as np
import pytest

import redundant_ik as rik
from conftest import DATA, ROOT


@pytest.mark.parametrize(
    "make",
    [
        lambda: rik.Robot.preset("panda"),
        lambda: rik.Robot.preset("paper"),
        lambda: rik.Robot.planar("0.4:0.5,0.5,0.4,0.3"),
        lambda: rik.Robot.from_urdf(ROOT / "robots" / "ur5e.urdf"),
        lambda: rik.Robot.from_urdf((DATA / "urdf" / "slider_arm.urdf").read_text(), tip="tool"),
    ],
)
def test_a_robot_pickles(make):
    robot = make()
    back = pickle.loads(pickle.dumps(robot))
    theta = np.linspace(-0.5, 0.5, robot.n)
    assert back.n == robot.n and back.name == robot.name and back._flags[0] == robot._flags[0]
    np.testing.assert_array_equal(back.jacobian(theta), robot.jacobian(theta))
    for k, v in robot.forward(theta).items():
        np.testing.assert_array_equal(back.forward(theta)[k], v)


def test_a_run_and_an_atlas_pickle():
    run = rik.simulate(task=2, method="distance", tf=2)
    back = pickle.loads(pickle.dumps(run))
    assert back.to_json() == run.to_json()
    np.testing.assert_array_equal(back.theta, run.theta)
    atlas = rik.atlas(grid=3, methods=["numerical"])
    assert pickle.loads(pickle.dumps(atlas)).to_json() == atlas.to_json()


def test_a_controller_says_what_to_pickle_instead():
    with pytest.raises(TypeError, match="Robot"):
        pickle.dumps(rik.Controller("paper"))


def test_a_robot_with_an_srdf_given_as_text_pickles(tmp_path):
    urdf = (DATA / "urdf" / "slider_arm.urdf").read_text()
    srdf = '<robot name="slider_arm"><disable_collisions link1="base" link2="upper_arm" reason="Never"/></robot>'
    robot = rik.Robot.from_urdf(urdf, tip="tool", srdf=srdf)
    assert "--srdf" in robot._flags
    back = pickle.loads(pickle.dumps(robot))
    assert back._flags == robot._flags
    run = rik.simulate(robot=back, method="qp", tf=1)
    assert run.to_json() == rik.simulate(robot=robot, method="qp", tf=1).to_json()
