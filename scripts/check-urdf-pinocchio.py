#!/usr/bin/env python3
"""Records an independent implementation's kinematics of every shipped URDF.

Pinocchio (pip install pin; its own URDF parser, urdfdom) reads each file
below; at 10 seeded random joint values within the limits it records every
moving joint's frame in the world (rotation by rows, translation), the tip
link's frame and the tip's 6 x n Jacobian (rows vx vy vz wx wy wz, in the
world's axes at the tip). tests/urdf.rs compares the reader's chain with
the frames to 1e-9 m and 1e-9 (rotation entries); the Jacobians wait for
the chain to run in the planner (docs/urdf.md).

    python3 -m venv /tmp/pin && /tmp/pin/bin/pip install pin
    /tmp/pin/bin/python scripts/check-urdf-pinocchio.py   # writes tests/data/urdf/pinocchio.json

Not part of `make test` (it needs Pinocchio from the package registry);
its output is committed.
"""
import json
import math
import os
import random

import numpy as np
import pinocchio as pin

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILES = [
    ("robots/panda.urdf", "flange"),
    ("robots/iiwa14.urdf", "flange"),
    ("robots/ur5e.urdf", "flange"),
    ("tests/data/urdf/slider_arm.urdf", "tool"),
]
SAMPLES = 10


def sample(model, rng):
    """Our joint values (one per moving joint) and Pinocchio's q."""
    ours, q = [], []
    for j in range(1, model.njoints):
        joint = model.joints[j]
        lo = model.lowerPositionLimit[joint.idx_q]
        hi = model.upperPositionLimit[joint.idx_q]
        if joint.nq == 2:  # a continuous joint: (cos, sin)
            v = rng.uniform(-math.pi, math.pi)
            q += [math.cos(v), math.sin(v)]
        else:
            lo, hi = (lo, hi) if np.isfinite(lo) and np.isfinite(hi) else (-math.pi, math.pi)
            v = rng.uniform(lo, hi)
            q.append(v)
        ours.append(v)
    return ours, np.array(q)


def placement(m):
    return {"rotation": m.rotation.tolist(), "translation": m.translation.tolist()}


def main():
    rng = random.Random(20261206)
    out = {"pinocchio": pin.__version__, "files": []}
    for path, tip in FILES:
        model = pin.buildModelFromUrdf(os.path.join(ROOT, path))
        data = model.createData()
        frame = model.getFrameId(tip)
        runs = []
        for _ in range(SAMPLES):
            ours, q = sample(model, rng)
            pin.forwardKinematics(model, data, q)
            pin.updateFramePlacements(model, data)
            jac = pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL_WORLD_ALIGNED)
            runs.append({
                "q": ours,
                "joints": [placement(data.oMi[j]) for j in range(1, model.njoints)],
                "tip": placement(data.oMf[frame]),
                "jacobian": jac.tolist(),
            })
        out["files"].append({"file": path, "tip": tip, "runs": runs})
    dest = os.path.join(ROOT, "tests/data/urdf/pinocchio.json")
    with open(dest, "w") as f:
        json.dump(out, f)
        f.write("\n")
    print(f"wrote {dest}: {len(FILES)} files x {SAMPLES} poses (Pinocchio {pin.__version__})")


if __name__ == "__main__":
    main()
