"""What the app shows: a state drawn as screen cells (table, aim aids, panel, boxes, menu).

`draw(state, cols, rows, geometry)` is the whole screen, and what it showed (`Seen`: the
table's layout, for the mouse). It reads the state and changes nothing in it: the aid's
prediction is brought up to date by the driver before it draws (ui.aid.refresh). The only
thing a screen keeps is its `Geometry` (the table's background for its size), so screens of
different sizes can draw one state.
"""

from __future__ import annotations

import os

import numpy as np

from termpool.game.layout import head_string
from termpool.physics.state import POCKETED
from termpool.rules import words
from termpool.rules.common import GROUPS, legal_targets
from termpool.rules.words import KITCHEN, MODE_NAMES
from termpool.text import shown
from termpool.ui import aid
from termpool.ui import overlay as ov
from termpool.ui.canvas import put_text
from termpool.ui.help import pretty
from termpool.ui.palette import DIM_TEXT_C, TEXT_C
from termpool.ui.panel import (
    FOUL_C,
    SPARE,
    TURN_C,
    PanelInfo,
    PlayerLine,
    blank_cells,
    box_clear_of,
    draw_box,
    draw_panel,
    fit_status,
    message_cells,
    too_small_lines,
    widget_fits,
)
from termpool.ui.predict import MAX_CUSHIONS
from termpool.ui.screens import TITLES, box_lines
from termpool.ui.state import (
    LOBBY_GAMES,
    Aiming,
    Answering,
    Help,
    Pause,
    Phase,
    Place,
    Quit,
    Run,
    Seen,
    Settings,
    State,
    Stats,
    Waiting,
    concedes,
    cue_index,
    help_of,
    lies_playable,
    lobby_choice,
    menu_entries,
    shown_theme,
    voice,
)
from termpool.ui.table_view import Geometry, Layout, TableView

SPIN_TEXT_COLS = 10  # the spin readout beside the face
POWER_COLS = 14  # the power meter's width in the panel


def draw(s: State, cols: int, rows: int, geometry: Geometry) -> tuple[tuple, Seen]:
    """The whole screen for the state, (chars, fg, bg) with fg and bg None in mono, and what
    it showed."""
    mono = s.depth == "mono"
    lay, table = None, None
    if s.phase is Phase.LOBBY:
        out = _lobby_cells(s, cols, rows, mono)
    elif s.phase is Phase.MENU or s.match is None:
        out = _menu_cells(s, cols, rows, mono)
    else:
        table = s.match.table
        lay, view = geometry.get(cols, rows, table, shown_theme(s))
        if lay is None:
            out = message_cells(cols, rows, too_small_lines(cols, rows), mono)
        else:
            out = _table_cells(s, lay, view, mono)
            draw_panel(out, lay, panel_info(s, lay), mono)
            _question(s, out, lay)
    box = s.box
    if isinstance(box, Help):
        pages = help_of(s, cols, rows)
        title, lines = pages[min(box.page, len(pages) - 1)]
        # Every page in a box of the same size and place: turning a page moves nothing.
        wide = min(max(len(x) for _, page in pages for x in page), cols - 6)
        tall = max(len(page) for _, page in pages)
        lines = [*lines[:-1], *[""] * (tall - len(lines)), lines[-1].ljust(wide)]  # (the
        # last line, how to turn the pages, stays at the foot)
        draw_box(out, lines, title, wrap=False)
    elif isinstance(box, Pause):
        draw_box(out, ["paused", "", "S: settings · any other key to go on"], "pause")
    elif isinstance(box, Settings | Stats):
        draw_box(out, box_lines(s, box, cols, rows), TITLES[type(box)], wrap=False)
    elif isinstance(box, Quit):  # drawn even over "make the window bigger": Q must show
        lines = ["Quit termpool?", "", "Y: quit    N: keep playing    M: menu"]
        if concedes(s):
            other = shown(s.match.players[s.remote[0]])[:16]
            lines[1:1] = ["", f"leaving gives {other} the match"]
        elif s.match is not None and s.match.winner is None and len(s.remote) < 2:
            # (M too: a game left for the menu does not wait there to be taken up again)
            lines[1:1] = ["", "Y and M both end the game in play"]
        draw_box(out, lines, "quit")
    return out, Seen(cols, rows, lay, table)


