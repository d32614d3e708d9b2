"""Training and evaluating networks, the shipped sets, the list of methods."""

import _thread
import json
import threading
import time

import pytest

import redundant_ik as rik
from conftest import cli


def test_methods_are_the_tools_with_their_parameters():
    methods = {m["name"]: m for m in rik.methods()}
    assert {"none", "numerical", "case1", "case2", "case3", "distance", "priority", "qp"} <= set(methods)
    assert methods["case3"]["networks"] and methods["qp"]["in_space"]
    qp = {p["name"]: p for p in methods["qp"]["params"]}
    assert qp["stop_distance"]["default"] == 0.02 and qp["influence"]["flag"] == "--influence"


def test_a_trained_network_runs_as_the_tool_runs_it(tmp_path):
    out = tmp_path / "v.json"
    report = rik.train(out, net="v", samples=300, epochs=3, seed=4)
    assert "-> " + str(out) in report and json.loads(out.read_text())
    run = rik.simulate(method="case2", v_weights=out, tf=2)
    assert run.to_json() == cli("simulate", "--method", "case2", "--v-weights", str(out), "--tf", "2", "--json")


def test_the_shipped_sets_run():
    for net in ("paper", "reach"):
        assert rik.simulate(method="case3", networks=net, tf=1).method == "case3"
    assert rik.simulate(arm="panda", method="case3", networks="panda-reach", tf=1).theta.shape[1] == 7
    assert set(rik.NETWORK_SETS) == {"paper", "reach", "panda-reach"}


def test_evaluate_gives_the_tools_numbers():
    mine = rik.evaluate(samples=200)
    assert mine == json.loads(cli("eval", "--json", "--samples", "200"))


def test_ctrl_c_stops_a_training_between_epochs(tmp_path, ctrl_c):
    timer = threading.Timer(0.5, _thread.interrupt_main)
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        rik.train(tmp_path / "phi.json", net="phi", recipe="reach", samples=3000, epochs=5000)
    assert time.perf_counter() - start < 30
    assert not (tmp_path / "phi.json").exists(), "a stopped training writes no file"
    timer.cancel()
