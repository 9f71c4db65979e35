"""Test-wide settings.

Hypothesis runs derandomized by default, so that the suite (and CI) is reproducible: the same
examples every run. Set HYPOTHESIS_PROFILE=explore to search new random examples instead.
"""

import os

from hypothesis import settings

settings.register_profile("repeatable", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))
