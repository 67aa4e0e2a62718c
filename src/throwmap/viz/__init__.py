"""throwmap.viz."""
