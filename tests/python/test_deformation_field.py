"""dnurbs.DeformationFieldModel from Python (dynamics/fields/deformation_field_model.h): the
cascade of deformation fields of Goldenstein et al. 2005 (eqs. 1-4) from Python functions, its
mass matrix against the closed-form integral and its static equilibrium under a point force, and
the face of a geometry image with its adaptive meshes."""

import numpy as np
import pytest

import dnurbs
from conftest import SOURCE_DIR


def plane(u, v):
    return np.array([u, v, 0.0])


def test_fields_from_functions_give_the_closed_form_mass_and_equilibrium():
    # x = (u, v, 0) + q_0 (u, v, 0) + q_1 e_z on [0, 2] x [0, 1]: integral |(u, v, 0)|^2 = 10/3,
    # integral |e_z|^2 = 2, the cross term 0; Gauss with 3 points is exact for these quadratics
    model = dnurbs.DeformationFieldModel(
        [(plane,), (plane, 0), (lambda u, v: np.array([0.0, 0.0, 1.0]), 1)],
        stiffness=[3.0, 8.0], domain=[0.0, 2.0, 0.0, 1.0], mass_density=1.5)
    assert model.coordinate_count == 2
    assert model.tessellation_max_error == 0.0
    mass = model.matrices(dense=True)["mass"]
    np.testing.assert_allclose(mass, 1.5 * np.diag([10.0 / 3.0, 2.0]), atol=1e-12)
    # A point force f at (0.5, 0.5): L^T f = (f . (0.5, 0.5, 0), f_z), q = L^T f / k
    system = dnurbs.System()
    system.add_model(model)
    system.add_point_force(0, [0.5, 0.5], [2.0, 4.0, 6.0])
    dnurbs.solve_static_equilibrium(system)
    np.testing.assert_allclose(system.coordinates, [3.0 / 3.0, 6.0 / 8.0], atol=1e-14)


def test_face_meshes_are_adaptive_to_the_max_error():
    path = str(SOURCE_DIR / "examples" / "faces" / "face_ada.gim")
    face = dnurbs.DeformationFieldModel.face(path, stiffness=[1.0] * 7, max_error=0.5,
                                             quadrature_cells=(4, 4), quadrature_points=2)
    assert face.coordinate_count == 7
    assert face.tessellation_max_error == 0.5
    q = np.zeros(7)
    q[6] = 1.0  # the jaw opened by 12 mm at the chin
    adaptive = face.tessellate(q, segments_u=4, segments_v=4)
    # Its own max error refines the 4 x 4 base: more than its 25 vertices, fewer than the
    # 65 x 65 samples of the geometry image
    assert 25 < adaptive.vertex_count < 65 * 65
    with pytest.raises(dnurbs.Error, match="stiffness"):
        dnurbs.DeformationFieldModel.face(path, stiffness=[-1.0] * 7)
