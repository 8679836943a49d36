"""dnurbs.DeformableSuperquadricModel from Python: the layout of q, the decoded state, the mass
properties of the unit sphere against the spherical shell's (m = 4 pi mu r^2, I = 2/3 m r^2),
momenta of rigid motions, and the library's messages for bad input."""

import math

import numpy as np
import pytest

import dnurbs

SPHERE = [1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0]  # a, a1, a2, a3, e1 = e2 = 1: the unit sphere


def test_rigid_sphere_layout_state_and_rotation():
    half = math.sqrt(0.5)
    model = dnurbs.DeformableSuperquadricModel(SPHERE, centre=[1, 2, 3],
                                               orientation=[half, 0, 0, half])
    assert model.is_rigid and model.coordinate_count == 7 and model.velocity_count == 6
    assert model.layout == {"translation_coordinate": 0, "quaternion_coordinate": 3,
                            "shape_coordinate": -1, "local_coordinate": -1,
                            "translation_velocity": 0, "rotation_velocity": 3,
                            "shape_velocity": -1, "local_velocity": -1}
    assert model.free_shape_parameters == []
    np.testing.assert_array_equal(model.centre(), [1, 2, 3])
    np.testing.assert_allclose(model.orientation(), [half, 0, 0, half], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(model.shape_parameters(), SPHERE)
    np.testing.assert_array_equal(model.rest_shape, SPHERE)
    # x(0, 0) = c + R (1, 0, 0) with R the quarter turn about z: (1, 2, 3) + (0, 1, 0); the
    # quaternion's rotation matrix is exact to round-off.
    np.testing.assert_allclose(model.position(None, [0.0, 0.0]), [1, 3, 3], rtol=0, atol=1e-15)


def test_sphere_mass_properties_match_the_spherical_shell():
    model = dnurbs.DeformableSuperquadricModel(SPHERE, mass_density=2.0)
    reference = model.reference_mass_properties
    mass = 8 * math.pi  # 4 pi r^2 mu
    # Gauss-Legendre with 3 points on 8 x 16 cells: the area element cos(u) integrates to
    # 1.8e-9 relative, the inertia's cos^3(u) to 1.7e-7 (measured); bounds 5x those.
    assert reference["mass"] == pytest.approx(mass, rel=1e-8)
    np.testing.assert_allclose(reference["inertia_about_centre"], 2 / 3 * mass * np.eye(3),
                               rtol=0, atol=1e-6 * 2 / 3 * mass)
    np.testing.assert_allclose(reference["centre_of_mass"], 0, atol=1e-14)
    now = model.mass_properties()
    assert now["mass"] == reference["mass"]
    np.testing.assert_array_equal(now["inertia_about_origin"], reference["inertia_about_origin"])
    # The quadrature: weights cover [-pi/2, pi/2] x [-pi, pi) and carry the mass.
    points = model.quadrature_points
    assert points.shape == (8 * 16 * 9, 3)
    assert points[:, 2].sum() == pytest.approx(2 * math.pi ** 2, rel=1e-13)
    assert model.quadrature_masses.sum() == pytest.approx(reference["mass"], rel=1e-13)
    np.testing.assert_allclose(model.centre_of_mass(), 0, atol=1e-14)


def test_momenta_of_rigid_motions():
    model = dnurbs.DeformableSuperquadricModel(SPHERE, centre=[0.5, 0, 0])
    mass = model.reference_mass_properties["mass"]
    velocity = np.array([0.1, -0.2, 0.3, 0, 0, 0])
    np.testing.assert_allclose(model.linear_momentum(None, velocity), mass * velocity[:3],
                               rtol=1e-13)
    spin = np.array([0, 0, 0, 0, 0, 2.0])  # about the body z axis through the centre
    inertia = model.reference_mass_properties["inertia_about_centre"]
    # L about the origin = c x m v_c + I w with v_c = 0 for a spin about the centre of mass.
    np.testing.assert_allclose(model.angular_momentum(None, spin), inertia @ spin[3:],
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(model.linear_momentum(None, spin), 0, atol=1e-12)
    # The exponential map: a body rotation of pi/2 about z turns the identity quaternion into
    # (cos pi/4, 0, 0, sin pi/4); dc moves the centre.
    q = model.advance_coordinates(None, [0.5, 0, 0, 0, 0, np.pi / 2])
    np.testing.assert_allclose(q[:3], [1, 0, 0], atol=1e-16)
    np.testing.assert_allclose(model.orientation(q), [np.sqrt(0.5), 0, 0, np.sqrt(0.5)],
                               atol=1e-15)
    with pytest.raises(ValueError, match="control point"):
        model.control_point_offset(0)


def test_global_parts_free_the_shape_parameters():
    model = dnurbs.DeformableSuperquadricModel(SPHERE, parts="global", free_shape=[0])
    assert model.free_shape_parameters == [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 13]
    assert not model.is_rigid
    assert model.layout["shape_coordinate"] == 7 and model.layout["shape_velocity"] == 6
    q = model.initial_coordinates()
    q[7 + 1] = 1.5  # a1, the second free entry
    shape = model.shape_parameters(q)
    assert shape[1] == 1.5 and shape[2] == 1
    # x(0, 0) = a a1 (1, 0, 0) on the equator at longitude 0.
    np.testing.assert_allclose(model.position(q, [0, 0]), [1.5, 0, 0], atol=1e-15)
    names = dnurbs.superquadric_parameter_names()
    assert len(names) == 14
    assert names[0] == "scale a" and names[4] == "squareness e1" and names[11] == "twist tau"


@pytest.mark.parametrize("arguments, message", [
    (dict(shape=[0] + SPHERE[1:]), "a"),
    (dict(shape=SPHERE, orientation=[2, 0, 0, 0]), "orientation|quaternion"),
    (dict(shape=SPHERE, parts="bogus"), "parts is \"bogus\""),
    (dict(shape=SPHERE, free_shape=[14]), "free shape parameter 14"),
    (dict(shape=SPHERE[:13]), r"shape must have shape \(14,\)"),
    (dict(shape=SPHERE, mass_density=float("nan")), "mass"),
])
def test_bad_superquadrics_raise_the_library_message(arguments, message):
    with pytest.raises(ValueError, match=message):
        dnurbs.DeformableSuperquadricModel(**arguments)
