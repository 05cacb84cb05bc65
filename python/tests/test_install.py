"""The package as `cmake --install` lays it out imports and renders on its own."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import SOURCE


def test_the_installed_package_imports_and_renders(tmp_path):
    build = os.environ.get("GLINT_BUILD_DIR")
    if not build:
        pytest.skip("GLINT_BUILD_DIR is not set (ctest sets it)")
    subprocess.run(["cmake", "--install", build, "--prefix", str(tmp_path)], check=True,
                   stdout=subprocess.DEVNULL)
    packages = list(tmp_path.glob("lib/python3*/dist-packages/glint"))
    assert len(packages) == 1
    names = {p.name for p in packages[0].iterdir()}
    assert {"__init__.py", "_glint.pyi", "py.typed"} <= names
    assert any(n.startswith("_glint.") and n.endswith(".so") for n in names)
    code = ("import glint, sys; s = glint.load(sys.argv[1], size=(16, 12)); "
            "print(glint.__file__, s.render().shape)")
    env = dict(os.environ, PYTHONPATH=str(packages[0].parent))
    out = subprocess.run([sys.executable, "-c", code, str(SOURCE / "scenes" / "cornell.test")],
                         env=env, check=True, capture_output=True, text=True, cwd=tmp_path).stdout
    assert out.startswith(str(packages[0])) and "(12, 16, 3)" in out
