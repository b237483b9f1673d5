"""Pinocchio's dynamics of URDF robots at seeded random states, as JSON, for `rne corpus`.

usage: pinocchio_values.py ROBOTS_DIR --out VALUES.json [--states N] [--seed S] [--only SUBSTR]

Every `*.urdf` under ROBOTS_DIR is loaded by Pinocchio twice: bolted to the world and on a
free-flyer (`JointModelFreeFlyer`), both with mimic semantics (`mimic=True`). When Pinocchio
cannot load a file with `mimic=True` (its parser wants every leader before its followers in
the tree) the file is loaded with `mimic=False` and the URDF mimic constraint
q_f = multiplier * q_l + offset is applied by the chain rule on Pinocchio's results:
q_full = q(q_l), v_full = G v, a_full = G a, tau = G^T rnea(q_full, G v, G a), M = G^T M G.
When even that cannot apply (a follower of a joint the file does not have, or a loop of
followers), every follower stays a joint of its own (`mimic=False`, "mode": "free"), which
`rne corpus` compares with rne's reading with mimic joints free.

Each state is written in a layout that does not depend on Pinocchio's: `joints` lists the joint
variables by URDF name in Pinocchio's velocity order; `q` holds one angle or distance per joint
(a continuous joint, which Pinocchio stores as (cos, sin), as its angle), after the seven
free-flyer entries [x, y, z, qx, qy, qz, qw] on a floating base; `v`, `a`, `tau` and every
output hold one entry per velocity (the free-flyer's six first, in its body frame). Outputs:
`tau` = RNEA(q, v, a), `M` (CRBA, made symmetric), `g` (generalized gravity), `bias`
(nonLinearEffects(q, v)), `qdd` = forward dynamics at `tau_fd` (ABA, or M⁻¹(tau - bias) for
models with mimic joints, which Pinocchio's ABA cannot do; null when M is singular).

Seeds: each file's states come from numpy's default_rng([seed, crc32(relative path)]), so a
file's values do not depend on which other files are in the directory.
"""
import argparse
import glob
import json
import os
import sys
import time
import xml.etree.ElementTree as ET
import zlib

import numpy as np
import pinocchio as pin


def urdf_mimics(path):
    """{follower: (leader, multiplier, offset)} of the moving joints' <mimic> elements."""
    mimics = {}
    for joint in ET.parse(path).getroot().iter("joint"):
        mimic = joint.find("mimic")
        if mimic is None or joint.get("type") == "fixed":
            continue
        mimics[joint.get("name")] = (
            mimic.get("joint"),
            float(mimic.get("multiplier", 1.0)),
            float(mimic.get("offset", 0.0)),
        )
    return mimics


def root_leader(mimics, name):
    """The joint `name` follows through chains, with the composed multiplier and offset."""
    multiplier, offset, seen = 1.0, 0.0, {name}
    while name in mimics:
        leader, m, o = mimics[name]
        if leader in seen:
            raise ValueError(f"mimic loop through {leader}")
        multiplier, offset = multiplier * m, multiplier * o + offset
        name = leader
        seen.add(name)
    return name, multiplier, offset


class Layout:
    """Pinocchio's joints with a velocity, and how a joint-name layout maps onto them."""

    def __init__(self, model):
        self.model = model
        self.joints = []  # (name, idx_q, nq, idx_v, kind)
        self.floating = False
        for j in range(1, model.njoints):
            jm = model.joints[j]
            if jm.nv == 0:
                continue  # a mimic joint of Pinocchio's own
            if jm.shortname() == "JointModelFreeFlyer":
                self.floating = True
                continue
            self.joints.append((model.names[j], jm.idx_q, jm.nq, jm.idx_v, jm.shortname()))

    def configuration(self, base, angles):
        """Pinocchio's q from a base configuration and one value per joint of this layout."""
        q = np.zeros(self.model.nq)
        if self.floating:
            q[:7] = base
        for k, (_, iq, nq, _, _) in enumerate(self.joints):
            if nq == 2:
                q[iq:iq + 2] = [np.cos(angles[k]), np.sin(angles[k])]
            else:
                q[iq] = angles[k]
        return q

    def velocity_order(self):
        """Index in Pinocchio's v of each entry of this layout's velocity."""
        order = list(range(6)) if self.floating else []
        return order + [iv for (_, _, _, iv, _) in self.joints]


