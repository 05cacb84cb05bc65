"""Bad input is a Python exception that says where, never a crash."""

import inspect

import numpy as np
import pytest

import glint
from conftest import data


def test_a_bad_scene_line_raises_scene_error_with_its_place(tmp_path):
    bad = tmp_path / "bad.test"
    bad.write_text("size 64 48\ncamera 0 0 4 0 0 0 0 1 0 45\nsphere 0 0 zero 1\n")
    with pytest.raises(glint.SceneError) as e:
        glint.load(bad)
    assert e.value.file == str(bad)
    assert (e.value.line, e.value.column) == (3, 12)
    assert "zero" in e.value.message
    assert str(e.value).startswith(f"{bad}:3:12: error: ")
    assert isinstance(e.value, ValueError)


def test_a_missing_file_and_a_bad_model_raise_scene_error(tmp_path):
    with pytest.raises(glint.SceneError, match="nothing.test"):
        glint.load(tmp_path / "nothing.test")
    with pytest.raises(glint.SceneError):
        glint.load(data("gltf", "bad-accessor.gltf"))


def test_warnings_are_python_warnings(tmp_path):
    odd = tmp_path / "odd.test"
    odd.write_text("size 32 24\ncamera 0 0 4 0 0 0 0 1 0 45\nsphere 0 0 0 0\n")
    with pytest.warns(glint.SceneWarning, match="odd.test:3"):
        glint.load(odd)
    # Option warnings name the option as Python spells it.
    with pytest.warns(glint.SceneWarning, match="^clamp_indirect= applies to the path tracer"):
        glint.load(data("cse167x", "scene6.test"), clamp_indirect=2)


def test_options_are_checked_as_the_command_line_checks_them(tmp_path):
    scene6 = data("cse167x", "scene6.test")
    with pytest.raises(TypeError, match="unexpected keyword argument 'sppp'"):
        glint.load(scene6, sppp=4)
    with pytest.raises(TypeError, match="output"):
        glint.load(scene6, output="x.png")
    with pytest.raises(ValueError, match="^spp: must be 1 to 65536, got 0$"):
        glint.load(scene6, spp=0)
    with pytest.raises(ValueError, match="size"):
        glint.load(scene6, size="big")
    scene = glint.load(scene6, size=(16, 12))
    with pytest.raises(ValueError, match="^integrator: unknown integrator 'magic'"):
        scene.render(integrator="magic")
    with pytest.raises(TypeError, match="glint.load"):
        scene.render(size=(8, 8))


GOOD_POSITIONS = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
GOOD_INDICES = np.array([[0, 1, 2]], dtype=np.int32)


@pytest.mark.parametrize(
    "positions, indices, error, match",
    [
        (GOOD_POSITIONS.astype(np.int32), GOOD_INDICES, TypeError, "float32 or float64"),
        (GOOD_POSITIONS[:, :2].copy(), GOOD_INDICES, ValueError, "shape"),
        (np.asfortranarray(np.tile(GOOD_POSITIONS, (2, 1))), GOOD_INDICES, ValueError,
         "C-contiguous"),
        (GOOD_POSITIONS.T, GOOD_INDICES, ValueError, "C-contiguous|shape"),
        (np.array([[0, 0, 0], [np.nan, 0, 0], [0, 1, 0]], np.float32), GOOD_INDICES, ValueError,
         "row 1 is not finite"),
        (np.array([[0, 0, 0], [np.inf, 0, 0], [0, 1, 0]]), GOOD_INDICES, ValueError,
         "not finite"),
        (np.array([[0, 0, 0], [1e300, 0, 0], [0, 1, 0]]), GOOD_INDICES, ValueError,
         "not finite"),
        (GOOD_POSITIONS, np.array([[0, 1, 3]]), ValueError, "names vertex 3"),
        (GOOD_POSITIONS, np.array([[0, -1, 2]]), ValueError, "names vertex -1"),
        (GOOD_POSITIONS, np.array([[0, 1, 2]], np.float32), TypeError, "integers"),
        (GOOD_POSITIONS, np.array([0, 1]), ValueError, "shape"),
        (np.zeros((0, 3), np.float32), GOOD_INDICES, ValueError, "no vertices"),
        ("not an array", GOOD_INDICES, TypeError, ""),
    ],
)
def test_mesh_arrays_are_checked(positions, indices, error, match):
    with pytest.raises(error, match=match):
        glint.Mesh(positions, indices)


