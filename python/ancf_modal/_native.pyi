"""Stubs of the extension module ``ancf_modal._native`` (checked against it
by mypy's stubtest in the Python suite). Units are SI; frequencies in Hz."""

import os
from typing import Any, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
from typing_extensions import final

__all__ = [
    "__version__",
    "AnalysisError",
    "FrfResult",
    "ModalResult",
    "Model",
    "ModelError",
    "frf",
    "frf_files",
]

__version__: str

class ModelError(ValueError):
    """A bad model file, model parameter or argument value (the command
    line's ``Error:`` line)."""

class AnalysisError(RuntimeError):
    """An analysis that failed on a valid model: a solver failure, a loss of
    stability, an internal error."""

@final
class Model:
    """A model: an assembly of ANCF beams, rigid bodies and point masses with
    joints, springs, loads and sensors (the JSON model file, SI units)."""

    @staticmethod
    def from_json(path_or_text: Union[str, "os.PathLike[str]"]) -> "Model":
        """Reads a model file (a path) or JSON text (a str starting with ``{``).

        Raises ModelError with the command line's message for a file that
        cannot be read, malformed JSON or an invalid value."""
    @staticmethod
    def builtin(name: str = "rcbo_free_free") -> "Model":
        """A shipped model by the file stem of ``models/`` (see
        ``builtin_names()``); the default is the command line's built-in
        model, the paper's free-free assembly."""
    @staticmethod
    def builtin_names() -> List[str]:
        """The names ``builtin`` accepts."""
    @property
    def name(self) -> str:
        """The model's ``name``."""
    @property
    def source(self) -> str:
        """Its path, ``<built-in model>`` or ``<json text>``."""
    @property
    def sha256(self) -> str:
        """SHA-256 of the JSON text it was read from (``model_sha256``)."""
    def to_json(self) -> str:
        """The model as pretty JSON: a valid model file."""
    def with_params(self, params: Mapping[str, float]) -> "Model":
        """A new model with numbers changed, keys as ``sweep --param`` names
        them (``"beams[blade].section.height"``, ``"young"``,
        ``"load_scale:F_x2"``; a key ending in ``+`` adds its value), values
        SI as in the model file [m, Pa, kg/m³, kg, N/m, …]."""
    def coordinates(self) -> List[str]:
        """What each coordinate of q is: beam nodes [rx, ry, r'x, r'y]
        [m, m, –, –], rigid bodies [x, y, θ] [m, m, rad], point masses
        [x, y] [m]."""
    def matrices(
        self,
        prestress: bool = False,
        format: Literal["scipy", "arrays"] = "scipy",
        load_scale: float = 1.0,
    ) -> Dict[str, Any]:
        """{"M", "K", "C_q"}: mass [kg, kg m, kg m²], tangent stiffness and
        constraint Jacobian as scipy.sparse CSR matrices or (data, indices,
        indptr, shape) tuples; at the reference, or with prestress=True at
        the equilibrium under the loads × load_scale [–] and gravity."""
    def modal(
        self,
        modes: int = 12,
        prestress: bool = False,
        solver: Literal["auto", "dense", "sparse"] = "auto",
        load_scale: float = 1.0,
    ) -> "ModalResult":
        """Frequencies and mode shapes (``ancf-modal modal``): ``modes``
        [count] modes including the zero-frequency ones; with
        prestress=True linearized at the static equilibrium under the loads
        × load_scale [–] and gravity."""

@final
class ModalResult:
    """The result of ``Model.modal``; ``repr`` is the command line's table."""

    @property
    def frequencies_hz(self) -> npt.NDArray[np.float64]:
        """Natural frequencies [Hz]; 0 for rigid and mechanism modes."""
    @property
    def eigenvalues(self) -> npt.NDArray[np.float64]:
        """ω² [rad²/s²]."""
    @property
    def error_bound(self) -> npt.NDArray[np.float64]:
        """Relative frequency error bound of the eigen-solve [–]; NaN for
        zero modes."""
    @property
    def damping_ratio(self) -> npt.NDArray[np.float64]:
        """Modal damping ratio ζ [–]; NaN for zero modes."""
    @property
    def kinds(self) -> List[str]:
        """``rigid``, ``mechanism``, ``bending``, ``axial`` or ``spring``."""
    @property
    def rigid_modes(self) -> int:
        """Number of zero-frequency modes (rigid and mechanism)."""
    @property
    def mechanism_modes(self) -> int:
        """How many zero-frequency modes are mechanisms."""
    @property
    def solver(self) -> str:
        """``dense`` or ``sparse shift-invert Lanczos``."""
    @property
    def shapes(self) -> npt.NDArray[np.float64]:
        """Mode shapes, modes × coordinates, mass-normalized (φᵀMφ = 1)."""
    def mac(self, other: "ModalResult") -> npt.NDArray[np.float64]:
        """MAC [–] of the elastic modes (rows) against ``other``'s (columns),
        on the translations at beam nodes and body points."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document of the result (``modal --json``)."""
    def write_uff(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes UFF 15 (nodes) and 55 (elastic modes) to ``path``."""
    def plot(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Draws the first six elastic mode shapes to ``path`` (.svg, .png)."""

@final
class FrfResult:
    """Measured FRFs and the modes fitted to them; ``repr`` is the command
    line's table."""

    @property
    def freq(self) -> npt.NDArray[np.float64]:
        """Frequencies [Hz]."""
    @property
    def h1(self) -> npt.NDArray[np.complex128]:
        """H1 = G_fx/G_ff [response unit per N]."""
    @property
    def h2(self) -> Optional[npt.NDArray[np.complex128]]:
        """H2 = G_xx/G_xf [response unit per N]; None for a measured FRF."""
    @property
    def coherence(self) -> Optional[npt.NDArray[np.float64]]:
        """γ² [–]; None for a measured FRF without one."""
    @property
    def band(self) -> Tuple[float, float]:
        """The fit band [Hz]."""
    @property
    def peaks(self) -> List[Dict[str, Any]]:
        """Identified modes: frequency_hz [Hz], damping_ratio [–],
        magnitude, residue."""
    @property
    def rejected(self) -> List[Dict[str, Any]]:
        """Stable poles not reported as modes, with the reason."""
    @property
    def stabilization(self) -> List[Dict[str, Any]]:
        """The stabilization diagram's poles."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document of the result (``frf --json``)."""

def frf(
    force: npt.ArrayLike,
    response: npt.ArrayLike,
    fs: float,
    window: str = "rect",
    estimator: Literal["h1", "h2"] = "h1",
    band: Optional[Tuple[float, float]] = None,
    max_order: int = 40,
    response_quantity: Literal["displacement", "velocity", "acceleration"] = "velocity",
) -> FrfResult:
    """H1/H2, coherence and the modal fit of hammer hits: ``force`` [N] and
    ``response`` [m, m/s or m/s²], 1-D (one hit) or 2-D (one hit per row),
    sampled at ``fs`` [Hz]; ``window`` rect, hann, force:P, exponential:P;
    ``band`` (LO, HI) [Hz] of the fit."""

def frf_files(
    paths: Sequence[Union[str, "os.PathLike[str]"]],
    force: Union[str, int, None] = None,
    response: Union[str, int, None] = None,
    window: str = "rect",
    estimator: Literal["h1", "h2"] = "h1",
    band: Optional[Tuple[float, float]] = None,
    max_order: int = 40,
    response_quantity: Literal["displacement", "velocity", "acceleration"] = "velocity",
) -> FrfResult:
    """``frf`` on measurement files (CSV or UFF 58), as ``ancf-modal frf``;
    ``force``/``response`` a column name or 1-based index."""
