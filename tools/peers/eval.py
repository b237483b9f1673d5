"""Pinocchio's dynamics of a URDF at one state, as JSON, to set beside `rne eval --json`.

usage: eval.py ROBOT.urdf --q a,b,.. [--qd ..] [--qdd ..]

Pinocchio loads the URDF on a fixed base with its default mimic handling (followers are joints
of their own: compare with `rne eval --mimic free`). Keys: `joints` (Pinocchio's joint names in
its order), `tau` (rnea), `M` (crba, both triangles), `g` (generalized gravity), `bias`
(nonLinearEffects: C q̇ + g) and `C` (Pinocchio's computeCoriolisMatrix: one valid
factorisation, not the Christoffel one rne generates; compare `bias`, not `C`).
"""
import argparse
import json

import numpy as np
import pinocchio as pin


def vector(text, size):
    if not text:
        return np.zeros(size)
    values = np.array([float(x) for x in text.split(",")])
    if len(values) != size:
        raise SystemExit(f"eval.py: expected {size} values, got {len(values)}: {text}")
    return values


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("urdf")
    parser.add_argument("--q", required=True)
    parser.add_argument("--qd")
    parser.add_argument("--qdd")
    args = parser.parse_args()
    model = pin.buildModelFromUrdf(args.urdf)
    data = model.createData()
    q = vector(args.q, model.nq)
    qd, qdd = vector(args.qd, model.nv), vector(args.qdd, model.nv)
    tau = pin.rnea(model, data, q, qd, qdd)
    mass = pin.crba(model, data, q)
    mass = np.triu(mass) + np.triu(mass, 1).T
    print(json.dumps({
        "joints": [model.names[j] for j in range(1, model.njoints)],
        "tau": tau.tolist(),
        "M": mass.tolist(),
        "g": pin.computeGeneralizedGravity(model, data, q).tolist(),
        "bias": pin.nonLinearEffects(model, data, q, qd).tolist(),
        "C": pin.computeCoriolisMatrix(model, data, q, qd).tolist(),
    }))


if __name__ == "__main__":
    main()
