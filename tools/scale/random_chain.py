#!/usr/bin/env python3
"""Write a random serial chain of N revolute joints as an rne TOML spec (seed = N): the
scale test of generation time (`rne stats chainN.toml` generates every kernel of docs/design.md §4).

Random unit joint axes (URDF-style origin and axis), link offsets of 0.1-0.3 m, masses
0.5-5 kg, COMs within 0.1 m of the joint, inertias of random boxes in random orientations
(positive definite, triangle inequality).

    python3 tools/scale/random_chain.py 48 > /tmp/gen-chains/chain48.toml
"""
import math
import random
import sys


def unit(rng):
    while True:
        v = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        if n > 1e-3:
            return [x / n for x in v]


def rotation(rng):
    """A random rotation matrix from a random unit quaternion."""
    w, x, y, z = unit4(rng)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def unit4(rng):
    v = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def inertia(rng, mass):
    """Principal moments of a random box, rotated: positive definite, triangle inequality."""
    a, b, c = (rng.uniform(0.05, 0.3) for _ in range(3))
    d = [mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12, mass * (a * a + b * b) / 12]
    r = rotation(rng)
    return [[sum(r[i][k] * d[k] * r[j][k] for k in range(3)) for j in range(3)] for i in range(3)]


def fmt(x):
    return f"{x:.6f}"


def chain(n):
    rng = random.Random(n)
    out = [f'name = "chain{n}"', 'gravity = [0, 0, -9.81]', ""]
    for i in range(1, n + 1):
        offset = [x * rng.uniform(0.1, 0.3) for x in unit(rng)]
        axis = unit(rng)
        mass = rng.uniform(0.5, 5.0)
        com = [rng.uniform(-0.1, 0.1) for _ in range(3)]
        inr = inertia(rng, mass)
        out += [
            "[[link]]",
            f'name = "link{i}"',
            'joint = "revolute"',
            f'q = "q{i}"',
            f"origin = {{ xyz = [{', '.join(map(fmt, offset))}], rpy = [0, 0, 0] }}",
            f"axis = [{', '.join(map(fmt, axis))}]",
            f"mass = {fmt(mass)}",
            f"com = [{', '.join(map(fmt, com))}]",
            f"inertia = {{ xx = {fmt(inr[0][0])}, yy = {fmt(inr[1][1])}, zz = {fmt(inr[2][2])}, "
            f"xy = {fmt(inr[0][1])}, xz = {fmt(inr[0][2])}, yz = {fmt(inr[1][2])} }}",
            "",
        ]
    return "\n".join(out)


if __name__ == "__main__":
    print(chain(int(sys.argv[1])))
