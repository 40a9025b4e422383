"""A figure of :func:`~microimpact.paper.reproduce` drawn from its table, the same bytes in any process:
the drawing of each figure (:func:`draw_figure`), its rendering to every format, and what makes the
bytes the same and the drawing quicker (one cache of parsed mathtext, fonts subset only when used, open
fonts forgotten in a forked process). The figure driver (``._driver``) and its second process
(``._worker``) both draw through here.
"""

from __future__ import annotations

import contextlib
import functools
import io
import sys

import numpy as np

from ..figures import paper as figs
from ._setup import FIG3_PRESSURES, FIG4_MODULI, FIG5_DENSITIES, FIGURES

__all__ = ["draw_figure", "one_mathtext_cache", "defer_font_subsetting", "forget_open_fonts"]

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


def defer_font_subsetting() -> bool:
    """Import ``fontTools.subset`` on its first use rather than with matplotlib's PDF backend.

    matplotlib's PDF and PS backends import it as they load (0.1-0.2 s, a twentieth of ``paper``)
    but call it only to embed a subset of a TrueType font as Type 42 (``pdf.fonttype: 42``,
    ``ps.fonttype: 42``) or in a PS file; the figures' PDFs embed Type 3 fonts. Here it becomes a
    module that Python's :class:`importlib.util.LazyLoader` loads at its first attribute read: the
    same module, loaded when used. Only for a process of this package's own (the ``paper``
    command, its workers); a no-op where the module is already imported or cannot be found.
    Returns whether it was deferred.
    """
    import importlib.util

    name = "fontTools.subset"
    if name in sys.modules:
        return False
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):
        return False
    if spec is None or spec.loader is None:
        return False
    spec.loader = importlib.util.LazyLoader(spec.loader)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    sys.modules["fontTools"].subset = module  # as an import would (find_spec imported it)
    return True


_MATHTEXT = {"depth": 0, "parses": {}}


@contextlib.contextmanager
def one_mathtext_cache():
    """While inside: every mathtext parser of this process shares one cache of parsed strings.

    matplotlib caches a parse per parser object, and each renderer makes its own parser: a label was
    parsed by the layout's renderer, again by the PDF's and again by the PNG's (at 300 dpi), and
    again for every figure that repeats it (an axis label, the strain band's note). A parse is a
    function of the parser's state (its output type), of the call's arguments (string, dpi, font,
    antialiasing, hinting; matplotlib's own cache keys on these) and of the rcParams it reads (the
    ``mathtext.*`` and ``font.*`` family settings), so one cache keyed on all of them returns what
    each parser would have computed: the same bytes in every file, half the parses. Nested uses share the outer cache, which goes when the outermost ends. Where
    matplotlib's parser is not the one this was written for (no ``_parse_cached`` wrapping a
    function), nothing changes.
    """
    from matplotlib.mathtext import MathTextParser

    cached = MathTextParser.__dict__.get("_parse_cached")
    parse = getattr(cached, "__wrapped__", None)
    if _MATHTEXT["depth"] == 0 and not callable(parse):
        yield
        return
    if _MATHTEXT["depth"] == 0:
        import matplotlib as mpl

        parses = _MATHTEXT["parses"]
        rc_names = [k for k in mpl.rcParams if k.startswith("mathtext.") or k.startswith("font.")]

        @functools.wraps(parse)
        def shared(self, *args):
            rc = tuple(tuple(v) if isinstance(v, list) else v for v in map(mpl.rcParams.__getitem__, rc_names))
            key = (type(self), tuple(sorted(vars(self).items())), args, rc)
            try:
                return parses[key]
            except KeyError:
                result = parses[key] = parse(self, *args)
                return result
            except TypeError:  # a part of the key that does not hash: as matplotlib would
                return cached(self, *args)

        MathTextParser._parse_cached = shared
        _MATHTEXT["restore"] = cached
    _MATHTEXT["depth"] += 1
    try:
        yield
    finally:
        _MATHTEXT["depth"] -= 1
        if _MATHTEXT["depth"] == 0:
            MathTextParser._parse_cached = _MATHTEXT.pop("restore")
            _MATHTEXT["parses"].clear()


def forget_open_fonts() -> None:
    """In a forked process: drop every font opened before the fork, and what holds one. A font file
    opened before it is one open file shared with the other process (one read position for both):
    glyphs read through it while the other reads too could be wrong. matplotlib drops its own open
    fonts at a fork (``font_manager``); parsed mathtext holds fonts, so its caches go too (matplotlib's
    and :func:`one_mathtext_cache`'s)."""
    from matplotlib import font_manager
    from matplotlib.mathtext import MathTextParser

    font_manager._get_font.cache_clear()
    cached = MathTextParser.__dict__.get("_parse_cached")
    for cache in (cached, getattr(cached, "__wrapped__", None), _MATHTEXT.get("restore")):
        if hasattr(cache, "cache_clear"):
            cache.cache_clear()
    _MATHTEXT["parses"].clear()


def draw_figure(stem, table, formats, rc=None) -> dict:
    """``{format: bytes}`` of figure ``stem`` drawn from its ``table`` (:func:`_render`), in the package's
    style over ``rc`` (the caller's rcParams, for a figure drawn in another process) or the current
    rcParams. The same bytes in any process, whatever it drew before (parsed mathtext is shared
    with the other figures drawn inside one :func:`one_mathtext_cache`)."""
    from ..figures import style as _style

    plt = _style.pyplot()
    with contextlib.ExitStack() as stack:
        stack.enter_context(one_mathtext_cache())
        if rc is not None:
            stack.enter_context(plt.rc_context(rc))
        stack.enter_context(_style.style())
        fig = np.ravel(_PLOTS[stem](table))[0].figure
        try:
            return _render(fig, formats)
        finally:
            plt.close(fig)
