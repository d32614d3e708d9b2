"""A sweep over many scenes on a dask.distributed cluster: the robustness
atlas of the paper's Task 1 for every obstacle radius and obstacle gain
lambda of a grid, one atlas per task on the cluster's workers.

Each task sends a ``Robot`` to a worker (it pickles) and gets an ``Atlas``
back (it pickles too); each atlas releases the GIL while it runs, so
threads work as well as processes.

    python python/examples/sweep_dask.py --workers 2 --grid 9

The tests run it on a local cluster of two worker processes.
"""

from __future__ import annotations

import argparse
import itertools
from typing import Dict, List, Sequence

import redundant_ik as rik


def one_atlas(robot: rik.Robot, radius: float, lam: float, grid: int, methods: Sequence[str]) -> rik.Atlas:
    """The atlas of one scene (one thread: the cluster spreads the scenes)."""
    return rik.atlas(robot=robot, task=1, radius=radius, lambda_=lam, grid=grid, methods=list(methods), threads=1)


def sweep(
    client, robot: rik.Robot, radii: Sequence[float], lambdas: Sequence[float], grid: int, methods: Sequence[str]
) -> List[Dict[str, object]]:
    """Every (radius, lambda) scene's atlas on the cluster; a row per scene
    and method: its success rate over the cells where avoidance is possible."""
    scenes = list(itertools.product(radii, lambdas))
    futures = [client.submit(one_atlas, robot, r, lam, grid, methods, pure=False) for r, lam in scenes]
    rows = []
    for (radius, lam), atlas in zip(scenes, client.gather(futures)):
        for m in atlas.methods:
            rows.append({"radius": radius, "lambda": lam, "method": m, "success": atlas.success_rate(m)})
    return rows


def main(argv: Sequence[str] | None = None) -> List[Dict[str, object]]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--workers", type=int, default=2, help="worker processes of the local cluster")
    p.add_argument("--grid", type=int, default=9, help="atlas points per side")
    p.add_argument("--radii", default="0.05,0.1,0.15", help="obstacle radii (m)")
    p.add_argument("--lambdas", default="2,4,8", help="obstacle gains lambda")
    p.add_argument("--methods", default="numerical,distance,qp")
    a = p.parse_args(argv)
    from dask.distributed import Client, LocalCluster

    radii = [float(x) for x in a.radii.split(",")]
    lambdas = [float(x) for x in a.lambdas.split(",")]
    methods = a.methods.split(",")
    robot = rik.Robot.preset("paper")
    with LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            rows = sweep(client, robot, radii, lambdas, a.grid, methods)
    print(f"{'radius':>7} {'lambda':>7} " + " ".join(f"{m:>11}" for m in methods))
    for r, lam in itertools.product(radii, lambdas):
        rates = {row["method"]: row["success"] for row in rows if row["radius"] == r and row["lambda"] == lam}
        print(f"{r:>7} {lam:>7} " + " ".join(f"{100 * rates[m]:>10.1f}%" for m in methods))
    return rows


if __name__ == "__main__":
    main()
