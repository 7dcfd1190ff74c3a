"""The oracle's own helpers, without rs274 or tnvctl."""
from __future__ import annotations

import sys
from pathlib import Path

ORACLE = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ORACLE))
import canon_compare  # noqa: E402


def test_exact_numbers_read_back_as_the_same_double():
    for value in [1.25 / 25.4, 2.5, 0.1, -4.0 / 25.4, 123.456 / 25.4, 1e-9, 0.0, 50.0 / 25.4]:
        text = canon_compare.exact(value)
        assert "e" not in text.lower(), text
        assert float(text) == value, (text, value)


def test_the_inch_table_holds_the_millimetre_tools_to_the_last_bit(tmp_path):
    mm, inch = canon_compare.default_tools(tmp_path)
    def rows(path: Path) -> list[tuple[float, float]]:
        out = []
        for line in path.read_text().splitlines():
            words = {w[0]: w[1:] for w in line.split(";")[0].split()}
            out.append((float(words["Z"]), float(words["D"])))
        return out
    for (z_mm, d_mm), (z_in, d_in) in zip(rows(mm), rows(inch), strict=True):
        assert z_in == z_mm / canon_compare.MM_PER_INCH
        assert d_in == d_mm / canon_compare.MM_PER_INCH
