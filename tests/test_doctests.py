"""Run every docstring example of the installed package as a doctest."""

import doctest
import importlib
import pkgutil
import warnings

import pytest

import microimpact

MODULES = sorted(
    m.name
    for m in pkgutil.walk_packages(microimpact.__path__, prefix="microimpact.")
    if ".cli" not in m.name and not m.name.endswith("__main__")
) + ["microimpact"]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    try:
        module = importlib.import_module(name)
    except ImportError as exc:  # an optional extra missing: nothing to run here
        pytest.skip(str(exc))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", microimpact.LargeStrainWarning)
        result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0, f"{result.failed} doctest(s) failed in {name}"
