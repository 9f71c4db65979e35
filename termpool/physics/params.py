"""Physical constants of balls and cloth (SI units), with standard defaults."""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from termpool.physics.ball_ball import MODELS as BALL_BALL
from termpool.physics.cushion import MODELS as CUSHIONS

BALL_RADIUS = 0.028575  # 2.25 in diameter
BALL_MASS = 0.170


def nose_reach(radius, cushion_height: float):
    """How close (horizontally) a ball's centre comes to a cushion's nose line when it touches
    the nose: less than the radius, since the nose is above the ball's equator. The engine's
    contact distance (`Engine.rc`), so a ball resting on a rail sits this far from it.
    `radius` may be a number or an array."""
    sin_t = np.clip((cushion_height - radius) / radius, -0.95, 0.95)
    return radius * np.sqrt(1.0 - sin_t * sin_t)


# What a scene or a saved match may set (docs/limits.md): (low, high) for each number of
# Physics. Values beyond them mean nothing on a pool table, and the extreme ones only overflow
# or ask the engine for unbounded work. The friction coefficients in FRICTIONLESS_OK may also
# be 0. The lower ends keep a run finite and the engine's tolerances true: a slip under
# state.EPS_U is completed at once, and the path it stands for strays from the slide by
# EPS_U^2 / (24.5 mu_slide g), under roots.SINK (0.45 um) only while mu_slide g >= 0.1 m/s^2
# (at 1e-4 x 0.1 a ball was set 2 mm into a rail, and the run never ended); with mu_roll and
# mu_spin at 1e-3 a ball stops or stops spinning within hours of simulated time, not weeks.
PHYSICS_RANGES = {
    "mu_slide": (0.1, 1.0), "mu_roll": (1e-3, 1.0), "mu_spin": (1e-3, 1.0),
    "mu_cushion": (0.0, 1.0), "e_ball": (0.0, 1.0), "e_cushion": (0.0, 1.0),
    "cushion_height": (0.0, 1.0), "g": (1.0, 100.0), "v_inelastic": (0.0, 1.0),
}
FRICTIONLESS_OK = ("mu_slide", "mu_roll", "mu_spin")
PHYSICS_UNITS = {"g": "m/s^2", "cushion_height": "m", "v_inelastic": "m/s"}


def within(val: float, limits: tuple[float, float], path: str, unit: str = "") -> None:
    """Raise ValueError naming `path` and the limit when val lies outside limits (low, high)."""
    lo, hi = limits
    unit = f" {unit}" if unit else ""
    if val < lo:
        raise ValueError(f"{path}: must be at least {lo:g}{unit}, not {val:g}")
    if val > hi:
        raise ValueError(f"{path}: must be at most {hi:g}{unit}, not {val:g}")


# The cushion of records and saved matches written before scenes could choose one.
LEGACY_CUSHION = "simple"


def as_recorded(d: dict) -> dict:
    """A recorded `physics` object as it was played: one without `cushion` predates the
    choice and was played with LEGACY_CUSHION, whatever the default is now."""
    return d if "cushion" in d else {**d, "cushion": LEGACY_CUSHION}


@dataclass(frozen=True)
class Physics:
    mu_slide: float = 0.2  # ball-cloth sliding friction
    mu_roll: float = 0.01  # rolling resistance
    mu_spin: float = 0.0127  # spin (z) decay; wz falls at 5 mu_spin g / (2 R)
    e_ball: float = 0.95  # ball-ball restitution
    # Cushion restitution and friction at its nose; None takes the cushion model's own
    # (E_CUSHION, MU_CUSHION of its module), since each model means its own thing by them.
    e_cushion: float | None = None
    mu_cushion: float | None = None
    cushion_height: float = 0.0366  # nose height above the slate (0.64 ball diameters)
    g: float = 9.81
    ball_ball: str = "frictional"  # the ball-ball model, a name in ball_ball.MODELS
    cushion: str = "mathavan"  # the cushion response model, a name in cushion.MODELS (why this
    # one: docs/physics.md, Cushions)
    # Closing speeds below this are treated as perfectly inelastic: touching balls then settle
    # in a few contacts instead of an endless geometric series of bounces.
    v_inelastic: float = 0.005

    def __post_init__(self) -> None:
        if not isinstance(self.cushion, str) or self.cushion not in CUSHIONS:
            names = ", ".join(f"'{k}'" for k in CUSHIONS)
            raise ValueError(f"physics.cushion: must be one of {names}")
        model = CUSHIONS[self.cushion]
        if self.e_cushion is None:
            object.__setattr__(self, "e_cushion", model.E_CUSHION)
        if self.mu_cushion is None:
            object.__setattr__(self, "mu_cushion", model.MU_CUSHION)

    @classmethod
    def from_dict(cls, d: dict) -> Physics:
        """Build from a scene's or a saved match's `physics` object, every number within
        PHYSICS_RANGES; raises ValueError naming a bad key."""
        names = {f.name for f in fields(cls)}
        kw = {}
        for key, val in d.items():
            if key not in names:
                raise ValueError(f"physics: unknown key '{key}'")
            if key == "ball_ball":
                if not isinstance(val, str) or val not in BALL_BALL:
                    names = " or ".join(f"'{k}'" for k in BALL_BALL)
                    raise ValueError(f"physics.ball_ball: must be {names}")
                kw[key] = val
                continue
            if key == "cushion":
                kw[key] = val  # checked by __post_init__
                continue
            if isinstance(val, bool) or not isinstance(val, (int, float)):
                raise ValueError(f"physics.{key}: must be a number")
            try:
                val = float(val)
            except OverflowError:  # an integer beyond any float
                val = float("inf")
            if not (val == val and abs(val) != float("inf")):
                raise ValueError(f"physics.{key}: must be finite")
            if val < 0:
                raise ValueError(f"physics.{key}: must not be negative")
            if not (val == 0 and key in FRICTIONLESS_OK):
                try:
                    within(val, PHYSICS_RANGES[key], f"physics.{key}", PHYSICS_UNITS.get(key, ""))
                except ValueError as e:
                    extra = " (or 0, frictionless)" if key in FRICTIONLESS_OK else ""
                    raise ValueError(f"{e}{extra}") from None
            kw[key] = val
        return cls(**kw)

    def to_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self)}
