"""Scenes from Python: TOML round trips, building a scene, errors with file and line."""

import math

import numpy as np
import pytest

import lsdem
from conftest import SCENES


@pytest.mark.parametrize("name", ["bounce.toml", "cube27.toml", "settle.toml"])
def test_toml_round_trip(name):
    scene = lsdem.Scene.from_toml(str(SCENES / name))
    text = scene.to_toml()
    again = lsdem.Scene.from_text(text, str(SCENES / "again.toml"))
    assert again.to_toml() == text
    assert again.grain_names == scene.grain_names
    assert again.boundary_names == scene.boundary_names
    assert np.array_equal(again.gravity, scene.gravity)


def test_scene_properties():
    scene = lsdem.Scene.from_toml(str(SCENES / "bounce.toml"))
    assert scene.asset_names == ["ball"]
    assert scene.material_names == ["steel", "floor"]
    assert scene.boundary_names == ["floor"]
    assert len(scene) == 1
    assert scene.units == {"length": "mm", "mass": "tonne", "time": "s", "force": "N"}
    assert scene.end_time == 0.25 and scene.time_step == 0.0
    assert scene.text
    scene.end_time = 0.01
    assert "end_time = 0.01" in scene.to_toml()
    assert scene.text == ""  # changed in Python: the file's text no longer describes it


def test_build_a_scene_and_write_it(sphere, tmp_path):
    sphere.save(str(tmp_path / "ball.vdb"))
    sphere.save(str(tmp_path / "ball.vdb"))
    scene = lsdem.Scene()
    scene.add_asset("ball", sphere)
    scene.add_material("steel", density=7.85e-9)
    scene.add_material("wall")
    scene.add_contact("steel", "wall", normal_stiffness=1e3, restitution=0.5)
    assert scene.add_grain("ball", "steel", [0, 0, 6], name="b") == 0
    scene.add_plane("floor", "wall", point=[0, 0, 0], normal=[0, 0, 2])
    scene.gravity = [0, 0, -9810]
    scene.end_steps = 10
    path = tmp_path / "built.toml"
    scene.save(str(path))
    read = lsdem.Scene.from_toml(str(path))
    assert read.grain_names == ["b"] and read.boundary_names == ["floor"]
    assert read.end_steps == 10
    assert "file = 'ball.vdb'" in read.text  # relative to the scene's folder


def test_bad_scenes_raise_with_file_and_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((SCENES / "bounce.toml").read_text().replace("radius = 5.0", "radius = -5.0"))
    with pytest.raises(lsdem.Error) as error:
        lsdem.Scene.from_toml(str(bad))
    assert "bad.toml:" in error.value.where and "radius" in str(error.value)
    with pytest.raises(lsdem.Error, match="unknown|not a"):
        lsdem.Scene.from_text((SCENES / "bounce.toml").read_text().replace(
            "end_time = 0.25", "end_time = 0.25\nbogus_key = 3"), "x.toml")
    with pytest.raises(lsdem.Error, match="no such file|missing|cannot"):
        lsdem.Scene.from_toml(str(tmp_path / "none.toml"))


def test_builder_errors():
    scene = lsdem.Scene()
    scene.add_asset("ball", lsdem.bake_sphere(1.0, voxel=0.1, nodes=50))
    scene.add_material("steel", density=1e-9)
    with pytest.raises(lsdem.Error, match="no material called 'rock'"):
        scene.add_grain("ball", "rock", [0, 0, 0])
    with pytest.raises(lsdem.Error, match="three numbers"):
        scene.add_grain("ball", "steel", [0, 0])
    with pytest.raises(lsdem.Error, match="already"):
        scene.add_material("steel")
    with pytest.raises(lsdem.Error, match="unit quaternion"):
        scene.add_grain("ball", "steel", [0, 0, 0], orientation=[2, 0, 0, 0])
    with pytest.raises(lsdem.Error):
        scene.add_contact("steel", "steel", formulation="magic", normal_stiffness=1.0)
    # An asset made in Python and never saved cannot be written as TOML.
    with pytest.raises(lsdem.Error, match="save"):
        scene.to_toml()


