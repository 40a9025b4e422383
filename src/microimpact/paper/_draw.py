"""A figure of :func:`~microimpact.paper.reproduce` drawn from its table, the same bytes in any process.

The figure driver (``._driver``) and its second process (``._worker``) both draw through
:func:`draw_figure`, so a figure's bytes depend neither on which process drew it nor on what it drew
before.
"""

from __future__ import annotations

import contextlib
import io

import numpy as np

from ..figures import paper as figs
from ._setup import FIG3_PRESSURES, FIG4_MODULI, FIG5_DENSITIES, FIGURES

__all__ = ["draw_figure"]

# Each figure drawn from its table alone (the table is ._driver's, from the public API).
_PLOTS = {
    "fig02": lambda t: figs.plot_restitution(table=t),
    "fig03": lambda t: figs.plot_energy_loss("limiting_pressure", FIG3_PRESSURES, table=t),
    "fig04": lambda t: figs.plot_energy_loss("particle_modulus", FIG4_MODULI, table=t),
    "fig05": lambda t: figs.plot_energy_loss("density", FIG5_DENSITIES, table=t),
    "fig06": lambda t: figs.plot_force_displacement(table=t),
    "fig07": lambda t: figs.plot_force_time(table=t),
    "fig08": lambda t: figs.plot_approach(table=t),
    "fig09": lambda t: figs.plot_contact_times(table=t),
    "fig10": lambda t: figs.plot_dynamics(table=t),
}
assert list(_PLOTS) == [f[0] for f in FIGURES]


def _render(fig, formats) -> dict:
    """``{format: bytes}`` of one figure: ``png`` (always, for the report) and each of ``formats``.

    Each figure is drawn once per format, after one constrained layout. The layout is computed here,
    before any ``savefig``, by the first vector format's renderer (as ``savefig`` would: text extents
    at 72 dpi); a vector format first, because its text extents are the larger: with them the
    raster's text keeps inside the figure (the other order pushed a label of Fig. 5 0.6 pt past the
    PDF's top edge). The layout engine is then removed (``set_layout_engine(None)``): while a figure
    has one, even a placeholder, each ``savefig`` draws the whole figure once more with layout only,
    to find a renderer, before its real draw (two of a figure's four draws were that: about a
    quarter of ``paper``'s time). The files are the same bytes as with those extra draws. PNGs at
    zlib level 1: the same pixels, about 13 % larger, encoded several times faster.
    """
    import matplotlib as mpl
    from matplotlib.backend_bases import get_registered_canvas_class

    from ..figures import style

    meta = {"pdf": {"CreationDate": None}, "svg": {"Date": None}}
    order = [f for f in formats if f != "png"] + ["png"]
    engine = fig.get_layout_engine()
    if engine is not None:
        canvas, dpi = fig.canvas, fig.dpi
        try:
            # savefig's own set-up for a layout: the format's canvas, the figure at savefig's dpi
            # (a vector format's printer sets 72 itself).
            get_registered_canvas_class(order[0])(fig)
            fig.dpi = style.DPI
            engine.execute(fig)
        finally:
            fig.set_canvas(canvas)
            fig.dpi = dpi
        with mpl.rc_context({"figure.autolayout": False, "figure.constrained_layout.use": False}):
            fig.set_layout_engine(None)  # with either set, None would mean an engine again
    images = {}
    for fmt in order:
        buf = io.BytesIO()
        if fmt == "png":
            fig.savefig(buf, format="png", dpi=style.DPI, pil_kwargs={"compress_level": 1})
        else:
            fig.savefig(buf, format=fmt, metadata=meta.get(fmt))
        images[fmt] = buf.getvalue()
    return images


def draw_figure(stem, table, formats, rc=None) -> dict:
    """``{format: bytes}`` of figure ``stem`` drawn from its ``table`` (:func:`_render`), in the package's
    style over ``rc`` (the caller's rcParams, for a figure drawn in another process) or the current
    rcParams. The same bytes in any process, whatever it drew before."""
    from ..figures import style as _style

    plt = _style.pyplot()
    with contextlib.ExitStack() as stack:
        if rc is not None:
            stack.enter_context(plt.rc_context(rc))
        stack.enter_context(_style.style())
        fig = np.ravel(_PLOTS[stem](table))[0].figure
        try:
            return _render(fig, formats)
        finally:
            plt.close(fig)
