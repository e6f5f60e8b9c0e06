"""The README's section "From Python": each of its Python blocks runs as
written, from the repository's root."""

from __future__ import annotations

import os
import re

import pytest

from conftest import ROOT


def blocks():
    text = (ROOT / "README.md").read_text()
    section = text.split("## From Python", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```python\n(.*?)```", section, re.S)


def test_the_section_has_its_blocks():
    assert len(blocks()) == 3


@pytest.mark.parametrize("n", range(3))
def test_readme_block(n, monkeypatch):
    pytest.importorskip("duckdb")
    pytest.importorskip("polars")
    pytest.importorskip("pandas")
    pytest.importorskip("can")
    monkeypatch.chdir(ROOT)
    exec(compile(blocks()[n], f"README.md, From Python, block {n + 1}", "exec"), {})
