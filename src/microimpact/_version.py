"""The package's version: the one place it is written (``pyproject.toml`` reads it from here).

A module of its own so that ``microimpact.__version__`` costs nothing to read: asking the installed
metadata (``importlib.metadata.version``) imports ``email``, ``zipfile`` and more, a large part of a
small command that stamps its output with the version.
"""

__version__ = "0.1.0"
