"""rne's Python kernels beside Pinocchio's Python bindings, in one process on one machine:
inverse dynamics (ID), forward dynamics (FD) and the derivatives of ID (dID) of UR5 and the
Panda arm (rne-models/robots, the same URDF files for both) over batches of 1, 100 and 10 000
states, against a Python loop of `pin.rnea` / `pin.aba` / `pin.computeRNEADerivatives` and
against `pin.rneaInParallel` / `pin.abaInParallel` at the same thread count, and against a
Python loop of MuJoCo's `mj_rne` (ID) and `mj_forward` (FD) on the same URDF; then one call's
time against the kernel's own (a state's share of a 10 000-state batch on one thread, one
state a call). rne's batches compute two states a call (SIMD lanes); the first column times
them one state a call (`RNE_JIT_LANES=1`), for what the lanes gain.

usage: PYTHON bench.py [--threads T] [--repeats R]     (from the repository root)

PYTHON must import both `rne` (pip install python/) and `pinocchio`, and `mujoco` for its
column (left empty, saying so, without it); docs/python.md gives the command and the table it
printed. Times are the best of R repetitions, in µs per state:
one thread's by the process's CPU time (time.process_time: what a run costs, whatever else the
machine runs), the threaded ones' by wall time (time.perf_counter). The cells of a table row
are timed in alternation, one run of each per repetition, so that the ratios compare the same
minutes of a noisy machine.
"""
import argparse
import os
import platform
import sys
import time
import timeit

# Python puts this script's folder first on the path, and that folder holds the package's
# sources (python/rne) with whatever extension `maturin develop` last built there: the rne
# to time is the installed one, so that first entry goes (the header prints which rne was
# taken; an editable install still finds its folder through its own path entry).
if sys.path and os.path.abspath(sys.path[0]) == os.path.dirname(os.path.abspath(__file__)):
    del sys.path[0]

# Pinocchio's OpenMP threads sleep between parallel calls instead of spinning, which would add
# their CPU time to the one-thread measurements that follow (set before OpenMP starts).
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402
import pinocchio as pin  # noqa: E402

import rne  # noqa: E402

try:
    import mujoco  # noqa: E402
except ImportError:
    mujoco = None

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROBOTS = [("UR5", "rne-models/robots/ur5.urdf"), ("Panda arm", "rne-models/robots/panda-arm.urdf")]
SIZES = [1, 100, 10_000]
KERNELS = ["inverse_dynamics", "forward_dynamics", "inverse_dynamics_derivatives"]


def best(f, repeats, clock=time.perf_counter, number=1):
    """The shortest of `repeats` runs of `number` calls of f(), s per call, by `clock`."""
    return min(timeit.repeat(f, timer=clock, number=number, repeat=repeats)) / number


def alternating(cases, repeats):
    """The shortest time of each of `cases` over `repeats` rounds, s per call: a case is
    (f, clock, number), `number` calls of f() timed by `clock` (time.process_time for one
    thread, time.perf_counter for several), or None (its time None). Within a round the
    cases run one after the other (f₁, f₂, …, f₁, f₂, …), so that a slow spell of the machine
    falls on all of them alike and the ratios of a row compare runs of the same minutes."""
    times = [[] for _ in cases]
    for _ in range(repeats):
        for case, t in zip(cases, times):
            if case is not None:
                f, clock, number = case
                t.append(best(f, 1, clock, number))
    return [min(t) if t else None for t in times]


def states(model, n, seed=0):
    rng = np.random.default_rng(seed)
    q = rng.uniform(-np.pi, np.pi, (n, model.nq))
    v, a = rng.uniform(-1, 1, (n, model.nv)), rng.uniform(-1, 1, (n, model.nv))
    return q, v, a


class Peer:
    """Pinocchio on the same URDF: a loop of calls and the parallel functions."""

    def __init__(self, path, threads):
        self.model = pin.buildModelFromUrdf(path)
        self.data = self.model.createData()
        self.pool = pin.ModelPool(self.model, threads)
        self.threads = threads

    def loop(self, f, *arrays):
        m, d = self.model, self.data
        return lambda: [f(m, d, *row) for row in zip(*arrays)]

    def parallel(self, f, *arrays):
        columns = [np.asfortranarray(x.T) for x in arrays]
        out = np.asfortranarray(np.zeros((self.model.nv, arrays[0].shape[0])))
        return lambda: f(self.threads, self.pool, *columns, out)


