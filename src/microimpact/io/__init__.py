"""Writing results: the one package through which microimpact writes every file.

Every file goes to a temporary name beside its target (same directory, so the
final :func:`os.replace` is a rename within one file system), is flushed and
``fsync``-ed, and is renamed into place only when complete. An exception of any
kind while writing -- including :class:`KeyboardInterrupt` (Ctrl-C, and SIGTERM
in the command line, which raises it too) and :class:`SystemExit` -- removes the
temporary file and leaves whatever was at the target before untouched. Nothing here
touches the process's signal handling: the command line turns a signal into a
:class:`KeyboardInterrupt`, and the ``finally`` blocks do the rest.

* :func:`atomic_write` -- one file (a context manager yielding the open file).
* :func:`owned_directory` -- an output folder (``microimpact paper``,
  ``microimpact export``) that owns only what it wrote: a manifest
  (``.microimpact-manifest.json``) lists every file written with its SHA-256, and
  a later run replaces or deletes only the files listed there whose content is
  unchanged; anything else in the folder (or an input of the run) makes it
  refuse, naming the file. A later run's files replace the earlier ones all
  together or not at all.
* :func:`write_csv`, :func:`write_json`, :func:`write_netcdf`,
  :func:`save_figure` -- the writers every command uses.
* :func:`csv_header` -- the project's one CSV layout.
* :func:`check_output_path` -- the checks a command makes on an output path
  before it computes anything.
* :func:`memory_budget`, :func:`check_memory` -- refusing sizes that would not
  fit in memory, before allocating them.
* :func:`progress_bar` -- the one progress-bar style (:mod:`tqdm`).
* :func:`load_restitution_csv` -- reading measured restitution data (what
  :func:`microimpact.fitting.fit_restitution` takes in), as :class:`RestitutionData`.

By subject: ``_files`` (the checks on a path, atomic files, owned folders and
their manifests), ``_formats`` (CSV, JSON, NetCDF, figures), ``_memory`` (the
memory budget, the progress bar), ``_read`` (tables and measured data read
back). Import the names from here, :mod:`microimpact.io`.

CSV layout (all CSV files microimpact writes)
---------------------------------------------
Line 1 is the header: column names, comma separated, each followed by its unit
in brackets, ``name [unit]`` (SI; ``[1]`` for dimensionless quantities and
flags, as CF/UDUNITS write it). Then zero or more comment lines starting with
``#`` (title, provenance, scalars, column descriptions), then one row per
record: floats in their shortest exact form (they read back bit for bit),
booleans as ``0``/``1``, non-finite values as ``nan``/``inf``/``-inf``. The
header comes first so that every common reader takes it:
``numpy.genfromtxt(f, delimiter=",", names=True)``,
``pandas.read_csv(f, comment="#")``, :func:`csv.DictReader` over the lines not
starting with ``#``, :func:`read_table` and
:func:`load_restitution_csv`.
"""

from ._files import (
    MANIFEST,
    MANIFEST_MAX_BYTES,
    atomic_directory,
    atomic_write,
    check_input_file,
    check_output_path,
    commit_check,
    owned_directory,
)
from ._formats import (
    check_figure_path,
    compute_here,
    csv_header,
    csv_rows,
    json_safe,
    save_figure,
    write_csv,
    write_json,
    write_netcdf,
    write_table,
)
from ._memory import MEMORY_ENV, MEMORY_FRACTION, MemoryBudgetError, check_memory, memory_budget, progress_bar
from ._read import RestitutionData, load_restitution_csv, read_table

__all__ = [
    "atomic_write",
    "owned_directory",
    "MANIFEST",
    "atomic_directory",
    "check_output_path",
    "check_input_file",
    "commit_check",
    "csv_header",
    "csv_rows",
    "write_csv",
    "write_table",
    "read_table",
    "write_json",
    "json_safe",
    "write_netcdf",
    "compute_here",
    "save_figure",
    "memory_budget",
    "check_memory",
    "MemoryBudgetError",
    "progress_bar",
    "MEMORY_ENV",
    "MEMORY_FRACTION",
    "MANIFEST_MAX_BYTES",
    "check_figure_path",
    "load_restitution_csv",
    "RestitutionData",
]

# Documented, pickled and shown as microimpact.io.NAME, where users import them from.
for _name in __all__:
    _obj = globals()[_name]
    if callable(_obj) and getattr(_obj, "__module__", "").startswith(__name__ + "."):
        _obj.__module__ = __name__
del _name, _obj
