"""Rendering through Python gives the glint program's images, bit for bit."""

import os
import subprocess

import numpy as np
import pytest

import glint
from conftest import SOURCE, data


def test_course_scene_equals_the_command_line(cli, course_scene6, tmp_path):
    scene = glint.load(course_scene6, size=(160, 120))
    image = scene.render(threads=2)
    assert isinstance(image, glint.Image) and isinstance(image, np.ndarray)
    assert image.shape == (120, 160, 3) and image.dtype == np.float32
    assert image.info["spp"] == 1 and image.display["tonemap"] == "clamp"
    # Float files hold the film as float32: the array itself.
    pfm = cli("scene6.pfm", course_scene6, "--size", "160x120")
    glint.write(tmp_path / "py.pfm", image)
    assert (tmp_path / "py.pfm").read_bytes() == pfm
    # 8-bit levels are decided at the film's precision: the same bytes as the program's PNG.
    png = cli("scene6.png", course_scene6, "--size", "160x120")
    glint.write(tmp_path / "py.png", image)
    assert (tmp_path / "py.png").read_bytes() == png
    assert image._repr_png_() == png
    assert image.mean() > 0.01


def test_a_path_traced_cornell_box_at_a_seed_equals_the_command_line(cli, tmp_path):
    box = SOURCE / "scenes" / "cornell.test"
    options = dict(size=(64, 64), integrator="path", spp=8, seed=7, srgb=True)
    image = glint.load(box, **options).render(threads=2)
    png = cli("cornell.png", box, "--size", "64x64", "--integrator", "path", "--spp", "8",
              "--seed", "7", "--srgb")
    glint.write(tmp_path / "py.png", image)
    assert (tmp_path / "py.png").read_bytes() == png
    # Another seed is another image: the seed is passed, not ignored.
    other = glint.load(box, **options).render(seed=8)
    assert not np.array_equal(other, image)


def test_a_gltf_model_equals_the_command_line_denoised_as_it_is(cli, tmp_path):
    model = data("gltf", "blender-monkey.gltf")
    image = glint.load(model, size=(96, 72)).render(spp=4, threads=2)
    assert image.info["denoised"]  # a model's default, as for the program
    assert image.display == {"exposure": 0.0, "srgb": True, "tonemap": "neutral"}
    png = cli("monkey.png", model, "--size", "96x72", "--spp", "4")
    glint.write(tmp_path / "py.png", image)
    assert (tmp_path / "py.png").read_bytes() == png
    raw = glint.load(model, size=(96, 72)).render(spp=4, denoise=False)
    assert not raw.info["denoised"] and not np.array_equal(raw, image)
    assert raw.info["denoiser"] is None


def test_the_denoiser_and_its_quality_are_chosen_as_on_the_command_line(cli, tmp_path):
    model = data("gltf", "blender-monkey.gltf")
    scene = glint.load(model, size=(96, 72))
    net = scene.render(spp=4, threads=2)
    assert net.info["denoiser"] == ("oidn balanced" if glint_has_oidn() else "nlm")
    nlm = scene.render(spp=4, threads=2, denoiser="nlm")
    assert nlm.info["denoiser"] == "nlm"
    if glint_has_oidn():
        assert not np.array_equal(nlm, net)
        fast = scene.render(spp=4, threads=2, denoise_quality="fast")
        assert fast.info["denoiser"] == "oidn fast"
        png = cli("fast.png", model, "--size", "96x72", "--spp", "4", "--denoise-quality", "fast")
        glint.write(tmp_path / "py.png", fast)
        assert (tmp_path / "py.png").read_bytes() == png
    with pytest.raises(ValueError, match="denoiser"):
        scene.render(denoiser="optix")


