"""Shared law checks for the engine tests (test_properties.py, test_stability.py).

The laws live in `bench/stability_cases.py`, where `termpool bench stability` uses them too;
this module re-exports them for the tests. Each check states a law of the model and is computed
from the engine's public state only: finite numbers, kinetic energy that never rises, no
interpenetration, balls kept within the cushion noses, and a generous physical bound on the
time a table takes to come to rest. The checks raise AssertionError at the first violation.
"""

from __future__ import annotations

from bench.stability_cases import (
    ENERGY_TOL,
    OVERLAP_TOL,
    check_positions,
    check_state,
    kinetic,
    momentum,
    nose_reach,
    rest_bound,
    run_checked,
    seg_distance,
)

__all__ = [
    "ENERGY_TOL",
    "OVERLAP_TOL",
    "check_positions",
    "check_state",
    "kinetic",
    "momentum",
    "nose_reach",
    "rest_bound",
    "run_checked",
    "seg_distance",
]
