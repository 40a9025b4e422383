"""The package's version: the one place it is written (``pyproject.toml`` reads it from here).

A module of its own so that ``microimpact.__version__`` costs nothing to read: asking the installed
metadata (``importlib.metadata.version``) imports ``email``, ``zipfile`` and more, 0.06-0.07 s of a
0.3 s command that writes a C file stamped with the version (issue 25).
"""

__version__ = "0.1.0"
