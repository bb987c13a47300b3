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
