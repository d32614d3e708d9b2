#!/usr/bin/env python3
"""Reference numbers for two 7-joint arms, from Robotics Toolbox for Python.

Writes `tests/data/space/panda.json` and `tests/data/space/iiwa14.json`:
for each arm its modified (Craig) DH rows, joint and rate limits, a ready
pose, and 24 poses (seeded; the first all zeros, the second the ready
pose, the rest uniform within the joint limits), each with the origin of
every MDH frame 1..7 and of the flange in the base frame, the positional
rows of the flange's geometric Jacobian in the base frame (rtb's
`jacob0`, rows 0-2) and each joint's rotation axis in the base frame.
The Rust tests check the crate's kinematics against these files.

NOT part of `make test`: it needs a Python environment of its own, kept
outside the repository, and is run by hand when the files are to be made
again. Made with roboticstoolbox-python 1.5.0, spatialmath-python 1.1.18,
numpy 2.4.6 (Python 3.11):

    python3 -m venv /work/venv-rtb
    /work/venv-rtb/bin/pip install roboticstoolbox-python==1.5.0 \
        spatialmath-python==1.1.18 numpy==2.4.6
    /work/venv-rtb/bin/python scripts/space-reference.py \
        [--drake-urdf PATH/iiwa14_no_collision.urdf]

The models:

- Panda: `rtb.models.DH.Panda()`, checked against Franka's FCI table
  (below). rtb's model carries the flange in its last row (d7 = 0.107)
  and a tool beyond it, `transl(0, 0, 0.103) @ trotz(-pi/4)` (the hand's
  TCP); the files hold the flange (d7 = 0, flange d = 0.107), no tool.
  Rate limits: rtb's `models.URDF.Panda().qdlim` (Franka's data).
- iiwa14: the KUKA LBR iiwa 14 as Drake describes it
  (RobotLocomotion/models, `iiwa_description/urdf/iiwa14_no_collision.urdf`,
  the same joints as `iiwa14_polytope_collision.urdf`; BSD-3-Clause), its
  joint chain written out below (`DRAKE_IIWA14`), built as an rtb ETS
  robot; the MDH rows are found from that chain at q = 0 and checked
  against it over all the poses. `--drake-urdf` checks the written-out
  numbers against a copy of Drake's URDF. rtb ships an iiwa of its own
  (`models.URDF.LBR`, ROS-Industrial's `lbr_iiwa_14_r820`): the script
  prints how far it is from Drake's.

Prints its cross-checks: the Jacobian against central differences of the
flange's position, rtb's Panda against the MDH rows written out, and the
iiwa's MDH chain against the ETS chain. Exits 1 if a check fails.
"""

import argparse
import hashlib
import json
import math
import sys
import xml.etree.ElementTree as ET_XML
from pathlib import Path

import numpy as np
import roboticstoolbox as rtb
import spatialmath
from roboticstoolbox import ET, DHRobot, RevoluteMDH
from spatialmath import SE3

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "tests" / "data" / "space"
SEED = 20260601
N_POSES = 24
TOL = 1e-12
PI = math.pi

# Franka's FCI table (frankaemika.github.io/docs/control_parameters.html).
PANDA = {
    "a": [0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088],
    "alpha": [0.0, -PI / 2, PI / 2, PI / 2, -PI / 2, PI / 2, PI / 2],
    "d": [0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0],
    "offset": [0.0] * 7,
    "flange": 0.107,
}
PANDA_LIMITS = [
    [-2.8973, 2.8973], [-1.7628, 1.7628], [-2.8973, 2.8973],
    [-3.0718, -0.0698], [-2.8973, 2.8973], [-0.0175, 3.7525],
    [-2.8973, 2.8973],
]
PANDA_RATES = [2.1750, 2.1750, 2.1750, 2.1750, 2.6100, 2.6100, 2.6100]
PANDA_QR = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, PI / 4]

