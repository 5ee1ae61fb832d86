"""txtool: lint, convert and verify robot transmission configurations."""

__version__ = "0.1.0"
