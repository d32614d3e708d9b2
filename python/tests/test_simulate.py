"""simulate() is the command line's `simulate --json`, byte for byte, and a
Run reads run files back."""

import numpy as np
import pytest

import redundant_ik as rik
from conftest import DATA, ROOT, cli

PLANAR = [m["name"] for m in rik.methods()]


@pytest.mark.parametrize("method", PLANAR)
def test_task1_in_every_method_is_the_tools_json(method):
    run = rik.simulate(task=1, method=method)
    assert run.to_json() == cli("simulate", "--task", "1", "--method", method, "--json")
    assert run.method == method
    assert run.theta.shape == (101, 3) and run.hand.shape == (101, 2)
    assert run.t[-1] == pytest.approx(10.0)


def test_keywords_are_the_flags_with_their_values_as_the_tool_reads_them():
    kw = dict(task=2, method="qp", lambda_=2.5, obstacles=[(0.6, 0.9, 0.08), (1.2, 0.3)], tf=5,
              dt=0.05, feedback=3, joint_limits="-2:2,-2.5:2.5,-2.5:2.5", stop_distance=0.03)
    flags = ["simulate", "--task", "2", "--method", "qp", "--lambda", "2.5", "--obstacle", "0.6,0.9,0.08",
             "--obstacle", "1.2,0.3", "--tf", "5", "--dt", "0.05", "--feedback", "3",
             "--joint-limits=-2:2,-2.5:2.5,-2.5:2.5", "--stop-distance", "0.03", "--json"]
    assert rik.simulate(**kw).to_json() == cli(*flags)


def test_the_panda_in_qp_is_the_tools_json():
    run = rik.simulate(arm="panda", method="qp")
    assert run.to_json() == cli("simulate", "--arm", "panda", "--method", "qp", "--json")
    assert run.hand.shape[1] == 3 and run.theta.shape[1] == 7
    assert run.summary["min_clearance"] > 0.019 and not run.summary["collided"]
    same = rik.simulate(robot=rik.Robot.preset("panda"), method="qp")
    assert same.to_json() == run.to_json()


def test_a_urdf_robot_is_the_tools_json():
    urdf = DATA / "urdf" / "slider_arm.urdf"
    robot = rik.Robot.from_urdf(urdf, tip="tool")
    run = rik.simulate(robot=robot, method="distance", tf=2)
    assert run.to_json() == cli("simulate", "--urdf", str(urdf), "--tip", "tool", "--method", "distance",
                                "--tf", "2", "--json")


def test_the_pose_task_records_the_hands_pose():
    run = rik.simulate(arm="panda", task="pose", method="numerical", tf=2)
    assert run.pose.shape == (41, 6) and run.hand.shape == (41, 3)
    assert run.to_json() == cli("simulate", "--arm", "panda", "--task", "pose", "--method", "numerical",
                                "--tf", "2", "--json")


def test_a_run_file_reads_back_and_replays():
    text = (DATA / "run-1-task2-case3-reach.json").read_text()
    run = rik.Run.from_json(text)
    assert run.method == "case3" and run.to_json() == text
    again = run.replay()
    np.testing.assert_allclose(again.theta, run.theta, atol=1e-9)
    assert rik.Run.from_json(again.to_json()).to_json() == again.to_json()


def test_a_run_file_from_the_page_replays(tmp_path):
    # What the page's "Download run" saved (tests/e2e/runs.mjs checks the
    # page writes what the tool writes; this one was saved by the page).
    path = DATA / "page-run-panda-qp.json"
    run = rik.Run.from_json(path.read_text())
    again = run.replay()
    np.testing.assert_allclose(again.theta, run.theta, atol=1e-9)
    assert again.summary["collided"] == run.summary["collided"]


def test_a_run_has_its_numbers_as_arrays():
    run = rik.simulate(task=1, method="case3", tf=2)
    assert run.clearance.dtype == float and run.collision.dtype == bool
    assert run.points.shape == (len(run), 4, 2)
    np.testing.assert_array_equal(run.points[:, -1, :], run.hand)
    assert set(run.summary) >= {"min_clearance", "final_error", "collided", "reached"}