# Drake's iiwa14: each joint's origin (xyz, rpy as the URDF's text), axis,
# limits and velocity limit, iiwa_joint_1 .. iiwa_joint_7, then the fixed
# tool0_joint to iiwa_link_ee (the flange; its rotation is not needed).
DRAKE_SOURCE = (
    "RobotLocomotion/models, iiwa_description/urdf/iiwa14_no_collision.urdf "
    "(joints identical in iiwa14_polytope_collision.urdf), checked at commit "
    "4723170e1c8ee8bc59c342bb5c491ab8f263f1fb (file last changed in "
    "fe6543985266eb4b53123c58441a2a57605aa313, moved there from drake's "
    "manipulation/models/iiwa_description/urdf/); BSD-3-Clause"
)
H = 1.570796326794897  # the URDF's pi/2 (its text, not math.pi / 2)
P = 3.141592653589793
DRAKE_IIWA14 = [
    # name, xyz, rpy, axis, lower, upper, velocity
    ("iiwa_joint_1", (0, 0, 0.1575), (0, 0, 0), (0, 0, 1),
     -2.96705972839, 2.96705972839, 1.4835298641951802),
    ("iiwa_joint_2", (0, 0, 0.2025), (H, 0, P), (0, 0, 1),
     -2.09439510239, 2.09439510239, 1.4835298641951802),
    ("iiwa_joint_3", (0, 0.2045, 0), (H, 0, P), (0, 0, 1),
     -2.96705972839, 2.96705972839, 1.7453292519943295),
    ("iiwa_joint_4", (0, 0, 0.2155), (H, 0, 0), (0, 0, 1),
     -2.09439510239, 2.09439510239, 1.3089969389957472),
    ("iiwa_joint_5", (0, 0.1845, 0), (-H, P, 0), (0, 0, 1),
     -2.96705972839, 2.96705972839, 2.2689280275926285),
    ("iiwa_joint_6", (0, 0, 0.2155), (H, 0, 0), (0, 0, 1),
     -2.09439510239, 2.09439510239, 2.356194490192345),
    ("iiwa_joint_7", (0, 0.081, 0), (-H, P, 0), (0, 0, 1),
     -3.05432619099, 3.05432619099, 2.356194490192345),
]
DRAKE_EE = ("tool0_joint", (0, 0, 0.045))
# Drake's ManipulationStation (examples/manipulation_station/
# manipulation_station.cc, q0_iiwa) and its Python examples start here.
IIWA_READY = [0.0, 0.6, 0.0, -1.75, 0.0, 1.0, 0.0]
# What the MDH rows found from the chain must be (all offsets 0).
IIWA_EXPECTED = {
    "a": [0.0] * 7,
    "alpha": [0.0, -PI / 2, PI / 2, PI / 2, -PI / 2, -PI / 2, PI / 2],
    "d": [0.36, 0.0, 0.42, 0.0, 0.4, 0.0, 0.0],
    "offset": [0.0] * 7,
    "flange": 0.126,
}

failures = []


def check(name, value, tol=TOL):
    ok = value <= tol
    print(f"  {'ok  ' if ok else 'FAIL'} {name}: {value:.3e} (tol {tol:.0e})")
    if not ok:
        failures.append(name)


def versions():
    from importlib.metadata import version

    return {
        "roboticstoolbox-python": version("roboticstoolbox-python"),
        "spatialmath-python": version("spatialmath-python"),
        "numpy": np.__version__,
        "python": sys.version.split()[0],
    }


def mdh_robot(m, name):
    links = [
        RevoluteMDH(a=m["a"][i], alpha=m["alpha"][i], d=m["d"][i],
                    offset=m["offset"][i])
        for i in range(7)
    ]
    return DHRobot(links, name=name, tool=SE3.Tz(m["flange"]))


def frames(robot, q):
    """MDH frames 1..7 in the base frame (SE3 list)."""
    all_ = robot.fkine_all(q)
    assert len(all_) == 8 and np.allclose(all_[0].A, np.eye(4))
    return [all_[i] for i in range(1, 8)]


def pose_record(robot, q):
    fs = frames(robot, q)
    flange = robot.fkine(q)
    jac = robot.jacob0(q)[:3, :]
    return {
        "q": [float(x) for x in q],
        "origins": [[float(x) for x in f.t] for f in fs]
        + [[float(x) for x in flange.t]],
        "jacobian": [[float(x) for x in row] for row in jac],
        "z_axes": [[float(x) for x in f.R[:, 2]] for f in fs],
    }


def poses(limits, ready):
    rng = np.random.default_rng(SEED)
    lo = np.array([l[0] for l in limits])
    hi = np.array([l[1] for l in limits])
    qs = [np.zeros(7), np.array(ready, dtype=float)]
    while len(qs) < N_POSES:
        qs.append(rng.uniform(lo, hi))
    return qs


