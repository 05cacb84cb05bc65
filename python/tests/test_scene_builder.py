"""Scenes made in code: the scene file they are, meshes of arrays, environments of arrays."""

import numpy as np

import glint


def small_scene() -> glint.Scene:
    scene = glint.Scene(size=(48, 36))
    scene.camera = dict(eye=(0, 1, 5), target=(0, 0, 0), up=(0, 1, 0), fov=40)
    scene.point_light((3, 4, 5), (0.9, 0.9, 0.8))
    scene.directional_light((-1, 1, 0.5), (0.2, 0.2, 0.3))
    scene.material(diffuse=(0.7, 0.2, 0.2), specular=(0.3, 0.3, 0.3), shininess=30)
    scene.sphere((-1, 0, 0), 0.8)
    with scene.transform():
        scene.translate((1.2, 0, 0))
        scene.rotate((0, 1, 0), 30)
        scene.material(diffuse=(0.2, 0.6, 0.3))
        scene.box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
    scene.plane((0, -0.8, 0), (0, 1, 0))
    return scene


def test_a_built_scene_renders_as_its_scene_file_does(cli, tmp_path):
    scene = small_scene()
    image = scene.render()
    assert image.shape == (36, 48, 3) and image.max() > 0.1
    path = tmp_path / "built.test"
    path.write_text(scene.text)
    assert "sphere -1.0 0.0 0.0 0.8" in scene.text and "pushTransform" in scene.text
    glint.write(tmp_path / "py.png", image)
    assert (tmp_path / "py.png").read_bytes() == cli("built.png", path)


def quad_arrays():
    positions = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float32)
    normals = np.tile(np.array([0, 0, 1], np.float32), (4, 1))
    uvs = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], np.float32)
    indices = np.array([[0, 1, 2], [0, 2, 3]], np.uint32)
    return positions, indices, normals, uvs


def test_a_mesh_of_arrays_renders_as_the_same_mesh_from_a_file(tmp_path):
    positions, indices, normals, uvs = quad_arrays()
    obj = tmp_path / "quad.obj"
    lines = [f"v {x} {y} {z}" for x, y, z in positions]
    lines += [f"vt {u} {v}" for u, v in uvs] + [f"vn {x} {y} {z}" for x, y, z in normals]
    lines += ["f " + " ".join(f"{i + 1}/{i + 1}/{i + 1}" for i in tri) for tri in indices]
    obj.write_text("\n".join(lines) + "\n")

    def scene_with(place) -> glint.Image:
        scene = glint.Scene(size=(32, 32))
        scene.camera = dict(eye=(0.3, 0.2, 3), target=(0, 0, 0))
        scene.point_light((1, 2, 3), (1, 1, 1))
        scene.material(diffuse=(0.5, 0.5, 0.8))
        with scene.transform():
            scene.rotate((1, 0, 0), -20)
            place(scene)
        return scene.render()

    from_file = scene_with(lambda s: s.mesh(obj))
    from_arrays = scene_with(lambda s: s.mesh(positions, indices, normals=normals, uvs=uvs))
    as_float64 = scene_with(lambda s: s.mesh(positions.astype(np.float64),
                                             indices.astype(np.int64), normals=normals))
    assert from_arrays.max() > 0.1
    assert np.array_equal(from_arrays, from_file)
    assert np.array_equal(as_float64, from_file)


def test_a_mesh_placed_twice_is_stored_once():
    positions, indices, _, _ = quad_arrays()
    mesh = glint.Mesh(positions, indices)
    scene = glint.Scene(size=(16, 16))
    scene.camera = dict(eye=(0, 0, 6), target=(0, 0, 0))
    scene.point_light((0, 0, 5), (1, 1, 1))
    scene.material(diffuse=(1, 1, 1))
    for x in (-1.5, 1.5):
        with scene.transform():
            scene.translate((x, 0, 0))
            assert scene.mesh(mesh) is mesh
    assert scene.text.count("mesh @mesh0") == 2
    image = scene.render()
    assert image[8, 3].max() > 0 and image[8, 12].max() > 0


def test_an_environment_of_an_array_is_the_same_as_from_its_file(tmp_path):
    rows, cols = 16, 32
    v, u = np.meshgrid(np.linspace(0, 1, rows), np.linspace(0, 1, cols), indexing="ij")
    sky = np.stack([0.2 + u, 0.5 * v, 1.0 - v], axis=-1).astype(np.float32)
    glint.write(tmp_path / "sky.pfm", sky)
    glint.write(tmp_path / "sky.exr", sky)

    def scene_lit(set_sky) -> glint.Image:
        scene = glint.Scene(size=(24, 24))
        scene.camera = dict(eye=(0, 0, 4), target=(0, 0, 0), fov=60)
        scene.material(diffuse=(0.8, 0.8, 0.8))
        scene.sphere((0, 0, 0), 1)
        scene.integrator = "path"
        set_sky(scene)
        return scene.render(spp=4, seed=3)

    from_array = scene_lit(lambda s: s.environment(sky, 2.0, 30))
    from_file = scene_lit(lambda s: s.environment(tmp_path / "sky.exr", 2.0, 30))
    assert np.array_equal(from_array, from_file)
    assert not np.array_equal(from_array, scene_lit(lambda s: s.environment(sky, 1.0, 30)))


def test_settings_and_repr():
    scene = small_scene()
    assert scene.size == (48, 36) and scene.integrator == "whitted"
    scene.integrator = "path"
    scene.size = (20, 10)
    assert scene.render(spp=1).shape == (10, 20, 3)
    assert scene.integrator == "path"
    assert "20x10" in repr(scene)
