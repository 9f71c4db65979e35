"""The app as a value: the view draws a state without changing it, two screens of different
sizes draw one state each as it alone would, and each screen's clicks and help pages are read
against what that screen showed."""

from __future__ import annotations

import math
from dataclasses import fields, replace

import numpy as np
import pytest

from termpool.ui import aid, phases
from termpool.ui.app import App, Options
from termpool.ui.headless import play, screen_text
from termpool.ui.keys import Key, Mouse, parse_script
from termpool.ui.phases.boxes import open_settings
from termpool.ui.phases.turn import start_turn
from termpool.ui.state import Aiming, Help, Phase, Place, help_of
from termpool.ui.table_view import Geometry
from termpool.ui.view import draw

SIZES = ((80, 24), (120, 40))


NAMES = ("menu", "place", "aim", "run", "cpu", "settings", "help")


@pytest.fixture(scope="module")
def states() -> dict:
    """States the game passes through: the menu, ball in hand, the aim with its aid, a shot
    rolling, the computer aiming, a box over the game."""
    return dict(_states())


def _states():
    menu = App(Options(colors="truecolor"))
    yield "menu", menu.state
    app = App(Options(mode="8ball", opponent="cpu", seed=2, colors="truecolor"))
    yield "place", app.state
    play(app, parse_script("enter left*3 w"), 100, 32)
    yield "aim", aid.refresh(app.state)
    app.key(Key("space"), 10.0)
    app.key(Key("space", kind="release"), 11.0)
    for k in range(20):
        app.tick(11.0 + k / 60)
    assert app.state.phase is Phase.RUN
    yield "run", app.state
    t = 11.0
    while app.state.phase is Phase.RUN:
        t += 1 / 30
        app.tick(t)
    m = app.state.match  # the computer's turn, whatever the break left
    m.state = replace(m.state, shooter=1)
    m.ball_in_hand = None
    app.state = start_turn(app.state)
    while not isinstance(app.state.part, Aiming):
        t += 1 / 30
        app.tick(t)
    yield "cpu", aid.refresh(app.state)
    yield "settings", open_settings(app.state)
    yield "help", replace(app.state, box=Help(3))


def snapshot(s) -> tuple:
    """What a state holds: each field (handles by identity), and the match's position."""
    m = s.match
    held = tuple(id(getattr(s, f.name)) for f in fields(s))
    if m is None:
        return held, None
    return held, (m.pos.tobytes(), m.on_table.tobytes(), len(m.history), m.state, m.option)


@pytest.mark.parametrize("name", NAMES)
def test_drawing_a_state_changes_nothing_in_it(states, name) -> None:
    state = states[name]
    before = snapshot(state)
    aid_before = (state.aid.job.instants, state.aid.job.done) if state.aid.job else None
    for cols, rows in SIZES:
        draw(state, cols, rows, Geometry())
    assert snapshot(state) == before, name
    assert ((state.aid.job.instants, state.aid.job.done) if state.aid.job else None) == \
        aid_before  # the aid runs on the clock's ticks, never while a screen draws


@pytest.mark.parametrize("name", NAMES)
def test_two_screens_draw_one_state_each_as_it_alone_would(states, name) -> None:
    state = states[name]
    small, large = Geometry(), Geometry()
    for _ in range(2):  # in turns, and again: neither screen's drawing leaks into the other
        for geometry, (cols, rows) in ((small, SIZES[0]), (large, SIZES[1])):
            shared, seen = draw(state, cols, rows, geometry)
            alone, _ = draw(state, cols, rows, Geometry())
            for a, b in zip(shared, alone, strict=True):
                assert (a is None and b is None) or np.array_equal(a, b), (name, cols)
            assert (seen.cols, seen.rows) == (cols, rows)
    text = [screen_text(draw(state, c, r, Geometry())[0][0]) for c, r in SIZES]
    assert text[0] != text[1]  # two sizes, two layouts


def test_a_click_is_read_on_the_screen_it_came_from() -> None:
    app = App(Options(mode="practice", seed=4, colors="mono"))
    s = app.state
    assert s.phase is Phase.PLACE
    target = (1.9, 0.35)
    found = []
    for cols, rows in SIZES:
        _, seen = draw(s, cols, rows, Geometry())
        x, y = seen.layout.to_pixels(*target)
        moved = phases.mouse(s, Mouse(int(x), int(y) // 2, "press"), 1.0, seen)
        cell = 2.0 / seen.layout.scale  # a cell is two pixels high
        assert isinstance(moved.part, Place)
        assert math.dist(moved.part.cursor, target) <= cell, (cols, rows)
        found.append(moved.part.cursor)
    # The same cell position read against the other screen's layout lands elsewhere.
    _, small = draw(s, *SIZES[0], Geometry())
    _, large = draw(s, *SIZES[1], Geometry())
    x, y = small.layout.to_pixels(*target)
    crossed = phases.mouse(s, Mouse(int(x), int(y) // 2, "press"), 1.0, large)
    assert math.dist(crossed.part.cursor, target) > 0.1
    # A screen that has not drawn this match's table takes no clicks.
    assert phases.mouse(s, Mouse(int(x), int(y) // 2, "press"), 1.0, None).part == s.part


def test_the_help_pages_turn_by_the_screen_that_shows_them() -> None:
    app = App(Options(mode="9ball", opponent="human", seed=0, colors="mono"))
    s = replace(app.state, box=Help())
    small = len(help_of(s, 80, 24))
    large = len(help_of(s, 200, 60))
    assert small > large >= 2  # the same pages, fewer on the larger screen
    _, seen_small = draw(s, 80, 24, Geometry())
    _, seen_large = draw(s, 200, 60, Geometry())
    far = s
    for k in range(small + 2):
        far = phases.key(far, Key("right"), float(k), seen_small)
    assert far.box == Help(small - 1)  # the small screen's last page
    # The large screen shows its own last page for it, and a step back from there.
    assert screen_text(draw(far, 200, 60, Geometry())[0][0]) == \
        screen_text(draw(replace(s, box=Help(large - 1)), 200, 60, Geometry())[0][0])
    back = phases.key(far, Key("left"), 20.0, seen_large)
    assert back.box == Help(large - 2)


def test_every_phase_has_its_keys() -> None:
    assert set(phases.KEYS) == set(Phase)


@pytest.mark.parametrize("cols, rows", [(80, 24), (120, 40), (45, 14)])
def test_the_layout_maps_a_cell_back_to_the_table_point_it_draws_there(cols, rows) -> None:
    app = App(Options(mode="practice", seed=4, colors="mono"))
    _, seen = draw(app.state, cols, rows, Geometry())
    lay = seen.layout
    table = app.state.match.table
    for x, y in ((0.3, 0.2), (table.length / 2, table.width / 2), (table.length - 0.1, 1.1)):
        px, py = lay.to_pixels(x, y)
        back = lay.to_table(int(px), int(py) // 2)
        # The centre of the cell: half a pixel across, a pixel up or down at most.
        assert abs(back[0] - x) <= 0.5 / lay.sx + 1e-12
        assert abs(back[1] - y) <= 1.0 / lay.sy + 1e-12
    col, row, _, _ = lay.panel_rect
    assert lay.to_table(col + 1, row) is None  # the panel is not the table
