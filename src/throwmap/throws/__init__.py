"""throwmap.throws."""
