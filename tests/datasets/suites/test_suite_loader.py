"""Suites as TOML: parsing, defaults and the errors bad files get."""

from __future__ import annotations

import pytest
from trackbench_suites.loader import _parsed, merge_tables, parse_suite

from benchmark.errors import DataError

GOOD = """
[suite]
name = "demo"
kind = "camera"

[defaults]
focal_px = 300.0
[defaults.optics]
blur_px = 0.0
noise_grey = 1.0

[[sequence]]
name = "A"
n_frames = 4
[sequence.optics]
noise_grey = 2.0

[[sequence]]
name = "B"
n_frames = 2
focal_px = 500.0
"""


def test_merge_tables_merges_nested_tables_and_replaces_the_rest() -> None:
    base = {"a": 1, "t": {"x": 1, "y": [1, 2]}, "l": [1]}
    merged = merge_tables(base, {"t": {"y": [3]}, "l": [2, 3], "b": 2})
    assert merged == {"a": 1, "t": {"x": 1, "y": [3]}, "l": [2, 3], "b": 2}
    assert base["t"] == {"x": 1, "y": [1, 2]}


def test_sequences_get_the_defaults_and_the_suite_prefix(kinds) -> None:
    name, sequences, *_ = parse_suite(GOOD, "demo.toml", kinds)
    assert name == "demo"
    a, b = (seq.spec for seq in sequences)
    assert (a.name, b.name) == ("demo/A", "demo/B")
    assert (a.focal_px, b.focal_px) == (300.0, 500.0)
    assert (a.optics.blur_px, a.optics.noise_grey, b.optics.noise_grey) == (0.0, 2.0, 1.0)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[suite\n", r"bad\.toml: not valid TOML"),
        (
            GOOD.replace('kind = "camera"', 'kind = "lidar"'),
            r"^bad\.toml: suite\.kind: must be one of the registered scene kinds "
            r"\['camera', 'camera-route', 'sonar', 'stereo', 'stereo-images'\], got 'lidar'$",
        ),
        (GOOD.replace('name = "B"', 'name = "A"'), r"^bad\.toml: sequence name\(s\) 'A' appear twice$"),
        (GOOD.replace('name = "B"\n', ""), r"^bad\.toml: sequence\[1\]: missing required key 'name'$"),
        (GOOD.replace('name = "B"', 'name = ""'), r"^bad\.toml: sequence\[1\]\.name: must not be empty$"),
        (GOOD.split("[[sequence]]")[0], r"^bad\.toml: missing required key 'sequence'$"),
        (
            "defaults = 3\n" + GOOD.split("[defaults]")[0] + "[[sequence]]" + GOOD.split("[[sequence]]", 1)[1],
            r"^bad\.toml: defaults: expected a table, got 3$",
        ),
        (
            GOOD.replace("n_frames = 4", "n_frames = 4\nfocal = 1.0"),
            r"^bad\.toml \[sequence A\]: unknown key 'focal' \(known: name, n_frames, ",
        ),
        (
            GOOD.replace("noise_grey = 2.0", "noise_grey = 2.0\nwater = { lamps = [{}, { cone_deg = 40.0, hotspot = -1 }] }"),
            r"^bad\.toml \[sequence A\]: optics\.water\.lamps\[1\]\.hotspot: must be >= 0, got -1$",
        ),
        (GOOD + "\n[extra]\n", r"^bad\.toml: unknown key 'extra' \(known: suite, sequence, defaults\)$"),
        (GOOD.replace('name = "demo"\n', ""), r"^bad\.toml: suite: missing required key 'name'$"),
        (GOOD.replace('kind = "camera"', 'kind = "camera"\ntraining = 3'), r"^bad\.toml: suite\.training: expected a string"),
        (
            GOOD.replace('kind = "camera"', 'kind = "camera"\ntraining = "demo"'),
            r"^bad\.toml: suite: training must name another suite, got 'demo'$",
        ),
        (GOOD.replace('kind = "camera"', 'kind = "camera"\nscored = "no"'), r"^bad\.toml: suite\.scored: expected true or false, got 'no'$"),
    ],
)
def test_bad_suite_files_name_file_and_sequence(kinds, text: str, message: str) -> None:
    with pytest.raises(DataError, match=message):
        parse_suite(text, "bad.toml", kinds)


def test_a_suite_may_name_any_kind_it_is_given_and_its_factory_builds_each_sequence() -> None:
    built = []

    def factory(table, where):
        built.append((dict(table), where))
        return table["name"]

    text = GOOD.replace('kind = "camera"', 'kind = "scan"')
    assert parse_suite(text, "scan.toml", {"scan": factory})[:2] == ("demo", ["demo/A", "demo/B"])
    (a, where_a), (b, _) = built
    assert where_a == "scan.toml [sequence A]"
    assert a == {"name": "demo/A", "focal_px": 300.0, "optics": {"blur_px": 0.0, "noise_grey": 2.0}, "n_frames": 4}
    assert (b["focal_px"], b["optics"]["noise_grey"]) == (500.0, 1.0)
    with pytest.raises(DataError, match=r"^scan\.toml: suite\.kind: must be one of the registered scene kinds \[\], got 'scan'$"):
        parse_suite(text, "scan.toml", {})


def test_a_text_is_parsed_once_and_what_a_factory_does_to_its_tables_reaches_no_later_read() -> None:
    built = []

    def vandal(table, where):
        built.append(repr(table))
        table.pop("n_frames", None)
        table.get("optics", {}).clear()
        return table["name"]

    text = GOOD.replace('kind = "camera"', 'kind = "vandalised"')
    parse_suite(text, "v.toml", {"vandalised": vandal})
    before = _parsed.cache_info()
    parse_suite(text, "v.toml", {"vandalised": vandal})
    after = _parsed.cache_info()
    assert (after.misses, after.hits) == (before.misses, before.hits + 1)
    assert built[2:] == built[:2] and "'noise_grey': 2.0" in built[0]


def test_a_suite_names_its_training_split_and_a_split_is_not_scored(kinds) -> None:
    plain = parse_suite(GOOD, "demo.toml", kinds)
    assert (plain.training, plain.scored) == (None, True)
    trained = parse_suite(GOOD.replace('kind = "camera"', 'kind = "camera"\ntraining = "demo-train"'), "d.toml", kinds)
    assert (trained.training, trained.scored) == ("demo-train", True)
    split = parse_suite(GOOD.replace('kind = "camera"', 'kind = "camera"\nscored = false'), "d.toml", kinds)
    assert (split.training, split.scored) == (None, False)