def positions(s: State):
    """The balls' positions and states on show: the shot's frame while it runs, the ball in
    hand where it would go."""
    m = s.match
    state = np.where(m.on_table, 0, POCKETED).astype(np.int8)
    part = s.part
    if isinstance(part, Run) and part.shown > 0:  # the shot's frame now on show
        p, st = part.frames[part.shown - 1]
        rows = part.shot.rows  # the engine holds only the balls that were on the table
        pos = m.pos.copy()
        pos[rows] = p
        state[rows] = st
        return pos, state
    cursor = part.cursor if isinstance(part, Place | Waiting) else None
    if cursor is not None:  # the ball in hand is drawn where the cursor is
        pos = m.pos.copy()
        c = cue_index(s)
        pos[c] = cursor
        state[c] = 0
        return pos, state
    return m.pos, state


def _aiming(s: State) -> bool:
    """A stick to draw: the player's, the computer's once it has decided, or the other
    player's of an online match as they move it."""
    return (s.phase is Phase.AIM or isinstance(s.part, Aiming | Answering)
            or isinstance(s.part, Waiting) and s.part.stick)


def _table_cells(s: State, lay: Layout, view: TableView, mono: bool):
    m = s.match
    pos, state = positions(s)
    c = cue_index(s)
    aiming = _aiming(s)
    pred = aid.prediction(s) if aiming and m.on_table[c] else None
    level = aid.level(s)
    called = called_pocket(s) if aiming else None
    kitchen = s.phase is Phase.PLACE and m.ball_in_hand == "kitchen"
    holes = m.table.hole_c.reshape(-1, 2)

    def mark(chars) -> None:
        if kitchen:
            ov.mono_head_string(chars, lay, head_string(m.table))
        if pred is not None:
            ov.mono_prediction(chars, lay, pred, level, float(m.radius[c]))
        if called is not None:
            ov.mono_called_pocket(chars, lay, holes[called])

    def paint(cv) -> None:
        if kitchen:
            ov.draw_head_string(cv, lay, head_string(m.table))
        if called is not None:
            ov.draw_called_pocket(cv, lay, holes[called], m.table.hole_r[called])
        if aiming and m.on_table[c]:
            if pred is not None:
                ov.draw_prediction(cv, lay, pred, m.radius[c], level)
            ch = s.controls.charge
            pull = ch.level(s.now) if ch.active else 0.0
            ov.draw_cue_stick(cv, lay, m.pos[c], m.radius[c], s.stroke.angle, pull)
        cursor = s.part.cursor if isinstance(s.part, Place | Waiting) else None
        if cursor is not None:
            ok = m.placement_error(*cursor) is None
            ov.draw_placement(cv, lay, cursor, m.radius[c], ok)

    return view.cells(m.ids, pos, state, m.radius, mono, paint=paint, mark=mark)


def called_pocket(s: State) -> int | None:
    """The index of the pocket called for the 8 on this shot (the human's call, or the
    computer's plan), None when no call is needed."""
    names_ = list(s.match.table.hole_names)
    if s.phase is Phase.AIM and s.match.needs_call():
        return names_.index(aid.called(s)[1])
    if isinstance(s.part, Aiming) and s.part.plan.called:
        return names_.index(s.part.plan.called[1])
    return None


NEAR_BALLS = 3.0  # the question box keeps clear of the balls this many ball diameters from
# the cue ball, where the screen allows (else of the cue ball alone)