def test_denoise_of_a_rendered_image_is_the_render_denoised():
    box = glint.load(os.path.join(SOURCE, "scenes", "cornell.test"), integrator="path",
                     size=(48, 48))
    noisy = box.render(spp=4, threads=2, seed=3, aov=["albedo", "normal", "variance"])
    clean = box.render(spp=4, threads=2, seed=3, aov=["albedo", "normal", "variance"],
                       denoise=True)
    out = glint.denoise(noisy)
    assert np.array_equal(out, clean)
    assert out.info["denoiser"] == clean.info["denoiser"] and out.info["denoised"]
    assert set(out.passes) >= {"albedo", "normal"}
    # An average of two renders (what the Blender add-on's rounds make) denoises as well.
    other = box.render(spp=4, threads=2, seed=4, aov=["albedo", "normal"])
    mean = (noisy + other) / 2
    both = glint.denoise(mean, passes={"albedo": (noisy.passes["albedo"] + other.passes["albedo"]) / 2,
                                       "normal": noisy.passes["normal"]}, denoiser="nlm")
    assert both.info["denoiser"] == "nlm" and both.shape == mean.shape
    assert np.abs(both - mean).mean() < np.abs(mean).mean()
    assert not np.array_equal(both, mean)
    with pytest.raises(ValueError, match="denoiser"):
        glint.denoise(noisy, denoiser="optix")
    with pytest.raises(TypeError, match="image / 255.0"):
        glint.denoise(np.zeros((4, 4, 3), np.uint8))


def glint_has_oidn():
    """Whether this build embeds OIDN's weights (make weights; denoise-weights/README.md)."""
    return "denoiser: oidn" in subprocess.run([os.environ["GLINT_BIN"], "--version"],
                                              capture_output=True, text=True).stdout


def test_render_options_override_the_load_options_for_one_render(course_scene6):
    scene = glint.load(course_scene6, size=(40, 30), spp=4)
    assert scene.render().info["spp"] == 4
    assert scene.render(spp=2).info["spp"] == 2
    assert scene.render().info["spp"] == 4  # kept from load


def test_passes_come_back_by_name_and_round_trip_through_exr(cli, tmp_path):
    box = SOURCE / "scenes" / "cornell.test"
    image = glint.load(box, size=(32, 32), integrator="path", spp=2).render(
        aov=["albedo", "normal", "depth", "variance"]
    )
    assert set(image.passes) == {"albedo", "normal", "depth", "variance", "albedoVariance"}
    assert image.passes["albedo"].shape == (32, 32, 3)
    assert image.passes["depth"].shape == (32, 32)
    assert image.passes["albedo"].dtype == np.float32
    exr = cli("box.exr", box, "--size", "32x32", "--integrator", "path", "--spp", "2",
              "--aov", "albedo,normal,depth,variance")
    glint.write(tmp_path / "py.exr", image)
    assert (tmp_path / "py.exr").read_bytes() == exr
    with pytest.raises(ValueError, match="OpenEXR"):
        glint.write(tmp_path / "py.png", image, passes=image.passes)


def test_writing_a_changed_image_writes_the_change(tmp_path, course_scene6):
    image = glint.load(course_scene6, size=(40, 30)).render()
    glint.write(tmp_path / "a.png", image)
    brighter = image * 2
    glint.write(tmp_path / "b.png", brighter)
    assert (tmp_path / "a.png").read_bytes() != (tmp_path / "b.png").read_bytes()
    # A plain array writes too, with the plain display (the course's clamp).
    glint.write(tmp_path / "c.png", np.asarray(image))
    assert (tmp_path / "c.png").read_bytes() == (tmp_path / "a.png").read_bytes()
    assert glint.encode(image, "png", exposure=1) == glint.encode(brighter, "png")


def test_the_camera_moves_without_loading_again(course_scene6):
    scene = glint.load(course_scene6, size=(40, 30))
    first = scene.render()
    camera = scene.camera
    scene.camera = dict(eye=(0.3, 0.2, 1.0))
    moved = scene.render()
    assert scene.camera["eye"] == (0.3, 0.2, 1.0) and scene.camera["fov"] == camera["fov"]
    assert not np.array_equal(first, moved)
    scene.camera = camera
    assert np.array_equal(scene.render(), first)
    with pytest.raises(ValueError, match="eye and target"):
        scene.camera = dict(eye=camera["target"])


def test_progress_is_reported_up_to_the_whole(course_scene6):
    seen = []
    glint.load(course_scene6, size=(80, 60)).render(progress=lambda f, s: seen.append((f, s)))
    assert seen and seen[-1][0] == pytest.approx(1.0)
    fractions = [f for f, _ in seen]
    assert fractions == sorted(fractions)


def test_an_exception_in_the_progress_callback_stops_the_render_and_is_raised(course_scene6):
    def fail(fraction, seconds):
        raise RuntimeError("stop here")

    scene = glint.load(course_scene6, size=(80, 60))
    with pytest.raises(RuntimeError, match="stop here"):
        scene.render(progress=fail)
    assert scene.render().shape == (60, 80, 3)  # usable afterwards
