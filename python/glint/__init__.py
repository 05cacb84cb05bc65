"""Glint from Python: load or build a scene, render it into NumPy arrays, write image files.

    import glint
    scene = glint.load("scene6.test")             # any file the glint command reads
    image = scene.render(spp=16)                  # float32 array, rows x columns x 3
    glint.write("scene6.png", image)              # the glint command's bytes

Keyword arguments are the glint command's options, named as on its command line with
underscores for dashes (``noise_threshold=0.02`` is ``--noise-threshold 0.02``). docs/python.md
has a walkthrough and the whole API.
"""

from __future__ import annotations

import os
import sys
from contextlib import contextmanager
from typing import Any, Callable, Iterator, Optional, Sequence, Union

import numpy as np

from . import _glint
from ._glint import Mesh, RenderError, SceneError, SceneWarning

__all__ = [
    "Image",
    "Mesh",
    "RenderError",
    "Scene",
    "SceneError",
    "SceneWarning",
    "denoise",
    "encode",
    "load",
    "write",
]

__version__: str = _glint.__version__


def __dir__() -> list:
    """What `dir(glint)` shows: the API, not the modules and names it is written with."""
    return sorted(__all__ + ["__version__"])

PathLike = Union[str, "os.PathLike[str]"]
Vec3 = Sequence[float]

# ---- Options: keyword arguments to the command line's options -------------------------------

_OPTION_NAMES = frozenset(_glint.option_names())
# What only the command line does: files, sequences and pieces of frames, reports.
_COMMAND_LINE_ONLY = frozenset(
    ["output", "frames", "check", "stats", "quiet", "crop", "samples", "part", "help", "version"]
)
# What may change from one render of a loaded scene to the next; the rest is given to load().
_RENDER_OPTIONS = frozenset(
    [
        "spp", "integrator", "threads", "seed", "aov", "denoise", "denoiser", "denoise-quality",
        "noise-threshold", "min-spp", "time", "maxdepth", "max-bounces", "clamp-indirect",
        "caustics",
        "exposure", "srgb", "tonemap",
    ]
)
# One name per option: the command line's, underscores for dashes (maxdepth, aov, tonemap, as
# --maxdepth, --aov, --tonemap and the scene format's maxdepth). Older spellings still work.
_ALIASES = {"max_depth": "maxdepth", "aovs": "aov", "passes": "aov", "tone_map": "tonemap"}
# Flags with a negative form: True gives --NAME, False --no-NAME.
_NEGATABLE = frozenset(["denoise", "srgb"])


def _option_args(options: dict, where: str, allowed: Optional[frozenset] = None) -> list:
    """The command-line arguments that keyword `options` stand for."""
    args = []
    for key, value in options.items():
        name = _ALIASES.get(key, key).replace("_", "-")
        if name in _COMMAND_LINE_ONLY or name not in _OPTION_NAMES:
            raise TypeError(f"{where}() got an unexpected keyword argument '{key}'")
        if allowed is not None and name not in allowed:
            raise TypeError(
                f"{where}() does not take '{key}': it changes what is loaded; pass it to "
                "glint.load()"
            )
        if value is None:
            continue
        flag = "--" + name
        if isinstance(value, (bool, np.bool_)):
            if name == "caustics":
                args += [flag, "on" if value else "off"]
            elif name in _NEGATABLE:
                args.append(flag if value else "--no-" + name)
            elif value:
                args.append(flag)
            continue
        if name == "aov" and not isinstance(value, str):
            value = ",".join(value)
        elif name == "size" and not isinstance(value, str):
            width, height = value
            value = f"{int(width)}x{int(height)}"
        elif isinstance(value, (float, np.floating)):
            value = repr(float(value))  # the shortest text that reads back as the same double
        args += [flag, str(value)]
    return args


# ---- Images -----------------------------------------------------------------------------------

_PLAIN = {"exposure": 0.0, "srgb": False, "tonemap": "clamp"}


