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
    "CalibrationResult",
    "ConvergenceResult",
    "FrfResult",
    "IdentifyResult",
    "ImpulseResult",
    "ModalResult",
    "Model",
    "ModelError",
    "ModelWarning",
    "ReducedBody",
    "StaticResult",
    "SweepResult",
    "SwitchOffResult",
    "TransientCalibrationResult",
    "TransientResult",
    "frf",
    "frf_files",
    "sweep",
    "sweep_merge",
    "_panic",
]

__version__: str

class ModelError(ValueError):
    """A bad model file, model parameter or argument value (the command
    line's ``Error:`` line)."""

class AnalysisError(RuntimeError):
    """An analysis that failed on a valid model: a solver failure, a loss of
    stability, an internal error."""

class ModelWarning(UserWarning):
    """A warning of the model or of a run (the command line's ``warning:``
    lines): sizes that look like other units, a state that is not an
    equilibrium, beyond beam theory, a run that ended early, a note on
    measured records. Raised at the call that gives it (``Model.from_json``
    and ``with_params`` for the model's, the analysis for its own) and
    listed at the end of the ``repr``."""

@final
class Model:
    """A model: an assembly of ANCF beams, rigid bodies and point masses with
    joints, springs, loads and sensors (the JSON model file, SI units);
    ``repr`` names it and lists its unit warnings as ``warning:`` lines.
    Pickles as its JSON, source and hash."""

    @staticmethod
    def from_json(path_or_text: Union[str, "os.PathLike[str]"]) -> "Model":
        """Reads a model file (a path) or JSON text (a str starting with ``{``).

        Raises ModelError with the command line's message for a file that
        cannot be read, malformed JSON or an invalid value; a
        ``ModelWarning`` for each size that looks like another unit."""
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
    def impulse(
        self,
        amplitude: Optional[float] = None,
        duration: Optional[float] = None,
        end_time: float = 0.1,
        step: float = 1e-6,
        spectral_radius: float = 0.9,
        sample_rate: float = 51200.0,
        sensor: Optional[str] = None,
        window: str = "hann",
        from_reference: bool = False,
    ) -> "ImpulseResult":
        """The time-domain test (``ancf-modal impulse``): the half-sine
        loads (``amplitude`` [N], ``duration`` [s] override them), ``end_time``
        [s] in steps of ``step`` [s], generalized-α with ``spectral_radius``
        [–], the sensor recorded at ``sample_rate`` [Hz] (0: every step),
        ``window`` one of rect, hann, flattop, blackman, force:P,
        exponential:P (as ``frf``)."""
    def calibrate(
        self,
        target_hz: Union[float, Sequence[float], None] = None,
        params: Union[str, Sequence[str], Mapping[str, Optional[Tuple[float, float]]], None] = None,
        mode_kind: Literal["bending", "axial", "spring"] = "bending",
        mode: Optional[Sequence[int]] = None,
        keep_mass: bool = False,
        prestress: bool = False,
        tolerance: Optional[float] = None,
        max_evaluations: int = 60,
        method: Literal["eigen", "impulse"] = "eigen",
        amplitude: Optional[float] = None,
        duration: Optional[float] = None,
        end_time: float = 0.1,
        step: float = 1e-6,
        spectral_radius: float = 0.9,
        sample_rate: float = 51200.0,
        sensor: Optional[str] = None,
        window: str = "hann",
        from_reference: bool = False,
        target_from: Optional[Union[str, "os.PathLike[str]"]] = None,
        quantity: Optional[Literal["time_to_distance_s"]] = None,
        target: Optional[float] = None,
        trajectory: Union[str, "os.PathLike[str]", Tuple[Sequence[float], Sequence[float], Sequence[float]], None] = None,
        balance: Optional[str] = None,
    ) -> Union["CalibrationResult", "TransientCalibrationResult"]:
        """Fits ``params`` (default "height"; names as ``calibrate --param``,
        bounds [SI]) so that the modes ``mode`` of ``mode_kind`` reach
        ``target_hz`` [Hz] (default: the model's reference frequency);
        ``tolerance`` [Hz] (default 1e-10 × target, 1e-3 Hz by the impulse
        method). Each candidate is evaluated by ``method``: "eigen" (the
        eigenproblem) or "impulse" (``calibrate --method impulse``: the
        experiment of ``impulse`` with ``amplitude`` [N] to ``window``, its
        first bending peak; one parameter, one target).

        With ``quantity`` "time_to_distance_s" and ``target`` [s], or with
        ``trajectory`` (a CSV path, or (t, x, y) sequences [s, m, m]), a
        calibration to the switch-off (``calibrate --quantity`` /
        ``--trajectory``): ``params`` named with SI bounds, ``balance``
        "SPRING:CONTACT", ``tolerance`` [s]; every run at a fixed 1 µs step;
        returns a ``TransientCalibrationResult``."""
    def switch_off(
        self,
        end_time: float = 3e-3,
        step: float = 1e-6,
        distance: float = 2e-3,
        direction: Tuple[float, float] = ...,  # (1.0, 0.0)
        point: Optional[str] = None,
        sample_rate: float = 67200.0,
        compare_rigid: bool = False,
        no_step_check: bool = False,
        fig10: bool = False,
    ) -> "SwitchOffResult":
        """The switch-off (``ancf-modal switch-off``): ``end_time`` [s] in
        steps of ``step`` [s]; the time for ``point`` ("BEAM:S", S [m], or
        "BODY") to travel ``distance`` [m] along ``direction``, sampled at
        ``sample_rate`` [Hz]; ``fig10`` adds the paper's Fig. 10 study
        (``SwitchOffResult.fig10``, predictions)."""
    def transient(
        self,
        end_time: float = 0.01,
        step: float = 1e-6,
        spectral_radius: float = 0.9,
        from_reference: bool = False,
        sample_rate: float = 51200.0,
        rigid_beams: bool = False,
    ) -> "TransientResult":
        """A time integration (``ancf-modal transient``): ``end_time`` [s] in
        steps of ``step`` [s], generalized-α ``spectral_radius`` [–], from
        rest at the static equilibrium under the loads at t = 0⁻ (the
        reference when it balances them), or at the reference with
        ``from_reference``; sensors at ``sample_rate`` [Hz]."""
    def convergence(self, max_elements: int = 64, modes: int = 3) -> "ConvergenceResult":
        """Mesh convergence of the first ``modes`` bending frequencies
        (``ancf-modal convergence``): beams meshed with 2, 4, 8, … elements
        up to ``max_elements``; errors against Euler–Bernoulli for a single
        free beam, else against the finest mesh."""
    def identify(
        self,
        amplitude: Optional[float] = None,
        duration: Optional[float] = None,
        end_time: float = 0.1,
        step: float = 1e-6,
        spectral_radius: float = 0.9,
        sample_rate: float = 51200.0,
        sensor: Optional[str] = None,
        window: str = "hann",
        from_reference: bool = False,
        calibrate: bool = False,
        measured: Optional[Sequence[Union[str, "os.PathLike[str]"]]] = None,
        measured_window: str = "rect",
        measured_band: Optional[Tuple[float, float]] = None,
    ) -> "IdentifyResult":
        """The main job (``ancf-modal identify``): the modal analysis, the
        impulse experiment (keyword arguments as ``impulse``'s) and their
        first bending frequencies beside the experiment's: the fitted mode
        of the ``measured`` hammer records (``measured_window``, fit band
        ``measured_band`` (LO, HI) [Hz]) nearest it of those that are a
        peak of the fitted spectrum (a ``ModelWarning`` when the records
        show no peak there or the fit misses them), else the model's
        ``reference``; ``calibrate`` fits the first beam's equivalent
        height to it."""
    def report(
        self,
        out: Union[str, "os.PathLike[str]"] = ...,  # "report.html"
        prestress: bool = False,
        amplitude: Optional[float] = None,
        duration: Optional[float] = None,
        end_time: float = 0.1,
        step: float = 1e-6,
        spectral_radius: float = 0.9,
        sample_rate: float = 51200.0,
        sensor: Optional[str] = None,
        window: str = "hann",
        from_reference: bool = False,
        calibrate: bool = False,
        measured: Optional[Sequence[Union[str, "os.PathLike[str]"]]] = None,
        measured_window: str = "rect",
        measured_band: Optional[Tuple[float, float]] = None,
    ) -> None:
        """One self-contained HTML file (``ancf-modal report``) written to
        ``out``: the assembly and its animated modes (``prestress``: also at
        the equilibrium under the loads); for a model with a half-sine or
        step load everything ``identify`` computes (its keyword arguments);
        the switch-off when the model releases something."""
    def reduce(
        self,
        interface: Sequence[Tuple[str, float]],
        modes: int = 8,
        method: str = "craig-bampton",
        prestress: bool = False,
        keep_supports: bool = False,
        load_scale: float = 1.0,
    ) -> "ReducedBody":
        """The model as a reduced flexible body (`ancf-modal reduce`)."""
    def static(self, load_scale: float = 1.0) -> "StaticResult":
        """The static equilibrium under the loads × load_scale [–] and
        gravity (``ancf-modal static``)."""

