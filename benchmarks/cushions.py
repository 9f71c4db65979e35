"""Rebounds of standard shots off a rail under each cushion model: the table in docs/physics.md.

python benchmarks/cushions.py             # termpool's models, a Markdown table
python benchmarks/cushions.py --pooltool  # and pooltool's four models on the same shots

Each shot meets the rail at 1 m/s (the models are linear in speed, so the figures are ratios)
on the 9-ft table's geometry: R 28.575 mm, m 170 g, nose 36.6 mm above the slate. A cell is
rebound speed / rebound angle from the rail's normal / follow after: R (w x z) . v / |v|^2
for the ball leaving, 1 for natural roll, 0 for stun, negative for draw (a rolling ball
that keeps part of its roll through the rail leaves with draw). --pooltool needs pooltool
0.6 importable (pip install pooltool-billiards in a separate environment); its models are
given the same ball, nose height and cloth friction, e 0.85 and mu 0.2 (its defaults).
"""

from __future__ import annotations

import math
import os
import sys

SHOTS = [  # name, angle of incidence from the normal (degrees), top spin R w / v, side R wz / v
    ("rolling, square", 0.0, 1.0, 0.0),
    ("rolling, 45°", 45.0, 1.0, 0.0),
    ("rolling, 45°, running side", 45.0, 1.0, 1.0),
    ("rolling, 45°, reverse side", 45.0, 1.0, -1.0),
    ("stun, square", 0.0, 0.0, 0.0),
    ("stun, 45°", 45.0, 0.0, 0.0),
    ("draw, square", 0.0, -0.5, 0.0),
]
R, M, H = 0.028575, 0.170, 0.0366


def incoming(angle: float, top: float, side: float) -> tuple[list, list]:
    """Velocity and spin at the rail, in a frame where the rail runs along x and the ball
    travels +x and +y into it (the rail's normal into the table is -y)."""
    a = math.radians(angle)
    v = [math.sin(a), math.cos(a)]
    # Rolling: v = R w x z, so w = (-vy, vx) / R; running side turns the contact point
    # (above +y) backwards along the rail, wz > 0 for a ball travelling +x.
    return v, [-top * v[1] / R, top * v[0] / R, side / R]


def cell(v: list, w: list) -> str:
    speed = math.hypot(*v)
    angle = round(math.degrees(math.atan2(v[0], -v[1])), 1) + 0.0  # no "-0.0"
    follow = R * (w[1] * v[0] - w[0] * v[1]) / (speed * speed)
    return f"{speed:.3f} / {angle:.1f}° / {follow:+.2f}"


def termpool_columns() -> dict:
    from termpool.physics.cushion import MODELS
    from termpool.physics.params import Physics

    cols = {f"{name} (e {Physics(cushion=name).e_cushion:g})": Physics(cushion=name)
            for name in MODELS}
    cols["mathavan (e 0.85, mu 0.2)"] = Physics(cushion="mathavan", e_cushion=0.85,
                                                mu_cushion=0.2)
    out = {}
    for label, ph in cols.items():
        ph = Physics(**{**ph.to_dict(), "cushion_height": H})
        model = MODELS[ph.cushion]
        out[label] = [cell(*model.bounce_one([0.0, -1.0], *incoming(a, t, s), R, M, ph))
                      for _, a, t, s in SHOTS]
    return out


def pooltool_columns() -> dict:
    import numpy as np
    import pooltool as pt
    from pooltool.objects.table.components import LinearCushionSegment
    from pooltool.physics.resolve.ball_cushion import ball_lcushion_models
    from pooltool.physics.resolve.models import BallLCushionModel

    rail = LinearCushionSegment("rail", p1=np.array([-5.0, 1.0, H]), p2=np.array([5.0, 1.0, H]))
    out = {}
    for model in ("impulse_frictional_inelastic", "han_2005", "mathavan_2010",
                  "stronge_compliant"):
        strategy = ball_lcushion_models[BallLCushionModel(model)]()
        cells = []
        for _, a, t, s in SHOTS:
            v, w = incoming(a, t, s)
            ball = pt.Ball.create("cue", xy=(0.0, 1.0 - R), m=M, R=R, e_c=0.85, f_c=0.2,
                                  u_s=0.2)
            ball.state.rvw[1] = [v[0], v[1], 0.0]
            ball.state.rvw[2] = w
            ball.state.s = pt.constants.sliding
            after, _ = strategy.solve(ball, rail)
            rvw = after.state.rvw
            cells.append(cell([float(rvw[1][0]), float(rvw[1][1])], [float(x) for x in rvw[2]]))
        out[f"pooltool {model}"] = cells
    return out


def table(cols: dict) -> str:
    names = list(cols)
    lines = ["| shot | " + " | ".join(names) + " |", "|---" * (len(names) + 1) + "|"]
    for k, (shot, *_) in enumerate(SHOTS):
        lines.append(f"| {shot} | " + " | ".join(cols[n][k] for n in names) + " |")
    return "\n".join(lines)


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    columns = termpool_columns()
    if "--pooltool" in sys.argv[1:]:
        columns |= pooltool_columns()
    print(table(columns))
