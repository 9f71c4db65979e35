"""What the app shows: its state drawn as screen cells (table, aim aids, panel, boxes, menu).

`cells(app, cols, rows)` is all the app needs; everything here reads the app and its match
and changes nothing but the app's `dirty` flag and its layout cache.
"""

from __future__ import annotations

from termpool.game.layout import head_string
from termpool.rules import words
from termpool.rules.common import legal_targets
from termpool.rules.words import KITCHEN, MODE_NAMES
from termpool.ui.canvas import put_text, to_cells
from termpool.ui.frame import message_cells, too_small_lines
from termpool.ui.palette import DIM_TEXT_C, TEXT_C
from termpool.ui.panel import (
    TURN_C,
    PanelInfo,
    PlayerLine,
    blank_cells,
    draw_box,
    draw_panel,
    widget_fits,
)


def cells(app, cols: int, rows: int):
    """The whole screen for the app's state: (chars, fg, bg), fg and bg None in mono."""
    app.dirty = False
    mono = app.depth == "mono"
    if app.phase == "menu" or app.match is None:
        out = _menu_cells(app, cols, rows, mono)
    else:
        lay, view = app._geometry(cols, rows)
        if lay is None:
            out = message_cells(cols, rows, too_small_lines(cols, rows), mono)
        else:
            out = _table_cells(app, lay, view, mono)
            draw_panel(out, lay, panel_info(app, lay), mono)
            _question(app, out)
    if app.overlay == "help":
        pages = help_pages(app, cols, rows)
        app.help_count = len(pages)  # for the keys that turn them
        app.help_page = min(app.help_page, len(pages) - 1)
        draw_box(out, pages[app.help_page][1], pages[app.help_page][0], wrap=False)
    elif app.overlay == "pause":
        draw_box(out, ["paused", "", "S: settings · any other key to go on"], "pause")
    elif app.screen is not None:  # settings, stats
        draw_box(out, app.screen.lines(app, cols, rows), app.screen.title, wrap=False)
    elif app.overlay == "quit":  # drawn even over "make the window bigger": Q must show
        draw_box(out, ["Quit termpool?", "", "y: quit    n: keep playing    m: menu"], "quit")
    return out


ARROWS = {"left": "←", "right": "→", "up": "↑", "down": "↓"}


def pretty(spec: str) -> str:
    """A key spec as the screen shows it: "left" -> "←", "shift+up" -> "⇧↑", "space" ->
    "Space", "w" -> "W"."""
    *mods, name = spec.split("+") if spec != "+" else ["+"]
    base = ARROWS.get(name) or (name.capitalize() if len(name) > 1 else name.upper())
    return "".join({"shift": "⇧", "ctrl": "^", "alt": "M-"}.get(m, m) for m in mods) + base


def help_pages(app, cols: int, rows: int) -> list[tuple[str, list[str]]]:
    """The help box's pages (ui.help): the keys, then the rules of the game in play as it is
    set (at the menu, of every game)."""
    from termpool.ui import help as box

    mode = app.match.mode if app.match is not None and app.phase != "menu" else None
    how = {"theme": app.opts.theme}
    if mode == "9ball":
        how["three_foul"] = app.match.three_foul
    elif mode == "8ball":
        how["eight_break"] = app.match.eight_break
    return box.help_pages(box.keymap_rows(app.keymap), mode, cols, rows, **how)