@pytest.mark.parametrize("key, value, problem", [
    ("normal_stiffness", 0.0, "must be > 0"),
    ("shear_stiffness", -1.0, "must be >= 0"),
    ("friction", float("inf"), "must be >= 0|is not finite"),
    ("restitution", 1.5, r"must be in \(0, 1\]"),
    ("friction", 0.3, "has no effect without shear springs"),
])
def test_contact_numbers_obey_one_schema_in_python_and_in_files(tmp_path, key, value, problem):
    """add_contact and a scene file's [[contacts]] refuse the same numbers with the same words
    (both ask the contact library's schema), naming the key. (A file's inf is refused earlier,
    as any number in a scene: "is not finite".)"""
    given = {"normal_stiffness": 1e3, key: value}
    scene = lsdem.Scene()
    scene.add_material("steel", density=1e-9)
    with pytest.raises(lsdem.Error, match=key + " .*(" + problem + ")"):
        scene.add_contact("steel", "steel", **given)
    value_text = "inf" if value == float("inf") else repr(value)
    text = "\n".join(["[materials.steel]", "density = 1e-9", "", "[[contacts]]",
                      'materials = ["steel", "steel"]']
                     + [f"{k} = {value_text if k == key else repr(v)}" for k, v in given.items()])
    path = tmp_path / "contact.toml"
    path.write_text(text + "\n")
    with pytest.raises(lsdem.Error, match=key + ": (" + problem + ")"):
        lsdem.Scene.from_toml(str(path))


@pytest.mark.parametrize("section, key, value, problem", [
    ("simulation", "global_damping", 1.0, r"must be in \[0, 1\) \(got 1\)"),
    ("simulation", "safety", 2.0, r"must be in \(0, 1\] \(got 2\)"),
    ("simulation", "end_time", -1.0, r"must be >= 0 \(got -1\)"),
    ("output", "vtk_period", -0.5, r"must be >= 0 \(got -0.5\)"),
    ("output", "checkpoint_period", -2.0, r"must be >= 0 \(got -2\)"),
    ("output", "history_every", -3, r"must be >= 0 \(got -3\)"),
])
def test_settings_obey_one_schema_in_python_and_in_files(tmp_path, section, key, value, problem):
    """Every [simulation] and [output] setting is a Scene property of the same name; Python and a
    file refuse the same value with the same words (both ask the scene library's schema)."""
    scene = lsdem.Scene.from_toml(str(SCENES / "bounce.toml"))
    before = getattr(scene, key)
    with pytest.raises(lsdem.Error, match=key + " " + problem):
        setattr(scene, key, value)
    assert getattr(scene, key) == before and scene.text  # refused: nothing changed
    # (bounce.toml gives history_period, which history_every would clash with)
    text = "\n".join(line for line in (SCENES / "bounce.toml").read_text().splitlines()
                     if not line.startswith(("history_", key + " "))) + "\n"
    header = "[" + section + "]\n"
    if header not in text:
        text += "\n" + header
    path = tmp_path / "bounce.toml"
    path.write_text(text.replace(header, header + f"{key} = {value!r}\n"))
    with pytest.raises(lsdem.Error, match=key + ": " + problem):
        lsdem.Scene.from_toml(str(path))


def test_output_settings_are_set_in_python_and_written():
    """[output]'s settings, set in Python, reach the written file and read back; each takes its
    own type only."""
    scene = lsdem.Scene.from_toml(str(SCENES / "bounce.toml"))
    scene.history_period = 0.0
    scene.vtk_period = 0.01
    scene.checkpoint_period = 0.05
    scene.contact_forces = False
    scene.history_every = 25
    text = scene.to_toml()
    for line in ["vtk_period = 0.01", "checkpoint_period = 0.05", "contact_forces = false",
                 "history_every = 25"]:
        assert line in text
    back = lsdem.Scene.from_text(text, str(SCENES / "written.toml"))
    assert (back.vtk_period, back.checkpoint_period, back.contact_forces, back.history_every) == \
        (0.01, 0.05, False, 25)
    with pytest.raises(lsdem.Error, match="whole number"):
        scene.history_every = 2.5
    with pytest.raises(lsdem.Error, match="True or False"):
        scene.contact_forces = 1
    with pytest.raises(lsdem.Error, match="both history_every and history_period"):
        scene.history_period = 0.1
        scene.to_toml()


