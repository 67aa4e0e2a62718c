"""``python -m throwmap``: the command line (see :mod:`throwmap.cli`)."""

from .cli import main

if __name__ == "__main__":
    main()
