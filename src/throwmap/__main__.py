"""``python -m throwmap``: the command line (see :mod:`throwmap.cli.app`)."""

from .cli.app import main

if __name__ == "__main__":
    main()
