"""The cache of compiled loops (an optimisation: never needed), for users and the command line.

The array computations compile their loops with numba once and keep the machine code in a cache
folder, so that a new process loads instead of compiling. These are the names of
:mod:`microimpact.core.arrays` that look at that folder or empty it (the same objects), so that code
outside the physics core, ``microimpact cache`` above all, reaches them without importing the core.
"""

from __future__ import annotations

from .core.arrays import CacheWarning, cache_dir, cache_info, clear_cache

__all__ = ["cache_dir", "cache_info", "clear_cache", "CacheWarning"]
