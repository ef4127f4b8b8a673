"""hexar.fastyaml reads every document as PyYAML's safe loader does: the same values of the same types, and for
what it leaves to PyYAML (anchors, tags, merge keys, several documents, broken text) the same values or errors."""

from __future__ import annotations

import datetime
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from rosbags.rosbag2 import StoragePlugin, Writer

from hexar import fastyaml
from hexar.evals.scenarios.bag import TYPESTORE

ROOT = Path(__file__).resolve().parents[2]
# strings YAML 1.1 reads as something else when plain, and some it does not
TRICKY = ["yes", "No", "on", "OFF", "y", "~", "null", "Null", "", "0x1F", "0o17", "017", "1_000", "1:30", "190:20:30",
          "+1", "-.5e3", ".inf", "-.Inf", ".NaN", "1e3", "6.8523015e+5", "2001-12-14", "2001-12-14t21:59:43.10-05:00",
          "2002-12-14 21:59:43.10 -5", "<<", "=", "a: b", "- x", "# not a comment", "it's", 'say "hi"', "Señal ✓",
          "multi\nline\n", "  padded ", "RIHS01_feb91e995ff9ebd0", "/map", "0", "-0", "0.", "1,000", "True", "TRUE"]


def _same(a: Any, b: Any) -> bool:
    """Equal and of the same types all the way down (True == 1 and 1 == 1.0 in Python)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return list(a) == list(b) and all(_same(k, k2) and _same(a[k], b[k2]) for k, k2 in zip(a, b, strict=True))
    if isinstance(a, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and a != a:
        return b != b
    return bool(a == b)


def _reference(text: str) -> Any:
    return yaml.load(text, Loader=yaml.CSafeLoader)


def _random_value(rng: np.random.Generator, depth: int = 0) -> Any:
    kind = int(rng.integers(7 if depth < 3 else 5))
    if kind == 0:
        return TRICKY[int(rng.integers(len(TRICKY)))]
    if kind == 1:
        return int(rng.integers(-(2**40), 2**40))
    if kind == 2:
        return float(rng.normal()) * 10 ** int(rng.integers(-5, 6))
    if kind == 3:
        return [None, True, False][int(rng.integers(3))]
    if kind == 4:
        return datetime.date(2000 + int(rng.integers(30)), 1 + int(rng.integers(12)), 1 + int(rng.integers(28)))
    if kind == 5:
        return [_random_value(rng, depth + 1) for _ in range(int(rng.integers(4)))]
    return {TRICKY[int(rng.integers(len(TRICKY)))]: _random_value(rng, depth + 1) for _ in range(int(rng.integers(4)))}


@pytest.mark.skipif(not fastyaml.LIBYAML, reason="PyYAML without libyaml reads everything itself")
def test_random_documents_in_every_style_read_as_the_safe_loader_reads_them() -> None:
    rng = np.random.default_rng(3)
    styles: list[dict[str, Any]] = [{}, {"default_flow_style": True}, {"default_style": '"'},
                                    {"default_style": "'"}, {"default_style": "|"}, {"allow_unicode": True}]
    built = 0
    for i in range(400):
        doc = {"data": _random_value(rng)}
        text = yaml.safe_dump(doc, **styles[i % len(styles)])
        try:
            got = fastyaml._Builder().build(text)
        except fastyaml._Unusual:
            assert "!!" in text  # forced quotes tag a quoted number or date: left to PyYAML
            got = fastyaml.load(text)
        else:
            built += 1
        assert _same(got, _reference(text)), text
    assert built > 250


def _project_yaml() -> list[Path]:
    listed = subprocess.run(["git", "ls-files", "*.yaml", "*.yml"], cwd=ROOT, capture_output=True, text=True,
                            check=True).stdout.split()
    return [ROOT / p for p in listed]


def test_every_yaml_file_of_the_project_reads_the_same() -> None:
    files = _project_yaml()
    assert len(files) > 20
    for path in files:
        text = path.read_text("utf-8")
        try:
            want = _reference(text)
        except yaml.YAMLError as err:
            with pytest.raises(type(err)):
                fastyaml.load(text)
            continue
        assert _same(fastyaml.load(text), want), path


@pytest.mark.parametrize("storage", [StoragePlugin.SQLITE3, StoragePlugin.MCAP])
def test_a_recordings_metadata_reads_the_same(tmp_path: Path, storage: StoragePlugin) -> None:
    bag = tmp_path / "rec"
    with Writer(bag, version=9, storage_plugin=storage) as writer:
        conn = writer.add_connection("/rosout", "rcl_interfaces/msg/Log", typestore=TYPESTORE)
        msg = TYPESTORE.types["rcl_interfaces/msg/Log"](
            stamp=TYPESTORE.types["builtin_interfaces/msg/Time"](sec=1, nanosec=2), level=20, name="amcl",
            msg="hello", file="f", function="g", line=3)
        writer.write(conn, 5, TYPESTORE.serialize_cdr(msg, "rcl_interfaces/msg/Log"))
    text = (bag / "metadata.yaml").read_text()
    got = fastyaml._Builder().build(text)
    assert _same(got, _reference(text)) and _same(fastyaml.load(text), got)
    assert got["rosbag2_bagfile_information"]["message_count"] == 1


@pytest.mark.parametrize("text", [
    "a: &x [1, 2]\nb: *x\n",  # anchor and alias
    "base: &b {x: 1}\nmore:\n  <<: *b\n  y: 2\n",  # merge key
    "s: !!set {a, b}\n",
    "b: !!binary aGVsbG8=\n",
    "o: !!omap [{a: 1}, {b: 2}]\n",
    "n: !!str 12\n",
    "q: ! 12\n",
])
def test_what_it_leaves_to_pyyaml_reads_the_same(text: str) -> None:
    assert _same(fastyaml.load(text), _reference(text))


@pytest.mark.parametrize("text", [
    "a: 1\n---\nb: 2\n",  # two documents
    "? [1, 2]\n: x\n",  # a list as a key
    "a: [1, 2\n",  # broken
    "a: !!python/object:os.system x\n",  # the safe loader refuses it
    "key: 'unterminated\n",
    "\t- tab\n",
    "x: =\n",  # YAML 1.1's value key, which the safe loader cannot construct
])
def test_what_the_safe_loader_refuses_is_refused_with_its_error(text: str) -> None:
    with pytest.raises(yaml.YAMLError) as want:
        _reference(text)
    with pytest.raises(type(want.value)) as got:
        fastyaml.load(text)
    assert str(got.value) == str(want.value)


def test_an_empty_document_is_none() -> None:
    assert fastyaml.load("") is None and fastyaml.load("# only a comment\n") is None
    assert fastyaml.load("---\n...\n") is _reference("---\n...\n")
