"""``python -m hoistsim.cli``."""

from . import main

main()
