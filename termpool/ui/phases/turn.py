"""The steps every phase shares: a new match, the turn that starts once the table is at rest,
a shot struck and finished, the way to the menu, and the match kept (--record, history).
Each takes a state and gives the next one (see ui.state)."""

from __future__ import annotations

import secrets
from dataclasses import replace

from termpool.ai import Computer
from termpool.game import Match, Shot
from termpool.physics.cue import clamp_tip
from termpool.rules import words
from termpool.ui.controls import PowerCharge
from termpool.ui.link import digest
from termpool.ui.settings import player_names
from termpool.ui.shots import DEFAULT_POWER, power_to_speed, simulate
from termpool.ui.state import (
    Aim,
    Lobby,
    Menu,
    Option,
    Over,
    Place,
    Power,
    Run,
    State,
    Stroke,
    Thinking,
    Waiting,
    concedes,
    cue_index,
    nearest_angle,
    shooter_is_cpu,
    shooter_is_remote,
    voice,
)
from termpool.ui.term import signals_held
from termpool.wire import LEAVE, MOVE, OVER, WHERE


def set_input_mode(s: State, mode: str) -> State:
    """How the terminal tells a held key: "release" (kitty protocol), "repeat" (infer holds)
    or "classic" (it cannot: press, press). The power setting picks the meter or digits over
    holds."""
    shoot_keys = s.keymap.keys_for("shoot")
    charge = PowerCharge("classic" if s.opts.power == "meter" else mode,
                         key_label=shoot_keys[0] if shoot_keys else "space")
    if s.opts.power == "digits":
        charge.preset(s.last_power)
    return replace(s, input_mode=mode, controls=replace(s.controls, charge=charge))


def apply_pending(s: State) -> State:
    """The settings changes held for the next game take effect (a new match starts)."""
    return replace(s, opts=replace(s.opts, **s.pending), pending={})


def new_match(s: State, mode: str, opponent: str) -> State:
    s = log_match(s)
    played = s.played + (s.match,) if s.match is not None and s.match.history else s.played
    s = apply_pending(s)
    opts = replace(s.opts, mode=mode, opponent=opponent)
    cpu = (False, opponent == "cpu" and mode != "practice")
    # Without a seed every game deals a new rack; the seed is in the record either way.
    seed = opts.seed if opts.seed is not None else secrets.randbits(63)
    names = player_names(opts.player1, opts.player2, mode, opponent)
    return begin_match(replace(s, played=played), opts, names, seed, cpu)


def begin_match(s: State, opts, names, seed: int, cpu: tuple[bool, bool],
                remote: tuple[int, ...] = ()) -> State:
    """A match of `names` as `opts` set it, from `seed`; `cpu` says which players the
    computer plays, `remote` which move on other screens (an online match: the other player,
    or both for a match being watched)."""
    mode = opts.mode
    players = tuple(Computer(opts.level, n) if c else n for n, c in zip(names, cpu, strict=True))
    match = Match(mode, table=opts.table, frames=opts.frames, players=players, seed=seed,
                  theme=opts.theme, three_foul=opts.three_foul and mode == "9ball",
                  eight_break=opts.eight_break)
    # Power starts afresh: no 20% safety breaks the next game.
    s = replace(s, opts=opts, match=match, cpu=cpu, remote=remote, last_power=DEFAULT_POWER,
                message=(), stroke=Stroke(), powers=(None, None))
    return start_turn(s)


def own_power(s: State) -> State:
    """The shooter's power as they left it at their last shot: a level set with a digit stays
    theirs, and another player's never carries over (one who has not shot yet starts at the
    default: 50% with digits, else holding)."""
    mine = s.powers[s.match.shooter]
    if mine is None:
        s.controls.charge.preset(DEFAULT_POWER if s.opts.power == "digits" else None)
        return replace(s, last_power=DEFAULT_POWER)
    s.controls.charge.preset(mine.preset)
    return replace(s, last_power=mine.last)


