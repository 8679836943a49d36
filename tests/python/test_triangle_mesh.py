"""dnurbs.TriangleMesh, export_meshes and import_meshes: arrays in and out as views, files
written in every format and read back with the same geometry, bad meshes rejected."""

import numpy as np
import pytest

import dnurbs


def square():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    triangles = np.array([[0, 1, 2], [0, 2, 3]])
    normals = np.tile([0.0, 0.0, 1.0], (4, 1))
    return dnurbs.TriangleMesh(vertices, triangles, normals, vertices[:, :2], name="square")


def test_mesh_arrays_are_views_with_checked_setters():
    mesh = square()
    assert mesh.vertex_count == 4 and mesh.triangle_count == 2
    assert mesh.triangles.dtype == np.int32 and mesh.uv.shape == (4, 2)
    assert np.shares_memory(mesh.vertices, mesh.vertices)
    assert not mesh.vertices.flags.writeable
    mesh.vertices = np.asarray(mesh.vertices) * 2
    assert mesh.vertices[2, 0] == 2.0
    with pytest.raises(dnurbs.Error, match="triangles\\[0, 1\\] is 1.5, must be an integer"):
        mesh.triangles = [[0, 1.5, 2]]
    with pytest.raises(dnurbs.Error, match="normals must have shape \\(4, 3\\)"):
        dnurbs.TriangleMesh(mesh.vertices, mesh.triangles, np.zeros((3, 3)))
    assert "square" in repr(mesh)


@pytest.mark.parametrize("suffix", [".obj", ".ply", ".stl", ".gltf", ".glb"])
def test_export_and_import_round_trip(tmp_path, suffix):
    mesh = square()
    path = tmp_path / f"square{suffix}"
    dnurbs.export_meshes([mesh], path)
    meshes = dnurbs.import_meshes(path)
    assert len(meshes) == 1
    back = meshes[0]
    assert back.triangle_count == 2
    # STL stores single precision; the square's coordinates are exact in it.
    np.testing.assert_array_equal(np.unique(back.vertices, axis=0),
                                  np.unique(mesh.vertices, axis=0))


def test_bad_exports_raise():
    mesh = square()
    with pytest.raises(dnurbs.Error, match="xyz"):
        dnurbs.export_meshes([mesh], "square.xyz")
    with pytest.raises(dnurbs.Error):
        dnurbs.export_meshes([], "empty.obj")
    mesh.triangles = [[0, 1, 7]]
    with pytest.raises(dnurbs.Error):
        dnurbs.export_meshes([mesh], "bad.obj")
    with pytest.raises(dnurbs.Error):
        dnurbs.import_meshes("/nonexistent/mesh.obj")
