"""What the screen fits at 80x24, 60x20 and below: verdicts wrapped whole, every key of a
phase on the key bar, the menu's tenth item by a key, the 'too small' words."""

from __future__ import annotations

from dataclasses import replace

import pytest

from termpool.ui.app import App, Options
from termpool.ui.headless import screen_text
from termpool.ui.keys import Key
from termpool.ui.panel import fit_status, too_small_lines
from termpool.ui.state import Phase
from termpool.ui.table_view import MIN_COLS, MIN_ROWS, layout
from termpool.ui.view import hint_lines

# Verdicts as the referee says them in 9-ball games, each two rows or more at 80 columns.
LONG_FOUL = ("Foul: the cue ball hit the 4 first, not the lowest ball, the 3; the 3 and the 7 "
             "pocketed on a foul stay down; Computer has ball in hand")
LONG_BREAK = ("legal break: 10 object balls reached a cushion, nothing pocketed; the table is "
              "open and it is Computer's turn")
SCRATCH = ("Foul: scratch: the cue ball went into the right head pocket; the 2 stays down; "
           "Computer has ball in hand")


def app_for(mode: str = "9ball", colors: str = "mono", **kw) -> App:
    app = App(Options(mode=mode, opponent="human" if mode == "practice" else "cpu",
                      colors=colors, seed=3, **kw), input_mode="release")
    app.key(Key("enter"), 0.0)  # ball in hand placed: aiming
    assert app.state.phase is Phase.AIM
    return app


def panel_rows(app: App, cols: int, rows: int) -> list[str]:
    lay = layout(cols, rows, app.state.match.table)
    text = screen_text(app.cells(cols, rows)[0]).split("\n")
    return [line.strip() for line in text[lay.panel_rect[1]:]]


def joined(rows: list[str]) -> str:
    return " ".join(" ".join(rows).split())


# ------------------------------------------------------------------- verdicts wrapped whole

def test_a_verdict_takes_the_power_line_s_row_to_wrap_whole() -> None:
    status = [("You to shoot · the 3 is on", "turn"), ("power 50% · first ball: the 3", "dim"),
              (LONG_FOUL, "foul")]
    out = fit_status(status, 3, 77)
    assert [t for t, _ in out][0] == status[0][0]
    assert " ".join(t for t, _ in out[1:]) == LONG_FOUL  # whole, over two rows
    assert all("…" not in t for t, _ in out)


def test_a_key_s_answer_keeps_its_row_before_the_power_line() -> None:
    """Tab's answer at 80x24 beside a warning: the answer to the key just pressed shows, the
    power line (always there) gives way until the aim moves."""
    answer = "the 6 is in the way of the 2, the only ball you may hit: a cushion first?"
    status = [("You to shoot · the 2 is on", "turn"),
              ("As aimed, a foul: the cue ball hit the 6 first, not the lowest ball, the 2",
               "warn"),
              ("power 60% · first ball: the 6", "dim"), (answer, "note")]
    out = [t for t, _ in fit_status(status, 3, 77)]
    assert out == [status[0][0], status[1][0], answer]
    out = [t for t, _ in fit_status(status, 4, 77)]
    assert out == [t for t, _ in status]  # room for all: in their order


def test_a_warning_and_a_verdict_each_keep_a_row_before_either_wraps() -> None:
    status = [("You to shoot", "turn"), (LONG_BREAK, "foul"), ("power 50%", "dim"),
              (LONG_FOUL, "plain")]
    out = [t for t, _ in fit_status(status, 4, 77)]
    assert out[0] == "You to shoot"
    assert " ".join(out[1:3]) == LONG_BREAK  # the first whole
    assert LONG_FOUL.startswith(out[3].rstrip("…")) and out[3].endswith("…")


@pytest.mark.parametrize(("cols", "rows", "verdict"),
                         [(80, 24, LONG_FOUL), (80, 24, LONG_BREAK), (80, 24, SCRATCH),
                          (60, 20, LONG_BREAK), (60, 20, SCRATCH)])
