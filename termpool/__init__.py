"""termpool: pool in the terminal on an exact, batched physics core."""

__version__ = "0.1.0"