def _question(s: State, cells, lay: Layout) -> None:
    m = s.match
    if s.phase is Phase.OPTION:
        lines = words.option_lines(m.option)
        title = f"{voice(s).whose(m.shooter)} call"  # whose: two players may share a screen
        c = cue_index(s)
        at = None
        if m.on_table[c]:
            near = np.hypot(*(m.pos - m.pos[c]).T) <= NEAR_BALLS * 2 * m.radius[c]
            col, row, _, _ = lay.panel_rect  # off the panel, whose players' row says whose
            table = (lay.cols, row) if lay.panel == "bottom" else (col, lay.rows)  # call it is
            tight = [x for x in lines if x]  # without its blank line: a row shorter
            cue = np.arange(len(m.ids)) == c
            # The cue ball and the balls by it in view, else the cue ball alone, on the
            # table: the box a row shorter if it must be; only then over the panel.
            for which, text, within in ((near & m.on_table, lines, table),
                                        (near & m.on_table, tight, table),
                                        (cue, lines, table), (cue, tight, table),
                                        (near & m.on_table, lines, None), (cue, lines, None)):
                keep = _cells_of(lay, m.pos[which], m.radius[which])
                at = box_clear_of(cells, text, keep, title, within=within)
                if at is not None:
                    lines = text
                    break
        draw_box(cells, lines, title, at=at)
    elif s.phase is Phase.OVER:
        why = s.message[-1][0] if s.message else ""
        again = "N: the lobby" if s.remote else "N: new game"  # online: a new challenge
        w = m.winner
        won = (words.match_won(voice(s), w, m.scores) if m.frames > 1
               else words.game_won(voice(s), w))  # a race: its score
        lines = [won, why, "",
                 f"{again}   M: menu   Q: quit", "W: watch this match"]
        records = s.files.records
        where = records.kept_at(m) if records is not None else None
        if where is not None:  # where to find it again (`termpool records` lists them)
            folder, name = os.path.split(where)
            lines.append(f"kept as {shown(os.path.join(os.path.basename(folder), name))}")
        draw_box(cells, lines, "game over", "good")


def _cells_of(lay: Layout, pos, radius) -> tuple[int, int, int, int]:
    """The cells (col, row, cols, rows) that balls at `pos` of `radius` are drawn in."""
    x, y = lay.to_pixels(pos[:, 0], pos[:, 1])
    r_x, r_y = radius * lay.sx, radius * lay.sy
    c0, c1 = int(np.floor((x - r_x).min())), int(np.floor((x + r_x).max()))
    r0, r1 = int(np.floor((y - r_y).min())) // 2, int(np.floor((y + r_y).max())) // 2
    return c0, r0, c1 - c0 + 1, r1 - r0 + 1


