"""CITATION.cff cites the software at the installed version, and the seed article."""

from pathlib import Path

import pytest

import microimpact

yaml = pytest.importorskip("yaml", reason="PyYAML is not installed")
CFF = Path(__file__).resolve().parents[1] / "CITATION.cff"
pytestmark = pytest.mark.skipif(not CFF.is_file(), reason="no CITATION.cff beside this tree (installed wheel)")


def test_citation_file():
    cff = yaml.safe_load(CFF.read_text())
    assert cff["cff-version"] == "1.2.0"
    assert cff["type"] == "software"
    # the version the project declares; the installed one too where the tree is installed (a source
    # tree on the path without installation knows no version: "0+unknown")
    import re

    declared = re.search(r'^version = "([^"]+)"', (CFF.parent / "pyproject.toml").read_text(), re.M).group(1)
    assert str(cff["version"]) == declared
    if microimpact.__version__ != "0+unknown":
        assert microimpact.__version__ == declared
    (article,) = [r for r in cff["references"] if r["type"] == "article"]
    assert article["title"].startswith("Dynamic impact model of plastic deformation between micro-particles")
    assert (article["journal"], article["volume"], article["issue"], article["start"], article["end"]) == (
        "Aerosol Science and Technology",
        50,
        4,
        321,
        330,
    )
    assert article["year"] == 2016
