"""The examples run: the Dask sweep on a local cluster of two workers."""

import pathlib
import runpy
import sys

import redundant_ik as rik

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def test_the_dask_sweep_runs_on_two_local_workers(capsys):
    sys.path.insert(0, str(EXAMPLES))
    try:
        sweep = runpy.run_path(str(EXAMPLES / "sweep_dask.py"))
    finally:
        sys.path.remove(str(EXAMPLES))
    rows = sweep["main"](["--workers", "2", "--grid", "5", "--radii", "0.05,0.1", "--lambdas", "2,4",
                          "--methods", "numerical,qp"])
    assert len(rows) == 2 * 2 * 2
    # A worker's atlas is this process's.
    here = rik.atlas(task=1, radius=0.1, lambda_=4, grid=5, methods=["numerical", "qp"], threads=1)
    got = {r["method"]: r["success"] for r in rows if r["radius"] == 0.1 and r["lambda"] == 4}
    assert got == {m: here.success_rate(m) for m in ["numerical", "qp"]}
    out = capsys.readouterr().out
    assert "radius" in out and "%" in out
