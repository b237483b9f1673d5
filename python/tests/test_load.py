"""rne.load's options change the model as rne's scene settings say, and every built-in robot
loads."""
import numpy as np
import pytest

import rne
from conftest import ROOT, random_states


@pytest.mark.parametrize("name", rne.BUILTIN_ROBOTS)
def test_every_builtin_robot_loads_with_every_kernel(name):
    model = rne.load(name)
    assert model.nq >= model.nv > 0
    assert len(model.joint_names) == (model.nv - 6 if model.floating_base else model.nv)
    assert set(model.kernels) <= set(rne.KERNELS)
    assert "inverse_dynamics" in model.kernels and model.name
    assert "rne.Model" in repr(model)


def test_paths_and_pathlike_load_the_same_model(ur5):
    from pathlib import Path

    model = rne.load(Path(ROOT / "rne-models/robots/ur5.urdf"))
    q, v, a, _ = random_states(ur5, 2, seed=0)
    assert model.rnea(q, v, a).tobytes() == ur5.rnea(q, v, a).tobytes()
    assert model.joint_names == ur5.joint_names and model.frame_names == ur5.frame_names


def test_the_regressor_times_the_standard_parameters_is_the_inverse_dynamics(ur5):
    """τ = Y_b π_b with the model's base parameters, and the identification's prediction."""
    q, v, a, _ = random_states(ur5, 3, seed=1)
    fit = rne.validate(ur5, _model_base_parameters(ur5), q, v, a)
    np.testing.assert_allclose(fit.tau, ur5.rnea(q, v, a), rtol=1e-9, atol=1e-9)
    yb = ur5.base_regressor(q, v, a)
    np.testing.assert_allclose(yb @ _model_base_parameters(ur5), ur5.rnea(q, v, a), atol=1e-9)


def _model_base_parameters(model):
    q, v, a, tau = random_states(model, 200, seed=2)
    tau = model.rnea(q, v, a)
    return rne.identify(model, q, v, a, tau).model


def test_gravity_lock_and_frames(ur5):
    q, v, a, _ = random_states(ur5, 1, seed=3)
    zero_g = rne.load("ur5", gravity=[0, 0, 0], kernels=["gravity_torques", "potential_energy"])
    assert not np.any(zero_g.computeGeneralizedGravity(q[0]))
    locked = rne.load("ur5", lock={"elbow_joint": 0.3})
    assert locked.nv == 5 and "elbow_joint" not in locked.joint_names
    full_q = q[0].copy()
    full_q[2] = 0.3
    assert np.allclose(locked.computeGeneralizedGravity(np.delete(full_q, 2)),
                       np.delete(ur5.computeGeneralizedGravity(full_q), 2), atol=1e-12)
    framed = rne.load("ur5", frames=["ee_link", "base_link"], kernels=["frame_placements"])
    assert framed.frame_names == ["ee_link", "base_link"]
    rotations, origins = framed.framePlacements(q[0])
    all_r, all_p = ur5.framePlacements(q[0])
    k = ur5.frame_index("ee_link")
    assert rotations.shape == (2, 3, 3) and origins[0].tobytes() == all_p[k].tobytes()


def test_floating_base_and_free_mimic_change_the_state():
    arm = rne.load("panda-arm", floating_base=True)
    assert arm.floating_base and arm.nq == 14 and arm.nv == 13
    hand = str(ROOT / "rne-models/corpus/tests/fixtures/hand_mimic.urdf")
    assert rne.load(hand, mimic="free").nv > rne.load(hand).nv


def test_friction_enters_the_dynamics_and_the_regressor():
    plain = rne.load("planar-elbow")
    rough = rne.load("planar-elbow", friction=True)
    q, v, a = [0.1, 0.2], [0.5, -0.5], [0.0, 0.0]
    f = rough.friction_torques(v)
    np.testing.assert_allclose(rough.rnea(q, v, a), plain.rnea(q, v, a) + f, atol=1e-12)
    assert len(rough.parameter_names) >= len(plain.parameter_names)


def test_runtime_parameters_can_be_set():
    model = rne.load("planar-elbow", parameters="runtime")
    names = model.runtime_parameter_names
    values = model.runtime_parameters
    assert len(names) == len(values) > 0
    q, v, a = [0.1, 0.2], [0.5, -0.5], [1.0, 1.0]
    before = model.rnea(q, v, a)
    np.testing.assert_allclose(before, rne.load("planar-elbow").rnea(q, v, a), atol=1e-12)
    masses = [k for k, n in enumerate(names) if n.startswith("m")]
    changed = values.copy()
    changed[masses] *= 2
    model.set_parameters(changed)
    assert not np.allclose(model.rnea(q, v, a), before)
    model.set_parameters(values)
    assert model.rnea(q, v, a).tobytes() == before.tobytes()


def test_fma_is_reported(ur5):
    fused = rne.load("ur5", fma=True, kernels=["inverse_dynamics"])
    assert not ur5.fused
    q, v, a, _ = random_states(ur5, 2, seed=4)
    np.testing.assert_allclose(fused.rnea(q, v, a), ur5.rnea(q, v, a), rtol=1e-12, atol=1e-12)
