"""What accuracy costs in time: the work-precision study (see hoistsim/studies/work_precision.py).

    python benchmarks/work_precision.py           # full study -> benchmarks/results/work_precision.{csv,png}
    python benchmarks/work_precision.py --smoke   # a few tolerances on one scene, seconds
    python benchmarks/work_precision.py --figure-only   # redraw the figure from the CSV
"""

from __future__ import annotations

import argparse
from pathlib import Path

from hoistsim.studies.work_precision import main, read_csv, write_figure

if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--smoke", action="store_true", help="a few tolerances on one scene")
    parser.add_argument("-o", "--output", default=str(Path(__file__).parent / "results"),
                        help="folder for the CSV and the figure")
    parser.add_argument("--figure-only", action="store_true", help="redraw the figure from the CSV, run nothing")
    args = parser.parse_args()
    if args.figure_only:
        folder = Path(args.output)
        write_figure(read_csv(folder / "work_precision.csv"), folder / "work_precision.png")
    else:
        main(smoke=args.smoke, output=args.output)
