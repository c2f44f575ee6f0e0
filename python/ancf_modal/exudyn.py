"""A reduced body of ancf-modal (``Model.reduce``) in Exudyn.

``add_flexible_body(mbs, body)`` builds Exudyn's ``FEMinterface`` from the
body's 3D node form (node positions [m], mass [kg] and stiffness [N/m] over
three translations per node, the basis over the same) and adds an
``ObjectFFRFreducedOrder`` on a floating frame with Rxyz rotation
parameters. The body is planar: the frame's out-of-plane motions (z,
rotation about x and about y) are fixed to the ground. Exudyn is imported
when the function is called, so ``ancf_modal`` does not need it.

The basis is M-orthogonal to the rigid motions the frame carries (as
Exudyn's ``excludeRigidBodyMotion``), so the frame and the modal
coordinates never count a motion twice. Damping, if wanted, is Exudyn's
Rayleigh damping on the modal coordinates.

Exudyn gets the basis with each column scaled to a largest node
displacement of 1 m (the body's file keeps the mass-normalised one, where
ΨᵀMΨ = I): Exudyn's modal coordinates are then metres of the column's
largest displacement. A mass-normalised column of a small body has
entries of order 1/√(mass) (about 1e12 m per unit for a 200 µm silicon
bridge), and Exudyn's import gives wrong frequencies for it (×14.7 there);
the scaled columns span the same motions, so nothing else changes. The
returned ``basis_scale`` maps back: η = ξ / scale, ξ Exudyn's modal
coordinates and η the file's.
"""

from __future__ import annotations

from typing import Any, Dict, Sequence, Tuple

import numpy as np


def _csr(triplets: Sequence[Sequence[float]], size: int) -> Any:
    from scipy.sparse import csr_matrix

    t = np.asarray(triplets, dtype=float).reshape(-1, 3)
    return csr_matrix(
        (t[:, 2], (t[:, 0].astype(int), t[:, 1].astype(int))), shape=(size, size)
    )


