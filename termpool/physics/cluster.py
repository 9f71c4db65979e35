"""Slow contacts in a cluster of touching balls, resolved together.

Resolving the contacts of a touching cluster one pair at a time (as fast collisions are)
converges slowly when nothing bounces: a ball pushing a row of frozen balls would take
thousands of tiny contacts. Below the inelastic speed the whole cluster is solved at once as a
linear complementarity problem: impulses lam >= 0 along every contact normal such that no
contact still closes (u >= 0) and only closing contacts push (lam * u = 0).

Every product and solve here is written out elementwise in a fixed order instead of going
through BLAS or LAPACK: their last bits depend on the library, the processor's kernels and
the number of threads, and a last bit is enough to change which contact comes next, so a
replay would differ from machine to machine. The small solves (most have one to three
unknowns) run in plain floats, operation for operation as the array code does them.
"""

from __future__ import annotations

import numpy as np

RANK_TOL = 1e-12  # a pivot this small against the largest diagonal marks a redundant contact
PLAIN = 64  # systems up to this size are solved in plain floats (the same bits, faster)
TOL = 1e-12  # solve_inelastic's tolerance on closing speeds, against the largest


class Rows:
    """Contact rows: ball a pushed along the unit normal n away from ball c (c = -1 for a
    cushion, which does not move). A contact's separating speed is n . (v[a] - v[c]); these
    are the rows of J in u = J v, kept sparse (a row touches at most two balls)."""

    def __init__(self, a: np.ndarray, c: np.ndarray, n: np.ndarray, balls: int) -> None:
        self.a = np.asarray(a, dtype=np.int64)
        self.c = np.asarray(c, dtype=np.int64)
        self.n = np.asarray(n, dtype=float).reshape(-1, 2)
        self.balls = balls
        self.ball = self.c >= 0
        self._c = np.maximum(self.c, 0)
        self._pattern: tuple | None = None
        self._last: tuple | None = None

    def __len__(self) -> int:
        return len(self.a)

    def speeds(self, v: np.ndarray) -> np.ndarray:
        """J v: each contact's separating speed for ball velocities v (balls, 2)."""
        rel = v[self.a] - np.where(self.ball[:, None], v[self._c], 0.0)
        return (rel * self.n).sum(axis=1)

    def spread(self, lam: np.ndarray, k: np.ndarray) -> np.ndarray:
        """k J^T lam as (balls, 2): what impulses (or forces) lam along the rows do to balls
        of inverse masses k. Each ball's sum runs in row order."""
        f = lam[:, None] * self.n
        cb = self._c[self.ball]
        out = np.empty((self.balls, 2))
        for d in (0, 1):
            out[:, d] = (np.bincount(self.a, f[:, d], self.balls)
                         - np.bincount(cb, f[self.ball, d], self.balls))
        return k[:, None] * out

    def matrix(self, k: np.ndarray) -> np.ndarray:
        """J diag(k) J^T for inverse masses k per ball: how an impulse along one contact
        changes the separating speed of another. Row i is k[a_i] times n_i . n_j signed by
        ball a_i's part in each contact j (+ as its ball a, - as its ball c), plus the same
        for ball c_i with the signs turned (contact i pushes it the other way). Exactly
        symmetric: two contacts share at most one ball."""
        key = k.tobytes()
        if self._last is not None and self._last[0] == key:  # push asks again with the same k
            return self._last[1]
        if self._pattern is None:  # what does not depend on k, for the next call
            a, c, n, ball = self.a, self.c, self.n, self.ball
            nn = (n[:, None] * n[None]).sum(axis=2)
            by_a = (a[None, :] == a[:, None]).astype(float) - (c[None, :] == a[:, None])
            by_c = (c[None, :] == c[:, None]).astype(float) - (a[None, :] == c[:, None])
            self._pattern = (nn * by_a, nn * np.where(ball[:, None], by_c, 0.0))
        from_a, from_c = self._pattern
        kc = np.where(self.ball, k[self._c], 0.0)  # a cushion moves nothing
        A = k[self.a][:, None] * from_a + kc[:, None] * from_c
        A.flags.writeable = False  # shared with the next caller that asks with this k
        self._last = (key, A)
        return A