def start_turn(s: State) -> State:
    """The next phase, once the table is at rest: the next frame or the match's end, an
    option to answer, the computer's turn, ball in hand or the aim."""
    m = s.match
    s.controls.charge.cancel()
    s = replace(s, stroke=replace(s.stroke, side=0.0, top=0.0, push_out=False,
                                  call_picked=False))
    if m.frame_over and m.winner is None:
        won = m.frame_winner
        m.new_frame()
        frame = (words.frame_won(voice(s), won, m.scores, m.shooter), "good")
        s = replace(s, message=(*s.message, frame))  # the news now
    if m.winner is not None:
        if len(s.remote) == 1:  # a player online: the server need not hold the match now
            s.link.send(OVER)
        return log_match(replace(s, part=Over()))
    if shooter_is_remote(s):  # their option, ball in hand or shot: it comes over the link
        return replace(s, part=Waiting())
    if m.option is not None:
        return replace(s, part=Thinking() if shooter_is_cpu(s) else Option())
    if shooter_is_cpu(s):
        return replace(s, part=Thinking())
    s = own_power(s)
    if m.ball_in_hand:
        c = cue_index(s)
        x, y = m.pos[c] if m.on_table[c] else m.table.head_spot
        if m.placement_error(x, y):
            x, y = m.table.head_spot
        return replace(s, part=Place((float(x), float(y))))
    angle = 0.0 if m.state.is_break else nearest_angle(s)
    return replace(s, part=Aim(), stroke=replace(s.stroke, angle=angle))


def own_move(s: State) -> str | None:
    """In an online match, before this screen's player moves: the match's digest, which the
    move carries to the other screen (ui.link); else None."""
    return digest(s.match) if s.remote and not shooter_is_remote(s) else None


def tell(s: State, at: str | None, **move) -> None:
    """The other screen of an online match makes this player's move too (`at`: own_move)."""
    if at is not None:
        s.link.send(MOVE, move={"at": at, **move})


def shoot(s: State, speed: float, angle: float, side: float, top: float, called=None,
          push_out: bool = False, keep_message: bool = False) -> State:
    """Strike: the whole shot is simulated now and shown frame by frame (ui.shots). A shot
    the match refuses is said, and the shooter aims again (the computer's shots are checked
    the same way; should one be refused, the shot is left to the keys rather than to a loop
    of refusals). With `keep_message` (the computer's shots) the words on show stay: its plan
    and the verdict on the shot before it (see cpu.plan)."""
    side, top = clamp_tip(side, top)  # the strike's own limit, for the computer's too
    shot = Shot(speed=speed, angle=angle, side=side, top=top, called=called,
                push_out=push_out)
    at = own_move(s)
    try:
        run = s.match.begin(shot)
    except ValueError as e:
        return replace(s, part=Aim(), message=((f"that shot cannot be played: {e}", "foul"),))
    tell(s, at, kind="shot", **shot.to_json())
    fast = s.opts.fast  # fast-forward is for one shot, unless the settings say
    fast = fast == "always" or (fast == "computer" and shooter_is_cpu(s))
    # The computer's plan stays in view while its shot runs, and then beside the verdict.
    note = s.cpu_note if keep_message else ()
    return replace(s, part=Run(run, simulate(run), s.now, fast), shot_note=note,
                   message=s.message if keep_message else ())


def shoot_human(s: State, level: float, called: tuple[str, str] | None) -> State:
    """The player's strike at power `level` (0 to 1) on the stroke set up."""
    preset, last = s.controls.charge.preset_level, level
    if s.match.state.is_break and s.match.mode != "practice" and s.opts.power != "digits":
        # A power set for a match's break is the break's: one tap of Space must not strike
        # the next shot at full power, nor the aid show it at the break's (with digits alone
        # a power is always set, and stays; practice's first shot is any shot).
        preset, last = None, DEFAULT_POWER
    mine = Power(preset, last)
    powers = tuple(mine if p == s.match.shooter else x for p, x in enumerate(s.powers))
    s = replace(s, last_power=level, powers=powers)
    st = s.stroke
    return shoot(s, power_to_speed(level), st.angle, st.side, st.top, called, st.push_out)


