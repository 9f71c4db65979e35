"""Help: the keys and the rules page of the game in play, in pages that fit the screen, in the
words the referees' verdicts use."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from termpool.rules import eight, nine
from termpool.rules.common import State
from termpool.rules.words import (
    BREAK_RAIL_BALLS,
    FOUL_LIMIT,
    KITCHEN,
    NO_HIT,
    NO_RAIL,
    PUSH_OUT_CHOICE,
    count_word,
    foul_warning,
    ordinal,
    rules_page,
    rules_text,
    voice,
)
from termpool.ui.app import App, Options
from termpool.ui.headless import screen_text
from termpool.ui.help import help_pages, key_lines, page_key, paginate
from termpool.ui.keys import Key
from termpool.ui.state import Help, help_of
from tests.test_rules import shot

ROOT = Path(__file__).resolve().parent.parent
MODES = ("8ball", "9ball", "practice")
TITLES = {"8ball": "8-ball rules", "9ball": "9-ball rules", "practice": "practice rules"}


def words(text: str) -> list[str]:
    return re.findall(r"[\w'-]+", text)


def app_in(mode: str | None, **kw) -> App:
    return App(Options(mode=mode, opponent="human", seed=0, colors="mono", **kw))


def help_screens(app: App, cols: int, rows: int) -> list[str]:
    """Every page of the help box as the screen shows it, turned with →."""
    app.key(Key("h"), 0.0)
    screens = [screen_text(app.cells(cols, rows)[0])]
    for k in range(1, len(help_of(app.state, cols, rows))):
        app.key(Key("right"), float(k))
        screens.append(screen_text(app.cells(cols, rows)[0]))
    return screens


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("cols, rows", [(80, 24), (40, 12), (120, 40)])
def test_h_shows_the_keys_then_the_whole_rules_page_of_the_game_in_play(mode, cols,
                                                                          rows) -> None:
    app = app_in(mode)
    screens = help_screens(app, cols, rows)
    n = len(screens)
    assert n >= 2 and f"keys · 1/{n}" in screens[0] and "shoot (hold to charge)" in screens[0]
    rules = [s for s in screens if TITLES[mode] in s]
    assert rules and all(t not in "".join(screens) for m, t in TITLES.items() if m != mode)
    # Each page is whole on the screen: its title, its last line and the way to close it.
    for k, s in enumerate(screens):
        assert f"{k + 1}/{n}" in s and "any other key closes" in s
        assert "┌" in s and "└" in s
    # Every word of the page is on some screen, in order.
    shown = [w for s in rules for line in s.splitlines() if "│" in line
             for w in words(line.split("│")[1])]
    want = [w for head, text in rules_page(mode, **_how(app)) for w in words(f"{head}: {text}")]
    assert _in_order(want, shown), mode


def box_text(screens: list[str]) -> str:
    """The text inside the help box of these screens, its lines joined by spaces."""
    inner = [line.split("│")[1].strip() for s in screens for line in s.splitlines()
             if line.count("│") >= 2]
    return " ".join(" ".join(inner).split())


def _how(app: App) -> dict:
    m = app.state.match
    return ({"three_foul": m.three_foul} if m.mode == "9ball" else
            {"eight_break": m.eight_break} if m.mode == "8ball" else {})


def _in_order(want: list[str], got: list[str]) -> bool:
    it = iter(got)
    return all(w in it for w in want)


def test_pages_turn_with_the_arrows_and_any_other_key_closes() -> None:
    app = app_in("9ball")
    help_screens(app, 80, 24)
    last = app.state.box.page
    assert last == len(help_of(app.state, 80, 24)) - 1 > 0
    app.key(Key("right"), 10.0)  # no page after the last
    assert app.state.box.page == last and isinstance(app.state.box, Help)
    app.key(Key("left"), 11.0)
    assert app.state.box.page == last - 1 and isinstance(app.state.box, Help)
    app.key(Key("x"), 12.0)
    assert app.state.box is None
    app.key(Key("h"), 13.0)  # opens at the keys again
    assert app.state.box.page == 0
    text = screen_text(app.cells(80, 24)[0])
    assert "keys · 1/" in text


@pytest.mark.parametrize("mode", [*MODES, None])
@pytest.mark.parametrize("cols, rows", [(80, 24), (60, 20), (120, 40)])
def test_every_help_page_is_a_box_of_the_same_size_and_place(mode, cols, rows) -> None:
    def frame(text: str) -> tuple:
        lines = text.split("\n")
        top = next(k for k, x in enumerate(lines) if "┌" in x)
        bottom = next(k for k, x in enumerate(lines) if "└" in x)
        return top, bottom, lines[top].index("┌"), lines[top].index("┐")

    screens = help_screens(app_in(mode), cols, rows)
    assert len(screens) > 1
    assert len({frame(x) for x in screens}) == 1, [frame(x) for x in screens]


def test_a_help_of_one_page_closes_on_any_key() -> None:
    keys = [("Q", "quit")]
    assert page_key("right", 0, 1) == (0, True)
    assert page_key("right", 0, 3) == (1, False) and page_key("left", 0, 3) == (0, False)
    assert page_key("q", 1, 3) == (1, True)
    (page,) = help_pages(keys, None, 80, 24)[:1]
    assert page[0].startswith("keys")


def test_the_menu_s_help_has_every_game_s_rules() -> None:
    app = app_in(None)
    app.key(Key("h"), 0.0)  # at the menu, H opens the help too
    screens = help_screens(app_in(None), 80, 24)
    joined = "".join(screens)
    assert all(t in joined for t in TITLES.values())


def test_the_page_says_how_the_game_in_play_is_set() -> None:
    on = box_text(help_screens(app_in("9ball", three_foul=True), 120, 40))
    off = box_text(help_screens(app_in("9ball"), 120, 40))
    assert "Three fouls: on in this game" in on and "Three fouls: off in this game" in off
    rerack = box_text(help_screens(app_in("8ball", eight_break="rerack"), 120, 40))
    assert "the balls are re-racked and the breaker breaks again" in rerack
    assert "re-spotted and the breaker shoots on" not in rerack
    classic = box_text(help_screens(app_in("8ball", theme="classic"), 120, 40))
    assert "the reds (1-7) or the yellows (9-15)" in classic


# ------------------------------------------------------------- the same words as the referee

BREAK = State(mode="8ball", is_break=True)
NINE = State(mode="9ball")


def test_break_cushion_count_is_the_one_the_page_states() -> None:
    rails = [f"{b}|" for b in ("2", "3", "4", "5", "6")[:BREAK_RAIL_BALLS]]
    for judge, state in ((eight.judge, BREAK), (nine.judge, State(mode="9ball",
                                                                  is_break=True))):
        ok, _ = judge(state, shot("cue-1", *rails, is_break=True))
        short, _ = judge(state, shot("cue-1", *rails[:-1], is_break=True))
        assert ok.foul is None and short.foul == "illegal_break"
        assert f"({BREAK_RAIL_BALLS} needed)" in short.reason
    for mode in ("8ball", "9ball"):
        assert f"at least {count_word(BREAK_RAIL_BALLS)} object balls" in "".join(
            text for _, text in rules_page(mode))


def test_three_fouls_lose_at_the_count_the_page_states() -> None:
    page = dict(rules_page("9ball", three_foul=True))["Three fouls"]
    assert f"{count_word(FOUL_LIMIT)} fouls in a row" in page
    assert f"on {count_word(FOUL_LIMIT - 1)}" in page
    for before in range(FOUL_LIMIT):
        st = State(mode="9ball", three_foul=True, fouls=(before, 0))
        out, _ = nine.judge(st, shot("cue-3", "3|"))  # the 1 is on: a foul
        lost = before + 1 >= FOUL_LIMIT
        assert (out.winner == 1) is lost
        assert (f"{ordinal(FOUL_LIMIT)} consecutive foul" in out.reason) is lost
    from termpool.game import Match

    m = Match("9ball", three_foul=True)
    m.state = State(mode="9ball", three_foul=True, fouls=(FOUL_LIMIT - 1, 0))
    warning = foul_warning(voice(m.players), m.warning())
    assert f"a {ordinal(FOUL_LIMIT)} foul in a row loses the frame" in warning


def test_fouls_ball_in_hand_and_push_out_are_said_alike() -> None:
    eight_page = " ".join(text for _, text in rules_page("8ball"))
    nine_page = " ".join(text for _, text in rules_page("9ball"))
    groups = State(mode="8ball", groups={0: "solids", 1: "stripes"})
    for judge, state, page in ((eight.judge, groups, eight_page), (nine.judge, NINE, nine_page)):
        out, _ = judge(state, shot("cue|"))
        assert NO_HIT in out.reason and NO_HIT in page
        out, _ = judge(state, shot("cue-1"))
        assert NO_RAIL in out.reason and NO_RAIL in page
    out, _ = eight.judge(BREAK, shot("cue-1", "3>side_left", "cue>head_left", is_break=True))
    assert f"ball in hand {KITCHEN}" in out.reason
    assert f"scratch on the break gives the other player ball in hand {KITCHEN}" in eight_page
    out, _ = nine.judge(State(mode="9ball", push_out="declared"), shot("cue|"))
    assert out.option == "shoot_or_pass" and f"chooses {PUSH_OUT_CHOICE}" in out.reason
    assert f"chooses {PUSH_OUT_CHOICE}" in nine_page


# ------------------------------------------------------------------------------- the layout


def test_key_lines_go_to_two_columns_when_one_is_too_tall() -> None:
    rows = [(f"k{n}", f"does thing {n}") for n in range(30)]
    assert len(key_lines(rows, 80, 40)) == 30
    two = key_lines(rows, 80, 20)
    assert len(two) == 15 and all(len(s) <= 80 - 6 for s in two)


def test_pages_break_at_paragraphs_and_never_lose_a_line() -> None:
    lines = ["a1", "a2", "", "b1", "b2", "b3", "", "c1"]
    assert paginate(lines, 5) == [["a1", "a2"], ["b1", "b2", "b3", "", "c1"]]
    lines = ["a1", "a2", "a3", "", "b1", "b2", "b3"]
    assert paginate(lines, 5) == [["a1", "a2", "a3"], ["b1", "b2", "b3"]]
    long = [f"l{n}" for n in range(12)]
    assert sum(paginate(long, 5), []) == long and max(map(len, paginate(long, 5))) == 5


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "termpool", *args], capture_output=True,
                          text=True, cwd=ROOT, timeout=60)


def test_rules_command_prints_the_pages() -> None:
    p = cli("rules", "9ball")
    assert p.returncode == 0 and p.stdout.splitlines() == rules_text("9ball")
    p = cli("rules")
    assert all(f"{m} rules" in p.stdout for m in ("8-ball", "9-ball", "practice"))
    assert max(len(s) for s in p.stdout.splitlines()) <= 80
    assert cli("rules", "snooker").returncode == 2


def test_rules_text_wraps_to_the_width_asked() -> None:
    for mode in MODES:
        lines = rules_text(mode, 60)
        assert lines[0] == TITLES[mode] and max(map(len, lines)) <= 60
    with pytest.raises(ValueError, match="mode"):
        rules_page("snooker")


def test_the_keys_page_wraps_at_80_columns_and_cuts_nothing() -> None:
    from termpool.ui.app import App, Options
    from termpool.ui.controls import ACTIONS
    from termpool.ui.headless import screen_text
    from termpool.ui.keys import Key

    app = App(Options(mode="8ball", opponent="cpu", colors="mono", seed=0))
    app.key(Key("h"), 0.0)
    text = screen_text(app.cells(80, 24)[0])
    assert "…" not in text
    words = " ".join(line.strip("│ ") for line in text.splitlines())
    for desc in ACTIONS.values():  # each whole, however it wrapped
        assert all(w in words.split() for w in desc.split()), desc


def test_the_rules_page_explains_the_pocket_names_as_the_screen_shows_them() -> None:
    from termpool.game import Match
    from termpool.rules.words import rules_page
    from termpool.ui.table_view import layout

    for mode in ("8ball", "9ball", "practice"):
        (text,) = [t for head, t in rules_page(mode) if head == "Pockets"]
        assert "head is the end you break from" in text
    # What the page says of the screen: the head at the left, the left pockets along the top.
    m = Match("8ball", seed=0)
    lay = layout(80, 24, m.table)
    names = list(m.table.hole_names)
    c = m.table.hole_c.reshape(-1, 2)

    def cell(name):
        x, y = c[names.index(name)]
        return lay.px + x * lay.sx, lay.py + (m.table.width - y) * lay.sy  # column, half-row

    assert cell("head_left")[0] < cell("side_left")[0] < cell("foot_left")[0]
    assert cell("head_left")[1] < cell("head_right")[1]
    assert cell("foot_left")[1] < cell("foot_right")[1]
    assert m.table.head_spot[0] < m.table.length / 2  # the break is from the head's end


def test_practice_key_help_names_take_back_and_re_rack_where_they_fit() -> None:
    from termpool.ui.app import App, Options
    from termpool.ui.headless import screen_text
    from termpool.ui.keys import Key

    for input_mode in ("release", "repeat"):
        app = App(Options(mode="practice", opponent="human", colors="mono", seed=0),
                  input_mode=input_mode)
        app.key(Key("enter"), 0.0)
        hint = screen_text(app.cells(80, 24)[0]).splitlines()[-1]
        assert "U undo" in hint and "R rack" in hint and hint.strip().endswith("Q quit")
        hint = screen_text(app.cells(160, 50)[0]).splitlines()[-1]
        assert "U take back" in hint and "R re-rack" in hint
    app = App(Options(mode="8ball", opponent="human", colors="mono", seed=0))
    app.key(Key("enter"), 0.0)
    assert "take back" not in screen_text(app.cells(160, 50)[0])


def test_practice_key_help_names_take_back_with_the_ball_in_hand_too() -> None:
    """Ball in hand in practice (its start, or after a scratch, where a take-back is most
    wanted): U and R are on the key line as they are while aiming."""
    from termpool.ui.app import App, Options
    from termpool.ui.headless import screen_text
    from termpool.ui.state import Phase

    app = App(Options(mode="practice", opponent="human", colors="mono", seed=0))
    assert app.state.phase is Phase.PLACE
    for cols, rows in ((80, 24), (60, 20)):
        hint = screen_text(app.cells(cols, rows)[0]).splitlines()[-1]
        assert "Enter place" in hint and "U " in hint and "R " in hint, hint
    app = App(Options(mode="8ball", opponent="human", colors="mono", seed=0))
    assert app.state.phase is Phase.PLACE
    hint = screen_text(app.cells(160, 50)[0]).splitlines()[-1]
    assert "Enter place" in hint and "take back" not in hint and "U " not in hint, hint


def _keys_page(app: App) -> str:
    app.key(Key("h"), 0.0)
    text = screen_text(app.cells(120, 40)[0])
    app.key(Key("esc"), 0.1)
    return " ".join(" ".join(line.strip("│ ").split()) for line in text.splitlines())


def test_the_keys_page_says_g_cycles_the_three_aid_levels() -> None:
    app = app_in("8ball")
    app.key(Key("enter"), 0.0)  # the cue ball placed: the aim, where G acts
    page = _keys_page(app)
    assert "G aim aid: every path, then the ghost ball only, then off (cycles)" in page
    seen = []
    for k in range(3):  # ... as G does
        app.key(Key("g"), 1.0 + k)
        seen.append(app.state.opts.aid)
    assert seen == ["ghost", "off", "full"]


def test_the_keys_page_lists_the_power_digits_unless_they_are_bound() -> None:
    from termpool.ui.controls import KeyMap

    app = app_in("8ball")
    app.key(Key("enter"), 0.0)
    assert "1-9, 0 power 10-90 %, 0: 100 %; then Space strikes" in _keys_page(app)
    for digit, level in (("3", 0.3), ("9", 0.9), ("0", 1.0)):  # ... as they do
        app.key(Key(digit), 1.0)
        assert app.state.controls.charge.preset_level == pytest.approx(level)
    bound = App(Options(mode="8ball", opponent="human", seed=0, colors="mono"),
                keymap=KeyMap({"rerack": ["1"]}))
    assert "1-9, 0" not in _keys_page(bound)  # "1" re-racks: the row would be wrong


def _within(entry: list[str], pages: list[list[str]]) -> bool:
    n = len(entry)
    return any(p[k:k + n] == entry for p in pages for k in range(len(p) - n + 1))


@pytest.mark.parametrize(("cols", "rows"), [(50, 16), (60, 20), (80, 24), (120, 40)])
def test_no_key_or_paragraph_is_split_across_pages_where_it_fits_one(cols, rows) -> None:
    from termpool.ui.app import App, Options
    from termpool.ui.help import BOX_ROWS, key_entries, keymap_rows, rules_lines
    from termpool.ui.state import help_of

    for mode in ("8ball", "9ball"):
        app = App(Options(mode=mode, opponent="human", colors="mono"))
        pages = [lines[:-2] for _, lines in help_of(app.state, cols, rows)]  # no footers
        height = rows - BOX_ROWS
        keys = key_entries(keymap_rows(app.state.keymap), cols, height)
        how = {"three_foul": False} if mode == "9ball" else {"eight_break": "respot"}
        paragraphs = [p.split("\n") for p in
                      "\n".join(rules_lines(mode, cols - 6, theme="standard", **how))
                      .split("\n\n")]
        for entry in keys + paragraphs:
            assert len(entry) > height or _within(entry, pages), entry


def test_a_page_after_the_keys_says_what_the_aim_aids_lines_are() -> None:
    from termpool.ui.state import help_of

    app = App(Options(mode="8ball", colors="mono"))
    pages = help_of(app.state, 100, 40)
    (aid,) = [lines for title, lines in pages if title.startswith("the aim aid")]
    text = " ".join(" ".join(line.split()) for line in aid)
    assert "Pink" in text and "the cue ball after the hit" in text and "ring (o)" in text
