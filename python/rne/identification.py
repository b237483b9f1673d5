"""Identification as ``rne identify`` does it, on numpy arrays.

- :func:`excitation`: a finite Fourier series per joint optimised for the condition number of
  the stacked base regressor within joint limits (Swevers, Ganseman, Tukel, De Schutter and
  Van Brussel, "Optimal robot excitation and identification", IEEE T-RA 13(5), 1997), and the
  measurements a torque sensor with Gaussian noise would record along it.
- :func:`identify`: the base parameters (Gautier's numerical base set) estimated by weighted
  least squares (Gautier and Poignet, "Extended Kalman filtering and weighted least squares
  dynamic identification of robot", Control Engineering Practice 9(12), 2001).
- :func:`validate`: the torques the identified model predicts on fresh data, and their error.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence, Union

import numpy as np

from . import _rne


@dataclass(frozen=True)
class Excitation:
    """An excitation trajectory and its simulated measurements (N samples)."""

    t: np.ndarray
    """Sample times, s (N,)."""
    q: np.ndarray
    """Configurations (N, nq)."""
    v: np.ndarray
    """Velocities (N, nv)."""
    a: np.ndarray
    """Accelerations (N, nv)."""
    tau: np.ndarray
    """Torques with noise (N, nv)."""
    condition_number: float
    """Condition number of the stacked base regressor over one period."""
    base_parameters: int
    """Number of base parameters."""
    period: float
    """Period of the Fourier series, s."""
    offsets: list
    """q_i0 per coordinate."""
    fourier_a: list
    """a_il per coordinate and harmonic."""
    fourier_b: list
    """b_il per coordinate and harmonic."""


@dataclass(frozen=True)
class Identification:
    """Base parameters estimated from measurements."""

    values: np.ndarray
    """The estimates θ (nb,)."""
    std: np.ndarray
    """Their standard deviations (nb,)."""
    names: list
    """Each base parameter as a combination of standard ones (``I1zz + 0.09·m2``)."""
    model: np.ndarray
    """The base parameters of the robot file's values (nb,)."""
    condition_number: float
    """Condition number of the stacked base regressor."""
    joint_std: np.ndarray
    """Each joint's equation error σ_j (the weights are 1/σ_j)."""
    weighted: bool
    """Weighted (True) or ordinary least squares."""
    standard_parameters: int
    """Number of standard parameters."""
    bodies: list
    """The link of each body number in ``names`` (index 0: body 1)."""
    samples: int
    """Number of samples used."""
    friction: bool
    """Friction identified for every joint."""
    armature: bool
    """Armature identified for every joint."""

    def relative_std(self) -> np.ndarray:
        """σ_i / |θ_i| of each estimate (infinite for θ_i = 0)."""
        with np.errstate(divide="ignore"):
            return self.std / np.abs(self.values)


@dataclass(frozen=True)
class Validation:
    """Predicted torques and, with measurements, their error."""

    tau: np.ndarray
    """Predicted torques (N, nv)."""
    relative_rms: Optional[float]
    """‖τ̂ − τ‖ / ‖τ‖ over every joint (None without measurements)."""
    joints: Optional[np.ndarray]
    """RMS(τ̂_j − τ_j) / RMS(τ_j) per joint (None without measurements)."""


def excitation(
    model: _rne.Model,
    *,
    period: float = 10.0,
    harmonics: int = 5,
    q_limit: Union[float, Sequence[float]] = 1.5,
    v_limit: Union[float, Sequence[float]] = 2.0,
    a_limit: Union[None, float, Sequence[float]] = None,
    iterations: int = 300,
    criterion_states: int = 100,
    seed: int = 1,
    duration: Optional[float] = None,
    rate: float = 100.0,
    noise: float = 0.01,
    friction: bool = False,
    armature: bool = False,
) -> Excitation:
    """An excitation trajectory for ``model`` and its simulated measurements
    (``rne identify MODEL --excite OUT.csv``).

    Limits are one number for every coordinate or one per coordinate (a floating base's six
    first: x, y, z in m, then angles in rad). ``noise`` is the torque noise's standard
    deviation relative to each joint's RMS torque; ``duration`` defaults to one period.
    """
    out = _rne.excitation(
        model,
        period=period,
        harmonics=harmonics,
        q_limit=_limits(q_limit),
        v_limit=_limits(v_limit),
        a_limit=None if a_limit is None else _limits(a_limit),
        iterations=iterations,
        criterion_states=criterion_states,
        seed=seed,
        duration=duration,
        rate=rate,
        noise=noise,
        friction=friction,
        armature=armature,
    )
    return Excitation(**out)


def identify(
    model: _rne.Model,
    q,
    v,
    a,
    tau,
    *,
    weighted: bool = True,
    friction: bool = False,
    armature: bool = False,
) -> Identification:
    """The base parameters of ``model`` estimated from N samples, 2-D arrays ``q`` (N, nq),
    ``v``, ``a`` and ``tau`` (N, nv) (``rne identify MODEL DATA.csv``): weighted least
    squares, or ordinary with ``weighted=False``; ``friction`` and ``armature`` add viscous and
    Coulomb friction and an offset, and a rotor inertia, to every joint's parameters."""
    out = _rne.identify(
        model, q, v, a, tau, weighted=weighted, friction=friction, armature=armature
    )
    return Identification(friction=friction, armature=armature, **out)


def validate(
    model: _rne.Model,
    identified: Union[Identification, Sequence[float], np.ndarray],
    q,
    v,
    a,
    tau=None,
    *,
    friction: Optional[bool] = None,
    armature: Optional[bool] = None,
) -> Validation:
    """The torques an identified model predicts at N samples (``rne identify ... --validate
    FRESH.csv``) and, when ``tau`` is given, their relative RMS error. ``identified`` is an
    :class:`Identification` (its friction and armature settings apply) or base parameter
    values."""
    if isinstance(identified, Identification):
        values = identified.values
        friction = identified.friction if friction is None else friction
        armature = identified.armature if armature is None else armature
    else:
        values = identified
    values = [float(x) for x in np.asarray(values, dtype=float).ravel()]
    out = _rne.validate(
        model, values, q, v, a, tau, friction=bool(friction), armature=bool(armature)
    )
    return Validation(
        tau=out["tau"], relative_rms=out.get("relative_rms"), joints=out.get("joints")
    )


def _limits(value) -> list:
    """One limit or one per coordinate, as a list of floats."""
    return [float(x) for x in np.atleast_1d(np.asarray(value, dtype=float))]
