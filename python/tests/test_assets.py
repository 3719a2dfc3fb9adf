"""Assets from Python: baking, numpy views of the nodes, save/load round trips, sampling."""

import gc
import math

import numpy as np
import pytest

import lsdem

CUBE_OBJ = """\
v 0 0 0
v 2 0 0
v 2 2 0
v 0 2 0
v 0 0 2
v 2 0 2
v 2 2 2
v 0 2 2
f 1 4 3
f 1 3 2
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
"""


def test_sphere_mass_properties(sphere):
    assert sphere.volume == pytest.approx(4.0 / 3.0 * math.pi * 125.0, rel=1e-12)
    inertia = sphere.inertia
    assert inertia.shape == (3, 3) and inertia.dtype == np.float64
    assert np.allclose(np.diag(inertia), 0.4 * sphere.volume * 25.0)
    assert sphere.principal_moments.shape == (3,)
    steel = sphere.mass_properties(density=7.85e-9)
    assert steel["mass"] == pytest.approx(7.85e-9 * sphere.volume)
    assert sphere.provenance["source"].startswith("sphere")


def test_node_arrays_are_read_only_views(sphere):
    nodes = sphere.nodes
    n = len(nodes)
    assert 400 < n < 600
    for array, shape in ((nodes.positions, (n, 3)), (nodes.normals, (n, 3)),
                         (nodes.areas, (n,))):
        assert array.shape == shape and array.dtype == np.float64
        assert not array.flags.writeable and not array.flags.owndata
    assert np.allclose(np.linalg.norm(nodes.positions, axis=1), 5.0, atol=1e-9)
    assert np.allclose(np.linalg.norm(nodes.normals, axis=1), 1.0)
    assert nodes.areas.sum() == pytest.approx(sphere.surface_area)
    with pytest.raises(ValueError):
        nodes.positions[0, 0] = 1.0


def test_views_keep_the_asset_alive():
    positions = lsdem.bake_sphere(2.0, voxel=0.2, nodes=100).nodes.positions
    gc.collect()  # the Asset and Nodes objects are gone; the view's base keeps the data
    assert np.allclose(np.linalg.norm(positions, axis=1), 2.0, atol=1e-9)


def test_save_load_round_trip(sphere, tmp_path):
    path = tmp_path / "sphere.vdb"
    sphere.save(str(path))
    assert sphere.path == str(path)
    loaded = lsdem.load(str(path))
    assert loaded.volume == sphere.volume
    assert np.array_equal(loaded.inertia, sphere.inertia)
    assert np.array_equal(loaded.nodes.positions, sphere.nodes.positions)
    assert np.array_equal(loaded.nodes.normals, sphere.nodes.normals)
    assert np.array_equal(loaded.nodes.areas, sphere.nodes.areas)
    points = np.random.default_rng(1).uniform(-6, 6, size=(1000, 3))
    for a, b in zip(loaded.sample(points), sphere.sample(points)):
        assert np.array_equal(a, b)


def test_bake_mesh_of_a_cube(tmp_path):
    path = tmp_path / "cube.obj"
    path.write_text(CUBE_OBJ)
    cube = lsdem.bake_mesh(str(path), voxel=0.1, node_spacing=0.25)
    assert cube.volume == pytest.approx(8.0, rel=1e-12)
    assert cube.surface_area == pytest.approx(24.0, rel=1e-9)
    # Stored in the principal frame: the centroid (1, 1, 1) of the input is the origin.
    assert np.allclose(cube.input_frame["centroid"], [1, 1, 1])
    phi, _ = cube.sample([[0.0, 0.0, 0.0]])
    assert phi[0] == pytest.approx(-1.0, abs=1e-3)


def uv_sphere_obj(rings, sectors):
    """A unit sphere as latitude-longitude quads split into triangles, with pole fans (OBJ)."""
    lines = ["v 0 0 1"]
    for i in range(1, rings):
        theta = np.pi * i / rings
        for j in range(sectors):
            phi = 2 * np.pi * j / sectors
            lines.append(f"v {np.sin(theta) * np.cos(phi):.9f} {np.sin(theta) * np.sin(phi):.9f} "
                         f"{np.cos(theta):.9f}")
    south = len(lines) + 1
    lines.append("v 0 0 -1")
    at = lambda i, j: 2 + (i - 1) * sectors + j % sectors  # 1-based OBJ indices
    for j in range(sectors):
        lines.append(f"f 1 {at(1, j)} {at(1, j + 1)}")
        lines.append(f"f {south} {at(rings - 1, j + 1)} {at(rings - 1, j)}")
    for i in range(1, rings - 1):
        for j in range(sectors):
            lines.append(f"f {at(i, j)} {at(i + 1, j)} {at(i + 1, j + 1)}")
            lines.append(f"f {at(i, j)} {at(i + 1, j + 1)} {at(i, j + 1)}")
    return "\n".join(lines) + "\n"