def fd_check(robot, qs, name):
    """Largest |jacob0[:3] - central difference of the flange|."""
    h = 1e-6
    worst = 0.0
    for q in qs:
        jac = robot.jacob0(q)[:3, :]
        for j in range(7):
            dq = np.zeros(7)
            dq[j] = h
            fd = (robot.fkine(q + dq).t - robot.fkine(q - dq).t) / (2 * h)
            worst = max(worst, float(np.max(np.abs(fd - jac[:, j]))))
    check(f"{name}: jacob0 vs central differences (h = 1e-6)", worst, 1e-8)
    return worst


# ---------------------------------------------------------------- Panda


def panda(src):
    print("Panda: rtb.models.DH.Panda()")
    ref = rtb.models.DH.Panda()
    print(f"  rtb tool (beyond its flange row):\n{ref.tool}")
    rows = {
        "a": [l.a for l in ref.links], "alpha": [l.alpha for l in ref.links],
        "d": [l.d for l in ref.links], "offset": [l.offset for l in ref.links],
    }
    assert all(l.mdh for l in ref.links) and all(l.isrevolute for l in ref.links)
    want = dict(PANDA)
    want_d = want["d"][:6] + [want["flange"]]  # rtb folds the flange into d7
    check("Panda: rtb a vs FCI", max(abs(x - y) for x, y in zip(rows["a"], want["a"])), 0)
    check("Panda: rtb alpha vs FCI",
          max(abs(x - y) for x, y in zip(rows["alpha"], want["alpha"])), 0)
    check("Panda: rtb d (d7 = flange) vs FCI",
          max(abs(x - y) for x, y in zip(rows["d"], want_d)), 0)
    check("Panda: rtb offsets", max(abs(x) for x in rows["offset"]), 0)
    check("Panda: rtb qlim vs FCI",
          float(np.max(np.abs(ref.qlim.T - np.array(PANDA_LIMITS)))), 0)
    check("Panda: rtb qr", float(np.max(np.abs(ref.qr - np.array(PANDA_QR)))), 0)
    urdf = rtb.models.URDF.Panda()
    check("Panda: rtb URDF.Panda qdlim[:7] vs rates",
          float(np.max(np.abs(urdf.qdlim[:7] - np.array(PANDA_RATES)))), 0)

    ours = mdh_robot(PANDA, "Panda (flange)")
    ref.tool = SE3()  # rtb's frame 7 is the flange
    qs = poses(PANDA_LIMITS, PANDA_QR)
    w_pos = w_jac = w_org = w_urdf = 0.0
    for q in qs:
        w_pos = max(w_pos, float(np.max(np.abs(ours.fkine(q).A - ref.fkine(q).A))))
        w_jac = max(w_jac, float(np.max(np.abs(ours.jacob0(q) - ref.jacob0(q)))))
        fo, fr = frames(ours, q), frames(ref, q)
        for i in range(6):
            w_org = max(w_org, float(np.max(np.abs(fo[i].A - fr[i].A))))
        # our frame 7 sits 0.107 behind rtb's along z7
        w_org = max(w_org, float(np.max(np.abs(
            fo[6].t - (fr[6].t - 0.107 * fr[6].R[:, 2])))))
        w_urdf = max(w_urdf, float(np.max(np.abs(
            ours.fkine(q).t - urdf.fkine(q, end="panda_link8").t))))
    check("Panda: our MDH flange pose vs rtb DH.Panda (tool removed)", w_pos)
    check("Panda: our MDH jacob0 vs rtb DH.Panda", w_jac)
    check("Panda: our MDH frames 1..7 vs rtb DH.Panda", w_org)
    check("Panda: our MDH flange vs rtb URDF.Panda panda_link8", w_urdf, 1e-9)
    fd = fd_check(ours, qs, "Panda")
    return {
        "source": {
            **src,
            "model": "roboticstoolbox models.DH.Panda() (modified DH, Franka FCI "
            "table; rtb's tool transl(0,0,0.103)*trotz(-pi/4) beyond the flange "
            "is left out: the flange is d = 0.107 beyond frame 7)",
            "limits": "Franka FCI joint limits = rtb DH.Panda qlim",
            "rate_limits": "Franka's, rtb models.URDF.Panda().qdlim[:7] "
            "(its panda_arm xacro's velocity limits)",
            "ready": "rtb DH.Panda qr",
            "poses": f"numpy default_rng({SEED}): zeros, ready, then uniform in the limits",
            "checks": {"jacobian_vs_central_differences": fd,
                       "mdh_vs_rtb_DH_Panda": max(w_pos, w_jac, w_org),
                       "mdh_vs_rtb_URDF_Panda_flange": w_urdf},
        },
        "mdh": dict(PANDA),
        "limits": PANDA_LIMITS,
        "rate_limits": PANDA_RATES,
        "ready": PANDA_QR,
        "poses": [pose_record(ours, q) for q in qs],
    }


