"""ancf_modal.frf on arrays: a single-degree-of-freedom hammer test whose
modes are known, and the same records through frf_files."""

import math
import re

import numpy as np
import pytest

import ancf_modal

FS = 10240.0
F_N, ZETA, MASS = 180.0, 0.01, 1.0


def hammer_hit(seed, seconds=2.0, amplitude=100.0, pulse=5e-4):
    """Force [N] (a half-sine pulse) and velocity [m/s] of a mass–spring–damper
    (f_n = 180 Hz, ζ = 1 %, m = 1 kg), the response summed exactly over the
    sampled force's impulses, with 0.05 % noise on the response."""
    n = int(seconds * FS)
    t = np.arange(n) / FS
    force = np.where(t < pulse, amplitude * np.sin(np.pi * t / pulse), 0.0)
    w = 2 * math.pi * F_N
    wd = w * math.sqrt(1 - ZETA**2)
    velocity = np.zeros(n)
    for k in np.nonzero(force)[0]:
        tau = t[k:] - t[k]
        unit = np.exp(-ZETA * w * tau) * (np.cos(wd * tau) - ZETA * w / wd * np.sin(wd * tau))
        velocity[k:] += force[k] / FS / MASS * unit
    rng = np.random.default_rng(seed)
    velocity += 5e-4 * np.max(np.abs(velocity)) * rng.standard_normal(n)
    return t, force, velocity


def write_csv(path, t, force, velocity):
    with open(path, "w") as f:
        f.write("time,force,velocity\n")
        for row in zip(t, force, velocity):
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def test_the_fit_finds_the_oscillator():
    _, force, velocity = hammer_hit(seed=1)
    r = ancf_modal.frf(force, velocity, FS)
    (peak,) = [p for p in r.peaks if abs(p["frequency_hz"] - F_N) < 0.1 * F_N]
    assert abs(peak["frequency_hz"] - F_N) / F_N < 1e-3
    assert abs(peak["damping_ratio"] - ZETA) / ZETA < 0.05
    # H1 of a velocity response: |H| = 1/(2 ζ m ω) at resonance.
    k = np.argmin(np.abs(r.freq - F_N))
    assert abs(abs(r.h1[k]) * 2 * ZETA * MASS * 2 * math.pi * F_N - 1.0) < 0.1
    assert r.h1.dtype == np.complex128 and r.freq.shape == r.h1.shape
    assert np.allclose(r.coherence, 1.0)  # one hit: γ² ≡ 1


@pytest.mark.parametrize("hits", [1, 2])
def test_arrays_equal_files(tmp_path, hits):
    records = [hammer_hit(seed=s) for s in range(hits)]
    paths = []
    for i, (t, f, v) in enumerate(records):
        paths.append(tmp_path / f"hit{i}.csv")
        write_csv(paths[-1], t, f, v)
    force = np.array([f for _, f, _ in records])
    velocity = np.array([v for _, _, v in records])
    if hits == 1:
        force, velocity = force[0], velocity[0]
    # A taper on impact records is warned about, from arrays and files alike.
    with pytest.warns(ancf_modal.ModelWarning, match="tapers the blow"):
        a = ancf_modal.frf(force, velocity, FS, window="hann")
    with pytest.warns(ancf_modal.ModelWarning, match="tapers the blow"):
        b = ancf_modal.frf_files(paths, window="hann")
    # The files' rate comes from their time column: equal to round-off.
    assert np.allclose(a.freq, b.freq, rtol=1e-9, atol=0)
    assert np.allclose(a.h1, b.h1, rtol=1e-9, atol=0)
    assert np.allclose(a.h2, b.h2, rtol=1e-9, atol=0)
    assert np.allclose(a.coherence, b.coherence, rtol=1e-9, atol=1e-12)
    fa = [p["frequency_hz"] for p in a.peaks]
    fb = [p["frequency_hz"] for p in b.peaks]
    assert len(fa) == len(fb) and np.allclose(fa, fb, rtol=1e-7)
    assert a.to_dict()["averages"] == hits


def test_frf_files_to_dict_equals_the_command_line(tmp_path, cli):
    t, f, v = hammer_hit(seed=3)
    path = tmp_path / "hit.csv"
    write_csv(path, t, f, v)
    mine = ancf_modal.frf_files([path]).to_dict()
    doc = cli.json("frf", str(path))
    for key, value in mine.items():
        assert key in doc, key
        if key in ("peaks", "rejected", "stabilization", "h1", "h2", "coherence"):
            assert len(value) == len(doc[key]), key
        else:
            assert value == doc[key], key
    assert np.allclose(
        [p["frequency_hz"] for p in mine["peaks"]],
        [p["frequency_hz"] for p in doc["peaks"]],
        rtol=1e-12,
    )
    assert repr(ancf_modal.frf_files([path])).splitlines()[0].startswith("measurement:")


def test_bad_arguments():
    _, f, v = hammer_hit(seed=0, seconds=0.5)
    with pytest.raises(ancf_modal.ModelError, match=r"^fs `-1(\.0)?`: must be a number > 0"):
        ancf_modal.frf(f, v, -1.0)
    with pytest.raises(ancf_modal.ModelError, match=r"^estimator `h3`"):
        ancf_modal.frf(f, v, FS, estimator="h3")
    with pytest.raises(ancf_modal.ModelError, match=r"^window `kaiser`"):
        ancf_modal.frf(f, v, FS, window="kaiser")
    with pytest.raises(ancf_modal.ModelError, match=r"^response "):
        ancf_modal.frf(f, v[:-1], FS)
    with pytest.raises(ancf_modal.ModelError, match=r"all zero|zero"):
        ancf_modal.frf(np.zeros_like(f), v, FS)


def test_swapped_channels_name_samples_not_file_lines(tmp_path):
    # The velocity given as the force rises again after its first swing
    # ends: a double impact, which arrays place by 0-based sample (they
    # have no file lines) and a CSV file by its line. (4 s: 45 decay times
    # of the 1 % mode, so the swung velocity is impulsive, peak > 10 RMS.)
    t, f, v = hammer_hit(seed=0, seconds=4.0)
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.frf(v, f, FS)
    message = str(e.value)
    assert "double impact" in message and "sample" in message and "line" not in message
    # The sample it names is where the swapped "force" rises again to 20 %
    # of its peak after falling under 5 % (the impact's end): computed here.
    sample = int(re.search(r"at sample (\d+)", message).group(1))
    end = int(re.search(r"ended at sample (\d+)", message).group(1))
    assert abs(v[sample]) > 0.2 * np.max(np.abs(v)) and sample > end
    path = tmp_path / "swapped.csv"
    write_csv(path, t, v, f)
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.frf_files([path], force="force")
    # The file's line of the same sample: a header line, then 1-based.
    assert f"{path}:{sample + 2}: double impact" in str(e.value)
