"""Modal and frequency-response analysis of planar rigid-flexible assemblies
whose flexible parts are ANCF beams, from Python: numpy in and out.

>>> import ancf_modal
>>> model = ancf_modal.Model.builtin()          # the paper's free-free assembly
>>> result = model.modal(modes=6)
>>> result.frequencies_hz                         # Hz, rigid modes at 0

Units are SI throughout (m, kg, s, N, Pa), frequencies in Hz. Errors are
``ModelError`` (a ``ValueError``: bad model, parameter or argument) and
``AnalysisError`` (a ``RuntimeError``: the analysis failed), with the
command line's one-line message. Each of the command line's ``warning:``
lines is a ``ModelWarning`` (a ``UserWarning``), raised at the call that
gave it (the model's when it is read, a run's own when it returns) and
listed at the end of the model's and the result's ``repr``.
"""

from ._native import (
    AnalysisError,
    CalibrationResult,
    ConvergenceResult,
    FrfResult,
    IdentifyResult,
    ImpulseResult,
    ModalResult,
    Model,
    ModelError,
    ModelWarning,
    ReducedBody,
    StaticResult,
    SweepResult,
    SwitchOffResult,
    TransientCalibrationResult,
    TransientResult,
    __version__,
    frf,
    frf_files,
    sweep,
    sweep_merge,
)

__all__ = [
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
    "__version__",
    "frf",
    "frf_files",
    "sweep",
    "sweep_merge",
]
