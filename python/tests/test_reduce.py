"""Reduced flexible bodies (`Model.reduce`) and their import into Exudyn.

Every number compared comes from an independent source: the full model's
own `modal` under the same boundary condition (a model file with the
support as a joint), Exudyn's eigenvalues of the imported body, or the
model's mass and inertia from its bodies' closed forms.
"""

import json

import numpy as np
import pytest
import scipy.linalg

import ancf_modal
from ancf_modal.exudyn import add_flexible_body

L = 0.1


def beam(elements=20, joints=(), length=L, section=(1e-3, 1e-2), material=(2.1e11, 7850)):
    return ancf_modal.Model.from_json(
        json.dumps(
            {
                "name": "steel_beam",
                "gravity": [0, 0],
                "beams": [
                    {
                        "id": "blade",
                        "start": [0, 0],
                        "angle_deg": 0,
                        "length": length,
                        "elements": elements,
                        "section": {"height": section[0], "width": section[1]},
                        "material": {"young": material[0], "density": material[1]},
                    }
                ],
                "joints": list(joints),
            }
        )
    )


WELD = {"type": "weld", "a": {"ground": [0, 0]}, "b": {"beam": "blade", "s": 0}}
PIN = {"type": "pin", "a": {"ground": [0, 0]}, "b": {"beam": "blade", "s": 0}}


def reduced_hz(body, held=()):
    """The package's reduced model [R Ψ] with the coordinates `held` held."""
    whole = np.hstack([body.rigid, body.basis])
    d = body.to_dict()
    q = np.asarray(d["q"])
    del q
    m = np.eye(whole.shape[1])
    k = np.zeros_like(m)
    r = body.rigid.shape[1]
    k[r:, r:] = body.stiffness
    if held:
        n = scipy.linalg.null_space(whole[list(held), :])
        m, k = n.T @ m @ n, n.T @ k @ n
    w2 = scipy.linalg.eigh(k, m, eigvals_only=True)
    return np.sign(w2) * np.sqrt(np.abs(w2)) / (2 * np.pi)


def full_elastic_hz(model, count):
    result = model.modal(modes=count + 3)
    kinds = result.kinds
    return np.array([f for f, kd in zip(result.frequencies_hz, kinds) if kd not in ("rigid", "mechanism")])[:count]


def exudyn_hz(body, clamp, count, hold_slope_length=False):
    exu = pytest.importorskip("exudyn")
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    added = add_flexible_body(mbs, body, clamp=clamp, hold_slope_length=hold_slope_length)
    mbs.Assemble()
    values, _ = exu.solver.ComputeODE2Eigenvalues(mbs, computeComplexEigenvalues=False, useAbsoluteValues=False)
    values = np.sort(np.asarray(values))
    return added, np.sqrt(np.abs(values[:count])) / (2 * np.pi)


def test_exudyn_agrees_with_the_reduced_body_and_the_full_cantilever():
    body = beam().reduce(interface=[("blade", 0.0), ("blade", L)], modes=8)
    _, hz = exudyn_hz(body, clamp=[0], count=6)
    # The clamp holds the root's position and the slope across the beam
    # (along x here: r'_y), as a weld does.
    own = reduced_hz(body, held=(0, 1, 3))[:6]
    np.testing.assert_allclose(hz, own, rtol=1e-6, err_msg="Exudyn against the package's reduced body")
    full = full_elastic_hz(beam(joints=[WELD]), 6)
    np.testing.assert_allclose(hz, full, rtol=1e-3, err_msg="Exudyn against the full clamped beam")


def test_free_interface_keeps_eight_free_free_modes():
    body = beam().reduce(interface=[("blade", 0.0), ("blade", L)], modes=8, method="free-interface")
    own = reduced_hz(body)[3:11]
    full = full_elastic_hz(beam(), 8)
    np.testing.assert_allclose(own, full, rtol=1e-8)
    # Its own check: the first interface point held.
    assert body.check["condition"] == {"kind": "held", "point": 1}


def test_pinned_free_error_falls_as_the_basis_grows():
    full = full_elastic_hz(beam(joints=[PIN]), 6)
    worst = []
    for k in (8, 16, 30):
        body = beam().reduce(interface=[("blade", 0.0), ("blade", L)], modes=k)
        own = reduced_hz(body, held=(0, 1))
        # The pinned beam's rigid rotation about the pin stays a zero mode.
        errors = (own[1:7] - full) / full
        assert np.all(errors > -1e-9), f"k = {k}: below the full model {errors}"
        worst.append(errors.max())
    assert worst[0] > worst[1] > worst[2], worst


