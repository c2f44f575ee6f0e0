#!/usr/bin/env python3
"""The impulse experiment on the bare blade, in Exudyn and in ancf-modal, alternately.

A bench, not a test: `benches/impulse-vs-exudyn` makes the venv and runs this.

The model is `models/beam_free_free.json`: the paper's blade (L = 25 mm,
h = 1.1 mm, w = 5.2 mm, rho = 8940 kg/m3, E = 127 GPa), free-free, 8 ANCF
cable elements along the x axis; the half-sine F0 = 4 N over tF = 0.1 ms at
node 0 along y (normal to the blade); 100 ms in steps of 1 us (100,000 steps)
with generalized-alpha at the spectral radius `ancf-modal impulse` uses
(0.9), fixed step, modified Newton (the Jacobian kept while it converges),
as the README's "Impulse experiment" describes ours.

Exudyn: `ObjectANCFCable2D` elements on `NodePoint2DSlope1` nodes, the
load's time function a symbolic (compiled, not Python) user function
(`--python-load`: a Python one, as a Python user would write it first;
on the shared 2-core machine 2.13 s against 1.91 s in quiet rounds, 3.26 s
in a loaded one), the tip node's velocity recorded
every step by an internal sensor (ancf-modal reads its sensor every step,
then resamples), no solution file, dense linear solver, Newton's relative
tolerance 1e-7 (its default 1e-8 is not reached at the first step: 1.6e-8
after 25 iterations; it then takes ~6 modified-Newton iterations a step,
ancf-modal 1.00 at its own tolerance, corrections below 1e-10 of the
blade's length).

Each round runs Exudyn in-process (model built and solved: wall time of the
whole `SolveDynamic` plus the build) and then the `ancf-modal impulse`
process (wall time of the whole process: parse, modal, integration,
resampling, FFT, report). The medians of the rounds and their ratio are
printed.
"""

import argparse
import json
import math
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def blade(model_path):
    m = json.loads(Path(model_path).read_text())
    (b,) = m["beams"]
    assert b["angle_deg"] == 0.0, "the bench builds the blade along x"
    (load,) = m["loads"]
    return {
        "length": b["length"],
        "elements": b["elements"],
        "height": b["section"]["height"],
        "width": b["section"]["width"],
        "young": b["material"]["young"],
        "density": b["material"]["density"],
        "force": load["force"],
        "duration": load["time"]["half_sine"]["duration"],
    }