class Image(np.ndarray):
    """A rendered image: linear radiance as float32, rows x columns x 3, row 0 at the top.

    An ndarray like any other, with what the render knows beside it:
      passes   the render passes asked for (``aov=``), by name: albedo, normal and variance
               (rows x columns x 3) and depth (rows x columns); with albedo and variance also
               albedoVariance, the albedo's (what the denoiser reads)
      info     spp, mean_spp, seconds, build_seconds, denoised, denoiser ("oidn balanced",
               "nlm"), denoise_seconds, rays, ...
      display  how an 8-bit file shows it: exposure, srgb, tonemap (the scene's way, as the
               glint command writes it)
    In a notebook it shows itself as a PNG.
    """

    passes: dict
    info: dict
    display: dict

    def __array_finalize__(self, obj: Any) -> None:
        self.passes = getattr(obj, "passes", {})
        self.info = getattr(obj, "info", {})
        self.display = getattr(obj, "display", dict(_PLAIN))
        self._frame = getattr(obj, "_frame", None)

    def _repr_png_(self) -> bytes:
        return encode(self, "png")


def _display(image: Any, exposure, srgb, tonemap) -> tuple:
    base = getattr(image, "display", _PLAIN)
    return (
        float(base["exposure"] if exposure is None else exposure),
        bool(base["srgb"] if srgb is None else srgb),
        str(base["tonemap"] if tonemap is None else tonemap),
    )


def _check_radiance(image: Any, where: str) -> None:
    """Images are linear radiance in floats: an array of integers (8-bit pixel values, most
    likely) would be written as radiance of 0 to 255, all white. Refused, saying how to convert."""
    dtype = np.asarray(image).dtype
    if dtype.kind in "iub":
        raise TypeError(
            f"{where}: the image is an array of {dtype} values; glint writes linear radiance "
            "as floats (a glint.Image, or float32/float64 arrays): for 8-bit pixel values, "
            "image / 255.0 is their value in [0, 1] (and, for an sRGB picture, "
            "((image / 255.0 + 0.055) / 1.055) ** 2.4 their linear radiance)"
        )


def write(
    path: PathLike,
    image: np.ndarray,
    *,
    exposure: Optional[float] = None,
    srgb: Optional[bool] = None,
    tonemap: Optional[str] = None,
    passes: Optional[dict] = None,
) -> None:
    """Writes `image` (rows x columns x 3) to `path`: .png, .ppm, .pfm or .exr, as the glint
    command writes it. 8-bit files go through the image's display (exposure, the sRGB curve, the
    tone mapper), which the keyword arguments change; float files hold linear radiance times
    2^exposure. An .exr file also holds the image's render passes (or `passes`) as layers."""
    path = os.fspath(path)
    _check_radiance(image, "write")
    if passes is None:
        passes = getattr(image, "passes", {}) if path.lower().endswith(".exr") else {}
    _glint.write(
        path, np.asarray(image), dict(passes), *_display(image, exposure, srgb, tonemap),
        getattr(image, "_frame", None),
    )


def encode(
    image: np.ndarray,
    format: str = "png",
    *,
    exposure: Optional[float] = None,
    srgb: Optional[bool] = None,
    tonemap: Optional[str] = None,
) -> bytes:
    """The bytes `write` would put in a file of `format` (png, ppm, pfm, exr)."""
    _check_radiance(image, "encode")
    return _glint.encode(
        format, np.asarray(image), {}, *_display(image, exposure, srgb, tonemap),
        getattr(image, "_frame", None),
    )


def denoise(
    image: np.ndarray,
    *,
    passes: Optional[dict] = None,
    denoiser: str = "auto",
    quality: str = "balanced",
    threads: int = 0,
) -> "Image":
    """`image` denoised as ``render(denoise=True)`` denoises, guided by its passes (or
    `passes`): albedo and normal as the network reads them, variance where there is one. For
    images put together from several renders (an average of rounds, say); the result keeps
    the image's passes and display, and its ``info["denoiser"]`` says which denoiser ran."""
    _check_radiance(image, "denoise")
    if passes is None:
        passes = getattr(image, "passes", {})
    guide = {k: v for k, v in dict(passes).items() if k in ("albedo", "normal", "variance")}
    pixels, method = _glint.denoise(np.asarray(image), guide, denoiser, quality, int(threads))
    out = pixels.view(Image)
    out.passes = dict(passes)
    out.info = dict(getattr(image, "info", {}), denoised=True, denoiser=method)
    out.display = dict(getattr(image, "display", _PLAIN))
    return out


