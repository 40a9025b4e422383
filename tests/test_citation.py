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
    # the version the project declares: pyproject.toml takes it from microimpact/_version.py, which
    # microimpact.__version__ reads (the installed metadata is compared with it in CI, on the wheel)
    import re

    pyproject = (CFF.parent / "pyproject.toml").read_text()
    assert re.search(r'^dynamic = \["version"\]$', pyproject, re.M)
    assert re.search(r'^version = \{attr = "microimpact\._version\.__version__"\}', pyproject, re.M)
    source = (CFF.parent / "src" / "microimpact" / "_version.py").read_text()
    declared = re.search(r'^__version__ = "([^"]+)"$', source, re.M).group(1)
    assert str(cff["version"]) == declared == microimpact.__version__
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