@pytest.mark.parametrize("colors", ["mono", "truecolor"])
def test_at_80x24_and_60x20_the_verdict_reads_whole(cols, rows, verdict, colors) -> None:
    app = app_for(colors=colors)
    app.state = replace(app.state, message=((verdict, "foul"),))
    shown = panel_rows(app, cols, rows)
    text = joined(shown)
    assert verdict in text, "\n".join(shown)
    assert "You to break" in text
    assert shown[-1].endswith("Q quit")  # and the keys' line stays


@pytest.mark.parametrize("colors", ["mono", "truecolor"])
def test_at_60x20_a_verdict_three_rows_long_takes_the_keys_row_to_read_whole(colors) -> None:
    # On your own turn: what to do, then the verdict; the keys' line gives way (H still
    # opens the help) rather than cut what the rule said.
    app = app_for(colors=colors)
    app.state = replace(app.state, message=((LONG_FOUL, "foul"),))
    shown = panel_rows(app, 60, 20)
    assert LONG_FOUL in joined(shown) and "You to break" in joined(shown), "\n".join(shown)
    assert not any("…" in line for line in shown)


@pytest.mark.parametrize(("cols", "rows"), [(80, 24), (60, 20)])
def test_a_warning_of_the_shot_aimed_reads_whole_beside_the_last_verdict(cols, rows) -> None:
    warning = ("As aimed: the cue ball hit the 9 first, not the lowest ball, the 4; third foul "
               "in a row: Computer wins the frame")
    app = app_for()
    app.state = replace(app.state, message=((warning, "foul"), (LONG_BREAK, "plain")))
    text = joined(panel_rows(app, cols, rows))
    assert warning in text and "You to break" in text
    assert "legal break: 10 object balls" in text  # the older verdict: its first row at least


@pytest.mark.parametrize("first", ["Your shot", "Computer is aiming at the 2"])
def test_a_dim_first_line_gives_way_to_a_verdict_three_rows_long(first) -> None:
    # At 60x20 while the balls run or the computer aims: the key bar says F and "any key",
    # the players' row whose turn it is; the verdict reads whole.
    verdict = ("Foul: the cue ball hit the 4 first, not the lowest ball, the 1; the 8 pocketed "
               "on a foul; Computer has ball in hand")
    status = [(first, "dim"), (verdict, "foul"), ("Computer: 1 in the top-right corner", "dim")]
    out = [t for t, _ in fit_status(status, 3, 57)]
    assert " ".join(out) == verdict


@pytest.mark.parametrize(("cols", "rows"), [(80, 24), (60, 20)])
def test_back_in_a_match_reads_beside_a_warning_and_the_last_verdict(cols, rows) -> None:
    # A player back in an online match on two fouls: the warning, the news and the last
    # verdict compete; the news is said once and reads whole.
    from termpool.ui.phases.remote import back_in

    app = app_for(three_foul=True)
    m = app.state.match
    m.state = replace(m.state, fouls=(2, 0))
    news = back_in(app.state, 0)
    app.state = replace(app.state, message=(news, (SCRATCH, "foul")))
    text = joined(panel_rows(app, cols, rows))
    assert news[0] in text and "two fouls" in text, text
    assert "Foul: scratch" in text


def test_news_before_the_verdict_keeps_its_row_while_the_verdict_wraps() -> None:
    # A player back in an online match: what to do, the news, then the last verdict.
    status = [("bob to shoot · ball in hand anywhere", "turn"),
              ("back in your match against ann", "turn"), (SCRATCH, "foul"),
              ("power 50%", "dim")]
    out = [t for t, _ in fit_status(status, 3, 77)]
    assert out[:2] == [status[0][0], status[1][0]]
    assert SCRATCH.startswith(out[2].rstrip("…"))
    out = [t for t, _ in fit_status(status, 4, 77)]
    assert " ".join(out[2:]) == SCRATCH


