"""Shared fixtures: the models the tests use (compiled once per session), seeded states, and
the `rne` command of the same checkout for bit-for-bit comparisons."""
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

import rne

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = Path(__file__).resolve().parent / "fixtures"


def rne_binary():
    """The `rne` command built from this checkout: $RNE_BIN, else target/{debug,release}/rne,
    else the one on PATH; None when there is none."""
    candidates = [os.environ.get("RNE_BIN")]
    candidates += [str(ROOT / "target" / p / "rne") for p in ("debug", "release")]
    for c in candidates:
        if c and Path(c).is_file() and os.access(c, os.X_OK):
            return c
    return shutil.which("rne")


def random_states(model, n, seed):
    """n states (q, v, a, tau) with unit quaternions on a floating base."""
    rng = np.random.default_rng(seed)
    q = rng.uniform(-1.5, 1.5, (n, model.nq))
    if model.floating_base:
        quat = rng.normal(size=(n, 4))
        q[:, 3:7] = quat / np.linalg.norm(quat, axis=1, keepdims=True)
    v, a, tau = (rng.uniform(-1, 1, (n, model.nv)) for _ in range(3))
    return q, v, a, tau


@pytest.fixture(scope="session")
def ur5():
    return rne.load("ur5")


@pytest.fixture(scope="session")
def panda():
    return rne.load("panda")


@pytest.fixture(scope="session")
def quadruped():
    return rne.load("quadruped", floating_base=True)