def test_build_servo_walls_a_cylinder_asset_sets_and_grain_files(sphere, tmp_path):
    """The builder makes what a scene file says with [asset_sets], [[grain_files]], servo
    walls and a cylinder: the TOML it writes reads back to the same text, and it simulates."""
    sphere.save(str(tmp_path / "ball.vdb"))
    (tmp_path / "catalog.csv").write_text("name,asset\nball,ball.vdb\n")
    (tmp_path / "packing.csv").write_text(
        "asset,x,y,z,qw,qx,qy,qz\nsand/ball,0,0,5,1,0,0,0\nsand/ball,0,0,15.5,1,0,0,0\n")
    scene = lsdem.Scene()
    assert scene.add_asset_set("sand", catalog=str(tmp_path / "catalog.csv")) == ["sand/ball"]
    scene.add_material("sand", density=2.65e-9)
    scene.add_material("wall")
    scene.add_contact("sand", "sand", normal_stiffness=1e3, restitution=0.5)
    scene.add_contact("sand", "wall", normal_stiffness=1e3, restitution=0.5)
    assert scene.add_grain_file(str(tmp_path / "packing.csv"), "sand") == 2
    scene.add_plane("floor", "wall", point=[0, 0, 0], normal=[0, 0, 1])
    for name, point, normal in [("x0", [-6, 0, 0], [1, 0, 0]), ("x1", [6, 0, 0], [-1, 0, 0]),
                                ("y0", [0, -6, 0], [0, 1, 0]), ("y1", [0, 6, 0], [0, -1, 0])]:
        scene.add_plane(name, "wall", point=point, normal=normal)
    scene.add_plane("lid", "wall", point=[0, 0, 21], normal=[0, 0, -1], stress=0.01,
                    area_walls=["x0", "x1", "y0", "y1"], max_speed=100.0, servo_gain=0.3)
    scene.add_cylinder_boundary("drum", "wall", center=[0, 0, 0], radius=7.0)
    scene.end_steps = 20
    scene.time_step = 1e-6
    path = tmp_path / "built.toml"
    scene.save(str(path))
    text = path.read_text()
    for line in ["[asset_sets.sand]", "catalog = 'catalog.csv'", "[[grain_files]]",
                 "file = 'packing.csv'", "stress = 0.01", "area_walls = ['x0', 'x1', 'y0', 'y1']",
                 "max_speed = 100.0", "servo_gain = 0.3", "type = 'cylinder'", "radius = 7.0"]:
        assert line in text, line
    read = lsdem.Scene.from_toml(str(path))
    assert read.to_toml() == scene.to_toml(str(tmp_path))
    assert len(read) == 2 and read.asset_names == ["sand/ball"]
    sim = lsdem.Simulation(read, threads=1)
    sim.run()
    assert sim.step == 20
    assert sim.boundaries["drum"].shape == "cylinder"
    # Not touching yet, the lid comes down at its limit speed: 20 steps of 100·1e-6.
    assert sim.boundaries["lid"].velocity[2] == pytest.approx(-100.0)


def test_orifice_plate_lets_a_ball_through_its_hole_and_holds_one_beside_it(sphere, tmp_path):
    """A ball (R 5) over the middle of a hole of radius 6 falls through it; one over the plate
    comes to rest on it, its weight on the plate. The scene writes and reads back the same."""
    sphere.save(str(tmp_path / "ball.vdb"))
    scene = lsdem.Scene()
    scene.add_asset("ball", sphere)
    scene.add_material("steel", density=7.85e-9)
    scene.add_material("wall")
    scene.add_contact("steel", "steel", normal_stiffness=1e3, restitution=0.2)
    scene.add_contact("steel", "wall", normal_stiffness=1e3, restitution=0.2)
    scene.add_grain("ball", "steel", [0, 0, 6], name="falls")
    scene.add_grain("ball", "steel", [30, 0, 6], name="rests")
    scene.add_orifice_boundary("floor", "wall", center=[0, 0, 0], radius=6.0, thickness=2.0)
    scene.gravity = [0, 0, -9810]
    scene.time_step = 2e-6
    scene.end_time = 0.05
    path = tmp_path / "orifice.toml"
    scene.save(str(path))
    assert "type = 'orifice'" in path.read_text() and "thickness = 2.0" in path.read_text()
    read = lsdem.Scene.from_toml(str(path))
    assert read.to_toml() == scene.to_toml(str(tmp_path))
    with pytest.raises(lsdem.Error, match="thickness must be > 0"):
        scene.add_orifice_boundary("bad", "wall", center=[0, 0, 0], radius=6.0, thickness=0.0)
    sim = lsdem.Simulation(read, threads=1)
    sim.run()
    assert sim.boundaries["floor"].shape == "orifice"
    z = sim.grains.positions[:, 2]
    # Free fall for 0.05 s from rest: 12.3 mm down, so well below the plate (R 5 at z 6).
    assert z[0] == pytest.approx(6.0 - 0.5 * 9810 * 0.05 ** 2, abs=1e-6)
    # The other rests on the upper face (z = 1): its centre R above it, less the sag until its
    # lowest nodes touch (500 nodes on R 5 are ~0.8 apart: up to ~0.02 below the pole).
    assert 5.95 < z[1] < 6.0 and abs(sim.grains.velocities[1][2]) < 1.0
    mass = 7.85e-9 * 4.0 / 3.0 * math.pi * 5.0 ** 3
    assert sim.boundaries["floor"].reaction[2] == pytest.approx(-mass * 9810, rel=0.05)