def finish_shot(s: State) -> State:
    """The shot's last frame is on show: it is judged and recorded, and the turn goes on."""
    m = s.match
    before = int(m.on_table.sum())
    shooter = m.shooter
    with signals_held():  # judged and recorded whole, whatever interrupts
        out = s.part.shot.finish()
    verdict = words.verdict(out, voice(s), shooter)
    # The verdict first, the plan it answers after (now in the past: "plan was"): where the
    # computer's next plan takes the old one's place, the verdict does not move.
    plan = ((words.computer_plan(s.cpu_plan, voice(s), done=True), "turn"),) \
        if s.shot_note and s.cpu_plan is not None else ()
    s = replace(s, message=(verdict, *plan), shot_note=plan)
    if s.files.records is not None:  # on disk after every shot, whatever comes next
        s.files.records.keep(m, on=s.opts.records)
    if s.opts.bell and (out.foul or int(m.on_table.sum()) < before):
        s = replace(s, bells=s.bells + 1)  # a pocketed ball or a foul
    return start_turn(s)


def log_match(s: State) -> State:
    """The match in play has ended or is being left: save its record and add it to the
    history of play (once; not one without shots). A file that cannot be written is one line
    for the terminal when the game ends."""
    if s.files.records is not None:
        s.files.records.keep(s.match, on=s.opts.records)
    sides = tuple(p for p in (0, 1) if p not in s.remote)  # online: this player's; none
    if s.files.history is not None and s.match is not None and sides:  # when watching
        warning = s.files.history.add(s.match, s.cpu, s.opts.level, sides=sides,
                                      online=bool(s.remote))
        if warning:
            return replace(s, notes=(*s.notes, warning))
    return s


def record(s: State) -> tuple[State, Match | None]:
    """The match to save (--record): this one if it has shots, else the last that had. A
    shot still rolling (the game was left mid-shot) is played out first: simulated again
    from its start, since an interrupt may have stopped its engine between two updates (the
    same steps give the same shot). Should even that fail, the match is kept as it stood
    before the shot, and the notes say so. The game is being left: its phase stays as it
    was."""
    m = s.match
    if m is not None and m.running is not None:
        shot = m.running.shot
        m.abandon(m.running)
        try:
            m.begin(shot).finish()
        except Exception as e:  # whatever went wrong, the shots before it are kept
            if m.running is not None:
                m.abandon(m.running)
            s = replace(s, notes=(*s.notes, f"the last shot could not be played out ({e}); "
                                            "the record ends with the shot before it"))
    if m is not None and m.history:
        return s, m
    return s, s.played[-1] if s.played else m


def give_match(s: State, player: int) -> State:
    """`player` leaves the match in play before its end: the other wins it (a shot still
    rolling is played out first; a match already over stays as it is)."""
    if isinstance(s.part, Run):
        s, _ = record(s)
    s.match.concede(player)
    return s


def concede_online(s: State) -> State:
    """This screen's player leaves an online match before its end (Q): the other player wins
    it. A connection that merely drops concedes nothing: the match waits for them to come
    back."""
    return give_match(s, 1 - s.remote[0]) if concedes(s) else s


def quit_game(s: State) -> State:
    """The player quits termpool: an online match is conceded and left first."""
    if s.remote:
        s = concede_online(s)
        s.link.send(LEAVE)
    return replace(s, done=True)


def to_menu(s: State) -> State:
    """Leave the match (or the lobby) for the menu: the match is saved and added to the
    history first; an online match is left for the other player too, and the lobby's
    challenges to and from this player are off (the server withdraws them)."""
    if isinstance(s.part, Run):
        s, _ = record(s)  # a shot still rolling is played out, as on the way out
    s = log_match(s)
    played = s.played + (s.match,) if s.match is not None and s.match.history else s.played
    if s.remote:
        s.link.send(LEAVE)
    elif isinstance(s.part, Lobby):
        s.link.send(WHERE, lobby=False)
        s.link.challenged = None
    return replace(s, box=None, part=Menu(), match=None, played=played, remote=(),
                   message=())