def panel_info(s: State, lay: Layout | None = None) -> PanelInfo:
    m = s.match
    st = m.state
    frames = m.frames
    theme = shown_theme(s)
    players = []
    for p in range(2):
        group = "" if st.groups is None else st.groups[p]
        balls, down = [], []
        if group:
            mine = [k for k, b in enumerate(m.ids) if b in GROUPS[group]]
            balls = [k for k in mine if m.on_table[k]]
            down = [k for k in mine if not m.on_table[k]]
        label = words.group_label(group, theme) if group else group
        # Fouls in a row matter only under 9-ball's three-foul rule: shown only then.
        fouls = st.fouls[p] if st.mode == "9ball" and st.three_foul else 0
        score = f"{m.scores[p]}/{frames}" if frames > 1 else None
        players.append(PlayerLine(m.players[p], label, balls, down, score,
                                  p == m.shooter and s.phase is not Phase.OVER, fouls))
    if st.mode == "practice":
        players = players[:1]
    widgets, most = [], []
    spin_words = True  # the tip offset goes in words unless the spin face shows it
    ch = s.controls.charge
    if s.depth != "mono":
        most = [(_spin_block(0.0, 0.0), "spin"),
                (ov.power_meter_cells(0.0, POWER_COLS, "power"), "power")]
    if s.phase in (Phase.AIM, Phase.CPU) and s.depth != "mono":
        block = _spin_block(s.stroke.side, s.stroke.top)
        if lay is None or widget_fits(lay, block):
            widgets.append((block, "spin"))
            spin_words = False
        if ch.active:
            widgets.append((ov.power_meter_cells(ch.level(s.now), POWER_COLS, "power"),
                            "power"))
    now = _status(s, spin_words)
    message = list(s.message)
    if s.phase is Phase.AIM and not ch.active:
        # A player's turn: what to do, the power and the first ball the aid sees (to act
        # on), then the last verdict, then the plan of the shot it was about.
        plans = [x for x in message if x in s.shot_note]
        status = now + [x for x in message if x not in plans] + plans
    else:
        # What to do now first, the last verdicts next, then the power, the aid, the spin.
        status = now[:1] + message + now[1:]
    # The computer's plan is a note: the verdict it led to wraps before it keeps a row.
    notes = set(s.shot_note) | set(s.cpu_note)
    status = [(text, "plan") if (text, tone) in notes and tone == "turn" else (text, tone)
              for text, tone in status]
    title = MODE_NAMES[st.mode]
    if frames > 1:
        title += f" · race to {frames}"
    # Before groups are set no player line shows the balls: a free row names them.
    legend = [k for k, b in enumerate(m.ids) if b != "cue" and m.on_table[k]] \
        if st.groups is None and s.phase is not Phase.RUN else []
    return PanelInfo(f"termpool · {title}", players, status, hint_lines(s), m.ids,
                     widgets=widgets, most_widgets=most, theme=theme, legend=legend)


def _spin_block(side: float, top: float):
    """The spin face with its readout to the left: "spin", the side and top offsets."""
    face = ov.spin_face_cells(side, top)
    rows = face[0].shape[0]
    text = blank_cells(SPIN_TEXT_COLS, rows, False)
    for r, (line, colour) in enumerate((("spin", DIM_TEXT_C.rgb),
                                        (f"side {words.signed(side)}", TEXT_C.rgb),
                                        (f"top  {words.signed(top)}", TEXT_C.rgb))):
        if r < rows:
            put_text(text, r, 0, line, colour, (0, 0, 0))
    return tuple(np.concatenate([a, b], axis=1) for a, b in zip(text, face, strict=True))