@pytest.mark.parametrize(("cols", "rows"), [(80, 24), (60, 20)])
def test_the_computer_s_plan_gives_its_row_to_the_foul_it_led_to(cols, rows) -> None:
    # Ball in hand after the computer's scratch: its plan, then the verdict, as the match
    # says them; the verdict reads whole, the plan waits.
    app = App(Options(mode="9ball", opponent="cpu", colors="mono", seed=3),
              input_mode="release")
    note = (("Computer: 5 in the bottom-right corner pocket", "turn"),)
    verdict = "Foul: scratch: the cue ball went into the top-right corner pocket; you have " \
        "ball in hand"
    app.state = replace(app.state, shot_note=note, message=(*note, (verdict, "foul")))
    assert app.state.phase is Phase.PLACE
    text = joined(panel_rows(app, cols, rows))
    assert verdict in text and "You to break" in text, text


# --------------------------------------------------------------------------- the key bar

@pytest.mark.parametrize("mode", ["practice", "9ball", "8ball"])
def test_at_80_columns_every_key_of_the_aim_shows(mode) -> None:
    app = app_for(mode)
    bar = panel_rows(app, 80, 24)[-1]
    for key in ("aim", "Space", "1-0", "spin", "G aid", "H help", "P pause", "Q quit"):
        assert key in bar, bar
    if mode == "practice":
        assert "U undo" in bar and "R rack" in bar, bar


@pytest.mark.parametrize("level", ["0", "4"])  # a power set by a digit: Esc goes back to hold
def test_at_60_columns_practice_keeps_undo_and_rack(level) -> None:
    app = app_for("practice")
    app.key(Key(level), 0.1)
    bar = panel_rows(app, 60, 20)[-1]
    for key in ("aim", "Space", "U undo", "R rack", "H help", "Q quit"):
        assert key in bar, bar
    if level == "4":
        assert "Esc hold" in bar, bar


@pytest.mark.parametrize("level", ["0", "4"])
def test_at_80_columns_practice_with_a_digit_s_power_keeps_esc_and_pause(level) -> None:
    app = app_for("practice")
    app.key(Key(level), 0.1)
    bar = panel_rows(app, 80, 24)[-1]
    for key in ("aim", "Space", "Esc hold", "spin", "G aid", "U undo", "R rack", "H help",
                "P pause", "Q quit"):
        assert key in bar, bar


def test_the_key_bar_is_parts_whole_in_one_of_their_forms() -> None:
    app = app_for("practice")
    bar = panel_rows(app, 80, 24)[-1]
    forms = {f for t, _ in hint_lines(app.state) for f in ((t,) if isinstance(t, str) else t)}
    rest = bar
    while rest:  # the bar is forms one space apart, in order, none cut
        head = max((f for f in forms if rest.startswith(f)), key=len)
        rest = rest[len(head):].lstrip(" ")


# ------------------------------------------------------------------------- the cue stick

@pytest.mark.parametrize(("cols", "rows"), [(80, 24), (60, 20), (120, 40)])
def test_the_stick_is_drawn_on_no_cell_a_ball_is_drawn_in(cols, rows) -> None:
    # Balls strewn about (a rack's worth, some touching the cue ball's line), the stick at
    # every angle and pull: every cell that shows part of a ball shows it as without the stick.
    import numpy as np

    import termpool.ui.overlay as ov
    from termpool.ui.canvas import to_cells
    from termpool.ui.table_view import TableView

    m = app_for(colors="truecolor").state.match
    lay = layout(cols, rows, m.table)
    view = TableView(m.table, lay)
    rng = np.random.default_rng(7)
    for trial in range(60):
        pos = m.pos.copy()
        pos[:, 0] = rng.uniform(0.1, m.table.length - 0.1, len(pos))
        pos[:, 1] = rng.uniform(0.1, m.table.width - 0.1, len(pos))
        angle = float(rng.uniform(0.0, 360.0))
        back = -np.array([np.cos(np.radians(angle)), np.sin(np.radians(angle))])
        pos[1] = pos[0] + back * 4 * m.radius[0]  # a ball right behind the cue ball
        bare = view.draw(m.ids, pos, None, m.radius).copy()
        cv = bare.copy()
        ov.draw_cue_stick(cv, lay, pos[0], m.radius[0], angle, float(rng.uniform(0.0, 1.0)))
        assert (cv.rgb != bare.rgb).any()  # the stick is drawn ...
        ball = ov._IS_BALL[bare.tag]
        in_ball = ball[0::2] | ball[1::2]
        for a, b in zip(to_cells(cv), to_cells(bare), strict=True):
            same = a == b if a.ndim == 2 else (a == b).all(axis=-1)
            assert same[in_ball].all(), trial  # ... on no cell of a ball

