"""Test-suite settings: hypothesis runs a fixed, derandomised profile so that every run (CI or not)
draws the same examples; ``HYPOTHESIS_PROFILE=explore`` draws fresh ones."""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", deadline=None, max_examples=1000)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