def _status(s: State, spin_words: bool = True) -> list[tuple[str, str]]:
    m = s.match
    name = m.players[m.shooter]
    out = []
    warned = m.warning() if s.phase in (Phase.AIM, Phase.PLACE) else None
    if warned is not None:
        out.append((words.foul_warning(voice(s), warned), "warn"))
    ch = s.controls.charge
    if s.phase is Phase.AIM:
        what = "break" if m.state.is_break else "shoot"
        line = f"{name} to {what}"
        if m.needs_call():
            ball, pocket = aid.called(s)
            line += f" · {words.calling(voice(s), ball, pocket)} (C to change)"
        if m.state.mode == "9ball" and not m.state.is_break:
            on = legal_targets(m.state, m.balls_on_table())
            if on:
                line += f" · the {on[0]} is on"
        if s.stroke.push_out:
            line += " · push-out"
        elif m.state.push_out == "available":
            line += " · O: push-out"
        if ch.waiting:  # a tap or a hold: no power to show yet
            out.insert(0, (ch.label, "turn"))
            out.append((line, "dim"))
        elif ch.active:  # while charging the power reading comes first
            out.insert(0, (f"power {round(100 * ch.level(s.now))}% · {ch.label}", "turn"))
            out.append((line, "dim"))
        else:
            tip = _tip_words(s) if spin_words else None
            out.append((line + (f" · {tip}" if tip else ""), "turn"))
            foreseen = aid.foreseen(s)
            warning = None if foreseen is None else \
                words.aid_warning(foreseen, voice(s), m.shooter)
            if warning:  # a shot the aid sees foul or lose, next to whose turn it is
                out.append((warning, "warn"))
            out.append((power_line(s), "dim"))
    elif s.phase is Phase.PLACE:
        where = KITCHEN if m.ball_in_hand == "kitchen" else "anywhere"
        what = "break" if m.state.is_break else "shoot"
        out.append((f"{name} to {what} · ball in hand {where}", "turn"))
    elif isinstance(s.part, Run):
        # (F is on the keys' line: said here once pressed)
        out.append((f"{voice(s).whose_first(m.shooter)} shot"
                    + (" · fast ×4 (F)" if s.part.fast else ""), "dim"))
    elif s.phase is Phase.CPU:
        plan = s.part.plan if isinstance(s.part, Aiming) else None
        if plan is None:  # deciding (a shot, or the answer to an option)
            out.append((f"{name} is thinking…", "dim"))
        elif plan.kind == "break":
            out.append((f"{name} is about to break", "dim"))
        else:  # the ball its plan is about, as its note names it (not the aid's first ball,
            # which its stick sweeps past, and its aim's error may change)
            at = f" at {voice(s).ball(plan.target)}" if plan.target is not None else ""
            out.append((f"{name} is aiming{at}", "dim"))
    elif s.phase is Phase.REMOTE:
        doing = ("answering" if m.option is not None else
                 "placing the cue ball" if m.ball_in_hand and not s.part.placed else "aiming")
        watching = "watching · " if len(s.remote) == 2 else ""
        link = s.link
        if link is not None and link.resume is not None:
            out.append(("back in the match: making its moves so far…", "dim"))
        elif link is not None and link.away == m.players[m.shooter]:
            out.append((f"{name}'s connection dropped: waiting for them to come back…",
                        "dim"))
        elif s.part.paused:
            out.append((f"{watching}{name} has paused the game…", "dim"))
        else:
            out.append((f"{watching}{name} is {doing}, on their own screen…", "dim"))
            power = s.part.power
            if s.part.stick and power is not None and aid.level(s) != "off":
                out.append((f"{name}'s aid at {round(100 * power)}% power{_first_ball(s)}",
                            "dim"))
    return out


def _tip_words(s: State) -> str | None:
    """The cue tip's offset in words (None when it is centred)."""
    st = s.stroke
    if not (st.side or st.top):
        return None
    return words.tip_words(st.side, st.top)


def power_hint(s: State) -> tuple[str, str]:
    """How Space gives power now, in the hint line's long and short forms."""
    ch = s.controls.charge
    k = pretty(ch.key_label)
    if ch.preset_level is not None:
        pct = f"{round(100 * ch.preset_level)}%"
        return f"{k}: strike at {pct}", f"{k}:{pct}"
    return {"release": (f"{k}: hold, let go", f"{k}:hold"),
            "repeat": (f"{k}: hold to charge", f"{k}:hold"),
            "classic": (f"{k}: meter, {k} strikes", f"{k}:meter")}[ch.mode]


def power_line(s: State) -> str:
    """The power the next shot (and the aid) has, and the first ball the aid sees hit."""
    ch = s.controls.charge
    if ch.preset_level is not None:
        line = f"power {round(100 * ch.preset_level)}%"
    elif aid.level(s) != "off":  # (the shooter's last shot's power, or half before one)
        line = f"aid at {round(100 * s.last_power)}% power"
    else:
        line = "power: " + ch.label
    return line + _first_ball(s)


def _first_ball(s: State) -> str:
    """The first ball the aid sees hit, and its pocket if it goes in; that it follows the cue
    ball through its cushions and sees none ("" while it runs, and where the cue ball stops
    or drops first: the warning says that)."""
    pred = aid.prediction(s)
    if pred is not None and pred.ball is None and pred.cue.end == "cushion":
        return f" · no ball within {MAX_CUSHIONS} cushions"
    if pred is None or pred.ball is None:
        return ""
    v = voice(s)
    line = f" · first ball: {v.ball(s.match.ids[pred.ball])}"
    if pred.object is not None and pred.object.end == "pocket":
        line += f", into the {v.pocket(pred.object.pocket)} pocket"
    return line


