"""rne: exact, fast robot dynamics from Python.

A robot (a built-in name or a URDF / rne TOML file) is read and every kernel of its dynamics
is compiled in memory to machine code for this processor (rne's JIT): the Newton-Euler
recursion of Høifødt, *Dynamics of robot manipulators by the Newton-Euler formulation* (NTNU,
2010), generated as optimised straight-line programs. ``rne.load`` returns a
:class:`Model` whose kernels carry Pinocchio's names (``rnea``, ``crba``, ``aba``,
``computeRNEADerivatives`` ...) and snake_case aliases, and take numpy arrays: a 1-D ``q`` is
one state, a 2-D ``(N, nq)`` array N states computed with the GIL released, optionally on
several threads (``threads=``).

>>> import numpy as np, rne
>>> model = rne.load("ur5")
>>> q = np.zeros(model.nq); v = np.zeros(model.nv)
>>> tau = model.rnea(q, v, v)

Identification (``excitation``, ``identify``, ``validate``) is the ``rne identify`` command's
on numpy arrays. docs/python.md maps every function to Pinocchio's and states the conventions.
"""
from ._rne import Model, builtin_robots, kernel_names, load
from .identification import Excitation, Identification, Validation, excitation, identify, validate

#: The built-in robots' names, for :func:`load`.
BUILTIN_ROBOTS = tuple(builtin_robots())

#: The kernels rne can compile (rne's names), for ``load(..., kernels=[...])``.
KERNELS = tuple(kernel_names())

__all__ = [
    "BUILTIN_ROBOTS",
    "KERNELS",
    "Excitation",
    "Identification",
    "Model",
    "Validation",
    "excitation",
    "identify",
    "load",
    "validate",
]
