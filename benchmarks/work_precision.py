"""What accuracy costs in time: the work-precision study (see hoistsim/study.py).

    python benchmarks/work_precision.py           # full study -> benchmarks/results/work_precision.{csv,png}
    python benchmarks/work_precision.py --smoke   # a few tolerances on one scene, seconds
"""

from __future__ import annotations

import argparse
from pathlib import Path

from hoistsim.study import main

if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--smoke", action="store_true", help="a few tolerances on one scene")
    parser.add_argument("-o", "--output", default=str(Path(__file__).parent / "results"),
                        help="folder for the CSV and the figure")
    args = parser.parse_args()
    main(smoke=args.smoke, output=args.output)
