"""The boxes a letter answers: the option (re-rack or accept, shoot or pass) and the game's
end (a new game, the menu, watching the match, quit)."""

from __future__ import annotations

from dataclasses import replace

from termpool.rules import words
from termpool.rules.codes import Option
from termpool.ui.phases.lobby import open_lobby
from termpool.ui.phases.turn import new_match, own_move, quit_game, start_turn, tell, to_menu
from termpool.ui.state import Phase, State
from termpool.ui.watch import Watch


def key(s: State, key) -> State | None:
    """The state after a letter answering the box on show; None if the key is not one (the
    other keys then do what they do in any phase)."""
    m = s.match
    if s.phase is Phase.OPTION:
        keys = {words.CHOICE_KEYS[c]: c for c in Option(m.option).choices}
        pick = keys.get(key.name)
        if pick is None:
            return None
        line = (words.chose(m.players[m.shooter], pick), "dim")
        at = own_move(s)
        m.choose(pick)
        tell(s, at, kind="choose", choice=str(pick))
        return start_turn(replace(s, message=(line,)))
    if key.name == "n" and s.remote:  # online: a new match is a new challenge
        return open_lobby(to_menu(s))
    if key.name == "n":
        return new_match(s, s.opts.mode, s.opts.opponent)
    if key.name == "m":
        return to_menu(s)
    if key.name == "w":  # watch the match just played, then come back here
        return replace(s, watch=Watch(m.to_json(), s.depth))
    if key.name == "q" or s.keymap.action(key) == "quit":
        return quit_game(s)  # the box says "q: quit": no second question on top
    return None


def nothing(s: State, key, action: str | None, t: float) -> State:
    """Keys that are not an answer do nothing more here (see `key`)."""
    return s
