"""throwmap.studies."""
