"""docs/python.md's section "pandas, polars, DuckDB": its examples run as
written (doctest), from the repository's root."""

from __future__ import annotations

import doctest
import re

import pytest

import motionwire
from conftest import ROOT


def test_the_pandas_section_runs(monkeypatch):
    pytest.importorskip("pandas")
    monkeypatch.chdir(ROOT)
    text = (ROOT / "docs" / "python.md").read_text()
    section = text.split("## pandas, polars, DuckDB", 1)[1].split("\n## ", 1)[0]
    examples = "".join(re.findall(r"```python\n(.*?)```", section, re.S))
    assert examples.count(">>>") >= 6
    test = doctest.DocTestParser().get_doctest(examples, {"motionwire": motionwire}, "pandas", "docs/python.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0 and runner.tries >= 6
