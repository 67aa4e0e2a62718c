"""throwmap.testing."""