def hint_lines(s: State) -> list[tuple]:
    """The panel's line of key help for this phase, as `panel.fit_hint` parts (text or
    (long, short), rank), with the keys the key map really binds."""
    def k(action: str) -> str:
        keys = s.keymap.keys_for(action)
        return pretty(keys[0]) if keys else "?"

    if s.box is not None:  # a box over the table says its own keys; the phase's do nothing
        return []
    quit_, help_ = (f"{k('quit')} quit", 0), (f"{k('help')} help", 1)
    ch = s.controls.charge
    # Practice's own keys rank with the help: a player who never sees U may never take a
    # shot back (after a scratch, from ball in hand, most of all).
    practice = [((f"{k('undo')} take back", f"{k('undo')} undo"), 1),
                ((f"{k('rerack')} re-rack", f"{k('rerack')} rack"), 1)] \
        if s.match.state.mode == "practice" else []
    if s.phase is Phase.PLACE:
        leave = ([((f"{k('cancel')} leave it", f"{k('cancel')} leave"), 2)]
                 if lies_playable(s) else [])
        return [(f"{k('aim_ccw')}{k('aim_fine_ccw')}{k('aim_fine_cw')}{k('aim_cw')} move", 0),
                ("(⇧ fine)", 3), (f"{k('confirm')} place", 0), *leave, ("mouse: click", 4),
                *practice, help_, quit_]
    if s.phase is Phase.AIM and ch.active:  # what Space does now: the status's first line
        return [(f"{k('cancel')} cancel", 0)]
    if s.phase is Phase.AIM:
        spin = "".join(k(a) for a in ("spin_up", "spin_left", "spin_down", "spin_right"))
        preset = ch.preset_level is not None
        cancel = [(f"{k('cancel')} {ch.way}", 1)] if preset else []
        # Where there is room to spare (it never shortens the rest).
        ball = [(f"{k('next_ball')} next ball", SPARE)]
        aim, fine = (f"{k('aim_ccw')}{k('aim_cw')}", f"{k('aim_fine_ccw')}{k('aim_fine_cw')}")
        return [((f"{aim} aim", f"{aim} aim", f"{aim}aim"), 0),
                ((f"{fine} fine", f"{fine} fine", f"{fine}fine"), 5),
                *ball,
                # A player who set the power with a digit knows the digits: Esc, which
                # gives the hold back, takes their place first.
                (power_hint(s), 0), ("1-0 power", 5 if preset else 2), *cancel,
                (f"{spin} spin", 2),
                (f"{k('aim_aid')} aid", 3), *practice, help_, (f"{k('pause')} pause", 4),
                quit_]
    if s.phase is Phase.OPTION:
        return [("answer with a letter in the box", 0), help_, quit_]
    if s.phase is Phase.OVER:
        return [("N lobby" if s.remote else "N new game", 0), ("M menu", 0), ("W watch", 0),
                quit_]
    if s.phase is Phase.CPU:
        return [("any key: shoot now", 0), help_, (f"{k('pause')} pause", 2), quit_]
    if s.phase is Phase.REMOTE:
        return [help_, quit_]
    return [(f"{k('fast_forward')} fast forward", 0), (f"{k('pause')} pause", 1), help_, quit_]


