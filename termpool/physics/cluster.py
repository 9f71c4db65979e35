"""Slow contacts in a cluster of touching balls, resolved together.

Resolving the contacts of a touching cluster one pair at a time (as fast collisions are)
converges slowly when nothing bounces: a ball pushing a row of frozen balls would take
thousands of tiny contacts. Below the inelastic speed the whole cluster is solved at once as a
linear complementarity problem: impulses lam >= 0 along every contact normal such that no
contact still closes (u >= 0) and only closing contacts push (lam * u = 0).
"""

from __future__ import annotations

import numpy as np


def solve_inelastic(A: np.ndarray, u0: np.ndarray, tol: float = 1e-12) -> np.ndarray:
    """Return lam >= 0 with u = u0 + A lam >= 0 and lam * u = 0 (A symmetric PSD).

    Active-set method: contacts that close are pushed until their normal speed is zero; a
    contact whose push would be negative is released, one that still closes is added.
    """
    k = len(u0)
    lam = np.zeros(k)
    if k == 0:
        return lam
    scale = max(float(np.abs(u0).max()), 1e-300)
    tol = tol * scale
    active = u0 < -tol
    for n in range(4 * k + 8):
        # Early passes move every offending contact at once; later ones one at a time, which
        # cannot cycle.
        bulk = n < 8
        lam[:] = 0.0
        a = np.nonzero(active)[0]
        if a.size:
            sub = A[np.ix_(a, a)]
            try:
                sol = np.linalg.solve(sub, -u0[a])
            except np.linalg.LinAlgError:  # redundant contacts (e.g. a ball in a corner)
                sol = np.linalg.lstsq(sub, -u0[a], rcond=None)[0]
            neg = sol < -tol
            if neg.any():
                active[a[neg] if bulk else a[np.argmin(sol)]] = False
                continue
            lam[a] = np.maximum(sol, 0.0)
        u = u0 + A @ lam
        bad = ~active & (u < -tol)
        if not bad.any():
            break
        if bulk:
            active |= bad
        else:
            idx = np.nonzero(bad)[0]
            active[idx[np.argmin(u[idx])]] = True
    return lam