def _table_cells(app, lay, view, mono: bool):
    from termpool.ui import overlay as ov

    m = app.match
    pos, state = app._positions()
    c = app.cue_index()
    aiming = app.phase == "aim" or (app.phase == "cpu" and app._cpu_plan not in (None,
                                                                                  "done"))
    pred = app.prediction() if aiming and m.on_table[c] else None
    level = app.aid_level()
    called = _called_pocket(app) if aiming else None
    kitchen = app.phase == "place" and m.ball_in_hand == "kitchen"
    if mono:
        chars = view.mono(m.ids, pos, state, m.radius)
        if kitchen:
            ov.mono_head_string(chars, lay, head_string(m.table))
        if pred is not None:
            ov.mono_prediction(chars, lay, pred, level, float(m.radius[c]))
        if called is not None:
            ov.mono_called_pocket(chars, lay, m.table.hole_c.reshape(-1, 2)[called])
        return chars, None, None
    cv = view.draw(m.ids, pos, state, m.radius)
    if kitchen:
        ov.draw_head_string(cv, lay, head_string(m.table))
    if called is not None:
        ov.draw_called_pocket(cv, lay, m.table.hole_c.reshape(-1, 2)[called],
                              m.table.hole_r[called])
    if aiming and m.on_table[c]:
        if pred is not None:
            ov.draw_prediction(cv, lay, pred, m.radius[c], level)
        pull = app.charge.level(app.now) if app.charge.active else 0.0
        ov.draw_cue_stick(cv, lay, m.pos[c], m.radius[c], app.angle, pull)
    if app.phase == "place":
        ok = app.match.placement_error(*app.cursor) is None
        ov.draw_placement(cv, lay, app.cursor, m.radius[c], ok)
    cells = to_cells(cv)
    view.numbers(cells, m.ids, pos, state, m.radius)
    return cells


def _called_pocket(app) -> int | None:
    """The index of the pocket called for the 8 on this shot (the human's call, or the
    computer's plan), None when no call is needed."""
    names = list(app.match.table.hole_names)
    if app.phase == "aim" and app.match.needs_call():
        return names.index(app._called()[1])
    plan = getattr(app, "_cpu_plan", None)
    if app.phase == "cpu" and getattr(plan, "called", None):
        return names.index(plan.called[1])
    return None


def _question(app, cells) -> None:
    if app.phase == "option":
        draw_box(cells, words.option_lines(app.match.option), "your call")
    elif app.phase == "over":
        m = app.match
        why = app.message[-1][0] if app.message else ""
        draw_box(cells, [words.game_won(app.voice(), m.winner), why, "",
                         "n: new game   m: menu   q: quit", "w: watch this match"],
                 "game over", "good")


def panel_info(app, lay=None) -> PanelInfo:
    from termpool.rules.common import GROUPS

    m = app.match
    st = m.state
    players = []
    for p in range(2):
        group = "" if st.groups is None else st.groups[p]
        balls, down = [], []
        if group:
            mine = [k for k, b in enumerate(m.ids) if b in GROUPS[group]]
            balls = [k for k in mine if m.on_table[k]]
            down = [k for k in mine if not m.on_table[k]]
        label = group
        if group and app.opts.theme != "standard":
            label = words.group_label(group, app.opts.theme)
        fouls = st.fouls[p] if st.mode == "9ball" else 0  # only 9-ball counts them
        score = f"{m.scores[p]}/{app.opts.frames}" if app.opts.frames > 1 else None
        players.append(PlayerLine(m.players[p], label, balls, down, score,
                                  p == m.shooter and app.phase != "over", fouls))
    if st.mode == "practice":
        players = players[:1]
    widgets, most = [], []
    spin_words = True  # the tip offset goes in words unless the spin face shows it
    if app.depth != "mono":
        from termpool.ui.overlay import power_meter_cells

        most = [(_spin_block(0.0, 0.0), "spin"), (power_meter_cells(0.0, 14, "power"), "power")]
    if app.phase in ("aim", "cpu") and app.depth != "mono":
        block = _spin_block(app.side, app.top)
        if lay is None or widget_fits(lay, block):
            widgets.append((block, "spin"))
            spin_words = False
        if app.charge.active:
            widgets.append((power_meter_cells(app.charge.level(app.now), 14,
                                              "power"), "power"))
    now = _status(app, spin_words)
    if app.phase == "aim" and not app.charge.active:
        # A player's turn: what to do, the power and the first ball the aid sees (to act
        # on), then the last verdict, then the plan of the shot it was about.
        plans = [x for x in app.message if x in app._shot_note]
        status = now + [x for x in app.message if x not in plans] + plans
    else:
        # What to do now first, the last verdicts next, then the power, the aid, the spin.
        status = now[:1] + app.message + now[1:]
    hint = hint_lines(app)
    title = MODE_NAMES[st.mode]
    if app.opts.frames > 1:
        title += f" · race to {app.opts.frames}"
    # Before groups are set no player line shows the balls: a free row names them.
    legend = [k for k, b in enumerate(m.ids) if b != "cue" and m.on_table[k]] \
        if st.groups is None and app.phase != "run" else []
    return PanelInfo(f"termpool · {title}", players, status, hint, m.ids,
                     widgets=widgets, most_widgets=most, theme=app.opts.theme, legend=legend)


