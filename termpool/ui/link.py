"""A game's line to the lobby of the server it runs under (`termpool serve`, termpool.wire).

The app polls it on its ticks; nothing here blocks for long: reads take what has come, and a
message is a line of a few hundred bytes. What arrives is kept for the phases to take: the
players online, a challenge to answer, a refusal or a decline to say, a match to start, the
other player's moves, and their leaving.

Both games of a match play it from the same settings and the same moves, each its own copy:
a move carries a digest of the match as the mover saw it before the move, so that two
copies that differ (they never should: the same shot gives the same result, bit for bit)
are noticed at once instead of playing on apart.
"""

from __future__ import annotations

import hashlib
import select
import socket
from collections import deque

from termpool import wire

SEND_TIMEOUT_S = 2.0  # a server that takes no bytes for this long is gone
AIM_EVERY_S = 0.1  # the stick's moves go to the other screens at most this often


def digest(match) -> str:
    """What both copies of a match must agree on before each move: where the balls are,
    whose turn it is, how many shots and what option is open."""
    h = hashlib.sha256()
    h.update(match.pos.tobytes())
    h.update(match.on_table.tobytes())
    h.update(repr((match.shooter, len(match.history), match.option,
                   match.ball_in_hand)).encode())
    return h.hexdigest()[:24]


class Link:
    def __init__(self, path: str, token: str) -> None:
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.settimeout(SEND_TIMEOUT_S)
        self.sock.connect(path)
        self.buf = b""
        self.closed = False
        self.players: list[dict] = []  # everyone online, this game's player too (`you`)
        self.you: int | None = None
        self.challenged: dict | None = None  # a challenge to answer: by, name, game
        self.news: deque = deque()  # (kind, name or code) to say: DECLINED, REFUSED
        self.start: dict | None = None  # a match to start: game, names, seat
        self.moves: deque = deque()  # the other player's moves, in order
        self.left: str | None = None  # the other player has left the match
        self.away: str | None = None  # ... or their connection dropped, and it waits for them
        self.said: deque = deque()  # (AWAY or BACK, name): news of the match to say
        self.resume: int | None = None  # this player's side in a match they are back in,
        # until its moves so far are made (made as a watcher's are)
        self.backlog = 0  # moves made before this screen joined the match (to watch)
        self.aim: dict | None = None  # the other player's stick or ball in hand, the latest
        self._aim_out: tuple | None = None  # this player's, as last sent, and when
        self._aim_at = -1e9
        self.send(wire.HELLO, token=token)

    @classmethod
    def open(cls, address: tuple[str, str] | None) -> Link | None:
        """The link to the lobby at `address` (wire.lobby_address), or None where there is
        none or it cannot be reached (the game is then played as on its own)."""
        if address is None:
            return None
        try:
            return cls(*address)
        except OSError:
            return None

    def send(self, kind: str, **fields) -> None:
        if self.closed:
            return
        try:
            self.sock.sendall(wire.encode(kind, **fields))
        except OSError:
            self.close()

    def poll(self) -> bool:
        """Take in whatever has arrived; True if anything did."""
        got = False
        while not self.closed:
            try:
                ready = select.select([self.sock], [], [], 0)[0]
                data = self.sock.recv(65536) if ready else None
            except OSError:
                data = b""
            if data is None:
                break
            if not data:
                self.close()
                got = True
                break
            self.buf += data
            if len(self.buf) > wire.MAX_LINE and b"\n" not in self.buf:
                self.close()
                break
            while b"\n" in self.buf:
                line, self.buf = self.buf.split(b"\n", 1)
                msg = wire.decode(line)
                if msg is not None:
                    self._take(msg)
                    got = True
        return got

    def _take(self, msg: dict) -> None:
        kind = msg["t"]
        if kind == wire.PLAYERS and isinstance(msg.get("players"), list):
            self.players = [p for p in msg["players"] if isinstance(p, dict)]
            self.you = msg.get("you")
        elif kind == wire.CHALLENGED:
            self.challenged = msg
        elif kind == wire.WITHDRAWN:
            if self.challenged is not None and self.challenged.get("by") == msg.get("by"):
                self.challenged = None
                self.news.append((wire.WITHDRAWN, str(msg.get("name", ""))))
        elif kind == wire.DECLINED:
            self.news.append((wire.DECLINED, str(msg.get("name", ""))))
        elif kind == wire.REFUSED:
            self.news.append((wire.REFUSED, str(msg.get("why", ""))))
        elif kind == wire.START:
            self.start = msg
            past = msg.get("moves")  # a match joined to watch: its moves so far
            self.moves = deque(m for m in past if isinstance(m, dict)) \
                if isinstance(past, list) else deque()
            self.backlog = len(self.moves)  # made at once: they are over already
            self.left = self.away = None
        elif kind == wire.MOVE and isinstance(msg.get("move"), dict):
            self.moves.append(msg["move"])
            self.aim = None  # what the move ends: its stick, its ball in hand
        elif kind == wire.AIM and isinstance(msg.get("aim"), dict):
            self.aim = msg["aim"]
        elif kind == wire.LEFT:
            self.left = str(msg.get("name", ""))
        elif kind in (wire.AWAY, wire.BACK):
            name = str(msg.get("name", ""))
            self.away = name if kind == wire.AWAY else None
            self.said.append((kind, name))

    def share_aim(self, aim: tuple, t: float) -> None:
        """Send this player's stick (angle, side, top) or ball in hand (x, y) when it has
        moved, at most every AIM_EVERY_S."""
        if aim != self._aim_out and t - self._aim_at >= AIM_EVERY_S:
            self._aim_out, self._aim_at = aim, t
            kind, *values = aim
            self.send(wire.AIM, aim={"kind": kind, "values": values})

    def others(self) -> list[dict]:
        """The other players online, by name (an order that does not change as people come
        and go)."""
        out = [p for p in self.players if p.get("id") != self.you]
        return sorted(out, key=lambda p: (str(p.get("name", "")), str(p.get("id"))))

    def close(self) -> None:
        if not self.closed:
            self.closed = True
            try:
                self.sock.close()
            except OSError:
                pass
