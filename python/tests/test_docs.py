"""The docs' examples run from a clone: docs/python.md's cells, in order, in a folder where only
the repository's own files are at hand (no ../shared beside it); and no example in the README
or the docs reads a file from outside the repository."""

import os
import re
from pathlib import Path

import pytest

import glint
from conftest import SOURCE

USER_DOCS = [SOURCE / "README.md", *sorted((SOURCE / "docs").glob("*.md"))]
# Files the examples may read: the repository's scenes, maps and test data.
REPOSITORY_FOLDERS = ["scenes", "tests"]


def code_blocks(path: Path, language: str = "") -> list:
    text = path.read_text()
    return [m.group(2) for m in re.finditer(r"```([a-z]*)\n(.*?)```", text, re.S)
            if not language or m.group(1) == language]


@pytest.mark.parametrize("doc", USER_DOCS, ids=lambda p: p.name)
def test_no_example_reads_a_file_from_outside_the_repository(doc):
    for block in code_blocks(doc):
        assert "../shared" not in block and "shared/real-world" not in block, (
            f"{doc.name}: an example reads ../shared, which a clone does not have:\n{block}"
        )


def test_the_python_walkthrough_runs_from_a_clone(tmp_path, monkeypatch):
    # A clone's folder as a newcomer has it: the repository's files, nothing beside it.
    clone = tmp_path / "clone"
    clone.mkdir()
    for folder in REPOSITORY_FOLDERS:
        (clone / folder).symlink_to(SOURCE / folder, target_is_directory=True)
    monkeypatch.chdir(clone)
    assert not (clone.parent / "shared").exists()
    cells = code_blocks(SOURCE / "docs" / "python.md", "python")
    assert len(cells) >= 5
    namespace = {"__name__": "walkthrough"}
    for i, cell in enumerate(cells):
        try:
            exec(compile(cell, f"docs/python.md cell {i}", "exec"), namespace)
        except Exception as e:  # noqa: BLE001: the cell's own failure, said with the cell
            pytest.fail(f"docs/python.md cell {i} failed: {type(e).__name__}: {e}\n{cell}")
    # What the cells made, where a newcomer would find it.
    assert (clone / "strip.png").exists() and (clone / "box.exr").exists()
    assert isinstance(namespace["image"], glint.Image)
    assert len(namespace["turntable"]) == 12
