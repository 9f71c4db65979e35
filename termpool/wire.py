"""The lobby's messages between `termpool serve` and the games it runs: one JSON object a line,
each with its kind in "t". Floats travel as JSON numbers, which Python writes and reads back
bit for bit, so a shot sent is the shot struck on both sides.

Game to server: HELLO (token), WHERE (in the lobby or not), CHALLENGE (to, game), ANSWER (to,
yes), WATCH (to: a player whose match to watch), MOVE (move), AIM (aim: the stick or the
ball in hand as the player moves it, for the other screens to show), OVER (the match has
ended on this player's screen: a drop from now on is no reason to wait), LEAVE.
Server to game: PLAYERS (players: id, name, where, with, challenge: {"to": id} or {"from":
id}), CHALLENGED (by, name, game),
DECLINED (name), WITHDRAWN (by, name: a challenge to this game is off), START (game, names,
seat: 0 or 1, or None to watch; moves: the match's moves so far), MOVE (move), AIM (aim),
LEFT (name), AWAY (name: a player's connection dropped; the match waits for them), BACK
(name: ... and they are back), REFUSED (why: a code, below).
"""

from __future__ import annotations

import json
import os

ENV_SOCKET = "TERMPOOL_LOBBY"  # where a game finds its server's lobby ...
ENV_TOKEN = "TERMPOOL_LOBBY_TOKEN"  # ... and the token that says which player it is

HELLO, WHERE, CHALLENGE, ANSWER, WATCH, MOVE, AIM, LEAVE = "hello", "where", "challenge", \
    "answer", "watch", "move", "aim", "leave"
PLAYERS, CHALLENGED, DECLINED, WITHDRAWN, START, LEFT, REFUSED = "players", "challenged", \
    "declined", "withdrawn", "start", "left", "refused"
AWAY, BACK, OVER = "away", "back", "over"

# Why a challenge or a message was refused.
BUSY = "busy"  # the player challenged is not in the lobby, or has a challenge open
GONE = "gone"  # the player challenged has left
BAD = "bad"  # a message the server cannot read
SELF = "self"  # the player challenged is the challenger, on another screen

MAX_LINE = 64 * 1024  # a longer line is not a message: the connection is closed

# The match settings a challenge carries, which both games build their match from.
GAME_KEYS = ("mode", "table", "frames", "seed", "three_foul", "eight_break", "theme")


def encode(kind: str, **fields) -> bytes:
    return (json.dumps({"t": kind, **fields}, separators=(",", ":"), allow_nan=False)
            + "\n").encode()


def decode(line: bytes) -> dict | None:
    """A message, or None for a line that is not one."""
    try:
        msg = json.loads(line)
    except (ValueError, UnicodeDecodeError, RecursionError):
        return None
    return msg if isinstance(msg, dict) and isinstance(msg.get("t"), str) else None


def lobby_address(env=None) -> tuple[str, str] | None:
    """(socket path, token) of the lobby this game runs under, or None outside a server."""
    env = os.environ if env is None else env
    path, token = env.get(ENV_SOCKET), env.get(ENV_TOKEN)
    return (path, token) if path and token else None