# ---------------------------------------------------------------- iiwa14


def drake_segments():
    """Drake's chain as one ETS per joint (origin, then Rz(q)), and the ee."""
    segs = []
    for k, (_, xyz, (r, p, y), axis, *_) in enumerate(DRAKE_IIWA14):
        assert axis == (0, 0, 1)
        e = rtb.ETS()
        for f, v in zip((ET.tx, ET.ty, ET.tz), xyz):
            if v:
                e = e * f(v)
        for f, v in ((ET.Rz, y), (ET.Ry, p), (ET.Rx, r)):  # URDF: Rz Ry Rx
            if v:
                e = e * f(v)
        segs.append(e * ET.Rz(jindex=k))
    return segs, rtb.ETS(ET.tz(DRAKE_EE[1][2]))


class DrakeChain:
    def __init__(self):
        segs, ee = drake_segments()
        self.partial = []
        e = rtb.ETS()
        for s in segs:
            e = e * s
            self.partial.append(e)
        self.full = e * ee
        self.robot = rtb.Robot(self.full, name="iiwa14 (Drake)")

    def links(self, q):
        """Drake's iiwa_link_1 .. iiwa_link_7 frames (SE3 list)."""
        return [SE3(self.partial[i].fkine(q[: i + 1]).A) for i in range(7)]

    def flange(self, q):
        return SE3(self.full.fkine(q).A)


def mdh_from_chain(chain):
    """Modified DH rows of the chain, from its axes at q = 0.

    Frame 0 is the base. Frame i's z is joint i's axis (its direction as
    Drake's, so q is not negated), its origin the foot of the common
    normal to axis i + 1 (their crossing where they meet), x_i along that
    normal (z_i x z_i+1 where they cross, the sign nearer x_i-1); frame 7
    has d7 = 0 and Drake's link-7 x, and the flange's d is along z7.
    """
    q0 = np.zeros(7)
    links = chain.links(q0)
    z = [np.array([0.0, 0, 1])] + [l.R[:, 2] for l in links]
    p = [np.zeros(3)] + [l.t for l in links]  # a point on each axis
    x = [np.array([1.0, 0, 0])]
    o = [np.zeros(3)]
    for i in range(1, 8):
        if i < 7:
            n = np.cross(z[i], z[i + 1])
            assert np.linalg.norm(n) > 1e-9, "parallel axes not handled"
            n = n / np.linalg.norm(n)
            # closest points between the lines p_i + s z_i, p_i+1 + t z_i+1
            w = p[i] - p[i + 1]
            b = z[i] @ z[i + 1]
            s = (b * (z[i + 1] @ w) - (z[i] @ w)) / (1 - b * b)
            t = ((z[i + 1] @ w) - b * (z[i] @ w)) / (1 - b * b)
            oi = p[i] + s * z[i]
            gap = p[i + 1] + t * z[i + 1] - oi
            if np.linalg.norm(gap) < 1e-12:
                xi = n if n @ x[i - 1] >= -1e-12 else -n
            else:
                xi = gap / np.linalg.norm(gap)
        else:
            # d7 = 0: where x6's line meets axis 7
            oi = o[i - 1] + ((p[i] - o[i - 1]) @ x[i - 1]) * x[i - 1]
            xi = links[6].R[:, 0]
        x.append(xi)
        o.append(oi)
    m = {"a": [], "alpha": [], "d": [], "offset": []}
    for i in range(1, 8):
        xp, zp, zi = x[i - 1], z[i - 1], z[i]
        assert abs(xp @ zi) < 1e-12 and abs(xp @ zp) < 1e-12
        v = o[i] - o[i - 1]
        a, d = float(v @ xp), float(v @ zi)
        assert np.linalg.norm(v - a * xp - d * zi) < 1e-12
        m["a"].append(a)
        m["d"].append(d)
        m["alpha"].append(float(math.atan2(np.cross(zp, zi) @ xp, zp @ zi)))
        m["offset"].append(float(math.atan2(np.cross(xp, x[i]) @ zi, xp @ x[i])))
    fl = chain.flange(q0).t - o[7]
    assert np.linalg.norm(fl - (fl @ z[7]) * z[7]) < 1e-12, "flange off axis 7"
    m["flange"] = float(fl @ z[7])
    # clean float noise (1e-17) to the exact values, after checking them
    noise = max(abs(g - w) for k in ("a", "alpha", "d", "offset")
                for g, w in zip(m[k], IIWA_EXPECTED[k]))
    noise = max(noise, abs(m["flange"] - IIWA_EXPECTED["flange"]))
    check("iiwa: MDH rows found vs IIWA_EXPECTED (before rounding)", noise, 1e-15)
    for k in ("a", "alpha", "d", "offset"):
        for i, (got, want) in enumerate(zip(m[k], IIWA_EXPECTED[k])):
            if abs(got - want) > 1e-15:
                failures.append(f"iiwa MDH {k}[{i}] = {got!r}, expected {want!r}")
            m[k][i] = want
    if abs(m["flange"] - IIWA_EXPECTED["flange"]) > 1e-15:
        failures.append(f"iiwa flange = {m['flange']!r}")
    m["flange"] = IIWA_EXPECTED["flange"]
    return m


