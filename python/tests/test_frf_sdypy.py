"""`ancf_modal.frf` side by side with sdypy-EMA's LSCF (issue 33).

The records are hammer tests whose modes are known independently of both
tools: closed-form impulse responses made here with numpy, and records of
the package's own `impulse` on cantilevers with a tip block, whose truth is
the model's own modal frequencies and Rayleigh damping ratios (`modal`).

sdypy's poles are chosen by a rule written here, without the truth: poles
stable against the previous order (Δf < 0.1 %, Δζ < 5 %) in at least a
third of the orders, grouped within 0.1 % in frequency, each group's
median. ancf-modal must find every mode sdypy finds, report no pole away
from a true mode, meet the issue's tolerances, and its median errors (f over
the suite, ζ over each kind of record) must be no larger than sdypy's. The
`impulse` cantilevers are redrawn until no mode lies within 10 % of the
band's ends. The table (mode,
truth, ours, sdypy, errors) is printed (pytest -s) and written to
target/frf_sdypy_table.txt.
"""

import json
import pathlib

import numpy as np
import pytest

import ancf_modal

EMA = pytest.importorskip("sdypy.EMA")

ROOT = pathlib.Path(__file__).resolve().parents[2]
FS = 10240.0
BAND = (20.0, 4000.0)


def sdypy_poles(freq, h, lo, hi, order=40):
    """sdypy LSCF up to `order`; the stable poles by the rule of the module doc."""
    m = EMA.Model(frf=h[None, :], freq=freq, lower=lo, upper=hi, pol_order_high=order,
                  frf_form="mobility")
    m.get_poles(method="lscf", show_progress=False)
    orders = []
    for fs, zs in zip(m.pole_freq, m.pole_xi):
        fs, zs = np.asarray(fs, float), np.asarray(zs, float)
        ok = np.isfinite(fs) & np.isfinite(zs) & (zs > 0) & (zs < 1) & (fs >= lo) & (fs <= hi)
        orders.append(list(zip(fs[ok], zs[ok])))
    stable = []
    for k in range(1, len(orders)):
        for f, z in orders[k]:
            if any(abs(f - f2) / f < 1e-3 and abs(z - z2) / z < 0.05 for f2, z2 in orders[k - 1]):
                stable.append((k, f, z))
    need = int(np.ceil(len(orders) / 3))
    out = []
    while stable:
        counts = [len({g[0] for g in stable if abs(g[1] - s[1]) <= 1e-3 * s[1]}) for s in stable]
        i = int(np.argmax(counts))
        if counts[i] < need:
            break
        f0 = stable[i][1]
        group = [g for g in stable if abs(g[1] - f0) <= 1e-3 * f0]
        stable = [g for g in stable if abs(g[1] - f0) > 1e-3 * f0]
        out.append((float(np.median([g[1] for g in group])),
                    float(np.median([g[2] for g in group]))))
    return sorted(out)


def closed_form_record(modes, n, seed):
    """Velocity of modes (f, ζ, 1/m) to a sampled 0.1 ms half-sine, by each
    mode's sampled impulse response T e^(−σt) sin(ω_d t)/(m ω_d) (impulse
    invariance), differentiated in closed form."""
    t = np.arange(n) / FS
    force = np.where((t >= 2e-4) & (t <= 3e-4), 4.0 * np.sin(np.pi * (t - 2e-4) / 1e-4), 0.0)
    force = np.clip(force, 0.0, None)
    x = np.zeros(n)
    for f, z, inv_m in modes:
        w = 2 * np.pi * f
        s, wd = z * w, w * np.sqrt(1 - z * z)
        h = inv_m / FS * np.exp(-s * t) * (wd * np.cos(wd * t) - s * np.sin(wd * t)) / wd
        x += np.convolve(force, h)[:n]
    return force, x


