"""The module's copies of the core's tables: the `stats` dict against the report's table
(SAP_FRAME_REPORT_FIELDS in frame_report.h), the Broadphase docstring against the config
table (every keyword, its default and what it takes). A failure names the field."""
import pathlib
import re

import sap_broadphase
from box_oracle import random_boxes

ROOT = pathlib.Path(__file__).resolve().parents[2]


def report_table():
    """(name, unit) of every row of SAP_FRAME_REPORT_FIELDS, in order."""
    header = (ROOT / "include/sap_broadphase/core/frame_report.h").read_text()
    table = header[header.index("#define SAP_FRAME_REPORT_FIELDS(X)"):]
    table = table[:table.index("// clang-format on")]
    rows = re.findall(r"X\([^,]+, (\w+), [^,]+, (k\w+),", table)
    assert len(rows) > 20, "the report's table was not read from frame_report.h"
    return rows


def test_stats_has_every_field_of_the_report_table_in_its_order():
    engine = sap_broadphase.Broadphase(threads=1)
    engine.update(random_boxes(200, 10.0, 1.0, 3))
    stats = engine.stats
    names = [name for name, _ in report_table()]
    missing = [name for name in names if name not in stats]
    extra = [key for key in stats if key not in names]
    assert not missing, f"stats lacks {missing} (frame_report.h's table)"
    assert not extra, f"stats has {extra}, which frame_report.h's table does not"
    assert list(stats) == names
    for name, unit in report_table():
        if unit == "kAxis":
            assert stats[name] in ("x", "y", "z"), name
        elif unit in ("kPath", "kSkinChoice"):
            assert isinstance(stats[name], str) and stats[name], name
        elif unit == "kFlag":
            assert isinstance(stats[name], bool), name
        else:
            assert isinstance(stats[name], (int, float)) and stats[name] >= 0, name


def test_the_docstring_lists_every_keyword_with_its_default():
    doc = sap_broadphase.Broadphase.__doc__
    for name, value in sap_broadphase.Broadphase().config.items():
        assert f"\n{name} (default {value!r}): " in doc, f"the docstring's keyword {name}={value!r}"
