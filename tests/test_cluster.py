"""The cluster solves written out: contact rows, the elimination, the complementarity problem.

The systems come from the geometry games are made of: racks (hexagonal packs, where contacts
outnumber what the balls can do, so many are redundant), a ball in a corner against two rails,
a straight row, and a pair. Dense matrices through numpy's BLAS serve only as the reference.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from termpool.physics import cluster
from termpool.physics.cluster import PLAIN, Rows, solve_inelastic, solve_psd
from termpool.physics.params import BALL_MASS, BALL_RADIUS

R = BALL_RADIUS


def _contacts(centres, rails=()) -> Rows:
    """Rows of every touching pair of balls at `centres` and of each (ball, inward normal)
    in `rails`."""
    p = np.array(centres, dtype=float)
    d = p[None] - p[:, None]
    dist = np.hypot(d[..., 0], d[..., 1])
    a, c = np.nonzero(np.triu(dist < 2 * R * (1 + 1e-9), 1))
    n = -d[a, c] / dist[a, c][:, None]
    a = list(a) + [b for b, _ in rails]
    c = list(c) + [-1] * len(rails)
    n = np.concatenate([n.reshape(-1, 2), np.array([nr for _, nr in rails]).reshape(-1, 2)])
    return Rows(np.array(a), np.array(c), n, len(p))


def _hex(rows: int, cols: int):
    return [(2 * R * j + R * (i % 2), math.sqrt(3) * R * i)
            for i in range(rows) for j in range(cols)]


def _rack(rows: int):
    """A triangle rack of `rows` rows, apex first, as the 8-ball rack is laid."""
    return [(math.sqrt(3) * R * i, (j - i / 2) * 2 * R) for i in range(rows) for j in range(i + 1)]


CASES = {
    "pair": _contacts([(0, 0), (2 * R, 0)]),
    "row of 6": _contacts([(2 * R * j, 0) for j in range(6)]),
    "corner": _contacts([(R, R), (3 * R, R)], rails=[(0, (1.0, 0.0)), (0, (0.0, 1.0)),
                                                      (1, (0.0, 1.0))]),
    "wedged": _contacts([(0, 0), (2 * R, 0), (R, math.sqrt(3) * R), (R, -math.sqrt(3) * R)]),
    "rack of 3 rows": _contacts(_rack(3)),  # 6 balls, 9 contacts
    "rack of 5 rows": _contacts(_rack(5)),  # the 8-ball rack: 15 balls, 30 contacts
    "hex 4x5": _contacts(_hex(4, 5)),
    "hex 6x7 on a rail": _contacts(_hex(6, 7), rails=[(7 * i, (1.0, 0.0)) for i in range(6)]),
}


def _dense(rows: Rows) -> np.ndarray:
    J = np.zeros((len(rows), rows.balls, 2))
    idx = np.arange(len(rows))
    J[idx, rows.a] = rows.n
    J[idx[rows.ball], rows.c[rows.ball]] = -rows.n[rows.ball]
    return J.reshape(len(rows), -1)


def _masses(rows: Rows, seed: int) -> np.ndarray:
    """Inverse masses: equal balls, or a mix of light, heavy and held (0) ones."""
    if seed == 0:
        return np.full(rows.balls, 1.0 / BALL_MASS)
    rng = np.random.default_rng(seed)
    return rng.choice([0.0, 1.0 / BALL_MASS, 0.1, 50.0], rows.balls)


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_rows_are_the_products_of_the_dense_contact_matrix(name, seed):
    rows = CASES[name]
    k = _masses(rows, seed)
    J = _dense(rows)
    kk = np.repeat(k, 2)
    rng = np.random.default_rng(seed)
    v = rng.normal(0, 1, (rows.balls, 2))
    lam = rng.uniform(0, 1, len(rows))
    A = rows.matrix(k)
    assert np.array_equal(A, A.T)
    assert np.allclose(A, (J * kk) @ J.T, rtol=0, atol=1e-12 * np.abs(kk).max())
    assert np.allclose(rows.speeds(v), J @ v.reshape(-1), rtol=0, atol=1e-14)
    assert np.allclose(rows.spread(lam, k), (kk * (J.T @ lam)).reshape(-1, 2), rtol=0,
                       atol=1e-13 * np.abs(kk).max())
    assert np.array_equal(rows.matrix(k), A)  # the cached pattern gives the same bits


def _velocities(k: np.ndarray, seed: int) -> np.ndarray:
    """Random ball velocities, held balls (k = 0) at rest."""
    v = np.random.default_rng(100 + seed).normal(0, 1, (len(k), 2))
    return np.where(k[:, None] > 0, v, 0.0)


def _system(name: str, seed: int):
    """A contact system S = J K J^T of the case, and a right side in its range, as the
    velocity solves have: the contacts' speeds with held balls at rest."""
    rows = CASES[name]
    k = _masses(rows, seed)
    return rows, k, rows.matrix(k), rows.speeds(_velocities(k, seed))


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_solve_psd_solves_every_row_and_moves_the_balls_as_least_squares_does(name, seed):
    rows, k, S, b = _system(name, seed)
    x = solve_psd(S, b)
    scale = np.abs(S).max() * np.abs(x).max() + np.abs(b).max()
    assert np.abs(S @ x - b).max() <= 1e-12 * scale
    # Redundant contacts: any solution gives the balls the same velocities (J^T x is
    # unique for b in the range of S), here the minimum-norm one.
    ref = np.linalg.lstsq(S, b, rcond=None)[0]
    vmax = np.abs(rows.spread(ref, k)).max()
    assert np.allclose(rows.spread(x, k), rows.spread(ref, k), rtol=0, atol=1e-10 * vmax)