class MuJoCo:
    """MuJoCo on the same URDF (its compiler reads URDF): a Python loop of calls, one state at a
    time. ID is `mj_rne` with the accelerations after the position and velocity stages it
    reads (`mj_kinematics`, `mj_comPos`, `mj_comVel`); FD is `mj_forward` with the constraint
    stage off (the URDF's joint limits would otherwise act: rne's FD has none), τ as
    `qfrc_applied`. The URDFs have no damping, armature or friction, so both compute what rne
    does (checked in `main`)."""

    def __init__(self, path):
        self.model = mujoco.MjModel.from_xml_path(path)
        self.model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONSTRAINT
        self.data = mujoco.MjData(self.model)

    def rnea(self, q, v, a):
        m, d = self.model, self.data
        d.qpos[:], d.qvel[:], d.qacc[:] = q, v, a
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        mujoco.mj_comVel(m, d)
        out = np.empty(m.nv)
        mujoco.mj_rne(m, d, 1, out)
        return out

    def aba(self, q, v, tau):
        m, d = self.model, self.data
        d.qpos[:], d.qvel[:], d.qfrc_applied[:] = q, v, tau
        mujoco.mj_forward(m, d)
        return d.qacc.copy()

    def loop(self, f, *arrays):
        return lambda: [f(*row) for row in zip(*arrays)]


def agree(ours, theirs, what, tolerance):
    """Asserts that the peer computes what rne does, relative to the largest entry."""
    ours, theirs = np.asarray(ours), np.asarray(theirs)
    error = np.max(np.abs(ours - theirs)) / np.max(np.abs(ours))
    assert error < tolerance, f"{what}: relative difference {error:.1e}"
    return error


def scalar_model(path):
    """The same kernels with batches one state a call (`RNE_JIT_LANES=1`, read when a model
    is compiled): a kernel's own time per state, and what the two lanes gain."""
    os.environ["RNE_JIT_LANES"] = "1"
    try:
        return rne.load(path, kernels=KERNELS)
    finally:
        del os.environ["RNE_JIT_LANES"]


def lane_compile_ms(model):
    """Per kernel, a fresh model's first 100-state batch less its second, in ms: the time to
    compile the kernel's two-lane version, which the first batch does."""
    q, v, a = states(model, 100)
    tau = model.rnea(q[0], v[0], a[0])
    calls = {"ID": lambda: model.rnea(q, v, a),
             "FD": lambda: model.aba(q, v, np.tile(tau, (100, 1))),
             "dID": lambda: model.computeRNEADerivatives(q, v, a)}
    times = {}
    for kernel, f in calls.items():
        first = best(f, 1)
        times[kernel] = (first - best(f, 3)) * 1e3
    return times


def batch_rows(name, model, scalar, peer, mj, threads, repeats):
    rows = []
    for n in SIZES:
        q, v, a = states(model, n)
        tau = model.rnea(q, v, a)
        # Each run covers 10 000 states (10 000 calls of one state, 100 of 100), so that the
        # process clock's resolution is far below a run.
        r, number = max(repeats, 3), 10_000 // n
        cases = [
            ("ID", lambda: model.rnea(q, v, a), lambda: scalar.rnea(q, v, a),
             lambda: model.rnea(q, v, a, threads=threads),
             peer.loop(pin.rnea, q, v, a), peer.parallel(pin.rneaInParallel, q, v, a),
             mj and mj.loop(mj.rnea, q, v, a)),
            ("FD", lambda: model.aba(q, v, tau), lambda: scalar.aba(q, v, tau),
             lambda: model.aba(q, v, tau, threads=threads),
             peer.loop(pin.aba, q, v, tau), peer.parallel(pin.abaInParallel, q, v, tau),
             mj and mj.loop(mj.aba, q, v, tau)),
            ("dID", lambda: model.computeRNEADerivatives(q, v, a),
             lambda: scalar.computeRNEADerivatives(q, v, a),
             lambda: model.computeRNEADerivatives(q, v, a, threads=threads),
             peer.loop(pin.computeRNEADerivatives, q, v, a), None, None),
        ]
        cpu_clock, wall = time.process_time, time.perf_counter
        for kernel, ours, ours_scalar, ours_t, loop, parallel, mj_loop in cases:
            timed = alternating([
                (ours, cpu_clock, number), (ours_scalar, cpu_clock, number),
                (ours_t, wall, number), (loop, cpu_clock, number),
                parallel and (parallel, wall, number), mj_loop and (mj_loop, cpu_clock, number),
            ], r)
            t1, ts, tt, tl, tp, tm = (t and t / n * 1e6 for t in timed)
            rows.append((name, kernel, n, ts, t1, tt, tl, tp, tm))
    return rows