def solve_psd(S: np.ndarray, b: np.ndarray) -> np.ndarray:
    """x with S x = b for a symmetric positive semi-definite S (k, k).

    Gaussian elimination with symmetric pivoting: each step takes the largest diagonal
    left. When that falls to RANK_TOL of the largest diagonal, the unknowns left depend on
    the others (a ball wedged between three others, a ball in a corner against two
    cushions): they are 0, and for b in the range of S the others still solve every row.
    A step updates only the entries whose row and column both meet the pivot's with a
    non-zero (contact matrices are sparse: a contact touches the few that share its balls).
    Up to PLAIN unknowns it runs in plain floats (_solve_few), with the same result.
    """
    if len(b) <= PLAIN:
        return np.array(_solve_few(S.tolist(), b.tolist()), dtype=float).reshape(len(b))
    return _solve_array(S, b)


def _solve_array(S: np.ndarray, b: np.ndarray) -> np.ndarray:
    """solve_psd on arrays: the pivot row and column are swapped to the front of what is
    left, so that each step works on the block after them."""
    k = len(b)
    W = np.empty((k, k + 1))
    W[:, :k] = S
    W[:, k] = b
    diag = np.diagonal(W)  # a view
    floor = RANK_TOL * float(diag.max())
    perm = list(range(k))
    n = 0  # unknowns eliminated
    while n < k:
        j = n + int(diag[n:].argmax())
        pivot = float(diag[j])
        if not pivot > floor:
            break
        if j != n:
            row = W[n].copy()
            W[n] = W[j]
            W[j] = row
            col = W[:, n].copy()
            W[:, n] = W[:, j]
            W[:, j] = col
            perm[n], perm[j] = perm[j], perm[n]
        rows = W[n + 1:, n].nonzero()[0] + (n + 1)
        if rows.size:
            cols = W[n, n + 1:].nonzero()[0] + (n + 1)
            W[rows[:, None], cols] -= np.multiply.outer(W[rows, n] / pivot, W[n, cols])
        n += 1
    x = np.zeros(k)
    rhs = W[:n, k].copy()
    for s in range(n - 1, -1, -1):
        x[s] = rhs[s] / W[s, s]
        rhs[:s] -= W[:s, s] * x[s]
    out = np.zeros(k)
    out[perm] = x
    return out


def _solve_few(S: list, b: list) -> list:
    """_solve_array in plain floats, operation for operation (bit-identical)."""
    k = len(b)
    W = [row + [bi] for row, bi in zip(S, b, strict=True)]
    floor = RANK_TOL * max(W[i][i] for i in range(k)) if k else 0.0
    perm = list(range(k))
    n = 0
    while n < k:
        j = n
        for i in range(n + 1, k):  # the first largest, as argmax finds it
            if W[i][i] > W[j][j]:
                j = i
        pivot = W[j][j]
        if not pivot > floor:
            break
        if j != n:
            W[n], W[j] = W[j], W[n]
            for row in W:
                row[n], row[j] = row[j], row[n]
            perm[n], perm[j] = perm[j], perm[n]
        top = W[n]
        cols = [c for c in range(n + 1, k + 1) if top[c] != 0.0]
        for i in range(n + 1, k):
            row = W[i]
            if row[n] != 0.0:
                m = row[n] / pivot
                for c in cols:
                    row[c] = row[c] - m * top[c]
        n += 1
    x = [0.0] * k
    rhs = [W[i][k] for i in range(n)]
    for s in range(n - 1, -1, -1):
        xs = x[s] = rhs[s] / W[s][s]
        for i in range(s):
            rhs[i] = rhs[i] - W[i][s] * xs
    out = [0.0] * k
    for s in range(k):
        out[perm[s]] = x[s]
    return out


def solve_inelastic(A: np.ndarray, u0: np.ndarray, tol: float = TOL) -> np.ndarray:
    """Return lam >= 0 with u = u0 + A lam >= 0 and lam * u = 0 (A symmetric PSD).

    Active-set method: contacts that close are pushed until their normal speed is zero; a
    contact whose push would be negative is released, one that still closes is added.
    Early passes move every offending contact at once; later ones one at a time, which
    cannot cycle. Up to PLAIN contacts it runs in plain floats, with the same result.
    """
    k = len(u0)
    if k <= PLAIN:
        return np.array(inelastic_plain(Columns(A), u0.tolist(), tol), dtype=float).reshape(k)
    return _inelastic_array(A, u0, tol)


