"""Shared fixtures of the Python module's tests (run by ctest as python.*; docs/python.md).

The build tree's package is imported (PYTHONPATH=build/python, set by CTest), and the glint
program beside it renders what the module's images are compared with."""

import os
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(__file__).resolve().parents[2]
SHARED = SOURCE.parent / "shared"


@pytest.fixture(scope="session")
def glint_bin() -> Path:
    path = Path(os.environ.get("GLINT_BIN", SOURCE / "build" / "glint"))
    if not path.exists():
        pytest.fail(f"the glint program is not built: {path}")
    return path


@pytest.fixture
def cli(glint_bin, tmp_path):
    """Runs the glint program with `args`, writing `name` in tmp_path; returns its bytes."""

    def run(name: str, *args: str) -> bytes:
        out = tmp_path / ("cli-" + name)
        subprocess.run([str(glint_bin), *map(str, args), "-q", "-o", str(out)], check=True)
        return out.read_bytes()

    return run


@pytest.fixture(scope="session")
def course_scene6() -> Path:
    return SOURCE / "tests" / "data" / "cse167x" / "scene6.test"


def data(*parts: str) -> Path:
    return SOURCE.joinpath("tests", "data", *parts)