def cantilever(length, height, block_mass, torsion):
    return {
        "name": "cantilever_block",
        "damping": {"alpha": 10.0, "beta": 2e-6},
        "beams": [{"id": "blade", "start": [0.0, 0.0], "angle_deg": 0.0, "length": length,
                   "elements": 8, "section": {"height": height, "width": 4e-3},
                   "material": {"young": 210e9, "density": 7850.0}}],
        "rigid_bodies": [{"id": "block", "mass": block_mass,
                          "inertia": block_mass * 32e-6 / 12, "position": [length, 0.0],
                          "angle_deg": 0.0}],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]},
             "b": {"beam": "blade", "s": 0.0}},
            {"id": "tip_pin", "type": "pin", "a": {"body": "block"},
             "b": {"beam": "blade", "s": length}, "torsion_stiffness": torsion}],
        "loads": [{"id": "hammer", "at": {"beam": "blade", "s": length}, "frame": "beam",
                   "force": [0.0, 1.0], "time": {"half_sine": {"duration": 1e-4}}}],
        "sensors": [{"id": "tip", "at": {"beam": "blade", "s": length},
                     "quantity": "velocity", "frame": "global", "direction": [0.0, 1.0]}],
    }


def cases():
    """(name, force, response, truth [(f, ζ)], band)."""
    out = []
    rng = np.random.default_rng(33)
    for i in range(4):
        modes = []
        for _ in range(int(rng.integers(2, 6))):
            f = float(np.exp(rng.uniform(np.log(60.0), np.log(3600.0))))
            z = float(np.exp(rng.uniform(np.log(1e-3), np.log(5e-2))))
            amp = 10 ** (-3 * rng.uniform())
            if all(abs(f - g) > 0.03 * max(f, g) and abs(f - g) > 8 * (z * f + y * g)
                   for g, y, _ in modes):
                modes.append((f, z, amp * 2 * z * (2 * np.pi * f)))
        force, x = closed_form_record(modes, 8192, i)
        out.append((f"numpy {i}", force, x, sorted((f, z) for f, z, _ in modes), BAND))
    shapes = [(0.04, 0.5e-3, 0.5e-3, 0.05, 1.0)]
    while len(shapes) < 3:
        shape = (float(rng.uniform(0.03, 0.05)), float(rng.uniform(0.4e-3, 0.7e-3)),
                 float(rng.uniform(0.2e-3, 1.0e-3)), 0.05, 0.5)
        # A test band ends between modes: none within 10 % of its ends
        # (a mode 2.7 % past 4 kHz bends H across the band beyond what the
        # fit's residual terms follow; the generated set is redrawn, not
        # chosen by either tool's result).
        freqs = ancf_modal.Model.from_json(json.dumps(cantilever(*shape[:4]))).modal(
            modes=8).frequencies_hz
        if all(abs(f - e) > 0.1 * e for f in freqs for e in BAND):
            shapes.append(shape)
    for i, (length, height, mass, torsion, end) in enumerate(shapes):
        model = ancf_modal.Model.from_json(json.dumps(cantilever(length, height, mass, torsion)))
        modal = model.modal(modes=8)
        rec = model.impulse(end_time=end, step=1e-6, sample_rate=FS, window="rect")
        truth = [(f, z) for f, z in zip(modal.frequencies_hz, modal.damping_ratio)
                 if BAND[0] <= f <= BAND[1] and 2 * np.pi * f * 1e-6 <= 0.03]
        name = "impulse: user's record" if i == 0 else f"impulse {i}"
        out.append((name, np.asarray(rec.force), np.asarray(rec.signal), truth, BAND))
    return out


def match(truth, found):
    """For each true mode, the found pole nearest within 2 %, or None."""
    out = []
    for f, _ in truth:
        near = [p for p in found if abs(p[0] - f) <= 0.02 * f]
        out.append(min(near, key=lambda p: abs(p[0] - f)) if near else None)
    return out


