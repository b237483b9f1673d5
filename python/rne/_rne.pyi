"""Type stubs of the extension module rne._rne (docs/python.md states the conventions).

Every kernel takes one state (1-D arrays: q of nq values, v, a, tau of nv) and returns one
result, or N states (2-D arrays (N, nq), (N, nv)) and returns results with N first, computed
with the GIL released on ``threads`` threads (1 by default, 0 for every core; at most one
thread per 256 states).
"""
import os
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Array = npt.NDArray[np.float64]
Scalar = Union[float, Array]

class Model:
    """A robot's kernels compiled in memory for this processor (made by rne.load)."""

    @property
    def name(self) -> str: ...
    @property
    def file(self) -> str: ...
    @property
    def nq(self) -> int: ...
    @property
    def nv(self) -> int: ...
    @property
    def floating_base(self) -> bool: ...
    @property
    def joint_names(self) -> List[str]: ...
    @property
    def frame_names(self) -> List[str]: ...
    @property
    def parameter_names(self) -> List[str]: ...
    @property
    def base_parameter_names(self) -> List[str]: ...
    @property
    def kernels(self) -> List[str]: ...
    @property
    def runtime_parameter_names(self) -> List[str]: ...
    @property
    def runtime_parameters(self) -> Array: ...
    def set_parameters(self, values: ArrayLike) -> None:
        """Sets the run-time parameters, in runtime_parameter_names' order."""
    @property
    def fused(self) -> bool: ...
    @property
    def load_times(self) -> Tuple[float, float]:
        """Seconds of generation and of compilation."""
    def frame_index(self, name: str) -> int:
        """The index of frame ``name`` in frame_names."""
    def base_parameters(self, standard: ArrayLike) -> Array:
        """Base parameters π_b (nb,) of standard parameters π (np,)."""
    def rnea(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, threads: Optional[int] = None) -> Array:
        """Joint torques τ = M(q) a + C(q, v) v + g(q) (nv,) — Pinocchio's rnea."""
    def inverse_dynamics(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of rnea."""
    def crba(self, q: ArrayLike, threads: Optional[int] = None) -> Array:
        """Mass matrix M(q) (nv, nv), full and symmetric — Pinocchio's crba."""
    def mass_matrix(self, q: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of crba."""
    def nonLinearEffects(self, q: ArrayLike, v: ArrayLike, threads: Optional[int] = None) -> Array:
        """Bias torques C(q, v) v + g(q) (nv,) — Pinocchio's nonLinearEffects."""
    def bias_torques(self, q: ArrayLike, v: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of nonLinearEffects."""
    def computeGeneralizedGravity(self, q: ArrayLike, threads: Optional[int] = None) -> Array:
        """Gravity torques g(q) (nv,) — Pinocchio's computeGeneralizedGravity."""
    def gravity_torques(self, q: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of computeGeneralizedGravity."""
    def coriolis_matrix(self, q: ArrayLike, v: ArrayLike, threads: Optional[int] = None) -> Array:
        """Christoffel Coriolis matrix C(q, v) (nv, nv)."""
    def aba(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, threads: Optional[int] = None) -> Array:
        """Forward dynamics a (nv,) — Pinocchio's aba."""
    def forward_dynamics(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of aba."""
    def computeMinverse(self, q: ArrayLike, threads: Optional[int] = None) -> Array:
        """M(q)⁻¹ (nv, nv), full and symmetric — Pinocchio's computeMinverse."""
    def mass_matrix_inverse(self, q: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of computeMinverse."""
    def computeRNEADerivatives(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, threads: Optional[int] = None) -> Tuple[Array, Array]:
        """(∂τ/∂q, ∂τ/∂v), each (nv, nv) — Pinocchio's computeRNEADerivatives."""
    def inverse_dynamics_derivatives(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, threads: Optional[int] = None) -> Tuple[Array, Array]:
        """Alias of computeRNEADerivatives."""
    def computeABADerivatives(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, threads: Optional[int] = None) -> Tuple[Array, Array, Array]:
        """(∂a/∂q, ∂a/∂v, M⁻¹), each (nv, nv) — Pinocchio's computeABADerivatives."""
    def forward_dynamics_derivatives(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, threads: Optional[int] = None) -> Tuple[Array, Array, Array]:
        """Alias of computeABADerivatives."""
    def framePlacements(self, q: ArrayLike, threads: Optional[int] = None) -> Tuple[Array, Array]:
        """(rotations (nf, 3, 3), origins (nf, 3)) of every frame in the world — Pinocchio's data.oMf."""
    def frame_placements(self, q: ArrayLike, threads: Optional[int] = None) -> Tuple[Array, Array]:
        """Alias of framePlacements."""
    def frameJacobians(self, q: ArrayLike, threads: Optional[int] = None) -> Array:
        """Jacobians (nf, 6, nv), rows [v; ω], LOCAL_WORLD_ALIGNED — Pinocchio's getFrameJacobian."""
    def frame_jacobians(self, q: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of frameJacobians."""
    def frameJacobianTimeVariationDotV(self, q: ArrayLike, v: ArrayLike, threads: Optional[int] = None) -> Array:
        """J̇ v (nf, 6), LOCAL_WORLD_ALIGNED: the classical acceleration at a = 0."""
    def frame_jacobian_dot_v(self, q: ArrayLike, v: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of frameJacobianTimeVariationDotV."""
    def friction_torques(self, v: ArrayLike, threads: Optional[int] = None) -> Array:
        """Joint friction f_v v + f_c sign(v) + offset (nv,)."""
    def computeJointTorqueRegressor(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, threads: Optional[int] = None) -> Array:
        """Regressor Y (nv, np) of τ = Y π — Pinocchio's computeJointTorqueRegressor (then friction, armature columns)."""
    def regressor(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, threads: Optional[int] = None) -> Array:
        """Alias of computeJointTorqueRegressor."""
    def base_regressor(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, threads: Optional[int] = None) -> Array:
        """Base regressor Y_b (nv, nb) of τ = Y_b π_b."""
    def computeKineticEnergy(self, q: ArrayLike, v: ArrayLike, threads: Optional[int] = None) -> Scalar:
        """Kinetic energy ½ vᵀ M v (a float, or (N,))."""
    def kinetic_energy(self, q: ArrayLike, v: ArrayLike, threads: Optional[int] = None) -> Scalar:
        """Alias of computeKineticEnergy."""
    def computePotentialEnergy(self, q: ArrayLike, threads: Optional[int] = None) -> Scalar:
        """Potential energy −Σ m gᵀ c (a float, or (N,))."""
    def potential_energy(self, q: ArrayLike, threads: Optional[int] = None) -> Scalar:
        """Alias of computePotentialEnergy."""

def load(
    robot: Union[str, "os.PathLike[str]"],
    floating_base: bool = False,
    mimic: str = "constrained",
    friction: bool = False,
    gravity: Optional[Sequence[float]] = None,
    lock: Optional[Dict[str, float]] = None,
    frames: Optional[Sequence[str]] = None,
    parameters: str = "constant",
    *,
    kernels: Optional[Sequence[str]] = None,
    fma: bool = False,
    strict: bool = False,
) -> Model:
    """Reads a robot (a built-in name or a URDF / TOML path) and compiles its kernels."""

def builtin_robots() -> List[str]: ...
def kernel_names() -> List[str]: ...
def excitation(model: Model, **options: object) -> dict: ...
def identify(model: Model, q: ArrayLike, v: ArrayLike, a: ArrayLike, tau: ArrayLike, **options: object) -> dict: ...
def validate(model: Model, values: Sequence[float], q: ArrayLike, v: ArrayLike, a: ArrayLike, tau: Optional[ArrayLike] = None, **options: object) -> dict: ...