# ---- Scenes -----------------------------------------------------------------------------------

ProgressCallback = Callable[[float, float], Any]


def _vec(values: Vec3, n: int = 3, what: str = "") -> list:
    out = [float(v) for v in values]
    if len(out) != n:
        raise ValueError(f"{what}: expected {n} numbers, got {len(out)}")
    return out


def _caller() -> tuple:
    """The file and line of the code outside this package that called it."""
    frame = sys._getframe(1)
    here = os.path.dirname(os.path.abspath(__file__))
    while frame is not None and os.path.dirname(os.path.abspath(frame.f_code.co_filename)) == here:
        frame = frame.f_back
    if frame is None:
        return ("<python>", 0)
    return (frame.f_code.co_filename, frame.f_lineno)


def load(path: PathLike, **options: Any) -> "Scene":
    """Loads a scene or model file, as ``glint PATH`` with `options` would: a CSE167x scene
    (.test), or an OBJ, glTF, PLY or STL model framed in the studio. `options` are the command
    line's (size=(640, 480), camera="orbit:30,20,3", integrator="whitted", ...); those of a render
    (spp, seed, ...) are kept for every render. Raises SceneError with the file, line and column
    of a problem in the file, ValueError for an option that does not fit."""
    scene = Scene.__new__(Scene)
    scene._init()
    scene._loaded = _glint.load(os.fspath(path), _option_args(options, "load"))
    return scene