def test_the_papers_assembly_imports_with_its_mass_and_inertia():
    model = ancf_modal.Model.builtin()
    body = model.reduce(interface=[("blade", 0.0), ("blade", 25e-3)], modes=8)
    added, hz = exudyn_hz(body, clamp=[0], count=4)
    spec = json.loads(model.to_json())
    blade = spec["beams"][0]
    rho_a = blade["material"]["density"] * blade["section"]["height"] * blade["section"]["width"]
    m_beam = rho_a * blade["length"]
    t = np.array([np.cos(np.radians(blade["angle_deg"])), np.sin(np.radians(blade["angle_deg"]))])
    mid = np.asarray(blade["start"]) + 0.5 * blade["length"] * t
    parts = [(m_beam, mid, m_beam * blade["length"] ** 2 / 12)]
    parts += [(b["mass"], np.asarray(b["position"]), b["inertia"]) for b in spec["rigid_bodies"]]
    parts += [(p["mass"], np.asarray(p["position"]), 0.0) for p in spec["point_masses"]]
    total = sum(p[0] for p in parts)
    # About the frame's origin (the model's origin): J_c + m |c|² per part.
    inertia_origin = sum(j + m * float(c @ c) for m, c, j in parts)
    cms = added["cms"]
    assert abs(cms.totalMass - total) <= 1e-12 * total
    assert abs(cms.inertiaLocal[2, 2] - inertia_origin) <= 1e-12 * inertia_origin
    centre = sum(m * c for m, c, _ in parts) / total
    np.testing.assert_allclose(cms.chiU[:2], centre, rtol=0, atol=1e-12 * 0.03)
    welded = dict(spec)
    welded["joints"] = spec["joints"] + [
        {"type": "weld", "a": {"ground": blade["start"]}, "b": {"beam": "blade", "s": 0.0}}
    ]
    full = full_elastic_hz(ancf_modal.Model.from_json(json.dumps(welded)), 4)
    # The clamp is the tool's weld: position and the slope's direction.
    np.testing.assert_allclose(hz, full, rtol=1e-3)
    # Holding the whole slope also forbids axial strain at the root: mode
    # 4 of this assembly moves axially there (28704.7 Hz against the
    # weld's 28468.5 Hz), as the full model with the four coordinates
    # held (the free-interface check's condition) has it.
    _, whole = exudyn_hz(body, clamp=[0], count=4, hold_slope_length=True)
    held = model.reduce(interface=[("blade", 0.0), ("blade", 25e-3)], modes=8, method="free-interface")
    np.testing.assert_allclose(whole, held.check["full_hz"][:4], rtol=1e-3)
    assert whole[3] / full[3] - 1 > 5e-3


def test_prestressed_reduction_checks_against_the_full_model_at_the_equilibrium():
    from conftest import MODELS

    model = ancf_modal.Model.from_json(MODELS / "rcbo_prestressed.json")
    with pytest.warns(ancf_modal.ModelWarning, match="rigid motions lose it") as record:
        body = model.reduce(interface=[("blade", 0.0), ("blade", 25e-3)], modes=12, prestress=True)
    check = body.check
    assert check["condition"] == {"kind": "free"}
    # The free body's rotation under the preload is stiff in the full
    # model (36 Hz); the floating frame carries no stiffness, as in Exudyn:
    # the check lists that mode apart instead of claiming agreement. The
    # warning's lost ω² is the rigid motions' own Rayleigh quotient, an
    # upper bound of that mode (36.21 Hz against 36.16: the full mode also
    # bends a little).
    assert len(check["frame_hz"]) == 1
    lost = [w for w in record if "rigid motions lose it" in str(w.message)][0]
    omega2 = float(str(lost.message).split("reach ")[1].split(" rad")[0])
    bound = np.sqrt(omega2) / (2 * np.pi)
    assert check["frame_hz"][0] == pytest.approx(bound, rel=1e-2)
    assert check["frame_hz"][0] <= bound * (1 + 1e-3)  # the warning prints 4 digits
    # The first 4 elastic modes, reduced against full, at the equilibrium.
    errors = np.asarray(check["relative_error"])[:4]
    assert np.all(np.abs(errors) <= 1e-3), errors
    assert body.to_dict()["prestress"] is True


def test_save_writes_json_and_npz(tmp_path):
    body = beam(elements=6).reduce(interface=[("blade", 0.0)], modes=4)
    body.save(tmp_path / "b.json")
    body.save(tmp_path / "b.npz")
    data = np.load(tmp_path / "b.npz")
    np.testing.assert_array_equal(data["basis"], body.basis)
    assert json.loads((tmp_path / "b.json").read_text())["method"] == "craig-bampton"
    with pytest.raises(ancf_modal.ModelError, match="path"):
        body.save(tmp_path / "b.txt")


