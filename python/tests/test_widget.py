"""The notebook widget: one pip install gives the numbers and the page.
Its front end (the npm package's widget.js, inside the wheel) renders the
demo from the Widget's traits in headless Chromium."""

import json
import pathlib
import shutil
import subprocess

import pytest

import redundant_ik as rik

HERE = pathlib.Path(__file__).resolve().parent


def test_the_widgets_traits_are_the_elements_attributes(tmp_path):
    w = rik.Widget(task=1, method="case3", lambda_=3, target=(0.6, 0.2), plots=True)
    state = w.get_state()
    assert {k: state[k] for k in ("task", "method", "lambda", "target", "plots")} == {
        "task": 1, "method": "case3", "lambda": 3, "target": [0.6, 0.2], "plots": True}
    (tmp_path / "widget.js").write_text(w._esm if isinstance(w._esm, str) else pathlib.Path(w._esm).read_text())
    (tmp_path / "state.json").write_text(json.dumps({k: state[k] for k in ("task", "method", "lambda", "target", "plots")}))
    node = shutil.which("node")
    assert node, "node runs the browser test (scripts/setup-wasm.sh installs it)"
    done = subprocess.run([node, str(HERE / "widget.mjs"), str(tmp_path)], capture_output=True, text=True, timeout=180)
    assert done.returncode == 0, done.stdout + done.stderr
    shown = json.loads(done.stdout.strip().splitlines()[-1])["shown"]
    assert shown["attributes"]["task"] == "1" and shown["attributes"]["method"] == "case3"
    assert shown["attributes"]["target"] == "0.6,0.2" and "plots" in shown["attributes"]
    assert shown["method"] == "case3" and shown["lambda"] == 3 and shown["target"] == [0.6, 0.2]


def test_a_widget_refuses_a_name_that_is_no_attribute():
    with pytest.raises(rik.Error, match="not an attribute"):
        rik.Widget(**{"Method!": "qp"})