def test_builder_refuses_bad_servo_walls_sets_and_tables(sphere, tmp_path):
    scene = lsdem.Scene()
    scene.add_material("wall")
    with pytest.raises(lsdem.Error, match="stress must be > 0"):
        scene.add_plane("lid", "wall", point=[0, 0, 1], normal=[0, 0, -1], stress=-1.0,
                        area=1.0, max_speed=1.0)
    with pytest.raises(lsdem.Error, match="needs the area"):
        scene.add_plane("lid", "wall", point=[0, 0, 1], normal=[0, 0, -1], stress=1.0,
                        max_speed=1.0)
    with pytest.raises(lsdem.Error, match="limit speed"):
        scene.add_plane("lid", "wall", point=[0, 0, 1], normal=[0, 0, -1], stress=1.0, area=1.0)
    with pytest.raises(lsdem.Error, match=r"\(0, 1\]"):
        scene.add_plane("lid", "wall", point=[0, 0, 1], normal=[0, 0, -1], stress=1.0, area=1.0,
                        max_speed=1.0, servo_gain=2.0)
    with pytest.raises(lsdem.Error, match="only makes sense for a servo wall"):
        scene.add_plane("lid", "wall", point=[0, 0, 1], normal=[0, 0, -1], area=1.0)
    with pytest.raises(lsdem.Error, match="chooses its own velocity"):
        scene.add_plane("lid", "wall", point=[0, 0, 1], normal=[0, 0, -1], stress=1.0, area=1.0,
                        max_speed=1.0, velocity=[0, 0, -1])
    with pytest.raises(lsdem.Error, match="no boundary named 'x0'"):
        scene.add_plane("lid", "wall", point=[0, 0, 1], normal=[0, 0, -1], stress=1.0,
                        area_walls=["x0", "x1", "y0", "y1"], max_speed=1.0)
    assert scene.boundary_names == []  # nothing half-added
    with pytest.raises(lsdem.Error, match="radius must be > 0"):
        scene.add_cylinder_boundary("drum", "wall", center=[0, 0, 0], radius=0.0)
    with pytest.raises(lsdem.Error, match="axis must not be the zero vector"):
        scene.add_cylinder_boundary("drum", "wall", center=[0, 0, 0], radius=1.0, axis=[0, 0, 0])
    with pytest.raises(lsdem.Error, match="catalogue not found"):
        scene.add_asset_set("sand", catalog=str(tmp_path / "none.csv"))
    (tmp_path / "catalog.csv").write_text("name,asset\nball,missing.vdb\n")
    with pytest.raises(lsdem.Error, match="file not found"):
        scene.add_asset_set("sand", catalog=str(tmp_path / "catalog.csv"))
    with pytest.raises(lsdem.Error, match="no '/'"):
        scene.add_asset_set("a/b", catalog=str(tmp_path / "catalog.csv"))
    scene.add_asset("ball", sphere)
    (tmp_path / "grains.csv").write_text("asset,x,y,z,qw,qx,qy,qz\nball,0,0,0,1,0,0,0\nrock,0,0,9,1,0,0,0\n")
    with pytest.raises(lsdem.Error, match="no asset named 'rock'") as error:
        scene.add_grain_file(str(tmp_path / "grains.csv"), "wall")
    assert "grains.csv:3" in error.value.where
    assert len(scene) == 0  # nothing half-added
    with pytest.raises(lsdem.Error, match="cannot read"):
        scene.add_grain_file(str(tmp_path / "none.csv"), "wall")