def test_bake_mesh_node_layouts(tmp_path):
    path = tmp_path / "ball.obj"
    path.write_text(uv_sphere_obj(24, 48))
    # Laid out centroidally: exactly the nodes asked for, sharing out the mesh's whole area.
    centroidal = lsdem.bake_mesh(str(path), voxel=0.05, nodes=300, node_layout="centroidal")
    assert len(centroidal.nodes.areas) == 300
    assert centroidal.node_layout == "centroidal"
    remeshed = lsdem.bake_mesh(str(path), voxel=0.05, nodes=300, node_layout="remesh")
    assert len(remeshed.nodes.areas) == pytest.approx(300, rel=0.15)
    assert remeshed.node_layout == "remesh"
    # The mesh's area by numpy, from the OBJ's own numbers (the sphere's 4π less the facets').
    verts = np.array([[float(x) for x in line.split()[1:]]
                      for line in path.read_text().splitlines() if line.startswith("v ")])
    faces = np.array([[int(x) - 1 for x in line.split()[1:]]
                      for line in path.read_text().splitlines() if line.startswith("f ")])
    a, b, c = verts[faces[:, 0]], verts[faces[:, 1]], verts[faces[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    assert centroidal.nodes.areas.sum() == pytest.approx(area, rel=1e-6)  # float coordinates
    # The remeshed surface, about 600 triangles, is a polyhedron short of the input's area by
    # its facets' sagitta (about 1 %), far more than round-off.
    assert remeshed.nodes.areas.sum() < (1 - 1e-3) * area
    with pytest.raises(lsdem.Error, match="node_layout"):
        lsdem.bake_mesh(str(path), voxel=0.05, nodes=300, node_layout="curvy")
    with pytest.raises(lsdem.Error, match="node_layout"):
        lsdem.bake_mesh(str(path), voxel=0.05, mesh_nodes=True, node_layout="centroidal")


def test_sample_shapes_and_threads(sphere):
    rng = np.random.default_rng(7)
    points = rng.uniform(-5.5, 5.5, size=(20000, 3))
    phi, grad = sphere.sample(points)
    assert phi.shape == (20000,) and grad.shape == (20000, 3)
    assert phi.dtype == np.float64 and grad.dtype == np.float64
    # Near the surface φ is the distance to it, to a fraction of a voxel: inside, and outside
    # where every corner of the cell lies in the exterior band (2 voxels = 0.5 by default;
    # a corner is up to √3 voxels from the point). Beyond, φ is positive and never more than
    # the distance (the background is the band's width).
    r = np.linalg.norm(points, axis=1)
    near = (r - 5.0 > -0.5) & (r - 5.0 < 0.5 - np.sqrt(3) * 0.25)
    assert near.sum() > 100
    assert np.allclose(phi[near], r[near] - 5.0, atol=0.02)
    outside = r - 5.0 > 0.1
    assert np.all(phi[outside] > 0.0) and np.all(phi[outside] <= r[outside] - 5.0 + 0.02)
    # Results do not depend on the threads; any leading shape is kept; lists are accepted.
    one = sphere.sample(points, threads=1)
    assert np.array_equal(one[0], phi) and np.array_equal(one[1], grad)
    phi2, grad2 = sphere.sample(points.reshape(100, 200, 3))
    assert phi2.shape == (100, 200) and grad2.shape == (100, 200, 3)
    assert np.array_equal(phi2.ravel(), phi)
    phi1, grad1 = sphere.sample([5.0, 0.0, 0.0])
    assert phi1.shape == () and grad1.shape == (3,)
    assert float(phi1) == pytest.approx(0.0, abs=1e-3)


def test_bad_input_raises_lsdem_error(sphere, tmp_path):
    with pytest.raises(lsdem.Error) as missing:
        lsdem.load(str(tmp_path / "missing.vdb"))
    assert "missing.vdb" in str(missing.value) and missing.value.fix
    not_vdb = tmp_path / "text.vdb"
    not_vdb.write_text("not an asset")
    with pytest.raises(lsdem.Error, match="text.vdb"):
        lsdem.load(str(not_vdb))
    with pytest.raises(lsdem.Error, match="place surface nodes"):
        lsdem.bake_sphere(1.0, voxel=0.1)
    with pytest.raises(lsdem.Error):
        lsdem.bake_sphere(1.0, voxel=-0.1, nodes=100)
    with pytest.raises(lsdem.Error, match="areas"):
        lsdem.bake_sphere(1.0, voxel=0.1, nodes=100, areas="round")
    with pytest.raises(lsdem.Error):
        lsdem.bake_mesh(str(tmp_path / "none.obj"), voxel=0.1, node_spacing=0.2)
    with pytest.raises(lsdem.Error, match="shape"):
        sphere.sample(np.zeros((4, 2)))
    assert issubclass(lsdem.Error, RuntimeError)


def test_bad_options_are_named_as_python_passes_them(sphere):
    for call, keyword in ((lambda: lsdem.bake_sphere(1.0, voxel=0.0, nodes=100), "voxel="),
                          (lambda: lsdem.bake_sphere(1.0, voxel=0.1, node_spacing=-1.0),
                           "node_spacing="),
                          (lambda: lsdem.bake_sphere(1.0, voxel=0.1, nodes=100, band=1),
                           "band")):
        with pytest.raises(lsdem.Error) as error:
            call()
        message = str(error.value) + " " + error.value.fix
        assert keyword in message and "--" not in message, message
    with pytest.raises(lsdem.Error, match=r"shape \(4, 2\)"):
        sphere.sample(np.zeros((4, 2)))
    with pytest.raises(lsdem.Error, match="threads wants a number from 1 to 1024"):
        sphere.sample(np.zeros((4, 3)), threads=100000)