@final
class ModalResult:
    """The result of ``Model.modal``; ``repr`` is the command line's table
    and its ``warning:`` lines."""

    @property
    def frequencies_hz(self) -> npt.NDArray[np.float64]:
        """Natural frequencies [Hz]; 0 for rigid and mechanism modes;
        −√|ω²|/2π for a negative eigenvalue (never 0)."""
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
        """``rigid``, ``mechanism``, ``bending``, ``axial``, ``spring``;
        ``unstable`` (negative ω² at a verified equilibrium) or ``negative``
        (negative ω² at a state that is not an equilibrium)."""
    @property
    def rigid_modes(self) -> int:
        """Number of zero-frequency modes (rigid and mechanism)."""
    @property
    def mechanism_modes(self) -> int:
        """How many zero-frequency modes are mechanisms."""
    @property
    def unstable_modes(self) -> int:
        """Reported modes of kind ``unstable``."""
    @property
    def negative_modes(self) -> int:
        """Reported modes of kind ``negative``."""
    @property
    def equilibrium(self) -> Dict[str, Any]:
        """Whether the modes' state is an equilibrium: ``balanced``,
        ``unbalanced_n`` [N], ``force_scale_n`` [N], ``tolerance``, ``at``
        (the coordinate), ``constraint_violation``, ``free_fall``. A state
        that is not one, or an unstable one, also gives a
        ``ModelWarning`` when ``Model.modal`` returns."""
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
class ImpulseResult:
    """The result of ``Model.impulse``; ``repr`` is the command line's report
    and its ``warning:`` lines."""

    @property
    def time(self) -> npt.NDArray[np.float64]:
        """Sample times [s]."""
    @property
    def signal(self) -> npt.NDArray[np.float64]:
        """The sensor's record [m, m/s or m/s²]."""
    @property
    def force(self) -> npt.NDArray[np.float64]:
        """The hammer force at the sample times [N]."""
    @property
    def sensor(self) -> str:
        """The sensor's id."""
    @property
    def sample_rate_hz(self) -> float:
        """Sampling rate of the records [Hz]."""
    @property
    def spectrum_hz(self) -> npt.NDArray[np.float64]:
        """Frequencies of the spectrum [Hz]."""
    @property
    def spectrum(self) -> npt.NDArray[np.float64]:
        """Amplitude spectrum of the signal [signal unit]."""
    @property
    def peaks_hz(self) -> npt.NDArray[np.float64]:
        """Spectrum peaks [Hz]."""
    @property
    def first_bending(self) -> Optional[Tuple[float, float, float]]:
        """(raw_hz, corrected_hz, eigen_hz) [Hz] of the first bending peak."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document of the result (``impulse --json``)."""
    def write_csv(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the records (time [s], sensor, force [N]) to ``path`` and
        the spectrum beside it as the stem + ``.spectrum.csv``
        (``impulse --csv``)."""
    def write_uff(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the force and sensor records as UFF 58 (``impulse --uff``)."""
    def plot(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Draws the spectrum to ``path`` (.svg, .png) and the response beside
        it as the stem + ``.response.<ext>`` (``impulse --plot``)."""

@final
class StaticResult:
    """The result of ``Model.static``; ``repr`` is the command line's table
    and its ``warning:`` lines."""

    @property
    def q(self) -> npt.NDArray[np.float64]:
        """Equilibrium coordinates [m, –, rad] about the centre of mass."""
    @property
    def multipliers(self) -> npt.NDArray[np.float64]:
        """Constraint multipliers λ [N, N m]."""
    @property
    def residual(self) -> float:
        """Final unbalanced force [N, N m]."""
    @property
    def load_scale(self) -> float:
        """The applied-load factor [–]."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's report (``static --json``)."""

@final
class CalibrationResult:
    """The result of ``Model.calibrate``; ``repr`` is the command line's table
    and its ``warning:`` lines."""

    @property
    def parameters(self) -> Dict[str, float]:
        """Fitted values by name [SI]."""
    @property
    def targets_hz(self) -> npt.NDArray[np.float64]:
        """Targets [Hz]."""
    @property
    def initial_hz(self) -> npt.NDArray[np.float64]:
        """The modes' frequencies before the fit [Hz]."""
    @property
    def achieved_hz(self) -> npt.NDArray[np.float64]:
        """The modes' frequencies of the fitted model [Hz]."""
    @property
    def evaluations(self) -> int:
        """Model evaluations, the start included."""
    @property
    def fitted_model(self) -> Model:
        """The calibrated model."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document (``calibrate --json``)."""
    def plot(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Draws the fit to ``path`` (.svg, .png) (``calibrate --plot``)."""

@final
class TransientCalibrationResult:
    """The result of a transient ``Model.calibrate`` (``quantity`` or
    ``trajectory``); ``repr`` is the command line's report and its
    ``warning:`` lines."""

    @property
    def quantity(self) -> str:
        """"time_to_distance_s" or "trajectory"."""
    @property
    def parameters(self) -> Dict[str, float]:
        """Fitted values by name [SI]."""
    @property
    def standard_errors(self) -> Dict[str, Optional[float]]:
        """Each parameter's standard error [SI] (a trajectory fit), else None."""
    @property
    def initial_time_s(self) -> Optional[float]:
        """Time to distance of the starting model [s] at the fixed step."""
    @property
    def achieved_time_s(self) -> Optional[float]:
        """Time to distance of the fitted model [s] at the fixed step."""
    @property
    def rms_m(self) -> Optional[float]:
        """The trajectory fit's rms residual [m] (None: a time fit)."""
    @property
    def evaluations(self) -> int:
        """Switch-off experiments run."""
    @property
    def fitted_model(self) -> Model:
        """The calibrated model."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document (``calibrate --quantity … --json``)."""

@final
class ConvergenceResult:
    """The result of ``Model.convergence``; ``repr`` is the command line's table
    and its ``warning:`` lines."""

    @property
    def elements(self) -> List[int]:
        """Elements per beam of each mesh, ascending."""
    @property
    def coordinates(self) -> List[int]:
        """Number of coordinates of each mesh."""
    @property
    def reference_hz(self) -> npt.NDArray[np.float64]:
        """Reference frequency of each bending mode [Hz]."""
    @property
    def frequencies_hz(self) -> npt.NDArray[np.float64]:
        """Bending mode k at mesh i [Hz] (modes × meshes); NaN where absent."""
    @property
    def relative_errors(self) -> npt.NDArray[np.float64]:
        """|f_k(n_i) − f_k|/f_k [–] (modes × meshes); NaN where undefined."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document (``convergence --json``)."""
    def plot(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Draws the errors against the element count (.svg or .png)."""

@final
class FrfResult:
    """Measured FRFs and the modes fitted to them; ``repr`` is the command
    line's table and its ``warning:`` lines."""

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
    def model_frf(self) -> Optional[npt.NDArray[np.complex128]]:
        """The model's FRF at its sensor ``at`` on ``freq`` [response unit
        per N]; None without ``model``."""
    @property
    def band(self) -> Tuple[float, float]:
        """The fit band [Hz]."""
    @property
    def peaks(self) -> List[Dict[str, Any]]:
        """Identified modes: frequency_hz [Hz], damping_ratio [–] and
        magnitude (None when the records do not resolve the damping),
        residue, damping_upper_bound (the largest ζ the records allow when
        they do not resolve it, else None), magnitude_lower_bound (then
        the smallest |H| at the peak they allow, else None) and own_peak
        (whether the mode makes its own peak of the fitted |H|)."""
    @property
    def rejected(self) -> List[Dict[str, Any]]:
        """Stable poles not reported as modes: dicts with frequency_hz [Hz],
        damping_ratio [–], reason (``outside_band``, ``left_band``,
        ``not_significant``, ``redundant``, ``unresolved_damping``,
        ``failed_refinement``, ``harmonic``, ``unfitted``) and why (in
        words)."""
    @property
    def stabilization(self) -> List[Dict[str, Any]]:
        """The stabilization diagram's poles."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document of the result (``frf --json``)."""
    def write_uff(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes H1 and the coherence as UFF 58 to ``path`` (``frf --uff``)."""
    def write_csv(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the spectra and the fit as CSV to ``path`` (``frf --csv``)."""
    def plot(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Draws the FRF, the coherence and the stabilization diagram to
        ``path`` (.svg, .png) (``frf --plot``)."""

@final
class IdentifyResult:
    """The result of ``Model.identify``; ``repr`` is the command line's
    report and its ``warning:`` lines."""

    @property
    def experiment_hz(self) -> Optional[float]:
        """The experiment's first bending frequency [Hz]; None without one."""
    @property
    def table(self) -> List[Dict[str, Any]]:
        """The comparison: source, first_bending_hz [Hz], error_percent and
        paper_error_percent [%] per row."""
    @property
    def paper(self) -> bool:
        """Whether the comparison is the paper's Table 3."""
    @property
    def frequencies_hz(self) -> npt.NDArray[np.float64]:
        """Natural frequencies of the modes at the reference [Hz]."""
    @property
    def calibrated_model(self) -> Optional[Model]:
        """The model with the fitted equivalent height (``calibrate=True``)."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document (``identify --json``, summary.json)."""
    def write_out_dir(self, out_dir: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the files of ``identify --out-dir`` into ``out_dir``."""
    def write_html(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes this run's report (``identify --html``) to ``path``."""

@final
class SweepResult:
    """The result of ``sweep``; ``repr`` is the command line's table
    and its ``warning:`` lines. Pickles as its document, every number
    exact."""

    @property
    def names(self) -> List[str]:
        """The parameters, in the order of ``values``' columns."""
    @property
    def values(self) -> npt.NDArray[np.float64]:
        """Parameter values [SI], points × parameters (row-major grid)."""
    @property
    def result(self) -> npt.NDArray[np.float64]:
        """The quantity at each point [Hz or s]; NaN where it failed."""
    @property
    def errors(self) -> List[Optional[str]]:
        """Each point's error message, None where it succeeded."""
    @property
    def failed_points(self) -> int:
        """Points that failed."""
    @property
    def frequencies_hz(self) -> Optional[npt.NDArray[np.float64]]:
        """Tracked frequencies [Hz], points × tracked modes."""
    def to_dict(self) -> Dict[str, Any]:
        """The sweep's JSON document (``sweep --json``)."""

@final
class SwitchOffResult:
    """The result of ``Model.switch_off``; ``repr`` is the command line's report
    and its ``warning:`` lines."""

    @property
    def time_to_distance_s(self) -> Optional[float]:
        """Time to the distance [s]."""
    @property
    def time(self) -> npt.NDArray[np.float64]:
        """Sample times [s]."""
    @property
    def x(self) -> npt.NDArray[np.float64]:
        """The tracked point's x [m]."""
    @property
    def y(self) -> npt.NDArray[np.float64]:
        """The tracked point's y [m]."""
    @property
    def released_loads(self) -> Dict[str, npt.NDArray[np.float64]]:
        """Released loads' magnitudes at the sample times [N]."""
    @property
    def rigid_time_to_distance_s(self) -> Optional[float]:
        """The rigid-beam model's time to the distance [s]."""
    @property
    def half_step_time_to_distance_s(self) -> Optional[float]:
        """The time to the distance at half the step [s]."""
    @property
    def fig10(self) -> Optional[Dict[str, Any]]:
        """The paper's Fig. 10 study (``fig10=True``; ``switch-off --json``'s
        ``fig10``): ``rows``, ``combined_ratio`` beside
        ``paper_combined_ratio``, ``calibrated``; predictions. None without it."""
    @property
    def warnings(self) -> List[str]:
        """Things the reader must know (also raised as ``ModelWarning``)."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document (``switch-off --json``)."""
    def write_csv(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the tracked point's samples as CSV (``switch-off --csv``)."""
    def plot(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Draws the travel to ``path`` (.svg, .png) and the trajectory
        beside it as the stem + ``.trajectory.<ext>`` (``switch-off
        --plot``)."""

@final
class TransientResult:
    """The result of ``Model.transient``; ``repr`` is the command line's report
    and its ``warning:`` lines."""

    @property
    def time(self) -> npt.NDArray[np.float64]:
        """Sample times [s]."""
    @property
    def sensors(self) -> Dict[str, npt.NDArray[np.float64]]:
        """Each sensor's samples [m, m/s or m/s²] by id."""
    def to_dict(self) -> Dict[str, Any]:
        """The library's JSON document (``transient --json``)."""
    def write_csv(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the samples as CSV (``transient --csv``)."""
    def write_uff(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the loads' and sensors' records as UFF 58 (``transient
        --uff``; needs a sample rate above 0)."""
    def plot(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Draws each sensor against time to ``path`` (.svg, .png)
        (``transient --plot``)."""

def sweep(
    model: Model,
    params: Mapping[
        str, Union[str, Tuple[float, float, int], Tuple[float, float, int, str], Sequence[float]]
    ],
    quantity: str,
    modes: int = 6,
    prestress: bool = False,
    solver: Literal["auto", "dense", "sparse"] = "auto",
    step: Optional[float] = None,
    end_time: Optional[float] = None,
    threads: Optional[int] = None,
    shard: Optional[Tuple[int, int]] = None,
    client: Optional[Any] = None,
    progress: bool = False,
) -> SweepResult:
    """A parameter study (``ancf-modal sweep``): ``quantity``
    (first_bending_hz [Hz], frequency:K [Hz], time_to_distance_s [s],
    peak:SENSOR) over the grid of ``params`` {name: "LO:HI:N[:log]",
    (LO, HI, N), "V1,V2,..." or a list of the values} [SI]; ``step``, ``end_time`` [s] of transient quantities;
    ``threads`` workers; ``shard=(k, n)`` only the points whose index is
    k − 1 modulo n (``--shard K/N``). KeyboardInterrupt stops it.
    ``client``, a ``dask.distributed.Client``: the points on its cluster,
    one thread per task, the same result (``progress``: Dask's progress
    bar); ``pip install "./python[dask]"``."""

def sweep_merge(
    shards: Sequence[Union[SweepResult, Mapping[str, Any], str, "os.PathLike[str]"]],
) -> SweepResult:
    """Joins the shards of a sweep (``ancf-modal sweep-merge``): results of
    ``sweep(..., shard=(k, n))``, their ``to_dict()``s or ``sweep --shard
    K/N --json`` files, into the result of one run of the whole grid."""

def frf(
    force: npt.ArrayLike,
    response: npt.ArrayLike,
    fs: float,
    window: str = "rect",
    estimator: Literal["h1", "h2"] = "h1",
    band: Optional[Tuple[float, float]] = None,
    max_order: int = 40,
    response_quantity: Optional[Literal["displacement", "velocity", "acceleration"]] = None,
    model: Optional[Model] = None,
    at: Optional[str] = None,
) -> FrfResult:
    """H1/H2, coherence and the modal fit of hammer hits: ``force`` [N] and
    ``response`` [m, m/s or m/s²], 1-D (one hit) or 2-D (one hit per row),
    sampled at ``fs`` [Hz]; ``window`` rect, hann, force:P, exponential:P;
    ``band`` (LO, HI) [Hz] of the fit; ``model`` and its sensor ``at``: the
    model's FRF beside the measured one."""

def frf_files(
    paths: Sequence[Union[str, "os.PathLike[str]"]],
    force: Union[str, int, None] = None,
    response: Union[str, int, None] = None,
    window: str = "rect",
    estimator: Literal["h1", "h2"] = "h1",
    band: Optional[Tuple[float, float]] = None,
    max_order: int = 40,
    response_quantity: Optional[Literal["displacement", "velocity", "acceleration"]] = None,
    model: Optional[Model] = None,
    at: Optional[str] = None,
) -> FrfResult:
    """``frf`` on measurement files (CSV or UFF 58), as ``ancf-modal frf``;
    ``force``/``response`` a column name or 1-based index; ``model`` and
    its sensor ``at`` as for ``frf``."""

def _panic(message: str) -> None:
    """Panics inside the library's call wrapper (for the test suite: raises
    AnalysisError)."""

@final
class ReducedBody:
    """A reduced flexible body: `Model.reduce`'s result."""

    @property
    def mass(self) -> npt.NDArray[np.float64]: ...
    @property
    def stiffness(self) -> npt.NDArray[np.float64]: ...
    @property
    def basis(self) -> npt.NDArray[np.float64]: ...
    @property
    def rigid(self) -> npt.NDArray[np.float64]: ...
    @property
    def check(self) -> Dict[str, Any]: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def save(self, path: Union[str, "os.PathLike[str]"]) -> None: ...