class Scene:
    """A scene to render: one loaded from a file (``glint.load``), or one made in code.

    Made in code, it is written as a scene file is (docs/scene-format.md), one method per
    command, which take effect in order: transforms and the material apply to what is added
    after them. Meshes come from NumPy arrays. ``scene.text`` is the scene file it makes.

        scene = glint.Scene(size=(320, 240))
        scene.camera = dict(eye=(0, 1, 4), target=(0, 0, 0), up=(0, 1, 0), fov=45)
        scene.point_light((2, 4, 3), (1, 1, 1))
        scene.material(diffuse=(0.8, 0.2, 0.2), specular=(0.2, 0.2, 0.2), shininess=40)
        scene.sphere((0, 0, 0), 1)
        image = scene.render(spp=4)
    """

    def __init__(self, size: Sequence[int] = (640, 480), *, name: str = "scene") -> None:
        self._init()
        self._name = name
        self._lines = []
        self._origins = []
        self._meshes = {}
        self._settings = {}
        self.size = size

    def _init(self) -> None:
        self._loaded = None
        self._lines = None
        self._environment = None

    # -- Building -------------------------------------------------------------------------------

    def command(self, name: str, *args: Any) -> "Scene":
        """Adds the scene-file command `name` with `args` (numbers or words), for the commands
        that have no method of their own (``scene.command("clearcoat", 1, 0.05)``)."""
        if self._lines is None:
            raise TypeError("a loaded scene cannot be added to; make one with glint.Scene()")
        words = [name]
        for a in args:
            if isinstance(a, (float, np.floating)):
                a = repr(float(a))
            elif isinstance(a, (list, tuple, np.ndarray)):
                words += [repr(float(v)) for v in a]
                continue
            text = str(a)
            if not text or any(c.isspace() for c in text) or "#" in text:
                raise ValueError(f"{name}: argument {text!r} cannot be written in a scene file")
            words.append(text)
        self._lines.append(" ".join(words))
        self._origins.append(_caller())
        self._loaded = None  # built again at the next render
        return self

    def _setting(self, name: str, *args: Any) -> None:
        """A command of which the last one counts (size, camera, integrator, ...)."""
        if self._lines is None:
            raise TypeError(f"{name}: a loaded scene's is set by glint.load's options")
        self._settings[name] = (args, _caller())
        self._loaded = None

    def translate(self, offset: Vec3) -> "Scene":
        return self.command("translate", _vec(offset, 3, "translate"))

    def rotate(self, axis: Vec3, degrees: float) -> "Scene":
        return self.command("rotate", _vec(axis, 3, "rotate"), float(degrees))

    def scale(self, factors: Union[float, Vec3]) -> "Scene":
        if np.isscalar(factors):
            factors = (factors, factors, factors)
        return self.command("scale", _vec(factors, 3, "scale"))

    def push(self) -> "Scene":
        return self.command("pushTransform")

    def pop(self) -> "Scene":
        return self.command("popTransform")

    @contextmanager
    def transform(self) -> Iterator["Scene"]:
        """``with scene.transform(): scene.translate(...); ...``: the transform is restored after."""
        self.push()
        try:
            yield self
        finally:
            self.pop()

    def material(self, **properties: Any) -> "Scene":
        """Sets the material of what follows: ambient, diffuse, specular, emission and
        transmission (colours), shininess, ior, roughness, metallic (numbers); only those given
        change, as in a scene file."""
        for key, value in properties.items():
            if key not in ("ambient", "diffuse", "specular", "emission", "transmission",
                           "shininess", "ior", "roughness", "metallic"):
                raise TypeError(f"material() got an unexpected keyword argument '{key}'")
            if np.isscalar(value):
                self.command(key, float(value))
            else:
                self.command(key, _vec(value, 3, key))
        return self

    def point_light(self, position: Vec3, color: Vec3) -> "Scene":
        return self.command("point", _vec(position, 3, "position"), _vec(color, 3, "color"))

    def spot_light(self, position: Vec3, direction: Vec3, color: Vec3, inner: float,
                   outer: float) -> "Scene":
        """A point light shining along `direction`, fully within `inner` degrees of it, not at
        all beyond `outer` (glTF's spot light)."""
        return self.command("spot", _vec(position, 3, "position"), _vec(direction, 3, "direction"),
                            _vec(color, 3, "color"), float(inner), float(outer))

    def directional_light(self, direction: Vec3, color: Vec3) -> "Scene":
        """A light infinitely far away; `direction` points towards it."""
        return self.command("directional", _vec(direction, 3, "direction"), _vec(color, 3, "color"))

    def quad_light(self, corner: Vec3, edge1: Vec3, edge2: Vec3, color: Vec3) -> "Scene":
        """A parallelogram emitting `color` from the side cross(edge1, edge2) points to."""
        return self.command(
            "quadLight", _vec(corner, 3, "corner"), _vec(edge1, 3, "edge1"),
            _vec(edge2, 3, "edge2"), _vec(color, 3, "color"),
        )

    def attenuation(self, constant: float, linear: float, quadratic: float) -> "Scene":
        return self.command("attenuation", float(constant), float(linear), float(quadratic))

    def _refuse(self, message: str) -> None:
        """Raises SceneError at the caller's line, as building the scene would later."""
        file, line = _caller()
        error = SceneError(f"{file}:{line}: error: {message}")
        error.file, error.line, error.column, error.message = file, line, 0, message
        raise error

    def _radius(self, what: str, radius: float, positive: bool) -> float:
        radius = float(radius)
        if positive and not radius > 0:
            self._refuse(f"{what} radius must be positive, got '{radius!r}'")
        if not positive and not radius >= 0:
            self._refuse(f"{what} radius must not be negative, got '{radius!r}'")
        return radius

    def sphere(self, center: Vec3, radius: float) -> "Scene":
        radius = self._radius("sphere", radius, False)
        return self.command("sphere", _vec(center, 3, "center"), radius)

    def box(self, corner0: Vec3, corner1: Vec3) -> "Scene":
        return self.command("box", _vec(corner0, 3, "corner0"), _vec(corner1, 3, "corner1"))

    def cylinder(self, end0: Vec3, end1: Vec3, radius: float) -> "Scene":
        radius = self._radius("cylinder", radius, True)
        return self.command("cylinder", _vec(end0, 3, "end0"), _vec(end1, 3, "end1"), radius)

    def cone(self, end0: Vec3, radius0: float, end1: Vec3, radius1: float) -> "Scene":
        radius0, radius1 = self._radius("cone", radius0, False), self._radius("cone", radius1, False)
        return self.command("cone", _vec(end0, 3, "end0"), radius0, _vec(end1, 3, "end1"), radius1)

    def disk(self, center: Vec3, normal: Vec3, radius: float) -> "Scene":
        radius = self._radius("disk", radius, True)
        return self.command("disk", _vec(center, 3, "center"), _vec(normal, 3, "normal"), radius)

    def plane(self, point: Vec3, normal: Vec3) -> "Scene":
        return self.command("plane", _vec(point, 3, "point"), _vec(normal, 3, "normal"))

    def mesh(
        self,
        positions: Union[Mesh, np.ndarray, PathLike],
        indices: Optional[np.ndarray] = None,
        *,
        normals: Optional[np.ndarray] = None,
        uvs: Optional[np.ndarray] = None,
    ) -> Mesh:
        """Places a triangle mesh under the current transform and material: a glint.Mesh, or
        one made of arrays (positions N x 3 and indices M x 3, with optional normals N x 3 and
        uvs N x 2; float32 is read as it is), or a mesh file (OBJ, glTF, PLY, STL). A Mesh
        placed several times is stored once. Returns the Mesh (None for a file)."""
        if isinstance(positions, (str, os.PathLike)):
            path = os.fspath(positions)
            if not os.path.isfile(path):
                why = "no such file" if not os.path.exists(path) else "not a file"
                self._refuse(f"cannot read mesh '{path}': {why}")
            self.command("mesh", path)
            return None
        mesh = positions if isinstance(positions, Mesh) else Mesh(positions, indices, normals, uvs)
        key = None
        for k, m in self._meshes.items():
            if m is mesh:
                key = k
        if key is None:
            key = f"@mesh{len(self._meshes)}"
            self._meshes[key] = mesh
        self.command("mesh", key)
        return mesh

    # -- Settings -------------------------------------------------------------------------------

    @property
    def size(self) -> tuple:
        """The image's width and height in pixels."""
        if self._lines is None:
            return self._loaded.size
        return self._settings["size"][0]

    @size.setter
    def size(self, value: Sequence[int]) -> None:
        width, height = (int(v) for v in value)
        if self._lines is None:
            self._loaded.size = (width, height)
        else:
            self._settings["size"] = ((width, height), _caller())
            if self._loaded is not None:
                self._loaded.size = (width, height)

    @property
    def camera(self) -> Optional[dict]:
        """The camera: a dict of eye, target, up, fov (vertical, degrees), aperture and focus
        (the thin lens; 0 for a pinhole). Set it (any of the keys) to move the camera; a loaded
        scene keeps everything else, and renders again without loading."""
        if self._lines is not None and self._loaded is None:
            cam = self._settings.get("camera")
            return dict(cam[0][0]) if cam else None
        return self._built().camera

    @camera.setter
    def camera(self, value: dict) -> None:
        value = dict(value)
        if self._lines is not None:
            old = self._settings.get("camera")
            merged = dict(old[0][0]) if old else {"up": (0.0, 1.0, 0.0), "fov": 45.0}
            merged.update(value)
            for key in ("eye", "target"):
                if key not in merged:
                    raise ValueError(f"camera: '{key}' is needed")
            self._settings["camera"] = ((merged,), _caller())
            value = merged
        if self._loaded is not None:
            self._loaded.camera = value

    def background(self, color: Vec3, up: Optional[Vec3] = None) -> "Scene":
        """The colour of rays that hit nothing; with `up`, a gradient from `color` (looking
        down) to `up` (looking up)."""
        args = [_vec(color, 3, "background")]
        if up is not None:
            args.append(_vec(up, 3, "background"))
        self._setting("background", *args)
        return self

    def environment(
        self, image: Union[np.ndarray, PathLike, None], scale: float = 1.0, rotation: float = 0.0
    ) -> "Scene":
        """Surroundings and light: an equirectangular map, an array (rows x columns x 3, linear
        radiance) or an .hdr/.exr file, times `scale`, turned `rotation` degrees about +y.
        None removes it. Also for a loaded scene."""
        if image is not None and not isinstance(image, np.ndarray):
            if self._lines is None:
                raise TypeError("environment: a loaded scene takes an array here (or "
                                "environment= to glint.load)")
            self._setting("environment", os.fspath(image), float(scale), float(rotation))
            return self
        self._environment = (image, float(scale), float(rotation))
        if self._loaded is not None:
            _glint.set_environment(self._loaded, image, float(scale), float(rotation))
        return self

    def lens(self, aperture: float, focus: float = 0.0) -> "Scene":
        self._setting("lens", float(aperture), float(focus))
        return self

    @property
    def integrator(self) -> str:
        """How light is computed: "whitted" (the course's) or "path" (the path tracer)."""
        if self._lines is not None and self._loaded is None:
            s = self._settings.get("integrator")
            return s[0][0] if s else "whitted"
        return self._built().integrator

    @integrator.setter
    def integrator(self, name: str) -> None:
        self._setting("integrator", str(name))

    @property
    def text(self) -> str:
        """The scene file this scene is (meshes of arrays appear as @meshN)."""
        if self._lines is None:
            raise TypeError("a loaded scene has no text here: it is its file's")
        return "\n".join(self._text_lines()[0]) + "\n"

    def _text_lines(self) -> tuple:
        lines, origins = [], []
        for name, (args, origin) in self._settings.items():
            if name == "size":
                lines.append(f"size {args[0]} {args[1]}")
            elif name == "camera":
                c = args[0]
                lines.append(
                    "camera " + " ".join(repr(float(v)) for v in
                                         [*c["eye"], *c["target"], *c["up"], c["fov"]])
                )
                if c.get("aperture", 0) or c.get("focus", 0):
                    lines.append(f"lens {float(c.get('aperture', 0))!r} "
                                 f"{float(c.get('focus', 0))!r}")
                    origins.append(origin)
            else:
                words = [name]
                for a in args:
                    words += ([repr(float(v)) for v in a] if isinstance(a, list)
                              else [repr(a) if isinstance(a, float) else str(a)])
                lines.append(" ".join(words))
            origins.append(origin)
        return lines + self._lines, origins + self._origins

    def _built(self):
        if self._loaded is not None:
            return self._loaded
        lines, origins = self._text_lines()
        text = "\n".join(lines) + "\n"
        try:
            loaded = _glint.from_text(text, self._name, self._meshes, [])
        except SceneError as e:
            if e.file != self._name or not 1 <= e.line <= len(origins):
                raise
            file, line = origins[e.line - 1]
            error = SceneError(f"{file}:{line}: error: {e.message} (in '{lines[e.line - 1]}')")
            error.file, error.line, error.column, error.message = file, line, 0, e.message
            raise error from None
        if self._environment is not None:
            _glint.set_environment(loaded, *self._environment)
        self._loaded = loaded
        return loaded

    # -- Rendering ------------------------------------------------------------------------------

    def render(self, *, progress: Optional[ProgressCallback] = None, **options: Any) -> Image:
        """Renders the scene and returns the image (glint.Image, float32 rows x columns x 3).

        `options` are the command line's rendering options: spp, integrator, threads, seed,
        aov (a list of albedo, normal, depth, variance: Image.passes), denoise, denoiser
        ("oidn", the network, where this build has its weights; "nlm"), denoise_quality
        ("fast", "balanced", "high"), noise_threshold, min_spp, time, maxdepth, max_bounces,
        clamp_indirect, caustics, and exposure, srgb and tonemap for how it is shown. A model (and nothing else)
        is sampled until clean and denoised unless told otherwise, as by the glint command. The interpreter's lock is
        released while it renders; Ctrl-C stops it (KeyboardInterrupt) within a fraction of a
        second. `progress(fraction, seconds)` is called about ten times a second."""
        args = _option_args(options, "render", _RENDER_OPTIONS)
        image, passes, info, frame = self._built().render(args, progress)
        out = image.view(Image)
        out.passes = passes
        out.info = info
        out.display = info["display"]
        out._frame = frame
        return out

    # -- What a loaded scene is ---------------------------------------------------------------

    @property
    def info(self) -> dict:
        """What was loaded: model (a model framed in the studio), note (how it was framed),
        triangles, lights, spp (the scene's), extensions and animations (a glTF file's)."""
        s = self._built()
        return dict(
            model=s.model, note=s.note, triangles=s.triangles, lights=s.lights, spp=s.spp,
            extensions=s.extensions, animations=s.animations, output=s.output,
        )

    def __repr__(self) -> str:
        w, h = self.size
        kind = "loaded" if self._lines is None else f"{len(self._lines)} commands"
        return f"<glint.Scene {w}x{h}, {kind}>"
