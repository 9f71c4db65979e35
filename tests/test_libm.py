"""The transcendental functions the game computes with are the C library's, element by element,
so a shot gives the same bits on every processor (numpy's own exp, sin, cos and tan, which it
picks on machines with AVX-512, differ from them in the last bit)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from termpool.physics import libm

ROOT = Path(__file__).resolve().parents[1] / "termpool"
# numpy's functions whose results may depend on the processor's vector code.
NUMPY_TRANSCENDENTAL = re.compile(
    r"\bnp\.(exp|exp2|expm1|log|log2|log10|log1p|sin|cos|tan|arcsin|arccos|arctan|arctan2|"
    r"sinh|cosh|tanh|arcsinh|arccosh|arctanh|power|float_power|cbrt)\b")


def _values() -> np.ndarray:
    rng = np.random.default_rng(7)
    special = [0.0, -0.0, 1e-300, -1e-300, 0.5, -0.5, math.pi, -math.pi, 709.0, -745.0, 700.5]
    return np.concatenate([special, rng.uniform(-20, 20, 2000), rng.uniform(-1e-3, 1e-3, 500)])


@pytest.mark.parametrize("name", ["exp", "sin", "cos", "tan"])
def test_each_function_is_the_c_librarys_bit_for_bit(name):
    x = _values()
    got = getattr(libm, name)(x.reshape(-1, 1, 7) if x.size % 7 == 0 else x)
    want = [getattr(math, name)(v) for v in x.tolist()]
    assert got.shape == (x.reshape(-1, 1, 7) if x.size % 7 == 0 else x).shape
    assert got.ravel().tobytes() == np.array(want).tobytes()
    assert getattr(libm, name)(0.25).shape == ()  # a scalar stays one


def test_out_of_range_values_give_what_numpy_gives():
    with np.errstate(all="ignore"):
        x = np.array([1e6, -1e6, np.inf, -np.inf, np.nan])
        for name in ("exp", "sin", "cos", "tan"):
            got, want = getattr(libm, name)(x), getattr(np, name)(x)
            assert np.array_equal(got, want, equal_nan=True), name


def test_arctan2_pairs_broadcast_arrays_and_is_the_c_librarys():
    y = _values()
    x = y[::-1].copy()
    assert libm.arctan2(y, x).tobytes() == np.array(
        [math.atan2(a, b) for a, b in zip(y.tolist(), x.tolist(), strict=True)]).tobytes()
    col = libm.arctan2(y[:5, None], x[None, :3])
    assert col.shape == (5, 3)
    assert col[4, 2] == math.atan2(float(y[4]), float(x[2]))


def test_no_module_calls_numpys_own_transcendental_functions():
    found = []
    for path in sorted(ROOT.rglob("*.py")):
        if path.name == "libm.py":
            continue
        for k, line in enumerate(path.read_text().splitlines(), 1):
            code = line.split("#", 1)[0]
            if NUMPY_TRANSCENDENTAL.search(code):
                found.append(f"{path.relative_to(ROOT.parent)}:{k}: {line.strip()}")
    assert not found, "use termpool.physics.libm:\n" + "\n".join(found)


def test_the_scan_finds_a_call():
    assert NUMPY_TRANSCENDENTAL.search("mu = 0.1 * np.exp(-v)")
    assert not NUMPY_TRANSCENDENTAL.search("d = np.hypot(x, y) + np.expand_dims(a, 0)")
