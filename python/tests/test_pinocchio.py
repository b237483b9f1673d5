"""The Python kernels agree with Pinocchio 4.1 to 1e-12 (relative to each quantity's largest
entry) on UR5, the Panda, a floating-base quadruped, Talos on a floating base and two robots
with mimic joints. CI has no Pinocchio: the values are committed (fixtures/pinocchio.json and
fixtures/pinocchio_talos.json from python/tools/pinocchio_expected.py; the mimic robots' from
rne-models' corpus fixtures, tools/peers/pinocchio_values.py).

Talos's URDF is example-robot-data's, not the repository's: its test runs where it finds the
very file the values were computed from (same SHA-256) — in $RNE_EXAMPLE_ROBOT_DATA (the
package's robots/ directory), this Python's example-robot-data, or the peers' environments of
tools/peers/setup.sh — and is skipped, saying so, elsewhere."""
import glob
import hashlib
import json
import os
import sysconfig
from pathlib import Path

import numpy as np
import pytest

import rne
from conftest import FIXTURES, ROOT

TOLERANCE = 1e-12
EXPECTED = json.loads((FIXTURES / "pinocchio.json").read_text())
TALOS = json.loads((FIXTURES / "pinocchio_talos.json").read_text())["robots"][0]
ROBOTS = {r["name"]: r for r in EXPECTED["robots"] + [TALOS]}
CORPUS = json.loads((ROOT / "rne-models/corpus/tests/fixtures/pinocchio.json").read_text())


def close(ours, theirs, what):
    ours, theirs = np.asarray(ours, dtype=float), np.asarray(theirs, dtype=float)
    assert ours.shape == theirs.shape, f"{what}: shape {ours.shape} != {theirs.shape}"
    scale = max(np.max(np.abs(theirs)), 1.0) if theirs.size else 1.0
    error = np.max(np.abs(ours - theirs)) / scale if theirs.size else 0.0
    assert error <= TOLERANCE, f"{what}: relative error {error:.3e}"


class Permutation:
    """Pinocchio's velocity order (the fixture's `joints`) against rne's joint order."""

    def __init__(self, model, expected):
        base = 6 if expected["floating_base"] else 0
        index = {name: k for k, name in enumerate(expected["joints"])}
        # rne index -> Pinocchio index, for every velocity entry.
        self.order = list(range(base)) + [base + index[j] for j in model.joint_names]
        qbase = 7 if expected["floating_base"] else 0
        self.q_order = list(range(qbase)) + [qbase + index[j] for j in model.joint_names]

    def vec(self, x):
        return np.asarray(x)[..., self.order]

    def mat(self, m):
        m = np.asarray(m)
        return m[..., self.order, :][..., :, self.order]

    def columns(self, m):
        return np.asarray(m)[..., self.order]


def example_robot_data():
    """The robots/ directories of example-robot-data this machine may have, most explicit first."""
    share = "cmeel.prefix/share/example-robot-data/robots"
    if os.environ.get("RNE_EXAMPLE_ROBOT_DATA"):
        yield Path(os.environ["RNE_EXAMPLE_ROBOT_DATA"])
    yield Path(sysconfig.get_paths()["purelib"]) / share
    for venv in ("rne-peers", "rne-pinocchio"):
        pattern = str(Path.home() / ".cache" / venv / "venv/lib/python3*/site-packages" / share)
        yield from (Path(p) for p in sorted(glob.glob(pattern)))


def robot_file(expected):
    """The robot's URDF: the repository's, or example-robot-data's file of the same SHA-256."""
    if not expected.get("example_robot_data"):
        return ROOT / expected["file"]
    for robots in example_robot_data():
        file = robots / expected["file"]
        if file.is_file() and hashlib.sha256(file.read_bytes()).hexdigest() == expected["sha256"]:
            return file
    pytest.skip(
        f"{expected['file']} of example-robot-data (SHA-256 {expected['sha256'][:12]}…) not found: "
        "set RNE_EXAMPLE_ROBOT_DATA to its robots/ directory (tools/peers/setup.sh installs it)"
    )


# The kernels the comparisons call (Talos's are compiled for these only, and its kinematics for
# the fixture's frames only).
COMPARED = [
    "inverse_dynamics", "mass_matrix", "bias_torques", "gravity_torques", "forward_dynamics",
    "mass_matrix_inverse", "kinetic_energy", "potential_energy", "inverse_dynamics_derivatives",
    "forward_dynamics_derivatives", "frame_placements", "frame_jacobians", "frame_jacobian_dot_qd",
    "regressor",
]