def add_flexible_body(
    mbs: Any,
    body: Any,
    position: Tuple[float, float, float] = (0.0, 0.0, 0.0),
    clamp: Sequence[int] = (),
    hold_slope_length: bool = False,
) -> Dict[str, Any]:
    """Adds ``body`` (an ``ancf_modal.ReducedBody``) to the Exudyn system ``mbs``.

    ``position`` [m] is the frame's reference position: node positions are
    the model's, so (0, 0, 0) puts the body where the model has it.
    ``clamp`` lists interface points (indices into the body's interface)
    to weld to the ground, as ancf-modal's weld joint does: the interface
    node is held in x and y, and its virtual node across the beam (the
    slope's direction; a distance constraint to a ground point 1 m away
    along the beam's normal, which holds the normal displacement in the
    linearization), so the beam may still stretch there. With
    ``hold_slope_length`` the virtual node is held in x and y too (the
    whole slope: no axial strain at the point). A body
    reduced with ``keep_supports`` carries its supports in its basis and
    no rigid motion on its frame: its frame is fixed to the ground.

    Returns a dict: ``object`` (the ObjectFFRFreducedOrder), ``nodes``
    (``rigid``: the frame's node, ``modal``: the modal coordinates' node,
    each coordinate the displacement [m] of its basis column's largest
    entry), ``basis_scale`` (per column, the largest displacement of the
    file's mass-normalised column [m per unit]: η = ξ / scale),
    ``markers`` (one MarkerSuperElementPosition per interface point, at the
    interface node, for the user's joints), ``interface_nodes`` (per
    interface point its node and virtual node), ``interface``
    (the ``FEMinterface``) and ``cms`` (the ObjectFFRFreducedOrderInterface).
    """
    import exudyn as exu
    import exudyn.itemInterface as eii
    from exudyn.FEM import FEMinterface, ObjectFFRFreducedOrderInterface

    doc = body.to_dict()
    if len(position) != 3:
        raise ValueError(f"position {tuple(position)!r}: give (x, y, z) in m")
    points = len(doc["interface"])
    for index in clamp:
        if not 0 <= int(index) < points:
            raise ValueError(
                f"clamp {list(clamp)!r}: {index} is not an interface point of the body "
                f"(indices 0 to {points - 1} into its interface)"
            )
    form = doc["nodes"]
    positions = np.asarray(form["positions"], dtype=float)
    size = 3 * len(positions)
    fem = FEMinterface()
    fem.nodes = {"Position": positions}
    fem.massMatrix = _csr(form["mass"], size)
    fem.stiffnessMatrix = _csr(form["stiffness"], size)
    basis = np.asarray(form["basis"], dtype=float)
    # Unit largest displacement per column (module doc): Exudyn is wrong
    # with the mass-normalised columns of a small body.
    scale = np.abs(basis).max(axis=0) if basis.size else np.zeros(0)
    scale = np.where(scale > 0.0, scale, 1.0)
    fem.modeBasis = {
        "matrix": basis / scale,
        "type": "ancf_modal " + doc["method"],
    }
    cms = ObjectFFRFreducedOrderInterface(
        fem, rigidBodyNodeType=exu.NodeType.RotationRxyz
    )
    added = cms.AddObjectFFRFreducedOrder(mbs, positionRef=list(position))
    obj = added["oFFRFreducedOrder"]
    rigid = added["nRigidBody"]
    modal = added["nGenericODE2"]
    ground_node = mbs.AddNode(eii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
    ground_coordinate = mbs.AddMarker(
        eii.MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0)
    )
    # Rxyz node: [x, y, z, φx, φy, φz]; hold z, φx, φy. A body that kept
    # its supports (no rigid motions left to the frame: `rigid` has no
    # column) has them in its basis: its frame is held in the plane too.
    carried = np.asarray(body.rigid).shape[1]
    for c in (2, 3, 4) if carried else range(6):
        m = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=rigid, coordinate=c))
        mbs.AddObject(eii.CoordinateConstraint(markerNumbers=[ground_coordinate, m]))
    markers = []
    interface_nodes = []
    for p in doc["interface"]:
        node, virtual = p["nodes"]
        interface_nodes.append((node, virtual))
        markers.append(
            mbs.AddMarker(
                eii.MarkerSuperElementPosition(
                    bodyNumber=obj, meshNodeNumbers=[node], weightingFactors=[1.0]
                )
            )
        )
    if clamp:
        ground = mbs.AddObject(eii.ObjectGround())
    def ground_at(point: np.ndarray) -> Any:
        at = np.asarray(position, dtype=float) + point
        return mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground, localPosition=list(at)))

    def body_at(node: int) -> Any:
        return mbs.AddMarker(
            eii.MarkerSuperElementPosition(
                bodyNumber=obj, meshNodeNumbers=[node], weightingFactors=[1.0]
            )
        )

    for index in clamp:
        node, virtual = interface_nodes[index]
        held = (node, virtual) if hold_slope_length else (node,)
        for k in held:
            mbs.AddObject(
                eii.ObjectJointSpherical(
                    markerNumbers=[ground_at(positions[k]), body_at(k)], constrainedAxes=[1, 1, 0]
                )
            )
        if not hold_slope_length:
            tangent = positions[virtual] - positions[node]
            normal = np.array([-tangent[1], tangent[0], 0.0]) / np.linalg.norm(tangent)
            mbs.AddObject(
                eii.ObjectConnectorDistance(
                    markerNumbers=[ground_at(positions[virtual] + normal), body_at(virtual)],
                    distance=1.0,
                )
            )
    return {
        "object": obj,
        "nodes": {"rigid": rigid, "modal": modal},
        "basis_scale": scale,
        "markers": markers,
        "interface_nodes": interface_nodes,
        "interface": fem,
        "cms": cms,
    }