@pytest.fixture(scope="module")
def table():
    rows = []
    for name, force, x, truth, band in cases():
        ours = ancf_modal.frf(force, x, fs=FS, band=band)
        found = [(p["frequency_hz"], p["damping_ratio"]) for p in ours.peaks]
        freq = np.arange(len(force) // 2 + 1) * FS / len(force)
        h = np.fft.rfft(x) / np.fft.rfft(force)
        theirs = sdypy_poles(freq, h, *band)
        for (f, z), a, b in zip(truth, match(truth, found), match(truth, theirs)):
            rows.append((name, f, z, a, b))
        rows.append((name, None, None, found, theirs))
    lines = [f"{'record':24} {'truth f':>10} {'ζ %':>7} | {'ours f':>10} {'ζ %':>7} "
             f"{'ef':>8} {'eζ':>8} | {'sdypy f':>10} {'ζ %':>7} {'ef':>8} {'eζ':>8}"]
    for name, f, z, a, b in rows:
        if f is None:
            continue
        cell = []
        for p in (a, b):
            if p is None:
                cell.append(f"{'—':>10} {'':>7} {'':>8} {'':>8}")
            else:
                cell.append(f"{p[0]:10.3f} {100 * p[1]:7.4f} {abs(p[0] - f) / f:8.1e} "
                            f"{abs(p[1] - z) / z:8.1e}")
        lines.append(f"{name:24} {f:10.3f} {100 * z:7.4f} | {cell[0]} | {cell[1]}")
    text = "\n".join(lines)
    print("\n" + text)
    out = ROOT / "target"
    out.mkdir(exist_ok=True)
    (out / "frf_sdypy_table.txt").write_text(text + "\n")
    return rows


def test_ancf_finds_every_mode_sdypy_finds(table):
    for name, f, z, ours, theirs in table:
        if f is not None and theirs is not None:
            assert ours is not None, f"{name}: sdypy finds {theirs}, ancf-modal not ({f} Hz)"


def test_ancf_reports_no_pole_away_from_a_true_mode(table):
    truths = {}
    for name, f, z, _, _ in table:
        if f is not None:
            truths.setdefault(name, []).append(f)
    for name, f, _, found, _ in table:
        if f is None:
            for p in found:
                assert any(abs(p[0] - g) <= 0.02 * g for g in truths.get(name, [])), \
                    f"{name}: spurious {p}"


def test_ancf_meets_the_issue_tolerances(table):
    """Noise-free closed-form records: 1e-5 in f, 0.5 % in ζ; records of
    `impulse` (2πfΔt ≤ 0.03): 1e-4 and 2 % (its integrator's own error)."""
    for name, f, z, ours, _ in table:
        if f is None:
            continue
        tf, tz = (1e-5, 5e-3) if name.startswith("numpy") else (1e-4, 2e-2)
        assert abs(ours[0] - f) <= tf * f, f"{name}: f {ours[0]} vs {f}"
        assert abs(ours[1] - z) <= tz * z, f"{name}: ζ {ours[1]} vs {z}"


def medians(pairs):
    ef = [(abs(a[0] - f) / f, abs(b[0] - f) / f) for f, z, a, b in pairs]
    ez = [(abs(a[1] - z) / z, abs(b[1] - z) / z) for f, z, a, b in pairs]
    return (np.median([e[0] for e in ef]), np.median([e[1] for e in ef]),
            np.median([e[0] for e in ez]), np.median([e[1] for e in ez]))


def test_ancf_median_errors_no_larger_than_sdypy(table):
    """The median error in f over the suite, and in ζ over each kind of
    record, is no larger than sdypy's. The median ζ error over the whole
    suite is not compared: its 24 rows split evenly between records where
    ancf-modal's error is ~1e-13 (closed form) and records of `impulse`
    (~1e-3, the integrator's own error included), so the pooled median is
    half the smallest `impulse` error, a number neither group shows."""
    rows = [(name, f, z, a, b) for name, f, z, a, b in table if f is not None and a and b]
    assert rows
    of, tf, _, _ = medians([r[1:] for r in rows])
    print(f"median f error over the suite: ours {of:.2e} sdypy {tf:.2e}")
    assert of <= tf
    for kind in ("numpy", "impulse"):
        group = [r[1:] for r in rows if r[0].startswith(kind)]
        _, _, oz, tz = medians(group)
        print(f"median ζ error, {kind} records: ours {oz:.2e} sdypy {tz:.2e}")
        assert oz <= tz
