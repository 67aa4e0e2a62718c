"""``python -m throwmap``: the command line (see :mod:`throwmap.cli`), started as the ``throwmap`` console script
is (:mod:`_throwmap_entry`: a Ctrl-C while the command line is still being imported exits 130 with one line)."""

from _throwmap_entry import main

if __name__ == "__main__":
    main()
