"""Every bad input raises a Python exception with a message naming what is wrong; none
crashes the interpreter."""
import numpy as np
import pytest

import rne
from conftest import ROOT, random_states


@pytest.fixture(scope="module")
def states(ur5):
    return random_states(ur5, 4, seed=9)


def test_wrong_lengths_raise_value_errors(ur5, states):
    q, v, a, _ = states
    with pytest.raises(ValueError, match=r"`q` has 5 values; the robot needs 6"):
        ur5.rnea(q[0, :5], v[0], a[0])
    with pytest.raises(ValueError, match=r"`a` has 7 values"):
        ur5.rnea(q[0], v[0], np.zeros(7))
    with pytest.raises(ValueError, match=r"`v` has rows of 5 values"):
        ur5.rnea(q, v[:, :5], a)
    with pytest.raises(ValueError, match=r"must be 1-D \(6,\) for one state or 2-D"):
        ur5.crba(np.zeros((2, 2, 6)))
    with pytest.raises(ValueError, match=r"must be 1-D"):
        ur5.crba(np.float64(1.0))


def test_mixed_or_uneven_batches_raise(ur5, states):
    q, v, a, _ = states
    with pytest.raises(ValueError, match=r"`q` holds 4 states \(2-D\) but `v` holds one state"):
        ur5.rnea(q, v[0], a)
    with pytest.raises(ValueError, match=r"`q` holds 4 states \(2-D\) but `a` holds 3 states"):
        ur5.rnea(q, v, a[:3])


def test_a_batch_too_large_for_memory_raises_memory_error(ur5, states):
    # A broadcast view holds 10**17 states in no memory; rne's copy of them (4.8e18 bytes,
    # beyond any address space) cannot be allocated: a MemoryError, not an abort.
    q, v, a, _ = states
    huge = np.broadcast_to(q[0], (10**17, ur5.nq))
    with pytest.raises(MemoryError, match=r"cannot allocate 600000000000000000 float64 values"):
        ur5.rnea(huge, huge, huge)


def test_non_finite_values_raise_naming_the_entry(ur5, states):
    q, v, a, _ = states
    bad = q.copy()
    bad[2, 4] = np.nan
    with pytest.raises(ValueError, match=r"`q\[2, 4\]` is NaN; every value must be finite"):
        ur5.rnea(bad, v, a)
    with pytest.raises(ValueError, match=r"`v\[1\]` is inf"):
        ur5.nonLinearEffects(q[0], [0, np.inf, 0, 0, 0, 0])
    with pytest.raises(ValueError, match=r"`tau\[0\]` is -inf"):
        ur5.aba(q[0], v[0], [-np.inf, 0, 0, 0, 0, 0])


@pytest.mark.parametrize("value,kind", [
    (np.zeros(6, dtype=bool), "bool"),
    (np.zeros(6, dtype=complex), "complex128"),
    (["a"] * 6, "<U1"),
    ([None] * 6, "object"),
    (None, "object"),
])
def test_wrong_types_raise_type_errors(ur5, value, kind):
    with pytest.raises(TypeError, match=r"`q` must hold real numbers .*" + kind):
        ur5.crba(value)


def test_ragged_lists_raise_value_errors(ur5):
    with pytest.raises(ValueError, match=r"`q` cannot be read as an array"):
        ur5.crba([[0.0] * 6, [0.0] * 5])


def test_bad_thread_counts_raise(ur5, states):
    q, v, a, _ = states
    with pytest.raises(ValueError, match=r"threads must be positive"):
        ur5.rnea(q, v, a, threads=-1)
    with pytest.raises(TypeError):
        ur5.rnea(q, v, a, threads="two")


def test_a_quaternion_of_wrong_norm_raises(quadruped):
    q, v, a, _ = random_states(quadruped, 3, seed=1)
    bad = q.copy()
    bad[1, 3:7] *= 1.01
    with pytest.raises(ValueError, match=r"q\[1, 3:7\].*has norm 1\.0[01].*unit quaternion"):
        quadruped.rnea(bad, v, a)
    with pytest.raises(ValueError, match=r"q\[3:7\]"):
        quadruped.crba(np.zeros(quadruped.nq))


def test_a_kernel_not_compiled_raises():
    model = rne.load("planar-elbow", kernels=["inverse_dynamics"])
    with pytest.raises(ValueError, match=r"no `mass_matrix` kernel.*kernels="):
        model.crba([0.0, 0.0])


def test_load_errors():
    with pytest.raises(FileNotFoundError, match=r"nor a built-in robot: planar-elbow"):
        rne.load("no-such-robot.urdf")
    with pytest.raises(TypeError, match=r"built-in name or a path"):
        rne.load(42)
    with pytest.raises(ValueError, match=r"mimic must be"):
        rne.load("ur5", mimic="loose")
    with pytest.raises(ValueError, match=r"parameters must be"):
        rne.load("ur5", parameters="variable")
    with pytest.raises(ValueError, match=r"gravity needs 3 values"):
        rne.load("ur5", gravity=[0, 0])
    with pytest.raises(ValueError, match=r"gravity must be finite"):
        rne.load("ur5", gravity=[0, 0, np.nan])
    with pytest.raises(ValueError, match=r"lock: the value of `elbow_joint` must be finite"):
        rne.load("ur5", lock={"elbow_joint": np.inf})
    with pytest.raises(ValueError, match=r"no_such_joint"):
        rne.load("ur5", lock={"no_such_joint": 0.0})
    with pytest.raises(ValueError, match=r"no_such_link"):
        rne.load("ur5", frames=["no_such_link"])
    with pytest.raises(ValueError, match=r"unknown kernel `rnea`"):
        rne.load("ur5", kernels=["rnea"])


def test_a_malformed_robot_file_raises(tmp_path):
    path = tmp_path / "broken.urdf"
    path.write_text("<robot name='x'><link name='a'></robot>")
    with pytest.raises(ValueError, match=r"broken\.urdf"):
        rne.load(str(path))
    toml = tmp_path / "bad.toml"
    toml.write_text("this is not toml = = =")
    with pytest.raises(ValueError, match=r"bad\.toml"):
        rne.load(toml)


def test_bad_parameters_raise(ur5):
    with pytest.raises(ValueError, match=r"`standard` has 3 values"):
        ur5.base_parameters([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"`values` has 2 values"):
        ur5.set_parameters([1.0, 2.0])
    with pytest.raises(ValueError, match=r"frame `nowhere`"):
        ur5.frame_index("nowhere")


def test_identification_errors(ur5, states):
    q, v, a, tau = states
    with pytest.raises(ValueError, match=r"`q` must be 2-D"):
        rne.identify(ur5, q[0], v, a, tau)
    with pytest.raises(ValueError, match=r"`tau` must be 2-D with one row per sample"):
        rne.identify(ur5, q, v, a, tau[:2])
    with pytest.raises(ValueError, match=r"q_limit: 2 values for 6 joints"):
        rne.excitation(ur5, q_limit=[1.0, 2.0], iterations=1)
    with pytest.raises(ValueError, match=r"values for .* base parameters"):
        rne.validate(ur5, [1.0, 2.0], q, v, a, tau)
    with pytest.raises(ValueError, match=r"excite every base parameter"):
        rne.identify(ur5, q, v, a, tau)