def test_builder_adds_patches_and_level_set_obstacles_as_a_file_does(sphere, tmp_path):
    """A plane patch and a level-set obstacle from Python read back from the saved scene as
    they were built, and a key that breaks a rule is refused in the reader's own words."""
    scene = lsdem.Scene()
    scene.add_asset("ball", sphere)
    scene.add_material("wall")
    scene.add_plane("ramp", "wall", point=[0, 0, 0], normal=[0, 0, 1], extent=(4.0, 2.0),
                    axis_u=[0.6, 0.8, 0], thickness=0.5)
    scene.add_level_set_boundary("rock", "wall", asset="ball", position=[0, 0, 9],
                                 orientation=[0, 0, 0, 1])
    assert scene.boundary_names == ["ramp", "rock"]
    text = scene.to_toml(str(tmp_path))
    assert "extent = [4.0, 2.0]" in text and "axis_u = [0.6, 0.8, 0.0]" in text
    assert "type = 'level-set'" in text and "orientation = [0.0, 0.0, 0.0, 1.0]" in text
    with pytest.raises(lsdem.Error, match="axis_u only makes sense with extent"):
        scene.add_plane("bad", "wall", point=[0, 0, 0], normal=[0, 0, 1], axis_u=[1, 0, 0])
    with pytest.raises(lsdem.Error, match="extent both widths must be > 0"):
        scene.add_plane("bad", "wall", point=[0, 0, 0], normal=[0, 0, 1], extent=(1.0, 0.0))
    with pytest.raises(lsdem.Error, match="cannot name a file"):
        scene.add_sphere_boundary("a/b", "wall", center=[0, 0, 0], radius=1.0)
    with pytest.raises(lsdem.Error, match="no asset called 'pebble'"):
        scene.add_level_set_boundary("bad", "wall", asset="pebble", position=[0, 0, 0])
    assert scene.boundary_names == ["ramp", "rock"]  # nothing half-added


def test_builder_refuses_what_it_cannot_mean(sphere):
    """NaN and infinite vectors, negative ends and masses, and a second law for one pair of
    materials are refused; a refused change leaves the scene (and its file's text) as it was."""
    scene = lsdem.Scene.from_toml(str(SCENES / "bounce.toml"))
    text = scene.text
    assert text
    nan, inf = float("nan"), float("inf")
    with pytest.raises(lsdem.Error, match="gravity must be finite"):
        scene.gravity = [nan, 0, 0]
    with pytest.raises(lsdem.Error, match="point must be finite"):
        scene.add_plane("wall", "steel", point=[nan, 0, 0], normal=[1, 0, 0])
    with pytest.raises(lsdem.Error, match="end_steps must be >= 0"):
        scene.end_steps = -5
    with pytest.raises(lsdem.Error, match="end_time must be >= 0"):
        scene.end_time = -1.0
    with pytest.raises(lsdem.Error, match="global_damping"):
        scene.global_damping = 2.0
    assert scene.text == text and scene.end_steps == 0 and scene.global_damping == 0.0
    assert list(scene.gravity) != [nan, 0, 0] and scene.boundary_names == ["floor"]

    built = lsdem.Scene()
    built.add_asset("ball", sphere)
    built.add_material("steel", density=1e-9)
    with pytest.raises(lsdem.Error, match="velocity must be finite"):
        built.add_grain("ball", "steel", [0, 0, 0], velocity=[0, inf, 0])
    with pytest.raises(lsdem.Error, match="mass must be >= 0"):
        built.add_grain("ball", "steel", [0, 0, 0], mass=-1.0)
    assert len(built) == 0
    # Friction without shear springs would be silently frictionless (the reader refuses it).
    with pytest.raises(lsdem.Error, match="friction has no effect without shear springs"):
        built.add_contact("steel", "steel", normal_stiffness=1.0, friction=0.5)
    with pytest.raises(lsdem.Error, match="friction has no effect"):
        built.add_contact("steel", "steel", formulation="volume", normal_stiffness=1.0,
                          friction=0.5)
    with pytest.raises(lsdem.Error, match="shear_stiffness has no effect with formulation"):
        built.add_contact("steel", "steel", formulation="volume", normal_stiffness=1.0,
                          shear_stiffness=1.0)
    built.add_contact("steel", "steel", normal_stiffness=1.0, shear_stiffness=0.5,
                      friction=0.5)
    with pytest.raises(lsdem.Error, match="already a contact law between materials"):
        built.add_contact("steel", "steel", normal_stiffness=2.0)