def _lobby_lines(s: State) -> tuple[list[tuple[str, object]], tuple[str, object]]:
    """The lobby's words: who is online (the one chosen marked), the game a challenge is to,
    a challenge to answer; and apart, the line of what to press (the last)."""
    link, part = s.link, s.part
    others, k = lobby_choice(s)
    lines = [("Players online", TURN_C), ("", None)]

    def where(p: dict) -> str:
        w, with_ = p.get("where"), shown(str(p.get("with") or ""))[:40]
        if w == "playing":
            return f"playing {with_} (Enter: watch)" if with_ else "playing (Enter: watch)"
        if w == "watching":
            return f"watching {with_}" if with_ else "watching"
        c = p.get("challenge")
        if w == "lobby" and isinstance(c, dict) and c:  # {"to": id} or {"from": id}
            way, who = next(iter(c.items()))
            name = "you" if who == link.you else shown(str(names.get(who, "someone")))[:16]
            return f"in the lobby, a challenge {'to' if way == 'to' else 'from'} {name}"
        return {"lobby": "in the lobby", "menu": "in the menu"}.get(w, "")

    names = {p.get("id"): p.get("name", "") for p in link.players}

    for n, p in enumerate(others):
        mark = "▶ " if n == k else "  "
        text = f"{mark}{shown(str(p.get('name', '')))[:16]}  {where(p)}"
        lines.append((text, TURN_C if n == k else TEXT_C.rgb))
    if not others:
        lines.append(("  nobody else yet: ask a friend to connect", DIM_TEXT_C.rgb))
    game = MODE_NAMES[LOBBY_GAMES[part.game]]
    lines.append(("", None))
    if link.challenged is None:  # the game of one's own challenges (not while answering one)
        lines += [(f"game: ◀ {game} ▶", TEXT_C.rgb), ("", None)]
    if link.challenged is not None:
        c = link.challenged
        what = MODE_NAMES.get((c.get("game") or {}).get("mode"), "a game")
        lines += [(f"{shown(str(c.get('name', '')))[:16]} challenges you to {what}", TURN_C),
                  ("", None)]
        keys = "Y accept · N or Esc decline"
    elif part.waiting is not None:
        lines += [(f"waiting for {part.waiting} to answer…", DIM_TEXT_C.rgb), ("", None)]
        keys = "Esc takes the challenge back"
    else:
        keys = "↑↓ choose · ←→ game · Enter challenge · Esc back"
    return lines, (keys, DIM_TEXT_C.rgb)


def _lobby_cells(s: State, cols: int, rows: int, mono: bool):
    lines, keys = _lobby_lines(s)
    return _centred(lines + _said(s, cols, rows - len(lines) - 1) + [keys], cols, rows, mono)


def _menu_cells(s: State, cols: int, rows: int, mono: bool):
    lines = [("termpool", TURN_C), ("real pool in your terminal", DIM_TEXT_C.rgb), ("", None)]
    for k, (label, what) in enumerate(menu_entries(s)):
        sel = k == s.menu_index
        if isinstance(what, tuple) and what[1] == "cpu":  # whom the game is against
            label += f" ({s.opts.level})"
        digit = (k + 1) % 10  # the key that picks it: 0 for the tenth
        lines.append(((f"▶ {digit}. {label}" if sel else f"  {digit}. {label}"),
                      TURN_C if sel else TEXT_C.rgb))
    lines += [("", None), ("↑↓ choose · Enter start · Q quit", DIM_TEXT_C.rgb)]
    # What ended an online match (the other player left), said where the match was left;
    # a settings or keys file's warning.
    lines += _said(s, cols, rows - len(lines))
    return _centred(lines, cols, rows, mono)


SAID_WIDTH = 64  # at most, so that the menu's block stays in the middle


def _said(s: State, cols: int, room: int) -> list[tuple[str, object]]:
    """The words on show, as lines of a menu or the lobby (a foul's in its colour), wrapped
    to the screen, in `room` rows at most."""
    width = max(min(cols - 2, SAID_WIDTH), 1)
    return [(text, FOUL_C if tone == "foul" else DIM_TEXT_C.rgb)
            for text, tone in fit_status(s.message, room, width)]


def _centred(lines: list[tuple[str, object]], cols: int, rows: int, mono: bool):
    """A blank screen with `lines` (text, colour) in the middle, left-aligned as a block."""
    cells = blank_cells(cols, rows, mono)
    top = max(0, (rows - len(lines)) // 2)
    left = max(0, (cols - max(len(text) for text, _ in lines)) // 2)
    for k, (text, colour) in enumerate(lines):
        if text:
            put_text(cells, top + k, left, text, colour, (0, 0, 0))  # clipped to the screen
    return cells