def run_exudyn(p, step, end_time, spectral_radius, python_load):
    import exudyn as exu
    from exudyn.advancedUtilities import CreateSymbolicUserFunction
    from exudyn.itemInterface import (
        LoadForceVector,
        MarkerNodePosition,
        NodePoint2DSlope1,
        ObjectANCFCable2D,
        SensorNode,
    )

    start = time.perf_counter()
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    area = p["height"] * p["width"]
    inertia = p["width"] * p["height"] ** 3 / 12.0
    n_el = p["elements"]
    le = p["length"] / n_el
    nodes = [
        mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[i * le, 0.0, 1.0, 0.0]))
        for i in range(n_el + 1)
    ]
    for i in range(n_el):
        mbs.AddObject(
            ObjectANCFCable2D(
                nodeNumbers=[nodes[i], nodes[i + 1]],
                length=le,
                massPerLength=p["density"] * area,
                bendingStiffness=p["young"] * inertia,
                axialStiffness=p["young"] * area,
            )
        )
    marker = mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[0]))
    fx, fy = p["force"]
    duration = p["duration"]
    esym = exu.symbolic

    def half_sine(mbs, t, loadVector):
        s = esym.IfThenElse(t < duration, esym.sin(math.pi / duration * t), esym.Real(0.0))
        return [fx * s, fy * s, 0.0]

    def half_sine_python(mbs, t, loadVector):
        s = math.sin(math.pi / duration * t) if t < duration else 0.0
        return [fx * s, fy * s, 0.0]

    if python_load:
        uf = half_sine_python
    else:
        uf = CreateSymbolicUserFunction(
            mbs, half_sine, "loadVectorUserFunction", itemTypeName="LoadForceVector"
        )
    mbs.AddLoad(
        LoadForceVector(markerNumber=marker, loadVector=[fx, fy, 0.0], loadVectorUserFunction=uf)
    )
    sensor = mbs.AddSensor(
        SensorNode(
            nodeNumber=nodes[-1],
            storeInternal=True,
            writeToFile=False,
            outputVariableType=exu.OutputVariableType.Velocity,
        )
    )
    mbs.Assemble()
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.numberOfSteps = round(end_time / step)
    ti.endTime = end_time
    ti.verboseMode = 0
    ti.generalizedAlpha.spectralRadius = spectral_radius
    ti.generalizedAlpha.useIndex2Constraints = False
    ti.generalizedAlpha.useNewmark = False
    ti.newton.useModifiedNewton = True
    # Its error is the residual relative to the first; 1e-8 (its default)
    # is not reached at the first step (1.6e-8 after 25 iterations).
    ti.newton.relativeTolerance = 1e-7
    ti.adaptiveStep = False
    s.solution.file.write = False
    s.solution.sensors.writePeriod = step
    s.linearSolver.solverType = exu.LinearSolverType.EigenDense
    s.show.computationTime = False
    s.show.statistics = False
    ok = mbs.SolveDynamic(s, showHints=True)
    it = mbs.sys["dynamicSolver"].it
    iterations = it.newtonStepsCount
    elapsed = time.perf_counter() - start
    assert ok, "Exudyn's SolveDynamic failed"
    v = mbs.GetSensorStoredData(sensor)
    return elapsed, len(v), float(abs(v[:, 2]).max()), iterations / ti.numberOfSteps, it.newtonJacobiCount


def run_ours(binary, model, step, end_time, spectral_radius):
    cmd = [
        str(binary),
        "impulse",
        str(model),
        "--step",
        repr(step),
        "--end-time",
        repr(end_time),
        "--spectral-radius",
        repr(spectral_radius),
    ]
    start = time.perf_counter()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return time.perf_counter() - start, out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--binary", default=ROOT / "target/release/ancf-modal")
    ap.add_argument("--model", default=ROOT / "models/beam_free_free.json")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--step", type=float, default=1e-6)
    ap.add_argument("--end-time", type=float, default=0.1)
    ap.add_argument("--spectral-radius", type=float, default=0.9)
    ap.add_argument(
        "--python-load",
        action="store_true",
        help="Exudyn's load time function as a Python user function (called from C++ at "
        "every evaluation) instead of a symbolic one",
    )
    a = ap.parse_args()
    p = blade(a.model)
    ex, ours = [], []
    for k in range(a.rounds):
        t_ex, samples, vmax, nit, jac = run_exudyn(
            p, a.step, a.end_time, a.spectral_radius, a.python_load
        )
        t_ours, out = run_ours(a.binary, a.model, a.step, a.end_time, a.spectral_radius)
        ex.append(t_ex)
        ours.append(t_ours)
        print(
            f"round {k + 1}: Exudyn {t_ex:.3f} s ({nit:.2f} Newton iterations/step, {jac} Jacobians, "
            f"{samples} samples, tip |v_y| max {vmax:.4e} m/s), ancf-modal {t_ours:.3f} s, ratio {t_ex / t_ours:.1f}",
            flush=True,
        )
    print(out.rstrip())
    m_ex, m_ours = statistics.median(ex), statistics.median(ours)
    print(
        f"median of {a.rounds} alternating rounds: Exudyn {m_ex:.3f} s, "
        f"ancf-modal {m_ours:.3f} s: {m_ex / m_ours:.1f}x"
    )


if __name__ == "__main__":
    sys.exit(main())