# ------------------------------------------------------------------------------ the menu

def test_0_picks_the_menu_s_tenth_item_and_the_menu_shows_it_as_0() -> None:
    from termpool.ui.phases import menu
    from termpool.ui.state import MENU, State

    app = App(Options(colors="mono"), input_mode="release")
    s = app.state
    assert s.phase is Phase.MENU
    ten = replace(s, link=object())  # under a server the menu has its tenth item
    entries = [e for e in MENU]
    assert len(entries) == 10 and entries[9][1] == "quit"
    picked = menu.key(ten, Key("0"), None, 0.0)
    assert isinstance(picked, State) and picked.done and picked.menu_index == 9
    nine = menu.key(s, Key("0"), None, 0.0)  # nine items: 0 picks nothing
    assert not nine.done and nine.menu_index == s.menu_index
    text = screen_text(app.cells(80, 24)[0])
    assert "9. Quit" in text
    app.state = ten
    text = screen_text(app.cells(80, 24)[0])
    assert "0. Quit" in text and "10." not in text


# -------------------------------------------------------------------- too small a window

@pytest.mark.parametrize(("cols", "rows"), [(c, r) for c in range(10, MIN_COLS)
                                            for r in range(3, MIN_ROWS)])
def test_the_too_small_words_fit_whole_down_to_10x3(cols, rows) -> None:
    lines = too_small_lines(cols, rows)
    assert len(lines) <= rows and all(len(s) <= cols for s in lines)
    text = " ".join(lines)
    assert f"{MIN_COLS}x{MIN_ROWS}" in text and f"{cols}x{rows}" in text


def test_a_20x6_window_says_how_big_it_must_be_whole_on_screen() -> None:
    app = App(Options(colors="mono", mode="9ball"), input_mode="release")
    app.key(Key("enter"), 0.0)
    text = screen_text(app.cells(20, 6)[0])
    assert "40x12" in text and "20x6" in text and "small" in text


# ------------------------------------------------------------------ a player's balls

@pytest.mark.parametrize("mono", [False, True])
def test_a_ball_pocketed_stays_in_its_place_dim_and_moves_no_other(mono) -> None:
    from termpool.ui.palette import DIM_TEXT_C
    from termpool.ui.panel import PanelInfo, PlayerLine, player_line

    ids = ["cue", *map(str, range(1, 16))]
    info = PanelInfo("t", [], [], [], ids)
    stripes = [ids.index(str(n)) for n in range(9, 16)]
    down = [ids.index(n) for n in ("10", "11", "15")]
    p = PlayerLine("You", "stripes", [k for k in stripes if k not in down], down)
    line = player_line(p, info, mono, 80)
    balls = [(t.strip().lstrip("●◐◉"), fg) for t, fg, _ in line[2:] if t.strip()]
    assert [b for b, _ in balls] == [str(n) for n in range(9, 16)]  # in order, none moved
    for b, fg in balls:
        assert (fg == DIM_TEXT_C.rgb) == (b in ("10", "11", "15"))