def check_drake_urdf(path):
    """Compare DRAKE_IIWA14 with a copy of Drake's URDF."""
    text = Path(path).read_bytes()
    root = ET_XML.fromstring(text)
    joints = {j.get("name"): j for j in root.findall("joint")}  # not <transmission>'s
    worst = 0.0
    for name, xyz, rpy, axis, lo, hi, vel in DRAKE_IIWA14:
        j = joints[name]
        org = j.find("origin")
        got = [float(v) for v in org.get("xyz").split()] + \
            [float(v) for v in org.get("rpy").split()] + \
            [float(v) for v in j.find("axis").get("xyz").split()]
        lim = j.find("limit")
        got += [float(lim.get("lower")), float(lim.get("upper")),
                float(lim.get("velocity"))]
        want = list(xyz) + list(rpy) + list(axis) + [lo, hi, vel]
        worst = max(worst, max(abs(a - b) for a, b in zip(got, want)))
        if j.find("parent").get("link") != f"iiwa_link_{int(name[-1]) - 1}":
            failures.append(f"{name}: parent link")
    ee = joints[DRAKE_EE[0]]
    got = [float(v) for v in ee.find("origin").get("xyz").split()]
    worst = max(worst, max(abs(a - b) for a, b in zip(got, DRAKE_EE[1])))
    if ee.find("child").get("link") != "iiwa_link_ee":
        failures.append("tool0_joint child")
    check(f"iiwa: script's Drake data vs {Path(path).name}", worst, 0)
    return {"file": Path(path).name, "sha256": hashlib.sha256(text).hexdigest()}


def rtb_lbr(chain, qs):
    """How far rtb's own iiwa (models.URDF.LBR) is from Drake's."""
    try:
        lbr = rtb.models.URDF.LBR()
    except Exception as e:  # xacro may be missing
        print(f"  rtb models.URDF.LBR did not load: {e!r}")
        return None
    worst = 0.0
    for q in qs:
        worst = max(worst, float(np.max(np.abs(
            lbr.fkine(q, end="tool0").t - chain.flange(q).t))))
    lim = float(np.max(np.abs(lbr.qlim.T - np.array(
        [[j[4], j[5]] for j in DRAKE_IIWA14]))))
    print(f"  rtb URDF.LBR tool0 vs Drake iiwa_link_ee: largest {worst:.3e} m "
          f"(its x offsets -/+0.00043624 at joints 2 and 4); qlim differ by "
          f"up to {lim:.3e} rad")
    return {"flange_position_difference": worst, "qlim_difference": lim}