def test_an_asset_saved_after_it_was_added_is_written_by_its_file(tmp_path):
    ball = lsdem.bake_sphere(1.0, voxel=0.1, nodes=50)
    scene = lsdem.Scene()
    scene.add_asset("ball", ball)
    with pytest.raises(lsdem.Error, match=r"asset.save\('ball.vdb'\)"):
        scene.to_toml()
    ball.save(str(tmp_path / "later.vdb"))
    assert "later.vdb" in scene.to_toml(str(tmp_path))


def test_a_fixed_wall_cannot_end_a_run_by_displacement():
    scene = lsdem.Scene.from_toml(str(SCENES / "bounce.toml"))
    with pytest.raises(lsdem.Error, match="does not move"):
        scene.set_end_displacement("floor", 1.0)


def test_patch_quadrature_is_written_refused_where_it_has_no_meaning_and_resolves_a_small_cap(
        sphere, tmp_path):
    """quadrature = "patch" (docs/contact.md) reads and writes back; the original law, which has
    no traction to integrate, refuses it. A ball of 500 nodes (spacing ~0.8 mm) pressed 0.05 mm
    into a floor touches it over a cap of radius sqrt(2Rδ) = 0.71 mm, less than a node spacing:
    with nodes as points the floor's reaction depends on where the nodes happen to be as the
    ball turns; with patches it stays near the traction's integral π·kn*·R·δ² (exact for a
    sphere on a plane), whatever the turn."""
    sphere.save(str(tmp_path / "ball.vdb"))
    with pytest.raises(lsdem.Error, match="quadrature"):
        s = lsdem.Scene()
        s.add_material("m")
        s.add_contact("m", "m", formulation="original", normal_stiffness=1e9, quadrature="patch")
    R, delta, kn = 5.0, 0.05, 1e3
    reference = math.pi * kn * R * delta ** 2
    errors = {}
    for quadrature in ("node", "patch"):
        errors[quadrature] = []
        for turn in np.linspace(0.0, 0.6, 7):
            scene = lsdem.Scene()
            scene.add_asset("ball", sphere)
            scene.add_material("steel", density=7.85e-9)
            scene.add_material("wall")
            scene.add_contact("steel", "wall", normal_stiffness=kn, quadrature=quadrature)
            scene.add_grain("ball", "steel", [0, 0, R - delta],
                            orientation=[math.cos(turn), math.sin(turn) * 0.6, math.sin(turn) * 0.8, 0])
            scene.add_plane("floor", "wall", point=[0, 0, 0], normal=[0, 0, 1])
            scene.time_step = 1e-12
            scene.end_steps = 1
            if quadrature == "patch" and turn == 0.0:
                text = scene.to_toml(str(tmp_path))
                assert "quadrature = 'patch'" in text
                assert lsdem.Scene.from_text(text, str(tmp_path / "s.toml")).to_toml(str(tmp_path)) == text
            sim = lsdem.Simulation(scene, threads=1)
            sim.run()
            errors[quadrature].append(sim.boundaries["floor"].reaction[2] / -reference - 1.0)
    node, patch = np.array(errors["node"]), np.array(errors["patch"])
    # Points: the cap holds a node or two, so the force swings by tens of per cent as the ball
    # turns (−22 … +27 % here). Patches (the nodes' Voronoi cells) tile the floor's side of the
    # ball whatever the turn: what is left is the level set's (the nodes sit on the zero of a
    # level set of voxel 0.25, ~voxel²/(8R) = 0.0016 mm off the sphere, 3 % of δ) and the 16
    # rays' over a cell's corners: −1.5 … +3.5 % here.
    assert np.ptp(node) > 0.3
    assert np.ptp(patch) < np.ptp(node) / 5
    assert np.abs(patch).max() < 0.06


