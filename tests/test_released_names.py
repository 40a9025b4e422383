"""Released public names keep working (issue 20): every public name of every public module as it was
released before the model-as-a-unit rework (``tests/reference/released_names.json``: each module's
``__all__``, else its public top-level names, at commit ``09d7058^``) still resolves; a name that moved
warns (:class:`DeprecationWarning`) naming its new home. One test lists every broken name at once.

When a deprecated name is finally removed (after its one release), remove it from the JSON file in
the same commit and say so.
"""

from __future__ import annotations

import importlib
import json
import warnings
from pathlib import Path

RELEASED = json.loads((Path(__file__).resolve().parent / "reference" / "released_names.json").read_text())


def test_the_list_is_the_release():
    assert len(RELEASED) > 40 and sum(map(len, RELEASED.values())) > 400
    assert "ContactPair" in RELEASED["microimpact"] and "DEFAULTS" in RELEASED["microimpact.core.models.hertz_tsuji"]


def test_every_released_name_still_resolves():
    broken = []
    for module_name, names in sorted(RELEASED.items()):
        with warnings.catch_warnings(record=True):
            warnings.simplefilter("always")
            try:
                module = importlib.import_module(module_name)
            except Exception as exc:  # noqa: BLE001  (reported, all at once)
                broken.append(f"{module_name}: the module does not import ({exc!r})")
                continue
        for name in names:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                try:
                    getattr(module, name)
                except AttributeError:
                    broken.append(f"{module_name}.{name}: gone")
                    continue
            for w in caught:
                if issubclass(w.category, DeprecationWarning) and "microimpact." not in str(w.message):
                    broken.append(f"{module_name}.{name}: its DeprecationWarning names no new home: {w.message}")
    assert not broken, f"released names broken ({len(broken)}):\n" + "\n".join(broken)
