"""Pinocchio's values of every kernel the Python package maps to it, at seeded states: the
expected values of python/tests/test_pinocchio.py (CI has no Pinocchio, so the output is
committed as python/tests/fixtures/pinocchio.json).

usage (from the repository root, with Pinocchio 4.1 from tools/peers/setup.sh):
    PY=~/.cache/rne-peers/venv/bin/python
    $PY python/tools/pinocchio_expected.py > python/tests/fixtures/pinocchio.json

Robots: UR5 and the Panda (rne-models/robots, fixed base) and the quadruped
(rne-models/robots/quadruped.urdf) on a free-flyer, written to stdout; with --talos FILE,
Talos (example-robot-data's talos_reduced.urdf, NV 38) on a free-flyer instead, at two states
and seven frames (the file is not in the repository: its entry records the file's SHA-256, and
the test runs when it finds the same file):
    $PY python/tools/pinocchio_expected.py --talos > python/tests/fixtures/pinocchio_talos.json Each state is written in a layout that
does not depend on Pinocchio's (tools/peers/pinocchio_values.py's): `joints` lists the joint
variables by URDF name in Pinocchio's velocity order; `q` holds one angle or distance per
joint (a continuous joint's angle, not Pinocchio's (cos, sin)), after the seven free-flyer
entries [x, y, z, qx, qy, qz, qw]; every nv-sized output is in Pinocchio's velocity order.
Frames are keyed by link name. Every float is written by repr(), so it reads back bit for bit.
"""
import argparse
import hashlib
import json
import os
import sys
import sysconfig

import numpy as np
import pinocchio as pin

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools", "peers"))
from pinocchio_values import Layout  # noqa: E402

ROBOTS = [
    ("ur5", "rne-models/robots/ur5.urdf", False),
    ("panda", "rne-models/robots/panda.urdf", False),
    ("quadruped", "rne-models/robots/quadruped.urdf", True),
]
STATES = 3
# Talos: the file within example-robot-data's robots/ directory, and the frames compared (the
# feet, a hand's fingertip behind fixed joints, an arm's last link, the head, the torso, the IMU).
TALOS = "talos_data/robots/talos_reduced.urdf"
TALOS_FRAMES = [
    "left_sole_link",
    "right_sole_link",
    "gripper_left_fingertip_3_link",
    "arm_right_7_link",
    "head_2_link",
    "torso_2_link",
    "imu_link",
]
TALOS_STATES = 2
SEED = 35
LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def symmetric(m):
    """Pinocchio fills the upper triangle of M and M⁻¹."""
    return np.triu(m) + np.triu(m, 1).T


def frames(model, data, q, v, only=None):
    """Placement, LOCAL_WORLD_ALIGNED Jacobian and J̇ v of every body frame (or of those named
    in `only`), by name."""
    out = {}
    pin.framesForwardKinematics(model, data, q)
    pin.computeJointJacobians(model, data, q)
    for fid, frame in enumerate(model.frames):
        if frame.type != pin.FrameType.BODY or (only is not None and frame.name not in only):
            continue
        placement = data.oMf[fid]
        out[frame.name] = {
            "rotation": placement.rotation.tolist(),
            "translation": placement.translation.tolist(),
            "jacobian": pin.getFrameJacobian(model, data, fid, LWA).tolist(),
        }
    pin.forwardKinematics(model, data, q, v, np.zeros(model.nv))
    pin.updateFramePlacements(model, data)
    pin.computeJointJacobiansTimeVariation(model, data, q, v)
    for fid, frame in enumerate(model.frames):
        if frame.name not in out:
            continue
        acc = pin.getFrameClassicalAcceleration(model, data, fid, LWA)
        out[frame.name]["classical_acceleration"] = np.concatenate([acc.linear, acc.angular]).tolist()
        dj = pin.getFrameJacobianTimeVariation(model, data, fid, LWA)
        out[frame.name]["jacobian_time_variation_v"] = (dj @ v).tolist()
    return out


