"""The ``microimpact history`` command and the history plot (seed Fig. 10)."""

import io

import numpy as np
import pytest

import microimpact as mi
from microimpact.cli import main

SILICON = mi.ContactPair.paper_case("silicon")


def run(argv, capsys):
    rc = main(argv)
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def read_csv(text):
    return np.genfromtxt(io.StringIO(text), delimiter=",", names=True)


def test_csv_on_stdout_is_the_api(capsys):
    rc, out, err = run(["history", "50", "--n", "201"], capsys)
    assert rc == 0
    assert out.splitlines()[0] == "time [s],approach [m],approach_velocity [m/s],force [N],stage [1]"
    data = read_csv(out)
    ref = SILICON.history(50.0, n=201)
    assert data.size == len(ref) == 203
    for col, name in (
        ("time_s", "time"),
        ("approach_m", "approach"),
        ("force_N", "force"),
        ("approach_velocity_ms", "approach_velocity"),
    ):
        assert np.array_equal(data[col], getattr(ref, name))
    out_ = SILICON.impact(50.0, warn=False)
    assert data["force_N"].max() == pytest.approx(float(out_.max_force), rel=1e-13)
    assert data["approach_velocity_ms"][-1] == pytest.approx(-float(out_.rebound_velocity), rel=1e-14)
    assert data["time_s"][-1] == pytest.approx(float(out_.contact_time), rel=1e-15)
    assert "warning" in err  # 50 m/s is beyond a/R* = 0.3 for this case


def test_csv_file_plot_and_ode(tmp_path, capsys):
    csv, png = tmp_path / "h.csv", tmp_path / "h.png"
    rc, out, err = run(
        [
            "history",
            "30",
            "--case",
            "mica",
            "--n",
            "101",
            "--out",
            str(csv),
            "--plot",
            str(png),
            "--method",
            "ode",
            "--hertz",
        ],
        capsys,
    )
    assert rc == 0 and str(csv) in out
    data = np.genfromtxt(csv, delimiter=",", names=True)
    mica = mi.ContactPair.paper_case("mica")
    closed = mica.history(30.0, times=data["time_s"])
    assert np.max(np.abs(data["force_N"] - closed.force)) < 1e-9 * closed.max_force
    # the ODE's own t1, t_L, t_c (equal to 1e-12) are on its grid: only those points may differ in stage
    assert np.sum(data["stage_1"].astype(int) != closed.stage) <= 3
    assert "# velocity = 30 m/s" in csv.read_text()
    image = pytest.importorskip("matplotlib.image").imread(png)
    assert image.ndim == 3 and image.shape[0] > image.shape[1] > 500  # three stacked panels, 300 dpi
    assert image[..., :3].std() > 0.05  # not blank


def test_plot_history_draws_the_history():
    plt = pytest.importorskip("matplotlib.pyplot")
    from microimpact.figures.history import plot_history

    h = SILICON.history(50.0, n=101)
    axes = plot_history(h, show_hertz=True)
    assert len(axes) == 3 and axes[0].get_shared_x_axes().joined(axes[0], axes[2])
    v_line = axes[0].get_lines()[0]
    np.testing.assert_allclose(v_line.get_xdata(), h.time * 1e9)  # ns
    np.testing.assert_allclose(v_line.get_ydata(), h.approach_velocity)
    np.testing.assert_allclose(axes[1].get_lines()[0].get_ydata(), h.force * 1e6)  # uN
    np.testing.assert_allclose(axes[2].get_lines()[0].get_ydata(), h.approach * 1e9)  # nm
    assert "(ns)" in axes[2].get_xlabel() and "(µN)" in axes[1].get_ylabel() and "(nm)" in axes[2].get_ylabel()
    labels = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert labels == ["1: Hertz loading", "2: plastic loading", "3: elastic unloading"]
    plt.close(axes[0].figure)
    # onto given axes; an elastic impact has no plastic stage
    fig, given = plt.subplots(3, 1)
    axes = plot_history(SILICON.elastic_equivalent().history(70.0, n=51), ax=given)
    assert axes[0] is given[0]
    labels = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert labels == ["1: Hertz loading", "3: elastic unloading"]
    with pytest.raises(ValueError, match="three Axes"):
        plot_history(SILICON.history(50.0, n=11), ax=given[:2])
    plt.close(fig)


@pytest.mark.parametrize(
    "argv, words",
    [
        (["history", "0"], "velocity"),
        (["history", "abc"], "velocity"),
        (["history", "-5"], "velocity"),
        (["history", "50", "--n", "1"], "--n"),
        (["history", "50", "--n", "ten"], "--n"),
        (["history", "50", "--limiting-pressure", "-1"], "--limiting-pressure"),
        (["history", "50", "--model", "nope"], "model must be one of"),
        (["history", "50", "--model", "hertz_tsuji"], "damping_ratio"),
        (["history", "50", "--model", "hertz_tsuji", "--param", "damping_ratio=0.2", "--method", "closed"], "ode"),
        (["history", "50", "--param", "x=1"], "'x'"),
    ],
)
def test_bad_input_exits_2_with_one_line(argv, words, capsys):
    rc, out, err = run(argv, capsys)
    assert rc == 2 and out == ""
    assert err.count("\n") == 1 and words in err and err.startswith("microimpact history: error:")


def test_other_models_are_integrated_with_their_own_force(tmp_path, capsys):
    """--model/--param: the history of a DEM law, integrated; its rebound and contact time are the
    model's closed form (pair.impact with the same model) and the plot names its stages plainly."""
    csv, png = tmp_path / "h.csv", tmp_path / "h.png"
    argv = ["history", "20", "--model", "hertz_tsuji", "--param", "damping_ratio=0.2", "--n", "301"]
    rc, out, err = run(argv + ["--out", str(csv), "--plot", str(png)], capsys)
    assert rc == 0 and "(ode, hertz_tsuji)" in out
    data = np.genfromtxt(csv, delimiter=",", names=True)
    closed = SILICON.impact(20.0, model="hertz_tsuji", damping_ratio=0.2, warn=False)
    assert data["approach_velocity_ms"][-1] == pytest.approx(-float(closed.rebound_velocity), rel=1e-7)
    assert data["time_s"][-1] == pytest.approx(float(closed.contact_time), rel=1e-7)
    text = csv.read_text()
    assert "model hertz_tsuji" in text and "equation numbers are the seed's" in text
    assert "# stage: 0 = no contact" in text and "1 = loading; 3 = unloading" in text
    assert set(np.unique(data["stage_1"]).astype(int)) <= {0, 1, 3}


def test_plot_history_names_plain_stages_for_other_models():
    plt = pytest.importorskip("matplotlib.pyplot")
    from microimpact.figures.history import plot_history

    axes = plot_history(SILICON.history(20.0, n=51, model="hertz_tsuji", damping_ratio=0.2))
    labels = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert labels == ["loading", "unloading"]
    assert axes[0].get_title().startswith("hertz_tsuji")
    plt.close(axes[0].figure)
    # LIGGGHTS' version of the seed's law keeps the seed's three stages
    axes = plot_history(SILICON.history(50.0, n=51, model="liggghts_thornton_ning"))
    labels = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert labels == ["1: Hertz loading", "2: plastic loading", "3: elastic unloading"]
    plt.close(axes[0].figure)
