"""The Python kernels return what rne's Rust kernels return, bit for bit: the same JIT, the
same programs, against `rne eval --engine jit --json` of the same checkout (CI builds it before
running these tests; elsewhere they are skipped without it)."""
import json
import os
import subprocess

import numpy as np
import pytest

import rne
from conftest import ROOT, random_states, rne_binary

BINARY = rne_binary()
if BINARY is None and os.environ.get("RNE_REQUIRE_BIN"):
    raise RuntimeError("RNE_REQUIRE_BIN is set but no rne binary was found (set RNE_BIN)")
pytestmark = pytest.mark.skipif(BINARY is None, reason="no rne binary (build rne-cli or set RNE_BIN)")

CASES = [
    ("ur5", {}),
    ("panda", {}),
    ("puma560", {}),
    ("planar-elbow", {}),
    (str(ROOT / "rne-models/robots/quadruped.urdf"), {"floating_base": True}),
    (str(ROOT / "rne-models/corpus/tests/fixtures/arm_mimic_chain.urdf"), {}),
    (str(ROOT / "rne-models/corpus/tests/fixtures/hand_mimic.urdf"), {"mimic": "free"}),
]


def cli(robot, options, q, v, a, tau):
    """`rne eval ROBOT --what all --engine jit --json` at one state."""
    listing = lambda x: ",".join(repr(float(y)) for y in x)  # noqa: E731
    command = [BINARY, "eval", robot, "--what", "all", "--engine", "jit", "--json",
               f"--q={listing(q)}", f"--qd={listing(v)}", f"--qdd={listing(a)}", f"--tau={listing(tau)}"]
    if options.get("floating_base"):
        command.append("--floating-base")
    if options.get("mimic"):
        command += ["--mimic", options["mimic"]]
    out = subprocess.run(command, capture_output=True, text=True, check=True, cwd=ROOT)
    return json.loads(out.stdout)


def same_bits(python, rust, what):
    python = np.asarray(python, dtype=np.float64)
    rust = np.asarray(rust, dtype=np.float64).reshape(python.shape)
    assert python.tobytes() == rust.tobytes(), f"{what}: {np.max(np.abs(python - rust))}"


@pytest.mark.parametrize("robot,options", CASES, ids=[c[0].split("/")[-1] for c in CASES])
def test_every_kernel_matches_the_rust_kernels_bit_for_bit(robot, options):
    model = rne.load(robot, **options)
    q, v, a, tau = (x[0] for x in random_states(model, 1, seed=7))
    r = cli(robot, options, q, v, a, tau)
    assert r["engine"] == "jit"
    assert r["joints"] == model.joint_names
    same_bits(model.rnea(q, v, a), r["tau"], "rnea")
    same_bits(model.crba(q), r["M"], "crba")
    same_bits(model.coriolis_matrix(q, v), r["C"], "C")
    same_bits(model.computeGeneralizedGravity(q), r["g"], "g")
    same_bits(model.nonLinearEffects(q, v), r["bias"], "bias")
    same_bits(model.computeKineticEnergy(q, v), r["kinetic"], "kinetic")
    same_bits(model.computePotentialEnergy(q), r["potential"], "potential")
    if "qdd" in r:
        same_bits(model.aba(q, v, tau), r["qdd"], "aba")
        dq, dv = model.computeRNEADerivatives(q, v, a)
        same_bits(dq, r["dtau_dq"], "dtau_dq")
        same_bits(dv, r["dtau_dqd"], "dtau_dv")
        fq, fv, minv = model.computeABADerivatives(q, v, tau)
        same_bits(fq, r["dqdd_dq"], "dqdd_dq")
        same_bits(fv, r["dqdd_dqd"], "dqdd_dv")
        same_bits(minv, r["Minv"], "Minv")
    assert r["frames"] == model.frame_names
    rotations, origins = model.framePlacements(q)
    same_bits(rotations, [p[0] for p in r["placements"]], "rotations")
    same_bits(origins, [p[1] for p in r["placements"]], "origins")
    same_bits(model.frameJacobians(q), r["jacobians"], "jacobians")
    same_bits(model.frameJacobianTimeVariationDotV(q, v), r["jacobian_dot_qd"], "jdot_v")
    assert r["parameters"] == model.parameter_names
    same_bits(model.computeJointTorqueRegressor(q, v, a), r["regressor"], "regressor")
    assert r["base_parameters"] == model.base_parameter_names
    same_bits(model.base_regressor(q, v, a), r["base_regressor"], "base_regressor")