def _tip_words(app) -> str | None:
    """The cue tip's offset in words (None when it is centred)."""
    if not (app.side or app.top):
        return None
    return f"tip {app.side:+.1f} side {app.top:+.1f} top"


SPIN_TEXT_COLS = 10  # the spin readout beside the face


def _spin_block(side: float, top: float):
    """The spin face with its readout to the left: "spin", the side and top offsets."""
    import numpy as np

    from termpool.ui.overlay import spin_face_cells

    face = spin_face_cells(side, top)
    rows = face[0].shape[0]
    text = blank_cells(SPIN_TEXT_COLS, rows, False)
    for r, (line, colour) in enumerate((("spin", DIM_TEXT_C.rgb),
                                        (f"side {side:+.1f}", TEXT_C.rgb),
                                        (f"top  {top:+.1f}", TEXT_C.rgb))):
        if r < rows:
            put_text(text, r, 0, line, colour, (0, 0, 0))
    return tuple(np.concatenate([a, b], axis=1) for a, b in zip(text, face, strict=True))


def _status(app, spin_words: bool = True) -> list[tuple[str, str]]:
    m = app.match
    name = m.players[m.shooter]
    out = []
    warned = m.warning() if app.phase in ("aim", "place") else None
    if warned is not None:
        out.append((words.foul_warning(app.voice(), warned), "foul"))
    if app.phase == "aim":
        what = "break" if m.state.is_break else "shoot"
        s = f"{name} to {what}"
        if m.needs_call():
            ball, pocket = app._called()
            s += f" · calling the {ball} in {app.voice().pocket(pocket)} (C to change)"
        if m.state.mode == "9ball" and not m.state.is_break:
            on = legal_targets(m.state, m.balls_on_table())
            if on:
                s += f" · the {on[0]} is on"
        if app.push_out:
            s += " · push-out"
        elif m.state.push_out == "available":
            s += " · O: push-out"
        if app.charge.waiting:  # a tap or a hold: no power to show yet
            out.insert(0, (app.charge.label, "turn"))
            out.append((s, "dim"))
        elif app.charge.active:  # while charging the power reading comes first
            level = round(100 * app.charge.level(app.now))
            out.insert(0, (f"power {level}% · {app.charge.label}", "turn"))
            out.append((s, "dim"))
        else:
            tip = _tip_words(app) if spin_words else None
            out.append((s + (f" · {tip}" if tip else ""), "turn"))
            out.append((_power_line(app), "dim"))
    elif app.phase == "place":
        where = KITCHEN if m.ball_in_hand == "kitchen" else "anywhere"
        what = "break" if m.state.is_break else "shoot"
        out.append((f"{name} to {what} · ball in hand {where}",
                    "turn"))
    elif app.phase == "run":
        out.append(("fast ×4 (F)" if app.fast else "F: fast forward", "dim"))
    elif app.phase == "cpu":
        plan = app._cpu_plan
        on_aim = plan is not None and not isinstance(plan, str) and app.angle == plan.angle
        pred = app.prediction() if on_aim else None  # not the balls its stick turns past
        at = f" at the {m.ids[pred.ball]}" if pred is not None and pred.ball is not None else ""
        out.append((f"{name} is thinking…" if app._cpu_plan is None else
                    f"{name} is aiming{at}", "dim"))
    return out


def power_hint(app) -> tuple[str, str]:
    """How Space gives power now, in the hint line's long and short forms."""
    ch = app.charge
    k = pretty(ch.key_label)
    if ch.preset_level is not None:
        pct = f"{round(100 * ch.preset_level)}%"
        return f"{k}: strike at {pct}", f"{k}:{pct}"
    return {"release": (f"{k}: hold, let go", f"{k}:hold"),
            "repeat": (f"{k}: hold to charge", f"{k}:hold"),
            "classic": (f"{k}: meter, {k} strikes", f"{k}:meter")}[ch.mode]


