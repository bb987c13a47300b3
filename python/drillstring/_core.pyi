"""Type stubs of the compiled module ``drillstring._core`` (Rust, PyO3)."""

from typing import Optional, TypedDict

import numpy as np
from numpy.typing import NDArray

__version__: str

class SolveOutput(TypedDict):
    t: NDArray[np.float64]
    y: NDArray[np.float64]
    status: str
    message: str
    nfev: int
    naccept: int
    nreject: int

class ModalSystem:
    """``M q'' + K q + grad V(q) = 0`` with diagonal M, K and quartic potential terms."""

    def __init__(
        self,
        mass: NDArray[np.float64],
        stiffness: NDArray[np.float64],
        quartic_index: NDArray[np.int64],
        quartic_coef: NDArray[np.float64],
    ) -> None: ...
    @property
    def modes(self) -> int: ...
    def acceleration(self, q: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def energy(self, q: NDArray[np.float64], qdot: NDArray[np.float64]) -> NDArray[np.float64]: ...

def solve_modal(
    system: ModalSystem,
    q0: NDArray[np.float64],
    v0: NDArray[np.float64],
    t_end: float,
    t_eval: Optional[NDArray[np.float64]],
    method: str,
    rtol: float,
    atol: float,
    dt: Optional[float] = None,
    max_steps: Optional[int] = None,
    first_step: Optional[float] = None,
    max_step: float = ...,
) -> SolveOutput: ...

class PdeSystem:
    """The torsion PDE on ``nodes`` grid points ``z_j = j l / (nodes - 1)`` (lumped-mass linear
    finite elements; the discrete energy ``H_h`` is conserved by the semi-discrete system)."""

    def __init__(
        self,
        k1: float,
        k2: float,
        k3: float,
        k4: float,
        k5: float,
        k6: float,
        length: float,
        nodes: int,
    ) -> None: ...
    @property
    def nodes(self) -> int: ...
    @property
    def length(self) -> float: ...
    @property
    def spacing(self) -> float: ...
    @property
    def coefficients(self) -> tuple[float, float, float, float, float, float]: ...
    @property
    def z(self) -> NDArray[np.float64]: ...
    @property
    def weights(self) -> NDArray[np.float64]: ...
    def acceleration(self, q: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def energy(self, q: NDArray[np.float64], qdot: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def initial_velocity_from_modes(self, c: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def linear_frequencies_squared(self, count: int) -> NDArray[np.float64]: ...

def solve_pde(
    system: PdeSystem,
    q0: NDArray[np.float64],
    v0: NDArray[np.float64],
    t_end: float,
    t_eval: Optional[NDArray[np.float64]],
    method: str,
    rtol: float,
    atol: float,
    dt: Optional[float] = None,
    max_steps: Optional[int] = None,
    first_step: Optional[float] = None,
    max_step: float = ...,
) -> SolveOutput: ...
