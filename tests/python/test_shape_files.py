"""Shape files from Python: NURBS curves, surfaces and triangular NURBS surfaces written and read
back bit for bit (the JSON numbers round-trip exactly), and the library's messages for bad files
and wrong argument types."""

import numpy as np
import pytest

import dnurbs


def same_shape(a, b):
    assert type(a) is type(b)
    np.testing.assert_array_equal(a.control_points, b.control_points)
    np.testing.assert_array_equal(a.weights, b.weights)


@pytest.mark.parametrize("shape", [dnurbs.full_circle(2.5, [1, 2, 3]), dnurbs.sphere(1.5),
                                   dnurbs.periodic_torus(3.0, 1.0)])
def test_nurbs_shapes_round_trip_exactly(shape, tmp_path):
    text = dnurbs.shape_to_json(shape)
    same_shape(dnurbs.parse_shape(text, "text"), shape)
    path = tmp_path / "shape.json"
    dnurbs.write_shape(path, shape)
    back = dnurbs.read_shape(path)
    same_shape(back, shape)
    assert not dnurbs.is_triangular_shape_file(path)


def test_triangular_shapes_round_trip_exactly(tmp_path):
    basis = dnurbs.TriangularBSplineBasis(dnurbs.l_shape_triangulation(1), 2)
    flat = dnurbs.flat_triangular_surface(basis)
    points = np.array(flat.control_points)
    points[:, 2] = np.sin(points[:, 0]) * np.cos(points[:, 1])
    surface = dnurbs.TriangularNurbsSurface(basis, points, np.linspace(1, 2, basis.function_count))
    text = dnurbs.triangular_shape_to_json(surface)
    back = dnurbs.parse_triangular_shape(text)
    np.testing.assert_array_equal(back.control_points, surface.control_points)
    np.testing.assert_array_equal(back.weights, surface.weights)
    path = tmp_path / "patch.json"
    dnurbs.write_triangular_shape(path, surface)
    assert dnurbs.is_triangular_shape_file(path)
    read = dnurbs.read_triangular_shape(path)
    u = np.array([[0.2, 0.3], [1.5, 0.4]])
    np.testing.assert_array_equal(read(u), surface(u))


def test_bad_shape_files_raise_the_library_message(tmp_path):
    text = dnurbs.shape_to_json(dnurbs.full_circle(1.0))
    with pytest.raises(ValueError, match=r"^mine: .*weight"):
        dnurbs.parse_shape(text.replace("0.7071067811865476", "-1", 1), "mine")
    with pytest.raises(ValueError, match="unparseable|JSON|expected"):
        dnurbs.parse_shape("{", "broken")
    with pytest.raises(ValueError, match="missing.json"):
        dnurbs.read_shape(tmp_path / "missing.json")
    with pytest.raises(TypeError, match="shape is a int, must be a NurbsCurve or a NurbsSurface"):
        dnurbs.shape_to_json(42)
    with pytest.raises(TypeError):
        dnurbs.write_triangular_shape(tmp_path / "x.json", dnurbs.sphere(1.0))


@pytest.mark.skipif(not dnurbs.cad_exchange_available(), reason="built without Open CASCADE")
@pytest.mark.parametrize("name", ["part.step", "part.igs"])
def test_cad_files_round_trip_exactly(name, tmp_path):
    # A periodic torus (periodic in both directions, rational) and a clamped circle.
    torus = dnurbs.periodic_torus(3.0, 1.0)
    circle = dnurbs.full_circle(2.5, [1, 2, 3])
    path = tmp_path / name
    dnurbs.write_cad_file(path, [circle, torus])
    shapes = dnurbs.read_cad_file(path)
    assert len(shapes) == 2
    # STEP lists faces before free edges; IGES keeps the order written.
    surface, curve = (shapes[0], shapes[1]) if name.endswith(".step") else (shapes[1], shapes[0])
    same_shape(surface, torus)
    same_shape(curve, circle)
    assert surface.knots_u.is_periodic and surface.knots_v.is_periodic
    with pytest.raises(dnurbs.Error, match="holds 2 curves and surfaces"):
        dnurbs.read_shape(path)
    with pytest.raises(TypeError, match="shape is a int, must be a NurbsCurve or a NurbsSurface"):
        dnurbs.write_cad_file(tmp_path / "bad.step", [1])
    with pytest.raises(dnurbs.Error, match="not a CAD file name"):
        dnurbs.write_cad_file(tmp_path / "bad.txt", [circle])


def test_obj_freeform_round_trips_exactly(tmp_path):
    torus = dnurbs.periodic_torus(3.0, 1.0)
    circle = dnurbs.full_circle(2.5, [1, 2, 3])
    path = tmp_path / "part.obj"
    dnurbs.write_obj_freeform(path, [circle, torus])
    curve, surface = dnurbs.read_obj_freeform(path)
    same_shape(curve, circle)
    same_shape(surface, torus)
    assert surface.knots_u.is_periodic and surface.knots_v.is_periodic
    path.write_text("v 0 0 0\ncstype bezier\n")
    with pytest.raises(dnurbs.Error, match="part.obj: line 2: "):
        dnurbs.read_obj_freeform(path)
