"""Benchmark suite of microimpact: ``python benchmarks/run.py [--quick] [--json FILE]``.

The same suite as ``microimpact bench`` (the code lives in
``microimpact.cli.bench`` so that the installed command has it). Writes
``benchmarks/results.json`` by default and prints the table shown in the README.
"""

import pathlib
import sys

from microimpact.cli.bench import main

if __name__ == "__main__":
    sys.exit(main(default_json=str(pathlib.Path(__file__).with_name("results.json"))))
