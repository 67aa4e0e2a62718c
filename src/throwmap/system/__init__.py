"""throwmap.system."""