def test_a_membrane_from_python(tmp_path):
    """add_membrane follows the [[membranes]] rules (MembraneKeys.h), the scene writes it, and
    a running simulation shows it: a tube of 24 facets round a ball, held by floor and lid."""
    ball = lsdem.bake_sphere(1.0, voxel=0.25, nodes=100)
    ball.save(str(tmp_path / "ball.vdb"))  # (a scene names its assets' files in TOML)
    scene = lsdem.Scene()
    scene.add_asset("ball", ball)
    scene.add_material("steel", density=7.85e-9)
    scene.add_material("latex")
    scene.add_contact("steel", "latex", normal_stiffness=1e3)
    scene.add_contact("steel", "steel", normal_stiffness=1e3)
    scene.add_grain("ball", "steel", [0, 0, 5])
    scene.add_plane("floor", "latex", point=[0, 0, 0], normal=[0, 0, 1])
    scene.add_plane("lid", "latex", point=[0, 0, 10], normal=[0, 0, -1])
    with pytest.raises(lsdem.Error, match=r"poisson must be in \[0, 0.5\)"):
        scene.add_membrane("sleeve", "latex", youngs=1.4, poisson=0.5, thickness=0.3,
                           density=1e-6, base=[0, 0, 0], radius=1.5, height=10, segments=24,
                           rings=8)
    with pytest.raises(lsdem.Error, match="no boundary called 'top'"):
        scene.add_membrane("sleeve", "latex", youngs=1.4, poisson=0.45, thickness=0.3,
                           density=1e-6, base=[0, 0, 0], radius=1.5, height=10, segments=24,
                           rings=8, hold=["top"])
    scene.add_membrane("sleeve", "latex", youngs=1.4, poisson=0.45, thickness=0.3, density=1e-6,
                       base=[0, 0, 0], radius=1.5, height=10, segments=24, rings=8,
                       pressure=0.01, prestretch=1.05, hold=["floor", "lid"])
    assert "[[membranes]]" in scene.to_toml()
    scene.end_steps = 5
    sim = lsdem.Simulation(scene)
    assert list(sim.membranes.keys()) == ["sleeve"] and "sleeve" in sim.membranes
    sleeve = sim.membranes["sleeve"]
    assert sleeve.positions.shape == (24 * 9, 3) and sleeve.triangles.shape == (24 * 8 * 2, 3)
    assert np.allclose(np.hypot(sleeve.positions[:, 0], sleeve.positions[:, 1]), 1.5)
    held = np.array(sleeve.held_by)
    assert (held[:24] == 0).all() and (held[-24:] == 1).all() and (held[24:-24] == -1).all()
    # A prism of 24 sides in a circle of radius 1.5: 12·r²·sin(2π/24)·h.
    assert sleeve.volume == pytest.approx(12 * 1.5**2 * math.sin(2 * math.pi / 24) * 10, rel=1e-12)
    assert sleeve.pressure == 0.01
    with pytest.raises(KeyError):
        sim.membranes["none"]

    # Placed from a state file (as a run left it): the vertices where the file puts them, the
    # rubber still the tube's (its unstretched areas unchanged).
    swollen = sleeve.positions * np.array([1.1, 1.1, 1.0])
    rows = np.hstack([swollen, np.zeros_like(swollen)])
    np.savetxt(tmp_path / "sleeve_state.csv", rows, delimiter=",", header="x,y,z,vx,vy,vz",
               comments="", fmt="%.17g")
    placed = lsdem.Scene()
    placed.add_asset("ball", ball)
    placed.add_material("steel", density=7.85e-9)
    placed.add_material("latex")
    placed.add_contact("steel", "latex", normal_stiffness=1e3)
    placed.add_grain("ball", "steel", [0, 0, 5])
    placed.add_plane("floor", "latex", point=[0, 0, 0], normal=[0, 0, 1])
    placed.add_plane("lid", "latex", point=[0, 0, 10], normal=[0, 0, -1])
    placed.add_membrane("sleeve", "latex", youngs=1.4, poisson=0.45, thickness=0.3,
                        density=1e-6, base=[0, 0, 0], radius=1.5, height=10, segments=24,
                        rings=8, prestretch=1.05, hold=["floor", "lid"],
                        state=str(tmp_path / "sleeve_state.csv"))
    placed.end_steps = 5
    moved = lsdem.Simulation(placed).membranes["sleeve"]
    assert np.array_equal(moved.positions, swollen)
    assert moved.volume == pytest.approx(1.21 * sleeve.volume, rel=1e-12)