def state_values(model, data, q, v, a, tau_fd, only=None):
    """Every kernel's value at one state, Pinocchio's layout."""
    dq, dv, _ = pin.computeRNEADerivatives(model, data, q, v, a)
    dq, dv = dq.copy(), dv.copy()
    fq, fv, minv = pin.computeABADerivatives(model, data, q, v, tau_fd)
    fq, fv, minv = fq.copy(), fv.copy(), symmetric(minv.copy())
    return {
        "rnea": pin.rnea(model, data, q, v, a).tolist(),
        "crba": symmetric(pin.crba(model, data, q).copy()).tolist(),
        "nonLinearEffects": pin.nonLinearEffects(model, data, q, v).tolist(),
        "computeGeneralizedGravity": pin.computeGeneralizedGravity(model, data, q).tolist(),
        "aba": pin.aba(model, data, q, v, tau_fd).tolist(),
        "computeMinverse": symmetric(pin.computeMinverse(model, data, q).copy()).tolist(),
        "dtau_dq": dq.tolist(),
        "dtau_dv": dv.tolist(),
        "dqdd_dq": fq.tolist(),
        "dqdd_dv": fv.tolist(),
        "dqdd_dtau": minv.tolist(),
        "computeKineticEnergy": float(pin.computeKineticEnergy(model, data, q, v)),
        "computePotentialEnergy": float(pin.computePotentialEnergy(model, data, q)),
        "computeJointTorqueRegressor": pin.computeJointTorqueRegressor(model, data, q, v, a).tolist(),
        "frames": frames(model, data, q, v, only),
    }


def robot(name, path, floating, file=None, count=STATES, only=None):
    """The robot's entry: `path` as the test finds it, read from `file` (default: the
    repository's `path`)."""
    root = [pin.JointModelFreeFlyer()] if floating else []
    model = pin.buildModelFromUrdf(file or os.path.join(ROOT, path), *root)
    data = model.createData()
    layout = Layout(model)
    rng = np.random.default_rng([SEED, len(name)])
    states = []
    for _ in range(count):
        base = None
        if floating:
            quat = rng.normal(size=4)
            quat /= np.linalg.norm(quat)
            base = np.concatenate([rng.uniform(-1, 1, 3), quat])
        angles = rng.uniform(-1.5, 1.5, len(layout.joints))
        v, a, tau_fd = (rng.uniform(-1, 1, model.nv) for _ in range(3))
        q = layout.configuration(base, angles)
        order = layout.velocity_order()
        # The state in the joint-name layout (velocity order of `joints`).
        state = {
            "q": ([] if base is None else base.tolist()) + angles.tolist(),
            "v": v[order].tolist(),
            "a": a[order].tolist(),
            "tau_fd": tau_fd[order].tolist(),
        }
        state.update(state_values(model, data, q, v, a, tau_fd, only))
        state["velocity_order"] = order
        states.append(state)
    return {
        "name": name,
        "file": path,
        "floating_base": floating,
        "joints": [j[0] for j in layout.joints],
        "states": states,
    }


def talos(robots_dir):
    """Talos on a free-flyer, the file's SHA-256 beside its values."""
    file = os.path.join(robots_dir, TALOS)
    with open(file, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    entry = robot("talos", TALOS, True, file, TALOS_STATES, TALOS_FRAMES)
    entry.update({"example_robot_data": True, "sha256": digest, "frames": TALOS_FRAMES})
    return entry


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = os.path.join(sysconfig.get_paths()["purelib"], "cmeel.prefix/share/example-robot-data/robots")
    parser.add_argument(
        "--talos",
        nargs="?",
        const=default,
        metavar="ROBOTS_DIR",
        help="Talos only, from example-robot-data's robots/ directory (default: this Python's)",
    )
    args = parser.parse_args()
    robots = [talos(args.talos)] if args.talos else [robot(*r) for r in ROBOTS]
    out = {
        "pinocchio": pin.__version__,
        "seed": SEED,
        "robots": robots,
    }
    json.dump(out, sys.stdout)
    print()


if __name__ == "__main__":
    main()