def test_a_spare_key_hint_shows_only_where_every_part_fits_whole():
    """A part of rank SPARE is there when the whole line fits in long forms, and gone,
    leaving the rest exactly as without it, when it does not."""
    from termpool.ui.panel import SPARE, fit_hint

    parts = [(("Space: hold, let go", "Space:hold"), 0), ("G aid", 2), ("Q quit", 0)]
    with_spare = [*parts[:1], ("Tab next ball", SPARE), *parts[1:]]
    wide = fit_hint(with_spare, 80)
    assert wide == "Space: hold, let go  Tab next ball  G aid  Q quit"
    for width in (40, 30, 20, 12):
        assert fit_hint(with_spare, width) == fit_hint(parts, width)
        assert "Tab" not in fit_hint(with_spare, width)


@pytest.mark.parametrize(("cols", "rows"), [(80, 24), (100, 32), (120, 40)])
def test_both_players_lines_show_their_balls_down_alike(cols, rows):
    """Groups taken and two balls of each down: where one player's line has room for its
    balls down (dim, in their places) and the other's has not, neither shows them."""
    from termpool.ui.phases.turn import start_turn

    app = App(Options(mode="8ball", opponent="cpu", colors="mono", seed=1))
    m = app.state.match
    m.state = replace(m.state, is_break=False, groups={0: "solids", 1: "stripes"})
    m.ball_in_hand = None
    for b in ("3", "5", "12", "15"):
        m.on_table[m.ids.index(b)] = False
    app.state = start_turn(app.state)
    (line,) = [x for x in screen_text(app.cells(cols, rows)[0]).splitlines() if "solids" in x]
    you, cpu = line.split("Computer")
    assert ("3" in you.split("solids")[1]) == ("12" in cpu)


def test_the_status_keeps_two_blank_columns_before_the_spin_face():
    """Status lines wrapped at every offset (a word of each length before them) never read
    on into the spin face's words: the two columns before them are blank on every row, and
    some row's text comes right up to them."""
    from termpool.ui.panel import blank_cells, draw_panel
    from termpool.ui.view import panel_info

    app = app_for(colors="truecolor")
    lay = layout(120, 40, app.state.match.table)
    info = panel_info(app.state, lay)
    assert [name for _, name in info.widgets] == ["spin"]
    reached = False
    for pad in range(12):
        text = "x" * (pad + 1) + " " + LONG_FOUL + " " + LONG_BREAK
        cells = blank_cells(120, 40, False)
        draw_panel(cells, lay, replace(info, status=[(text, "warn"), (text, "foul")]))
        rows = screen_text(cells[0]).splitlines()
        readout = [r for r in rows if "side " in r or "top  " in r]
        assert len(readout) == 2
        for row in readout:
            col = row.index("side ") if "side " in row else row.index("top  ")
            assert row[col - 2:col] == "  ", row
            reached |= row[col - 3] != " "
    assert reached


@pytest.mark.parametrize(("cols", "rows"), [(80, 24), (120, 40), (60, 20)])
def test_each_pocket_s_words_say_where_the_screen_draws_it(cols, rows):
    """"top"/"bottom" and "left"/"right" in a pocket's spoken name are where its hole is
    drawn on screen (a side pocket is midway along)."""
    from termpool.rules.words import spoken_pocket

    app = app_for()
    table = app.state.match.table
    lay = layout(cols, rows, table)
    px, py = lay.to_pixels(table.hole_c[:, 0], table.hole_c[:, 1])
    mid_x, mid_y = px.mean(), py.mean()
    for k, name in enumerate(table.hole_names):
        words = spoken_pocket(name)
        assert ("top" in words) == (py[k] < mid_y), (name, words)  # pixel rows grow down
        assert ("bottom" in words) == (py[k] > mid_y), (name, words)
        if "side" in words:
            assert abs(px[k] - mid_x) < 2, (name, words)
        else:
            assert ("left" in words) == (px[k] < mid_x), (name, words)