def test_redundant_contacts_take_no_impulse():
    """A hexagonal pack has more contacts than its balls have ways to move: the elimination
    gives as many impulses as the system's rank, and the contacts left over exactly 0."""
    rows, _, S, b = _system("hex 4x5", 0)
    x = solve_psd(S, b)
    rank = np.linalg.matrix_rank(S)
    assert rank < len(rows)
    assert np.count_nonzero(x) == rank


@pytest.mark.parametrize("size", [1, 2, 3, 4, 5, 6, 8, 9, 13, 16, 24, 31, 40, 52, PLAIN])
def test_plain_floats_and_arrays_give_the_same_bits(size):
    """solve_psd takes plain floats up to PLAIN unknowns and arrays beyond: the two are the
    same operations in the same order, on full-rank and redundant systems, with zeros."""
    rng = np.random.default_rng(size)
    systems = []
    for name in CASES:
        rows, _, S, b = _system(name, size % 3)
        pick = rng.choice(len(rows), min(size, len(rows)), replace=False)
        systems.append((S[np.ix_(pick, pick)], b[pick]))
    M = rng.normal(0, 1, (size, size + 2))
    systems.append((M @ M.T, rng.normal(0, 1, size)))
    low = rng.normal(0, 1, (size, max(size // 2, 1)))
    systems.append((low @ low.T, low @ rng.normal(0, 1, low.shape[1])))
    systems.append((np.zeros((size, size)), np.zeros(size)))
    for S, b in systems:
        S = (S + S.T) / 2
        plain = np.array(cluster._solve_few(S.tolist(), b.tolist()))
        arrays = cluster._solve_array(S, b)
        assert np.array_equal(plain, arrays), (S, b)
        assert np.array_equal(np.signbit(plain), np.signbit(arrays))


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_solve_inelastic_meets_the_complementarity_conditions(name, seed):
    """Closing contacts stop closing, none pulls, and only those that would close push."""
    rows = CASES[name]
    k = _masses(rows, seed % 2)
    live = np.abs(rows.matrix(k)).sum(axis=1) > 0
    A = rows.matrix(k)[np.ix_(live, live)]
    u0 = rows.speeds(_velocities(k, seed))[live]
    lam = solve_inelastic(A, u0)
    u = u0 + A @ lam
    tol = 1e-9 * np.abs(u0).max()
    assert (lam >= 0).all()
    assert (u >= -tol).all()
    assert np.abs(lam * u).max() <= tol * max(lam.max(), 1.0)


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_the_complementarity_problem_in_plain_floats_and_arrays_gives_the_same_bits(name, seed):
    rows = CASES[name]
    if len(rows) > PLAIN:
        pytest.skip("solved on arrays only")
    k = _masses(rows, seed % 2)
    A = rows.matrix(k)
    for u0 in (rows.speeds(_velocities(k, seed)), -np.abs(rows.speeds(_velocities(k, seed)))):
        plain = np.array(cluster._inelastic_few(A.tolist(), u0.tolist(), 1e-12))
        arrays = cluster._inelastic_array(A, u0, 1e-12)
        assert np.array_equal(plain, arrays)
        assert np.array_equal(np.signbit(plain), np.signbit(arrays))



def _problems(rows: Rows, seed: int):
    """Complementarity problems of the case as the solves meet them: random speeds, all of
    them closing, and a frozen cluster (every speed an exact 0 or -0.0) with one contact
    closing, as a slow ball meets a rack at rest."""
    k = _masses(rows, seed % 2)
    u = rows.speeds(_velocities(k, seed))
    one = np.where(np.arange(len(rows)) % 2 == 0, 0.0, -0.0)
    one[seed % len(rows)] = -1e-3
    return rows.matrix(k), (u, -np.abs(u), one)


def _parting(rows: Rows, seed: int) -> np.ndarray:
    """One contact closing, every other parting fast: only the closing one is pushed."""
    u0 = np.full(len(rows), 1.0)
    u0[seed % len(rows)] = -1e-3
    return u0


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_the_plain_solve_reading_columns_gives_the_bits_of_the_array_solve(name, seed):
    """The plain-float complementarity solve reads the matrix column by column (Columns)
    and writes out one contact and one-contact eliminations: the same bits as the array
    form, signed zeros included, on racks, packs on a rail, a corner, a wedged ball, held
    balls; it reads the columns of the contacts it pushes, and only those: one contact
    closing while the others part reads one column."""
    rows = CASES[name]
    if len(rows) > PLAIN:
        pytest.skip("solved on arrays only")
    A, problems = _problems(rows, seed)
    for u0 in (*problems, _parting(rows, seed)):
        cols = _Counted(A)
        plain = np.array(cluster.inelastic_plain(cols, u0.tolist(), 1e-12))
        arrays = cluster._inelastic_array(A, u0, 1e-12)
        assert plain.tobytes() == arrays.tobytes()
        assert set(np.flatnonzero(plain > 0).tolist()) <= cols.read
    assert cols.read == {seed % len(rows)}  # the parting case: one column read, of them all


class _Counted(cluster.Columns):
    """Columns that note which columns are read."""

    def __init__(self, A: np.ndarray) -> None:
        super().__init__(A)
        self.read: set[int] = set()

    def __getitem__(self, j: int) -> list:
        self.read.add(j)
        return super().__getitem__(j)


@pytest.mark.parametrize("d", [1.0, 2.5e3, 1e-300, 5e-324, 0.0, -0.0, -1.0, math.inf,
                               math.nan])
@pytest.mark.parametrize("u", [-1.0, -1e-13, -5e-324, 0.0, -0.0, 1.0, -math.inf, math.nan])
def test_one_contact_written_out_gives_the_bits_of_the_array_solve(d, u):
    """A single contact (a group's usual problem): any diagonal, even one the elimination
    refuses (zero, negative, not a number), any speed, closing or not."""
    with np.errstate(all="ignore"):
        plain = np.array(cluster.inelastic_plain([[d]], [u], 1e-12))
        arrays = cluster._inelastic_array(np.array([[d]]), np.array([u]), 1e-12)
    assert plain.tobytes() == arrays.tobytes()