def single_rows(name, model, scalar, peer, mj, repeats):
    """One call (1-D arrays) against the kernel's own time (a share of a 10 000-state batch
    one state a call, as a single call computes it)."""
    q, v, a = states(model, 10_000)
    tau = model.rnea(q, v, a)
    q0, v0, a0, t0 = q[0], v[0], a[0], tau[0]
    m, d = peer.model, peer.data
    calls = 20_000
    rows = []
    for kernel, one, batch, theirs, mj_one in [
        ("ID", lambda: model.rnea(q0, v0, a0), lambda: scalar.rnea(q, v, a),
         lambda: pin.rnea(m, d, q0, v0, a0), mj and (lambda: mj.rnea(q0, v0, a0))),
        ("FD", lambda: model.aba(q0, v0, t0), lambda: scalar.aba(q, v, tau),
         lambda: pin.aba(m, d, q0, v0, t0), mj and (lambda: mj.aba(q0, v0, t0))),
        ("dID", lambda: model.computeRNEADerivatives(q0, v0, a0),
         lambda: scalar.computeRNEADerivatives(q, v, a),
         lambda: pin.computeRNEADerivatives(m, d, q0, v0, a0), None),
    ]:
        clock = time.process_time
        call, own, pin_call, mj_call = alternating([
            (one, clock, calls), (batch, clock, 1), (theirs, clock, calls),
            mj_one and (mj_one, clock, calls),
        ], max(repeats, 3))
        call, own, pin_call = call * 1e6, own / 10_000 * 1e6, pin_call * 1e6
        mj_call = mj_call and mj_call * 1e6
        rows.append((name, kernel, call, own, call - own, pin_call, mj_call))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--threads", type=int, default=os.cpu_count())
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    print(f"# {platform.processor() or platform.machine()}, {os.cpu_count()} cores; "
          f"Python {platform.python_version()}, numpy {np.__version__}, Pinocchio {pin.__version__}, "
          f"MuJoCo {mujoco.__version__ if mujoco else 'not installed'}; {args.threads} threads; "
          f"rne from {os.path.dirname(rne.__file__)}\n")
    batch, single = [], []
    for name, file in ROBOTS:
        path = os.path.join(ROOT, file)
        model, scalar = rne.load(path, kernels=KERNELS), scalar_model(path)
        lanes = lane_compile_ms(rne.load(path, kernels=KERNELS))
        print(f"{name}: a kernel's first batch compiles its lanes: "
              + ", ".join(f"{k} {ms:.1f} ms" for k, ms in lanes.items()))
        peer = Peer(path, args.threads)
        q, v, a = states(model, 3)
        assert np.allclose(model.rnea(q, v, a), [pin.rnea(peer.model, peer.data, *s) for s in zip(q, v, a)])
        mj = MuJoCo(path) if mujoco else None
        if mj:
            # MuJoCo's compiler turns each inertia to its principal axes (an eigendecomposition
            # to about 1e-10 for the Panda arm's), hence the tolerances.
            tau = model.rnea(q, v, a)
            errors = (agree(tau, [mj.rnea(*s) for s in zip(q, v, a)], f"{name} mj_rne", 1e-8),
                      agree(model.aba(q, v, tau), [mj.aba(*s) for s in zip(q, v, tau)],
                            f"{name} mj_forward", 1e-6))
            print(f"{name}: MuJoCo's ID and FD differ from rne's by {errors[0]:.1e} and "
                  f"{errors[1]:.1e} relative to the largest entry")
        batch += batch_rows(name, model, scalar, peer, mj, args.threads, args.repeats)
        single += single_rows(name, model, scalar, peer, mj, args.repeats)
    t = args.threads
    print(f"| robot | kernel | states | rne, 1 thread, 1 state a call | rne, 1 thread | rne, {t} threads | Pinocchio loop | "
          f"Pinocchio InParallel, {t} threads | MuJoCo loop | loop / rne {t}t | InParallel / rne {t}t | "
          f"MuJoCo loop / rne {t}t |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, kernel, n, ts, t1, tt, tl, tp, tm in batch:
        par, ratio = (f"{tp:.3f}", f"{tp / tt:.1f}×") if tp else ("—", "—")
        mj, mj_ratio = (f"{tm:.3f}", f"{tm / tt:.1f}×") if tm else ("—", "—")
        print(f"| {name} | {kernel} | {n} | {ts:.3f} | {t1:.3f} | {tt:.3f} | {tl:.3f} | {par} | {mj} | "
              f"{tl / tt:.1f}× | {ratio} | {mj_ratio} |")
    print("\nµs per state, best of the repetitions: CPU time of the process for the one-thread "
          "columns, wall time for the threaded ones; rne computes two states a call (SIMD lanes) "
          "but in the first column.\n")
    print("| robot | kernel | rne, one call (1-D) | rne kernel's own time | overhead | Pinocchio, one call | "
          "MuJoCo, one call |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for name, kernel, call, own, over, pin_call, mj_call in single:
        mj = f"{mj_call:.3f}" if mj_call else "—"
        print(f"| {name} | {kernel} | {call:.3f} | {own:.3f} | {over:.3f} | {pin_call:.3f} | {mj} |")
    print("\nµs per call (CPU time); the kernel's own time is a state's share of a 10 000-state "
          "batch on one thread, one state a call.")


if __name__ == "__main__":
    main()
