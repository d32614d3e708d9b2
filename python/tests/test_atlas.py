"""atlas() is the tool's `atlas --json` as arrays; the GIL is released
while it runs, and Ctrl-C stops it."""

import _thread
import threading
import time

import numpy as np
import pytest

import redundant_ik as rik
from conftest import cli


def test_the_planar_atlas_is_the_tools():
    a = rik.atlas(task=1, grid=5, methods=["none", "numerical", "qp"])
    assert a.to_json() == cli("atlas", "--task", "1", "--grid", "5", "--methods", "none,numerical,qp", "--json")
    assert a.methods == ["none", "numerical", "qp"] and a.centres.shape == (25, 2)
    assert set(a.classes["qp"]) <= {"success", "collision", "limit", "missed", "failed", "path_blocked",
                                     "start_overlap"}
    assert np.isnan(a.clearance["qp"][a.classes["qp"] == "start_overlap"]).all()


def test_the_slice_atlas_in_space():
    a = rik.atlas(arm="panda", grid=3, methods="numerical,qp", threads=1)
    assert a.to_json() == cli("atlas", "--arm", "panda", "--grid", "3", "--methods", "numerical,qp", "--json")
    assert a.centres.shape == (9, 3)
    # The same on two threads: the rows are independent.
    assert rik.atlas(arm="panda", grid=3, methods="numerical,qp", threads=2).to_json() == a.to_json()


def test_to_pandas_has_a_row_per_cell_and_method():
    import pandas as pd  # python/requirements-test.txt

    a = rik.atlas(grid=4, methods=["numerical", "distance"])
    df = a.to_pandas()
    assert isinstance(df, pd.DataFrame) and len(df) == 32
    assert list(df.columns[:3]) == ["x", "y", "method"]
    rate = (df[(df.method == "distance") & ~df["class"].isin(["path_blocked", "start_overlap"])]["class"]
            == "success").mean()
    assert rate == pytest.approx(a.success_rate("distance"))


def test_the_gil_is_released_while_an_atlas_runs():
    done = threading.Event()
    worker = threading.Thread(target=lambda: (rik.atlas(grid=13, methods="all", threads=1), done.set()))
    ticks = 0
    worker.start()
    while not done.is_set() and worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    # Held, the GIL would leave this loop a tick or two until the atlas ended.
    assert ticks > 20


def test_ctrl_c_stops_an_atlas_between_rows(ctrl_c):
    timer = threading.Timer(0.3, _thread.interrupt_main)
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        rik.atlas(grid=41, methods="all", threads=1)
    assert time.perf_counter() - start < 10
    timer.cancel()
