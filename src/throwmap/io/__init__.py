"""throwmap.io."""
