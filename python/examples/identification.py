"""Identification as `rne identify` does it, from Python: an excitation trajectory optimised
for the condition number of the base regressor, torques simulated with 1 % noise, the base
parameters by weighted least squares, and their prediction on a fresh record.

    python python/examples/identification.py [ROBOT]
"""
import sys

import numpy as np

import rne

model = rne.load(sys.argv[1] if len(sys.argv) > 1 else "irb140-3dof")
data = rne.excitation(model, noise=0.01, seed=1, iterations=100)
print(f"{model.name}: {len(data.t)} samples, condition number {data.condition_number:.3e}")

result = rne.identify(model, data.q, data.v, data.a, data.tau)
print(f"{len(result.values)} base parameters of {result.standard_parameters} standard ones")
print(f"{'':>4}  {'estimate':>12}  {'std/|θ|':>8}  {'model':>12}  combination")
for k, (value, rel, truth, name) in enumerate(
    zip(result.values, result.relative_std(), result.model, result.names)
):
    print(f"b{k + 1:<3}  {value:12.5e}  {100 * rel:7.2f} %  {truth:12.5e}  {name}")

fresh = rne.excitation(model, noise=0.01, seed=2, iterations=100)
check = rne.validate(model, result, fresh.q, fresh.v, fresh.a, fresh.tau)
print(f"prediction on a fresh record: RMS torque error {100 * check.relative_rms:.2f} % "
      f"(per joint {np.round(100 * check.joints, 2)} %)")
