"""Every corpus file is read, shown and converted without a traceback."""

from __future__ import annotations

import pytest

from tests.corpus import corpus_file, corpus_names
from txtool.dialects.read import read_source
from txtool.io.load import load
from txtool.io.xmlio import InputError, local
from txtool.transform.convert import convert_source


def _load(name: str):
    path = corpus_file(name)
    try:
        return load(str(path))
    except InputError as exc:
        message = str(exc)
        assert "\n" not in message and message.startswith(str(path))
        return None


@pytest.mark.parametrize("name", corpus_names())
def test_show_counts_every_transmission_of_the_expanded_document(name):
    source = _load(name)
    if source is None:
        return  # a one-line message naming the file, checked above
    found = read_source(source)
    expected = [e for e in source.root.iter() if local(e) == "transmission"]
    assert len(found) == len(expected)
    for f in found:
        assert f.transmission.location.line >= 1


@pytest.mark.parametrize("name", corpus_names())
@pytest.mark.parametrize("target", ["ros1", "ros2-p1", "ros2-p2"])
def test_every_corpus_file_converts_or_says_why(name, target):
    source = _load(name)
    if source is None:
        return
    result = convert_source(source, target)
    assert result.data.strip()
    for message in result.losses + result.notes:
        assert "\n" not in message


@pytest.mark.parametrize("name", corpus_names())
def test_cli_show_and_convert_exit_cleanly(run, name):
    path = str(corpus_file(name))
    code, out, err = run("show", path)
    assert code in (0, 2), err
    if code == 2:
        assert err.count("\n") == 1 and path in err
    code, out, err = run("convert", path, "--to", "ros2-p2")
    assert code in (0, 1, 2)