def projection(full, mimics):
    """For a model loaded with mimic=False: the reduced joint names, G (nv_full x nv_red) and
    the map from reduced joint values to the full ones."""
    names = [name for (name, *_rest) in full.joints]
    followers = {n: root_leader(mimics, n) for n in names if n in mimics}
    reduced = [n for n in names if n not in followers]
    offset = 6 if full.floating else 0
    order = full.velocity_order()
    G = np.zeros((full.model.nv, offset + len(reduced)))
    for k in range(offset):
        G[k, k] = 1.0
    for k, name in enumerate(names):
        leader, m, _ = followers.get(name, (name, 1.0, 0.0))
        G[order[offset + k], offset + reduced.index(leader)] = m

    def expand(angles):
        values = dict(zip(reduced, angles))
        return [
            values[followers[n][0]] * followers[n][1] + followers[n][2] if n in followers else values[n]
            for n in names
        ]

    return reduced, G, expand


def evaluate(path, rel, floating, states, seed):
    root = [pin.JointModelFreeFlyer()] if floating else []
    mimics = urdf_mimics(path)
    mode = "none" if not mimics else "pinocchio"
    try:
        model = pin.buildModelFromUrdf(path, *root, mimic=bool(mimics))
    except Exception as e:  # noqa: BLE001 - Pinocchio raises plain exceptions
        if not mimics:
            return {"error": str(e).strip()}
        try:
            model = pin.buildModelFromUrdf(path, *root, mimic=False)
            mode = "projected"
        except Exception as e2:  # noqa: BLE001
            return {"error": str(e2).strip()}
    layout = Layout(model)
    data = model.createData()
    if mode == "projected":
        try:
            names, G, expand = projection(layout, mimics)
        except (ValueError, KeyError):
            # A mimic joint that follows no moving joint of the file (or a loop of them) has
            # no URDF meaning: every follower stays a joint of its own, Pinocchio's default,
            # compared with rne's `mimic: free`.
            mode = "free"
    if mode != "projected":
        names = [name for (name, *_rest) in layout.joints]
        nv = model.nv
        order = layout.velocity_order()
        G = np.zeros((nv, nv))
        for k, iv in enumerate(order):
            G[iv, k] = 1.0
        expand = lambda angles: list(angles)  # noqa: E731
    nv = G.shape[1]
    njoints = len(names)
    if nv == 0:
        return {"joints": [], "nv": 0, "mimic": mode, "states": []}
    rng = np.random.default_rng([seed, zlib.crc32(rel.encode()), int(floating)])
    out = []
    for _ in range(states):
        base = None
        if floating:
            quat = rng.normal(size=4)
            quat /= np.linalg.norm(quat)
            base = np.concatenate([rng.uniform(-1, 1, 3), quat])
        angles = rng.uniform(-1.5, 1.5, njoints)
        v, a, tau_fd = (rng.uniform(-1, 1, nv) for _ in range(3))
        q_full = layout.configuration(base, expand(angles))
        v_full, a_full = G @ v, G @ a
        tau = G.T @ pin.rnea(model, data, q_full, v_full, a_full)
        M_full = pin.crba(model, data, q_full)
        M_full = np.triu(M_full) + np.triu(M_full, 1).T
        M = G.T @ M_full @ G
        g = G.T @ pin.computeGeneralizedGravity(model, data, q_full)
        bias = G.T @ pin.nonLinearEffects(model, data, q_full, v_full)
        qdd = None
        if np.linalg.cond(M) < 1e10:
            if mode in ("none", "free"):
                qdd = pin.aba(model, data, q_full, v_full, G @ tau_fd)[layout.velocity_order()]
            else:
                qdd = np.linalg.solve(M, tau_fd - bias)
        out.append({
            "base": None if base is None else base.tolist(),
            "q": angles.tolist(), "v": v.tolist(), "a": a.tolist(), "tau_fd": tau_fd.tolist(),
            "tau": tau.tolist(), "M": M.tolist(), "g": g.tolist(), "bias": bias.tolist(),
            "qdd": None if qdd is None else np.asarray(qdd).tolist(),
        })
    return {"joints": names, "nv": nv, "mimic": mode, "states": out}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("robots")
    ap.add_argument("--out", required=True)
    ap.add_argument("--states", type=int, default=4)
    ap.add_argument("--seed", type=int, default=2024)
    ap.add_argument("--only", default="")
    args = ap.parse_args()
    files = sorted(glob.glob(os.path.join(args.robots, "**", "*.urdf"), recursive=True))
    robots = []
    for path in files:
        rel = os.path.relpath(path, args.robots)
        if args.only not in rel:
            continue
        entry = {"file": rel}
        for base in ("fixed", "floating"):
            start = time.perf_counter()
            entry[base] = evaluate(path, rel, base == "floating", args.states, args.seed)
            entry[base]["pinocchio_ms"] = (time.perf_counter() - start) * 1e3
        robots.append(entry)
        print(rel, entry["fixed"].get("nv", entry["fixed"].get("error")), file=sys.stderr)
    with open(args.out, "w") as f:
        json.dump({"pinocchio": pin.__version__, "seed": args.seed, "states": args.states,
                   "robots": robots}, f)


if __name__ == "__main__":
    main()