def iiwa(src, drake_urdf):
    print("iiwa14: Drake's chain as an rtb ETS robot")
    verified = check_drake_urdf(drake_urdf) if drake_urdf else None
    chain = DrakeChain()
    m = mdh_from_chain(chain)
    print(f"  MDH rows found: {m}")
    ours = mdh_robot(m, "iiwa14 (MDH)")
    limits = [[j[4], j[5]] for j in DRAKE_IIWA14]
    rates = [j[6] for j in DRAKE_IIWA14]
    qs = poses(limits, IIWA_READY)
    # each MDH frame i is Drake's link i frame times a constant transform
    q0 = np.zeros(7)
    const = [l.inv() * f for l, f in zip(chain.links(q0), frames(ours, q0))]
    w_frame = w_org = w_fl = w_jac = w_z = 0.0
    for q in qs:
        fo, dl = frames(ours, q), chain.links(q)
        for i in range(7):
            w_frame = max(w_frame, float(np.max(np.abs(fo[i].A - (dl[i] * const[i]).A))))
            w_org = max(w_org, float(np.max(np.abs(fo[i].t - (dl[i] * const[i]).t))))
            w_z = max(w_z, float(np.max(np.abs(fo[i].R[:, 2] - dl[i].R[:, 2]))))
        w_fl = max(w_fl, float(np.max(np.abs(ours.fkine(q).t - chain.flange(q).t))))
        w_jac = max(w_jac, float(np.max(np.abs(
            ours.jacob0(q)[:3] - chain.robot.jacob0(q)[:3]))))
    check("iiwa: MDH frame origins vs ETS chain (link i * const)", w_org)
    check("iiwa: MDH frames (pose) vs ETS chain", w_frame)
    check("iiwa: MDH joint axes vs Drake's axes (same sign)", w_z)
    check("iiwa: MDH flange vs Drake iiwa_link_ee", w_fl)
    check("iiwa: MDH jacob0[:3] vs ETS robot jacob0[:3]", w_jac)
    fd = fd_check(ours, qs, "iiwa")
    lbr = rtb_lbr(chain, qs)
    return {
        "source": {
            **src,
            "model": "KUKA LBR iiwa 14, Drake's description: " + DRAKE_SOURCE
            + "; built as an rtb ETS robot, MDH rows found from its axes at "
            "q = 0; flange = iiwa_link_ee (0.045 beyond iiwa_link_7 along z)",
            "drake_joints": [
                {"name": n, "xyz": list(map(float, xyz)), "rpy": list(map(float, rpy)),
                 "axis": list(map(float, ax))}
                for n, xyz, rpy, ax, *_ in DRAKE_IIWA14
            ] + [{"name": DRAKE_EE[0], "xyz": list(map(float, DRAKE_EE[1]))}],
            "verified_against": verified,
            "limits": "the URDF's joint limits (170, 120, 170, 120, 170, 120, 175 deg)",
            "rate_limits": "the URDF's velocity limits, rad/s "
            "(85, 85, 100, 75, 130, 135, 135 deg/s)",
            "ready": "Drake's ManipulationStation default q0_iiwa",
            "signs": "q_i of the MDH chain = q_i of Drake's (no joint negated)",
            "poses": f"numpy default_rng({SEED}): zeros, ready, then uniform in the limits",
            "checks": {"jacobian_vs_central_differences": fd,
                       "mdh_vs_ets_chain": max(w_frame, w_org, w_fl, w_jac, w_z),
                       "rtb_URDF_LBR_vs_drake": lbr},
        },
        "mdh": m,
        "limits": limits,
        "rate_limits": rates,
        "ready": IIWA_READY,
        "poses": [pose_record(ours, q) for q in qs],
    }


def dumps(v, indent=0):
    """JSON with lists of numbers on one line; floats as repr."""
    pad = "  " * (indent + 1)
    if isinstance(v, dict):
        items = [f"{pad}{json.dumps(k)}: {dumps(x, indent + 1)}" for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + "  " * indent + "}"
    if isinstance(v, list):
        if all(isinstance(x, (int, float)) for x in v):
            return "[" + ", ".join(json.dumps(float(x)) for x in v) + "]"
        if all(isinstance(x, list) and all(isinstance(y, (int, float)) for y in x)
               for x in v):
            return "[" + ", ".join(dumps(x) for x in v) + "]"
        return "[\n" + ",\n".join(pad + dumps(x, indent + 1) for x in v) + "\n" \
            + "  " * indent + "]"
    return json.dumps(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--drake-urdf", help="a copy of Drake's iiwa14_no_collision.urdf")
    args = ap.parse_args()
    v = versions()
    print(f"versions: {v}")
    src = {"versions": v}
    arms = {"panda": panda(src), "iiwa14": iiwa(src, args.drake_urdf)}
    if failures:
        print("FAILED:", *failures, sep="\n  ")
        sys.exit(1)
    OUT.mkdir(parents=True, exist_ok=True)
    for name, data in arms.items():
        path = OUT / f"{name}.json"
        path.write_text(dumps(data) + "\n")
        print(f"wrote {path.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
