"""The warnings channel (shaftfe.util.notices): printed once on stderr inside a collection,
collected for summary.json, and a Python warning outside one."""

import warnings

import pytest

from shaftfe.util.notices import ShaftfeWarning, collected, collecting, warn


def test_collected_once_and_printed_once(capsys):
    with collecting() as box:
        warn("sharp-shoulder", "shoulder:collar", "zero radius:  a singular corner")
        warn("sharp-shoulder", "shoulder:collar", "zero radius: a singular corner")
        warn("overspeed", "--allow-overspeed", "above max_rpm")
        assert [d["code"] for d in collected()] == ["sharp-shoulder", "overspeed"]
    assert len(box) == 2
    err = capsys.readouterr().err.splitlines()
    assert err == ["shaftfe: warning: shoulder:collar: zero radius: a singular corner",
                   "shaftfe: warning: --allow-overspeed: above max_rpm"]
    assert collected() == []


def test_outside_a_collection_is_a_python_warning():
    with pytest.warns(ShaftfeWarning, match="shoulder:collar"):
        warn("sharp-shoulder", "shoulder:collar", "a singular corner")


def test_silent_collection(capsys):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with collecting(echo=False):
            warn("x", "y", "z")
            assert collected() == [{"code": "x", "where": "y", "text": "z"}]
    assert capsys.readouterr().err == ""
