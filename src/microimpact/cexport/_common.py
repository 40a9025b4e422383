"""What the three exports share: one-line comment text and a pair rescaled to a diameter."""

from __future__ import annotations

from .._validation import check_positive

__all__ = ["comment_text", "sized_pair"]


def comment_text(text) -> str:
    """``text`` made safe inside a C block comment and on one line of a CSV comment.

    Control characters and line breaks become spaces, anything outside printable
    ASCII becomes ``?``, and the comment delimiters ``*/`` and ``/*`` are broken
    apart (``* /``, ``/ *``), so a label cannot end the comment and inject code.
    Two question marks in a row are set apart too (``? ?``): ``??`` and one of ``= / ' ( ) ! < > -``
    is a trigraph, replaced before comments are recognised by a compiler that honours them
    (``gcc -std=c99``, ``-trigraphs``); ``??/`` is a backslash, which before a line break joins
    the next line to the comment. Both rules are applied until none is left (a non-ASCII
    character becoming ``?`` can make a new pair).
    """
    out = "".join(
        c if 32 <= ord(c) < 127 else (" " if ord(c) < 32 or c in "\u2028\u2029\x85" else "?") for c in str(text)
    )
    while "*/" in out or "/*" in out or "??" in out:
        out = out.replace("*/", "* /").replace("/*", "/ *").replace("??", "? ?")
    return out


def check_size_names(sizes):
    """Refuse two diameters whose per-size file names (``d<micrometres:g>um``) would be the same."""
    seen = {}
    for d in sizes:
        tag = f"{float(d) * 1e6:g}"
        if tag in seen:
            raise ValueError(
                f"diameters {seen[tag]!r} and {float(d)!r} m would both be written to the table d{tag}um "
                "(its name keeps 6 significant digits): give diameters that differ there"
            )
        seen[tag] = float(d)


def sized_pair(pair, diameter):
    """``pair`` at particle diameter ``diameter`` [m] (ValueError without a density)."""
    if pair.density is None:
        raise ValueError("the pair needs a particle density to be rescaled to other diameters")
    return pair.vary(diameter=float(check_positive("diameter", diameter)))