class Columns:
    """The columns of a matrix (k, k) as lists, each taken from it when first asked for: the
    plain-float solve reads only the columns of the contacts it pushes (one or two of a
    rack's thirty, usually)."""

    __slots__ = ("A", "_got")

    def __init__(self, A: np.ndarray) -> None:
        self.A = A
        self._got: dict[int, list] = {}

    def __getitem__(self, j: int) -> list:
        col = self._got.get(j)
        if col is None:
            col = self._got[j] = self.A[:, j].tolist()
        return col


def _inelastic_array(A: np.ndarray, u0: np.ndarray, tol: float) -> np.ndarray:
    k = len(u0)
    lam = np.zeros(k)
    tol = tol * max(float(np.abs(u0).max()), 1e-300)
    active = u0 < -tol
    for n in range(4 * k + 8):
        bulk = n < 8
        lam[:] = 0.0
        a = active.nonzero()[0]
        u = u0
        if a.size:
            sol = solve_psd(A[a[:, None], a], -u0[a])
            neg = sol < -tol
            if neg.any():
                active[a[neg] if bulk else a[np.argmin(sol)]] = False
                continue
            lam[a] = np.maximum(sol, 0.0)
            for j in a.tolist():  # u0 + A lam, summed in the order of the contacts
                u = u + A[:, j] * lam[j]
        bad = ~active & (u < -tol)
        if not bad.any():
            break
        if bulk:
            active |= bad
        else:
            idx = bad.nonzero()[0]
            active[idx[np.argmin(u[idx])]] = True
    return lam


def _inelastic_few(A: list, u0: list, tol: float) -> list:
    """_inelastic_array in plain floats (A as lists of rows), operation for operation."""
    return inelastic_plain([list(col) for col in zip(*A, strict=True)], u0, tol)


def inelastic_plain(col, u0: list, tol: float) -> list:
    """_inelastic_array in plain floats, operation for operation (bit-identical), with
    col[j] the matrix's column j as a list (a list of columns, or `Columns`)."""
    k = len(u0)
    tol = tol * max(max(map(abs, u0)), 1e-300) if k else tol * 1e-300
    # The loop's first pass where at most one contact closes (the usual problem), written
    # out: it ends there unless that contact's push is negative or closes another.
    first = -1
    for i, x in enumerate(u0):
        if x < -tol:
            if first >= 0:
                return _inelastic_loop(col, u0, tol)
            first = i
    if first < 0:
        return [0.0] * k
    c = col[first]
    sol = _one(c[first], -u0[first])
    if sol < -tol:
        return _inelastic_loop(col, u0, tol)
    push = sol if sol > 0.0 else 0.0  # as np.maximum(x, 0.0): -0.0 becomes 0.0
    for i, (x, y) in enumerate(zip(u0, c, strict=True)):
        if i != first and x + y * push < -tol:
            return _inelastic_loop(col, u0, tol)
    lam = [0.0] * k
    lam[first] = push
    return lam


def _inelastic_loop(col, u0: list, tol: float) -> list:
    """`inelastic_plain`'s loop (tol already scaled by the largest speed)."""
    k = len(u0)
    lam = [0.0] * k
    active = [x < -tol for x in u0]
    for n in range(4 * k + 8):
        bulk = n < 8
        lam = [0.0] * k
        a = [i for i in range(k) if active[i]]
        u = u0
        if a:
            cols = [col[j] for j in a]
            if len(a) == 1:
                i = a[0]
                sol = [_one(cols[0][i], -u0[i])]
            else:
                sol = _solve_few([[c[i] for c in cols] for i in a], [-u0[i] for i in a])
            if any(x < -tol for x in sol):
                if bulk:
                    for i, x in zip(a, sol, strict=True):
                        if x < -tol:
                            active[i] = False
                else:
                    active[a[min(range(len(sol)), key=sol.__getitem__)]] = False
                continue
            for i, x in zip(a, sol, strict=True):
                lam[i] = x if x > 0.0 else 0.0  # as np.maximum(x, 0.0): -0.0 becomes 0.0
            for j, c in zip(a, cols, strict=True):  # u0 + A lam, in the order of the contacts
                lj = lam[j]
                u = [x + y * lj for x, y in zip(u, c, strict=True)]
        bad = [i for i in range(k) if not active[i] and u[i] < -tol]
        if not bad:
            break
        if bulk:
            for i in bad:
                active[i] = True
        else:
            active[min(bad, key=u.__getitem__)] = True
    return lam


def _one(d: float, b: float) -> float:
    """`_solve_few([[d]], [b])[0]`: b / d, or 0 for a pivot too small (no pivot at all)."""
    return b / d if d > RANK_TOL * d else 0.0