def test_the_command_line_writes_npz_that_numpy_reads_as_the_json_says(cli, tmp_path):
    # numpy's own reader (np.load) against the JSON document of the same
    # run: every array, integers as integers, shapes as documented.
    from conftest import MODELS

    args = ["reduce", str(MODELS / "rcbo_prestressed.json"), "--interface", "blade:0,blade:0.025", "--modes", "6", "--prestress"]
    for out in ["b.npz", "b.json"]:
        p = cli.run(*args, "--out", str(tmp_path / out))
        assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "b.json").read_text())
    with np.load(tmp_path / "b.npz") as data:
        for name in ["mass", "stiffness", "basis", "rigid", "q", "origin", "component_hz", "basis_hz"]:
            np.testing.assert_array_equal(data[name], np.asarray(doc[name]), err_msg=name)
        assert data["total_mass_kg"].shape == () and data["total_mass_kg"] == doc["total_mass_kg"]
        assert data["inertia_kg_m2"] == doc["inertia_kg_m2"] and data["load_scale"] == doc["load_scale"] == 1.0
        assert data["interface_coordinates"].dtype.kind == "i"
        np.testing.assert_array_equal(data["interface_coordinates"], [p["coordinates"] for p in doc["interface"]])
        np.testing.assert_array_equal(data["interface_nodes"], [p["nodes"] for p in doc["interface"]])
        nodes = doc["nodes"]
        np.testing.assert_array_equal(data["node_positions"], nodes["positions"])
        np.testing.assert_array_equal(data["node_mass"], nodes["mass"])
        np.testing.assert_array_equal(data["node_stiffness"], nodes["stiffness"])
        np.testing.assert_array_equal(data["node_basis"], nodes["basis"])
        for key in ["full_hz", "reduced_hz", "relative_error", "frame_hz"]:
            np.testing.assert_array_equal(data["check_" + key], doc["check"][key], err_msg=key)
        assert data["check_condition"] == "free" and data["check_held_point"] == 0
        assert data["check_zero_modes"] == doc["check"]["zero_modes"]
        for key in ["model", "method", "modes", "prestress", "keep_supports", "coordinates"]:
            assert data[key] == doc[key], key
        assert list(data["removed_supports"]) == doc["removed_supports"]
        assert list(data["interface_beam"]) == [p["beam"] for p in doc["interface"]]
        np.testing.assert_array_equal(data["interface_s"], [p["s"] for p in doc["interface"]])
        assert list(data["node_kinds"]) == nodes["kinds"]
        m = len(doc["basis_hz"])
        assert data["basis"].shape == (doc["coordinates"], m)
        assert data["node_basis"].shape == (3 * len(nodes["positions"]), m)
    error = cli.error(*args, "--out", str(tmp_path / "b.txt"))
    assert "--out" in error and "b.txt" in error and ".npz" in error
    assert not (tmp_path / "b.txt").exists()


@pytest.mark.parametrize("size", [0.2, 200e-6])
def test_exudyn_imports_a_small_body_as_well_as_a_large_one(size):
    # A silicon bridge of length `size` (200 µm: the micro-bridge; 0.2 m:
    # the same shape ×1000), free, root and tip interface, root clamped
    # in Exudyn (node and virtual node held: position and whole slope).
    # Its mass-normalised basis grows as 1/√mass (~1e12 m per unit at
    # 200 µm): Exudyn must still give the full cantilever's frequencies.
    def bridge(joints=()):
        return beam(joints=joints, length=size, section=(size / 100, size / 20), material=(169e9, 2330))

    body = bridge().reduce(interface=[("blade", 0.0), ("blade", size)], modes=8)
    _, hz = exudyn_hz(body, clamp=[0], count=4)
    full = full_elastic_hz(bridge(joints=[WELD]), 4)
    np.testing.assert_allclose(hz, full, rtol=1e-3, err_msg=f"Exudyn against the full cantilever, {size} m")


def test_a_body_that_kept_its_supports_imports_with_its_frame_fixed():
    # Welded at the root, supports kept, the tip as interface: the frame
    # carries nothing (no rigid column) and add_flexible_body fixes it, so
    # Exudyn gives the full cantilever's modes (Euler–Bernoulli's first).
    model = beam(joints=[WELD])
    body = model.reduce(interface=[("blade", L)], modes=8, keep_supports=True)
    assert body.rigid.shape[1] == 0
    _, hz = exudyn_hz(body, clamp=[], count=4)
    full = full_elastic_hz(model, 4)
    np.testing.assert_allclose(hz, full, rtol=1e-3)
    ei, rho_a = 2.1e11 * 1e-2 * 1e-3**3 / 12, 7850 * 1e-2 * 1e-3
    f1 = 1.8751040687**2 / (2 * np.pi * L**2) * np.sqrt(ei / rho_a)
    assert hz[0] == pytest.approx(f1, rel=1e-4)


def test_add_flexible_body_refuses_a_clamp_or_position_it_cannot_use():
    exu = pytest.importorskip("exudyn")
    body = beam(elements=6).reduce(interface=[("blade", 0.0)], modes=4)
    mbs = exu.SystemContainer().AddSystem()
    with pytest.raises(ValueError, match=r"clamp \[1\]: 1 is not an interface point .*0 to 0"):
        add_flexible_body(mbs, body, clamp=[1])
    with pytest.raises(ValueError, match="position"):
        add_flexible_body(mbs, body, position=(0.0, 0.0))
