"""Ball motion states and the tolerances the engine's parts share."""

from __future__ import annotations

STATIONARY, SPINNING, SLIDING, ROLLING, POCKETED = range(5)
STATE_NAMES = ("stationary", "spinning", "sliding", "rolling", "pocketed")
# A slip this small (m/s) would slide for under 0.15 ms: it is completed at once (see
# motion.snap), so a pair pressed together cannot chatter through endless tiny slides.
EPS_U = 1e-3
EPS_V = 1e-9  # m/s below which a ball counts as not translating
EPS_W = 1e-9  # rad/s of side spin below which a ball counts as still
CLUSTER_GAP = 1e-6  # m: balls (and cushions) this close count as touching in a cluster
