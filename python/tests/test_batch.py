"""Batches equal loops of single calls bit for bit, threads equal one thread, and the arrays
numpy users pass (non-contiguous, Fortran-ordered, lists, integers, float32) are read as
float64 values."""
import numpy as np
import pytest

from conftest import random_states

N = 57  # not a multiple of the thread count: uneven shares
# Enough states that even the cheaper kernels are worth several threads (a batch takes one
# thread per 100 000 operations of the kernel's program); odd, for uneven shares.
N_THREADED = 2001


def kernels(model):
    """(name, arguments) of every state kernel, for states (q, v, a, tau)."""
    return [
        ("rnea", "qva"), ("crba", "q"), ("nonLinearEffects", "qv"),
        ("computeGeneralizedGravity", "q"), ("coriolis_matrix", "qv"), ("aba", "qvt"),
        ("computeMinverse", "q"), ("computeRNEADerivatives", "qva"),
        ("computeABADerivatives", "qvt"), ("framePlacements", "q"), ("frameJacobians", "q"),
        ("frameJacobianTimeVariationDotV", "qv"), ("friction_torques", "v"),
        ("computeJointTorqueRegressor", "qva"), ("base_regressor", "qva"),
        ("computeKineticEnergy", "qv"), ("computePotentialEnergy", "q"),
    ]


def arguments(spec, q, v, a, tau):
    return [{"q": q, "v": v, "a": a, "t": tau}[c] for c in spec]


def as_tuple(x):
    return x if isinstance(x, tuple) else (x,)


def bits(x):
    return np.asarray(x, dtype=np.float64).tobytes()


@pytest.mark.parametrize("robot", ["ur5", "panda", "quadruped"])
def test_batches_equal_loops_and_threads_equal_one_thread(robot, request):
    model = request.getfixturevalue(robot)
    q, v, a, tau = random_states(model, N, seed=3)
    for name, spec in kernels(model):
        f = getattr(model, name)
        batch = as_tuple(f(*arguments(spec, q, v, a, tau)))
        for k in range(N):
            one = as_tuple(f(*arguments(spec, q[k], v[k], a[k], tau[k])))
            assert len(one) == len(batch)
            for b, o in zip(batch, one):
                assert b.shape[0] == N and b.shape[1:] == np.shape(o), name
                assert bits(b[k]) == bits(o), f"{name}: state {k}"
    q, v, a, tau = random_states(model, N_THREADED, seed=4)
    for name, spec in kernels(model):
        f = getattr(model, name)
        one = as_tuple(f(*arguments(spec, q, v, a, tau)))
        for threads in (2, 3, 0):
            threaded = as_tuple(f(*arguments(spec, q, v, a, tau), threads=threads))
            for b, t in zip(one, threaded):
                assert bits(b) == bits(t), f"{name}: {threads} threads"
            assert all(t.flags.c_contiguous for t in threaded), name


def test_results_are_fresh_contiguous_writeable_float64_arrays(ur5):
    # A batch's arrays own their memory through a base object of rne's (which hands it to the
    # next batch once the array is freed): each its own, sharing memory with nothing given.
    q, v, a, _ = random_states(ur5, 4, seed=1)
    results = (ur5.rnea(q[0], v[0], a[0]), ur5.crba(q), *ur5.computeRNEADerivatives(q, v, a))
    for k, result in enumerate(results):
        assert result.dtype == np.float64 and result.flags.c_contiguous and result.flags.writeable
        assert result.flags.owndata or type(result.base).__name__ == "_BatchValues"
        for other in (q, v, a, *results[k + 1:]):
            assert not np.shares_memory(result, other)
    big = 3000  # above the size from which batches' memory is kept
    q, v, a, _ = random_states(ur5, big, seed=3)
    first = ur5.rnea(q, v, a)
    kept = first.copy()
    second = ur5.rnea(q[::-1], v[::-1], a[::-1])
    assert not np.shares_memory(first, second)
    assert bits(first) == bits(kept), "a live result is never reused"
    del first
    assert bits(ur5.rnea(q, v, a)) == bits(kept), "memory given back gives the same values"
    assert isinstance(ur5.computeKineticEnergy(q[0], v[0]), float)
    assert ur5.computeKineticEnergy(q, v).shape == (big,)


def test_an_empty_batch_gives_empty_results(ur5):
    empty = np.zeros((0, ur5.nq))
    assert ur5.rnea(empty, empty, empty).shape == (0, ur5.nv)
    assert ur5.crba(empty, threads=2).shape == (0, ur5.nv, ur5.nv)
    dq, dv = ur5.computeRNEADerivatives(empty, empty, empty)
    assert dq.shape == dv.shape == (0, ur5.nv, ur5.nv)


def test_non_contiguous_and_converted_inputs_give_the_same_bits(ur5):
    q, v, a, _ = random_states(ur5, 5, seed=2)
    expected = ur5.rnea(q, v, a)
    wide = np.zeros((5, 2 * ur5.nq))
    wide[:, ::2] = q  # every other column: strided rows
    assert not wide[:, ::2].flags.c_contiguous
    assert bits(ur5.rnea(wide[:, ::2], v, a)) == bits(expected)
    assert bits(ur5.rnea(np.asfortranarray(q), v, a)) == bits(expected)
    assert bits(ur5.rnea(q[::-1], v[::-1], a[::-1])[::-1]) == bits(expected)
    assert bits(ur5.rnea(q[0].tolist(), list(v[0]), tuple(a[0]))) == bits(expected[0])
    big_endian = q.astype(">f8")
    assert bits(ur5.rnea(big_endian, v, a)) == bits(expected)
    ints = np.arange(ur5.nq)
    assert bits(ur5.crba(ints)) == bits(ur5.crba(ints.astype(float)))
    q32 = q.astype(np.float32)
    assert bits(ur5.crba(q32)) == bits(ur5.crba(q32.astype(np.float64)))
    # float64 values at an odd address (numpy's `aligned` flag off) are copied, not read in place.
    raw = np.zeros(q.size * 8 + 1, dtype=np.uint8)
    unaligned = raw[1:].view(np.float64).reshape(q.shape)
    unaligned[...] = q
    assert not unaligned.flags.aligned
    assert bits(ur5.rnea(unaligned, v, a)) == bits(expected)
    assert bits(ur5.rnea(unaligned[0], v[0], a[0])) == bits(expected[0])


def test_the_input_arrays_are_not_modified(ur5):
    q, v, a, _ = random_states(ur5, 3, seed=5)
    copies = [x.copy() for x in (q, v, a)]
    ur5.rnea(q, v, a, threads=2)
    for x, c in zip((q, v, a), copies):
        assert bits(x) == bits(c)


def test_a_batch_releases_the_gil():
    """While a worker thread's batch runs, the main thread runs Python: the GIL is released
    for the kernels (with it held, the main thread could not run between the worker's entry
    into the call, plus one switch interval, and its return)."""
    import sys
    import threading
    import time

    import rne

    model = rne.load("panda", kernels=["inverse_dynamics_derivatives"])
    q, v, a, _ = random_states(model, 20000, seed=4)
    window = []

    def work():
        window.append(time.perf_counter())
        model.computeRNEADerivatives(q, v, a)
        window.append(time.perf_counter())

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        for _ in range(200):
            pass
    worker.join()
    margin = 2 * sys.getswitchinterval()
    enter, leave = window
    assert leave - enter > 4 * margin, "the batch is too short to tell"
    during = [t for t in ticks if enter + margin < t < leave - margin]
    assert len(during) > 10, f"the main thread ran {len(during)} times during the batch"
