"""``microimpact oblique``."""

from __future__ import annotations

import json

import numpy as np
import pytest

from microimpact import oblique as ob
from microimpact.cli import main


def test_json_matches_the_api(capsys):
    assert main(["oblique", "--alumina", "--angles", "5,20,45", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    c = ob.ALUMINA_CASE
    for model in ("mindlin", "rigid"):
        out = ob.oblique_impact(
            ob.alumina_pair(),
            c["velocity"],
            [5.0, 20.0, 45.0],
            c["friction"],
            tangential=model,
        )
        got = doc["models"][model]
        np.testing.assert_allclose(got["e_t"], out.tangential_restitution, rtol=1e-12)
        np.testing.assert_allclose(got["spin_rad_s"], out.rebound_spin, rtol=1e-12)
        assert got["regime"] == list(out.regime)


def test_table_and_plot(tmp_path, capsys):
    png = tmp_path / "o.png"
    assert (
        main(
            [
                "oblique",
                "30",
                "--particle",
                "nh4fl",
                "--surface",
                "silicon",
                "--radius",
                "2.45e-6",
                "--angles",
                "10,60",
                "--tangential",
                "mindlin",
                "--plot",
                str(png),
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    assert "tangential model: mindlin" in text
    assert "rigid" not in text
    assert png.stat().st_size > 10_000


@pytest.mark.parametrize("argv", [["oblique", "10", "--friction", "-1"], ["oblique", "10", "--angles", "95"]])
def test_bad_input_exits_2(argv, capsys):
    assert main(argv) == 2
    assert "error" in capsys.readouterr().err
