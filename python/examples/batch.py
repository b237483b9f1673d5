"""A batch of 10 000 states: inverse dynamics, forward dynamics and the derivatives of the
inverse dynamics in one call each, with the GIL released, on one and on two threads; the
batch equals a loop of single calls bit for bit.

    python python/examples/batch.py [ROBOT]
"""
import sys
import time

import numpy as np

import rne

model = rne.load(sys.argv[1] if len(sys.argv) > 1 else "ur5")
rng = np.random.default_rng(0)
n = 10_000
q = rng.uniform(-np.pi, np.pi, (n, model.nq))
v, a = rng.uniform(-1, 1, (n, model.nv)), rng.uniform(-1, 1, (n, model.nv))

for threads in (1, 2):
    start = time.perf_counter()
    tau = model.rnea(q, v, a, threads=threads)
    qdd = model.aba(q, v, tau, threads=threads)
    dtau_dq, dtau_dv = model.computeRNEADerivatives(q, v, a, threads=threads)
    elapsed = time.perf_counter() - start
    print(f"{model.name}, {n} states, {threads} thread(s): rnea + aba + derivatives in {1e3 * elapsed:.1f} ms")

print("forward dynamics undoes inverse dynamics:", np.max(np.abs(qdd - a)))
loop = np.array([model.rnea(q[k], v[k], a[k]) for k in range(100)])
assert loop.tobytes() == tau[:100].tobytes(), "a batch is a loop of single calls, bit for bit"
print("batch == loop of single calls, bit for bit; dtau_dq:", dtau_dq.shape)