@pytest.fixture(scope="module", params=list(ROBOTS))
def case(request):
    expected = ROBOTS[request.param]
    options = {"kernels": COMPARED, "frames": expected["frames"]} if "sha256" in expected else {}
    model = rne.load(str(robot_file(expected)), floating_base=expected["floating_base"], **options)
    return model, expected, Permutation(model, expected)


def states(model, expected, p):
    for s in expected["states"]:
        yield np.asarray(s["q"])[p.q_order], p.vec(s["v"]), p.vec(s["a"]), p.vec(s["tau_fd"]), s


def test_dynamics(case):
    model, expected, p = case
    for q, v, a, tau, s in states(model, expected, p):
        close(model.rnea(q, v, a), p.vec(s["rnea"]), "rnea")
        close(model.crba(q), p.mat(s["crba"]), "crba")
        close(model.nonLinearEffects(q, v), p.vec(s["nonLinearEffects"]), "nonLinearEffects")
        close(model.computeGeneralizedGravity(q), p.vec(s["computeGeneralizedGravity"]), "gravity")
        close(model.aba(q, v, tau), p.vec(s["aba"]), "aba")
        close(model.computeMinverse(q), p.mat(s["computeMinverse"]), "computeMinverse")
        close(model.computeKineticEnergy(q, v), s["computeKineticEnergy"], "kinetic energy")
        close(model.computePotentialEnergy(q), s["computePotentialEnergy"], "potential energy")


def test_derivatives(case):
    model, expected, p = case
    for q, v, a, tau, s in states(model, expected, p):
        dq, dv = model.computeRNEADerivatives(q, v, a)
        close(dq, p.mat(s["dtau_dq"]), "dtau/dq")
        close(dv, p.mat(s["dtau_dv"]), "dtau/dv")
        fq, fv, minv = model.computeABADerivatives(q, v, tau)
        close(fq, p.mat(s["dqdd_dq"]), "dqdd/dq")
        close(fv, p.mat(s["dqdd_dv"]), "dqdd/dv")
        close(minv, p.mat(s["dqdd_dtau"]), "dqdd/dtau")


def test_frames(case):
    model, expected, p = case
    for q, v, a, tau, s in states(model, expected, p):
        rotations, origins = model.framePlacements(q)
        jacobians = model.frameJacobians(q)
        jdot_v = model.frameJacobianTimeVariationDotV(q, v)
        compared = 0
        for k, name in enumerate(model.frame_names):
            if name not in s["frames"]:
                continue
            f = s["frames"][name]
            close(rotations[k], f["rotation"], f"{name} rotation")
            close(origins[k], f["translation"], f"{name} translation")
            close(jacobians[k], p.columns(f["jacobian"]), f"{name} Jacobian")
            close(jdot_v[k], f["classical_acceleration"], f"{name} J̇ v")
            compared += 1
        assert compared == len(model.frame_names), "every rne frame is a Pinocchio body frame"


def test_regressor(case):
    model, expected, p = case
    # Ten columns per body, the free-flyer's body first, then one body per joint: in rne's joint
    # order, Pinocchio's block of the same joint (fixed links merged into their moving parent
    # by both); rows are velocities.
    base = 1 if expected["floating_base"] else 0
    index = {name: k for k, name in enumerate(expected["joints"])}
    blocks = list(range(base)) + [base + index[j] for j in model.joint_names]
    columns = [10 * b + c for b in blocks for c in range(10)]
    assert len(columns) == len(model.parameter_names)
    for q, v, a, tau, s in states(model, expected, p):
        theirs = np.asarray(s["computeJointTorqueRegressor"])[p.order][:, columns]
        close(model.computeJointTorqueRegressor(q, v, a), theirs, "regressor")


@pytest.mark.parametrize("file", ["arm_mimic_chain.urdf", "hand_mimic.urdf"])
def test_mimic_robots(file):
    robot = next(r for r in CORPUS["robots"] if r["file"] == file)["fixed"]
    assert robot["mimic"] in ("pinocchio", "projected")
    model = rne.load(str(ROOT / "rne-models/corpus/tests/fixtures" / file))
    assert model.joint_names == robot["joints"]
    for s in robot["states"]:
        q, v, a = s["q"], s["v"], s["a"]
        close(model.rnea(q, v, a), s["tau"], "rnea")
        close(model.crba(q), s["M"], "crba")
        close(model.computeGeneralizedGravity(q), s["g"], "gravity")
        close(model.nonLinearEffects(q, v), s["bias"], "nonLinearEffects")
        if s["qdd"] is not None:
            close(model.aba(q, v, s["tau_fd"]), s["qdd"], "forward dynamics")
