"""Bad input raises redundant_ik.Error (a ValueError) with the core's
message; none of it crashes the interpreter."""

import numpy as np
import pytest

import redundant_ik as rik
from conftest import DATA


def test_error_is_a_value_error():
    assert issubclass(rik.Error, ValueError)


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(lambda_=float("nan")), "lambda"),
        (dict(method="nonsense"), "nonsense"),
        (dict(stop_distance=0.5, influence=0.3), "stop"),
        (dict(theta0=[0.1, 0.2]), "theta"),
        (dict(tf=0.33), "whole number"),
        (dict(obstacles=[(0.0, 0.5, 0.1)]), "overlaps the fixed base post"),
        (dict(arm="0.5:"), "^invalid value '0.5:' for 'arm': arm '0.5:': '' is not a finite number$"),
        (dict(no_such_thing=1), "no keyword 'no_such_thing'"),
        (dict(target=(1.0, "x")), "target"),
        (dict(arm="panda", obstacles=[(1, 2)]), "^obstacles: X,Y places a disc"),
        (dict(arm="iiwa14", method="case1"), "no networks are shipped for iiwa14"),
        (dict(json=True), "no keyword 'json'"),
        (dict(arm="ur99"), "unknown arm 'ur99': the planar paper, four, five, iiwa-planar or, in space, panda, iiwa14"),
    ],
)
def test_simulate_refuses(kwargs, message):
    with pytest.raises(rik.Error, match=message):
        rik.simulate(**kwargs)


def test_the_controller_says_which_argument_and_what_it_expected():
    c = rik.Controller("panda", method="qp")
    good = c.theta0
    for theta, message in [
        ([0.0] * 3, "theta: expected 7 numbers"),
        (np.zeros((7, 1)), "shape"),
        (np.zeros(7, dtype=np.int64), "dtype"),
        ("abc", "theta: expected 7 numbers"),
        (np.full(7, np.nan), "not a finite number"),
    ]:
        with pytest.raises(rik.Error, match=message):
            c.rates(theta, [0.0, 0.0, 0.0])
    with pytest.raises(rik.Error, match="xdot: expected 3 numbers"):
        c.rates(good, [0.0, 0.0])
    with pytest.raises(rik.Error, match="not a finite time"):
        c.step(good, float("inf"))
    with pytest.raises(rik.Error):
        rik.Controller("panda", method="qp", influence=-1)
    with pytest.raises(rik.Error, match="preset"):
        rik.Controller("nonsense")


def test_a_strided_array_is_read_as_its_values():
    c = rik.Controller("panda", method="numerical")
    wide = np.zeros(14)
    wide[::2] = c.theta0
    np.testing.assert_array_equal(c.rates(wide[::2], [0.0, 0.1, 0.0]), c.rates(c.theta0, [0.0, 0.1, 0.0]))


HOSTILE = {
    "not xml": "this is not xml",
    "a DTD (billion laughs)": """<?xml version="1.0"?>
<!DOCTYPE lolz [<!ENTITY lol "lol"><!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">]>
<robot name="x"><link name="&lol2;"/></robot>""",
    "deep nesting": "<robot name='x'>" + "<a>" * 5000 + "</a>" * 5000 + "</robot>",
    "a joint loop": """<robot name="x"><link name="a"/><link name="b"/>
<joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
<joint name="j2" type="revolute"><parent link="b"/><child link="a"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint></robot>""",
    "no moving joint": "<robot name='x'><link name='a'/></robot>",
    "a NaN origin": """<robot name="x"><link name="a"/><link name="b"/><link name="c"/>
<joint name="j1" type="revolute"><parent link="a"/><child link="b"/><origin xyz="NaN 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
<joint name="j2" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint></robot>""",
}


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_a_hostile_urdf_raises(name):
    with pytest.raises(rik.Error):
        rik.Robot.from_urdf(HOSTILE[name])


def test_an_unknown_preset_names_every_arm():
    with pytest.raises(rik.Error, match="no preset 'ur99': the planar paper, four, five, iiwa-planar or, in space, panda, iiwa14"):
        rik.Robot.preset("ur99")


def test_a_missing_urdf_file_raises():
    with pytest.raises(rik.Error, match="cannot read"):
        rik.Robot.from_urdf("/no/such/robot.urdf")


def test_a_corrupt_weights_file_raises(tmp_path):
    for text in ["{", '{"format": 1}', "null", '{"nets": [{"layers": "x"}]}', "x" * 100]:
        bad = tmp_path / "bad.json"
        bad.write_text(text)
        with pytest.raises(rik.Error):
            rik.simulate(method="case1", phi_weights=bad)


def test_a_corrupt_run_file_raises():
    for text in ["", "{}", '{"steps": []}', "[1, 2]", '{"steps": [{"t": 0}]}']:
        with pytest.raises((rik.Error, KeyError, TypeError)):
            rik.Run.from_json(text)


def test_unknown_methods_and_keywords_for_the_controller():
    with pytest.raises(rik.Error, match="nonsense"):
        rik.Controller("paper", method="nonsense")
    with pytest.raises(rik.Error, match="no keyword 'gain'"):
        rik.Controller("paper", method="qp", gain=3)
