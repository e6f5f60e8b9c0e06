"""The README's section "From Python": each of its Python blocks runs as
written, from the repository's root."""

from __future__ import annotations

import os
import re

import pytest

from conftest import ROOT


def blocks(spark: bool = False):
    """The section's Python blocks; those of `motionwire.spark`
    (`spark=True`) need a SparkSession and run in test_spark.py."""
    text = (ROOT / "README.md").read_text()
    section = text.split("## From Python", 1)[1].split("\n## ", 1)[0]
    found = re.findall(r"```python\n(.*?)```", section, re.S)
    return [b for b in found if ("motionwire import spark" in b) == spark]


def test_the_section_has_its_blocks():
    assert len(blocks()) == 3
    assert len(blocks(spark=True)) == 1


@pytest.mark.parametrize("n", range(3))
def test_readme_block(n, monkeypatch):
    pytest.importorskip("duckdb")
    pytest.importorskip("polars")
    pytest.importorskip("pandas")
    pytest.importorskip("can")
    monkeypatch.chdir(ROOT)
    exec(compile(blocks()[n], f"README.md, From Python, block {n + 1}", "exec"), {})