def test_mesh_attribute_arrays_are_checked():
    with pytest.raises(ValueError, match="one per vertex"):
        glint.Mesh(GOOD_POSITIONS, GOOD_INDICES, normals=np.zeros((2, 3), np.float32))
    with pytest.raises(ValueError, match="uvs"):
        glint.Mesh(GOOD_POSITIONS, GOOD_INDICES, uvs=np.zeros((3, 3), np.float32))
    with pytest.raises(ValueError, match="not finite"):
        glint.Mesh(GOOD_POSITIONS, GOOD_INDICES,
                   normals=np.array([[0, 0, 1], [0, 0, np.nan], [0, 0, 1]], np.float32))
    mesh = glint.Mesh(GOOD_POSITIONS, GOOD_INDICES.ravel(), uvs=np.zeros((3, 2)))
    assert (mesh.vertices, mesh.triangles) == (3, 1)


def test_a_bad_builder_call_is_reported_at_the_python_line():
    scene = glint.Scene(size=(16, 12))
    scene.camera = dict(eye=(0, 0, 4), target=(0, 0, 0))
    # At the call itself, not at the render.
    line = inspect.currentframe().f_lineno + 2
    with pytest.raises(glint.SceneError) as e:
        scene.sphere((0, 0, 0), -1)
    assert e.value.file == __file__ and e.value.line == line
    assert e.value.message == "sphere radius must not be negative, got '-1.0'"
    with pytest.raises(glint.SceneError, match="disk radius must be positive"):
        scene.disk((0, 0, 0), (0, 1, 0), 0)
    line = inspect.currentframe().f_lineno + 2
    with pytest.raises(glint.SceneError) as e:
        scene.mesh("no/such/mesh.obj")
    assert e.value.line == line
    assert e.value.message == "cannot read mesh 'no/such/mesh.obj': no such file"
    assert scene.text.count("\n") == 2  # size and camera: nothing bad was added
    # What only the whole scene shows is still found at render, at the line that added it.
    scene.pop(); line = inspect.currentframe().f_lineno  # noqa: E702
    with pytest.raises(glint.SceneError) as e:
        scene.render()
    assert e.value.file == __file__ and e.value.line == line
    with pytest.raises(ValueError, match="cannot be written"):
        scene.command("texture", "a file.png")


def test_errors_name_the_options_as_python_spells_them(tmp_path):
    unknown = tmp_path / "unknown.test"
    unknown.write_text("size 8 8\ncamera 0 0 4 0 0 0 0 1 0 45\nbogus 1 2\n")
    with pytest.raises(glint.SceneError) as e:
        glint.load(unknown)
    assert "lenient=True" in e.value.message and "--lenient" not in str(e.value)
    assert (e.value.line, e.value.column) == (3, 1)
    with pytest.warns(glint.SceneWarning, match="unknown command 'bogus' skipped"):
        assert glint.load(unknown, lenient=True) is not None
    with pytest.raises(ValueError, match="^maxdepth: must be 0 to 64, got 99$"):
        glint.load(data("cse167x", "scene6.test"), maxdepth=99)
    # One name per option, the command line's: older spellings still work.
    scene = glint.load(data("cse167x", "scene6.test"), size=(8, 6), max_depth=2)
    assert scene.render(maxdepth=1, aov=["albedo"]).passes["albedo"].shape == (6, 8, 3)
    # Limits by kind, as --max-bounces; a bad one is named as Python spells it.
    assert scene.render(integrator="path", spp=1, max_bounces="transmission=2").shape == (6, 8, 3)
    with pytest.raises(ValueError, match="^max_bounces: unknown kind 'glass'"):
        scene.render(max_bounces="glass=2")


def test_integer_images_are_refused_with_how_to_convert_them(tmp_path):
    pixels = np.full((4, 4, 3), 200, np.uint8)
    with pytest.raises(TypeError, match="uint8.*image / 255.0"):
        glint.write(tmp_path / "x.png", pixels)
    with pytest.raises(TypeError, match="linear radiance as floats"):
        glint.encode(pixels.astype(np.int64))
    assert not (tmp_path / "x.png").exists()
    glint.write(tmp_path / "x.png", pixels / 255.0)
    assert (tmp_path / "x.png").exists()


def test_the_package_shows_its_api_and_version():
    assert dir(glint) == sorted(glint.__all__ + ["__version__"])
    assert "np" not in dir(glint) and "os" not in dir(glint)
    import re
    assert re.fullmatch(r"\d+\.\d+\.\d+", glint.__version__)


def test_bad_images_and_environments_are_refused(tmp_path):
    with pytest.raises(ValueError, match="shape"):
        glint.write(tmp_path / "x.png", np.zeros((4, 4)))
    with pytest.raises(ValueError, match="unknown image format"):
        glint.write(tmp_path / "x.jpg", np.zeros((4, 4, 3)))
    scene = glint.Scene(size=(8, 8))
    scene.camera = dict(eye=(0, 0, 4), target=(0, 0, 0))
    scene.environment(np.full((4, 8, 3), -1.0))
    with pytest.raises(ValueError, match="negative"):
        scene.render()