def _power_line(app) -> str:
    """The power the next shot (and the aid) has, and the first ball the aid sees hit."""
    ch = app.charge
    if ch.preset_level is not None:
        line = f"power {round(100 * ch.preset_level)}%"
    elif app.aid_level() != "off":
        whose = "the last shot's" if app.shot_power_set else "until you give one"
        line = f"aid at {round(100 * app.last_power)}% power ({whose})"
    else:
        line = "power: " + ch.label
    pred = app.prediction()
    if pred is not None and pred.ball is not None:
        line += f" · first ball: the {app.match.ids[pred.ball]}"
        if pred.object is not None and pred.object.end == "pocket":
            line += f", into the {pred.object.pocket.replace('_', ' ')} pocket"
    return line


def hint_lines(app) -> list[tuple]:
    """The panel's line of key help for this phase, as `panel.fit_hint` parts (text or
    (long, short), rank), with the keys the key map really binds."""
    def k(action: str) -> str:
        keys = app.keymap.keys_for(action)
        return pretty(keys[0]) if keys else "?"

    quit_, help_ = (f"{k('quit')} quit", 0), (f"{k('help')} help", 1)
    if app.phase == "place":
        return [(f"{k('aim_ccw')}{k('aim_fine_ccw')}{k('aim_fine_cw')}{k('aim_cw')} move", 0),
                ("(⇧ fine)", 3), (f"{k('confirm')} place", 0), ("mouse: click", 4), help_,
                quit_]
    if app.phase == "aim" and app.charge.active:
        return [(app.charge.label, 0), (f"{k('cancel')} cancel", 0)]
    if app.phase == "aim":
        spin = "".join(k(a) for a in ("spin_up", "spin_left", "spin_down", "spin_right"))
        cancel = [(f"{k('cancel')} hold", 1)] if app.charge.preset_level is not None else []
        practice = [((f"{k('undo')} take back", f"{k('undo')} undo"), 3),
                    ((f"{k('rerack')} re-rack", f"{k('rerack')} rack"), 3)] \
            if app.match.state.mode == "practice" else []
        return [(f"{k('aim_ccw')}{k('aim_cw')} aim", 0),
                (f"{k('aim_fine_ccw')}{k('aim_fine_cw')} fine", 5),
                (power_hint(app), 0), ("1-0 power", 2), *cancel, (f"{spin} spin", 2),
                (f"{k('aim_aid')} aid", 3), *practice, help_, (f"{k('pause')} pause", 4),
                quit_]
    if app.phase == "option":
        return [("answer with a letter in the box", 0), help_, quit_]
    if app.phase == "over":
        return [("N new game", 0), ("M menu", 0), ("W watch", 0), quit_]
    if app.phase == "cpu":
        return [("any key: shoot now", 0), help_, (f"{k('pause')} pause", 2), quit_]
    return [(f"{k('fast_forward')} fast forward", 0), (f"{k('pause')} pause", 1), help_, quit_]


def _menu_cells(app, cols: int, rows: int, mono: bool):
    from termpool.ui.app import MENU

    cells = blank_cells(cols, rows, mono)
    lines = [("termpool", TURN_C), ("real pool in your terminal", DIM_TEXT_C.rgb), ("", None)]
    for k in range(len(MENU)):
        label, sel = app.menu_label(k), k == app.menu_index
        lines.append(((f"▶ {k + 1}. {label}" if sel else f"  {k + 1}. {label}"),
                      TURN_C if sel else TEXT_C.rgb))
    lines += [("", None), ("↑↓ choose · Enter start · Q quit", DIM_TEXT_C.rgb)]
    top = max(0, (rows - len(lines)) // 2)
    width = max(len(s) for s, _ in lines)
    left = max(0, (cols - width) // 2)
    for k, (s, colour) in enumerate(lines):
        if s:
            put_text(cells, top + k, left, s, colour, (0, 0, 0))
    return cells
