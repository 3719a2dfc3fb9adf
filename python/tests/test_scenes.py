"""Scenes from Python: TOML round trips, building a scene, errors with file and line."""

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
