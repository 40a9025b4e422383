"""Temporary names for :mod:`microimpact.io` until it calls :mod:`tempfile` and :mod:`hashlib` itself.

Not part of the physics and not public: the on-disk cache moved to :mod:`microimpact.engine.cache`.
These three keep the contracts they had (an exclusive, owner-only temporary file or folder in the
folder asked; SHA-256), through the standard library.
"""

from __future__ import annotations

import hashlib
import tempfile

__all__: list = []  # not public: the three names below are for microimpact.io alone


def mkstemp(folder, prefix: str = "", suffix: str = "") -> tuple[int, str]:
    """``(fd, path)`` of a new file ``folder/prefix<random>suffix``: :func:`tempfile.mkstemp`."""
    return tempfile.mkstemp(suffix=suffix, prefix=prefix, dir=folder)


def mkdtemp(folder, prefix: str = "", suffix: str = "") -> str:
    """Path of a new folder ``folder/prefix<random>suffix``: :func:`tempfile.mkdtemp`."""
    return tempfile.mkdtemp(suffix=suffix, prefix=prefix, dir=folder)


def sha256(data: bytes = b""):
    """A ``hashlib.sha256`` object of ``data``."""
    return hashlib.sha256(data)
