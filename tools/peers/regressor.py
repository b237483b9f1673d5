"""Pinocchio's joint-torque regressor at seeded states, as JSON: the expected values of
tests/tests/regressor_pinocchio.rs (CI has no Python, so the output is committed).

usage: regressor.py ROBOT.urdf [--states N] [--seed S] > expected.json

Pinocchio (4.1) loads the URDF with a fixed base and no mimic constraints; for each state it
calls computeJointTorqueRegressor(model, data, q, v, a): nv rows, ten columns per joint
(m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz about the joint frame's origin, in its axes).
States: q uniform in [-pi, pi], v and a uniform in [-2, 2], from numpy's PCG64 with the seed.
Every float is printed by repr(), so it reads back bit for bit."""
import argparse
import json
import os

import numpy as np
import pinocchio as pin

parser = argparse.ArgumentParser()
parser.add_argument("urdf")
parser.add_argument("--states", type=int, default=3)
parser.add_argument("--seed", type=int, default=14)
args = parser.parse_args()

model = pin.buildModelFromUrdf(args.urdf)
data = model.createData()
rng = np.random.default_rng(args.seed)
states = []
for _ in range(args.states):
    q = rng.uniform(-np.pi, np.pi, model.nq)
    v = rng.uniform(-2.0, 2.0, model.nv)
    a = rng.uniform(-2.0, 2.0, model.nv)
    y = pin.computeJointTorqueRegressor(model, data, q, v, a)
    states.append({"q": q.tolist(), "v": v.tolist(), "a": a.tolist(), "regressor": y.tolist()})
print(json.dumps({
    "pinocchio": pin.__version__,
    "urdf": os.path.basename(args.urdf),
    "seed": args.seed,
    "gravity": model.gravity.linear.tolist(),
    "joints": [model.names[j] for j in range(1, model.njoints)],
    "states": states,
}))
