"""The package's version (one place; ``throwmap.__version__`` re-exports it)."""

__version__ = "0.1.0"
