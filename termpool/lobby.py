"""The lobby of `termpool serve`: who is connected, their challenges, and the matches between
two of them, whose moves it passes on as they come, to the other player and to anyone
watching. The games play their matches themselves, each its own copy, from the same
settings and the same moves; the lobby never simulates anything.

A player whose connection drops (without leaving the match) is away: the match waits for
them for RESUME_WAIT_S, the others are told (AWAY), and the next game of that name to connect
is put back in it, given its moves so far to catch up (START), while the others are told it
is back (BACK). The other player may go on with their turn meanwhile; their moves wait too.
A match whose end a player's screen has shown (OVER) waits for no one: a drop is a leaving.

Messages are termpool.wire's, one JSON object a line.
"""

from __future__ import annotations

import asyncio
import secrets
from dataclasses import dataclass, field

from termpool import wire

MAX_MOVES = 10_000  # a match's moves kept for those who come to watch it (a long match has
# a few hundred)
RESUME_WAIT_S = 300.0  # how long a match waits for a player whose connection dropped


@dataclass
class Seat:
    """A game connected to the lobby: whose it is, where its player is ("lobby" when the
    lobby screen is open, "playing" or "watching" a match, else "menu"), the challenge it
    has open, and its match."""

    id: int
    name: str
    writer: asyncio.StreamWriter
    where: str = "menu"
    challenge: int | None = None  # the seat it challenged, until answered
    game: dict | None = None  # ... with these match settings
    table: Table | None = None  # the match it plays or watches


@dataclass
class Table:
    """A match between two seats: how it began and its moves so far, and who watches it."""

    game: dict
    players: list[int]  # the seats of its two players, in the match's order
    names: list[str]
    moves: list = field(default_factory=list)
    watchers: set[int] = field(default_factory=set)
    away: set[int] = field(default_factory=set)  # sides (0, 1) whose connection dropped
    over: bool = False  # a player's screen has seen its end: a drop then is a leaving
    timer: asyncio.TimerHandle | None = None  # when it stops waiting for them


class Lobby:
    def __init__(self) -> None:
        self.tokens: dict[str, str] = {}  # a session's token -> its player's name
        self.seats: dict[int, Seat] = {}
        self.waiting: list[Table] = []  # matches with a player away
        self.resume_wait = RESUME_WAIT_S
        self._next = 1

    def admit(self, name: str) -> str:
        """A token for `name`'s game (given to it in its environment)."""
        token = secrets.token_hex(16)
        self.tokens[token] = name
        return token

    def forget(self, token: str) -> None:
        self.tokens.pop(token, None)

    def _send(self, dest: Seat, kind: str, /, **fields) -> None:
        if not dest.writer.is_closing():
            dest.writer.write(wire.encode(kind, **fields))

    def _players(self) -> None:
        """Everyone's list of who is here, after any change."""
        names = [{"id": s.id, "name": s.name, "where": s.where, "with": self._with(s),
                  "challenge": self._challenge_of(s)} for s in self.seats.values()]
        for seat in self.seats.values():
            self._send(seat, wire.PLAYERS, players=names, you=seat.id)

    def _with(self, seat: Seat) -> str | None:
        """Whom a player plays ("bob"), or what they watch ("ann v bob")."""
        table = seat.table
        if table is None:
            return None
        if seat.where == "watching":
            return " v ".join(table.names)
        return table.names[1] if table.names[0] == seat.name else table.names[0]

    def _challenge_of(self, seat: Seat) -> dict | None:
        """The challenge a player in the lobby is in: {"to": id} or {"from": id} (the other
        player's seat), for each screen to say in its own words."""
        if seat.challenge in self.seats:
            return {"to": seat.challenge}
        by = next((s for s in self.seats.values() if s.challenge == seat.id), None)
        return None if by is None else {"from": by.id}

    async def connection(self, reader: asyncio.StreamReader,
                         writer: asyncio.StreamWriter) -> None:
        """One game's connection, from its HELLO to its end."""
        seat = None
        try:
            msg = wire.decode(await reader.readline())
            name = self.tokens.get(msg.get("token")) if msg and msg["t"] == wire.HELLO else None
            if not isinstance(name, str):
                writer.write(wire.encode(wire.REFUSED, why=wire.BAD))
                return
            seat = Seat(self._next, name, writer)
            self._next += 1
            self.seats[seat.id] = seat
            self._resume(seat)
            self._players()
            while True:
                line = await reader.readline()
                if not line.endswith(b"\n"):  # the end, or a line cut off
                    return
                msg = wire.decode(line)
                if msg is None:
                    self._send(seat, wire.REFUSED, why=wire.BAD)
                    continue
                self.handle(seat, msg)
        except (ConnectionError, ValueError):  # ValueError: a line past the limit
            return
        finally:
            if seat is not None:
                self.gone(seat)
            writer.close()

    def handle(self, seat: Seat, msg: dict) -> None:
        kind = msg["t"]
        if kind == wire.WHERE and seat.table is None:
            seat.where = "lobby" if msg.get("lobby") is True else "menu"
            if seat.where != "lobby":
                self._withdraw(seat)
            self._players()
        elif kind == wire.CHALLENGE:
            self._challenge(seat, msg.get("to"), msg.get("game"))
        elif kind == wire.ANSWER:
            self._answer(seat, msg.get("to"), msg.get("yes") is True)
        elif kind == wire.WATCH:
            self._watch(seat, msg.get("to"))
        elif kind == wire.MOVE and seat.where == "playing":
            self._move(seat, msg.get("move"))
        elif kind == wire.AIM and seat.where == "playing":
            self._pass_on(seat.table, seat, wire.AIM, aim=msg.get("aim"))
        elif kind == wire.OVER and seat.where == "playing":
            seat.table.over = True
        elif kind == wire.LEAVE:
            self._part(seat)
            self._players()
        else:
            self._send(seat, wire.REFUSED, why=wire.BAD)

    def _challenge(self, seat: Seat, to, game) -> None:
        other = self.seats.get(to) if isinstance(to, int) else None
        if (not isinstance(game, dict) or set(game) != set(wire.GAME_KEYS)
                or seat.where != "lobby"):
            self._send(seat, wire.REFUSED, why=wire.BAD)
        elif other is None:
            self._send(seat, wire.REFUSED, why=wire.GONE)
        elif other.name == seat.name:  # one player on two screens
            self._send(seat, wire.REFUSED, why=wire.SELF)
        elif (other is seat or other.where != "lobby" or seat.challenge is not None
              or other.challenge is not None  # waiting for their own answer
              or any(s.challenge in (other.id, seat.id)  # one of them has one to answer
                     for s in self.seats.values())):
            self._send(seat, wire.REFUSED, why=wire.BUSY)
        else:
            seat.challenge, seat.game = other.id, game
            self._send(other, wire.CHALLENGED, by=seat.id, name=seat.name, game=game)
            self._players()  # both are now in a challenge, for everyone to see

    def _answer(self, seat: Seat, to, yes: bool) -> None:
        other = self.seats.get(to) if isinstance(to, int) else None
        if other is None or other.challenge != seat.id:
            self._send(seat, wire.REFUSED, why=wire.GONE)
            return
        game = other.game
        other.challenge = other.game = None
        if not yes or seat.where != "lobby" or other.where != "lobby":
            self._send(other, wire.DECLINED, name=seat.name)
            self._players()
            return
        self._withdraw(seat)
        # The challenger is the first player.
        table = Table(game, [other.id, seat.id], [other.name, seat.name])
        for n, s in enumerate((other, seat)):
            s.table, s.where = table, "playing"
            self._send(s, wire.START, game=game, names=table.names, seat=n, moves=[])
        self._players()

    def _watch(self, seat: Seat, to) -> None:
        """`seat` watches the match player `to` plays: the match so far, then each move."""
        other = self.seats.get(to) if isinstance(to, int) else None
        if seat.where != "lobby":
            self._send(seat, wire.REFUSED, why=wire.BAD)
        elif other is None or other.table is None or other.where != "playing":
            self._send(seat, wire.REFUSED, why=wire.GONE)
        else:
            self._withdraw(seat)
            table = other.table
            table.watchers.add(seat.id)
            seat.table, seat.where = table, "watching"
            self._send(seat, wire.START, game=table.game, names=table.names, seat=None,
                       moves=table.moves)
            self._players()

    def _move(self, seat: Seat, move) -> None:
        table = seat.table
        if len(table.moves) >= MAX_MOVES:
            self._send(seat, wire.REFUSED, why=wire.BAD)
            return
        table.moves.append(move)
        self._pass_on(table, seat, wire.MOVE, move=move)

    def _pass_on(self, table: Table, seat: Seat, kind: str, /, **fields) -> None:
        """To the other player of `seat`'s match `table` and to its watchers."""
        for k in (*table.players, *sorted(table.watchers)):
            if k != seat.id and k in self.seats:
                self._send(self.seats[k], kind, **fields)

    def _withdraw(self, seat: Seat) -> None:
        """The challenges to and from `seat` are off."""
        if seat.challenge in self.seats:
            self._send(self.seats[seat.challenge], wire.WITHDRAWN, by=seat.id, name=seat.name)
        seat.challenge = seat.game = None
        for s in self.seats.values():
            if s.challenge == seat.id:
                s.challenge = s.game = None
                self._send(s, wire.DECLINED, name=seat.name)

    def _part(self, seat: Seat) -> None:
        """`seat` leaves its match. A watcher just goes; a player ends it: the other player
        and the watchers are told, and all are back in the menu."""
        table, seat.table = seat.table, None
        if table is None:
            return
        was, seat.where = seat.where, "menu"
        if was == "watching":
            table.watchers.discard(seat.id)
            return
        self._end(table, seat.name, seat)

    def _end(self, table: Table, name: str, seat: Seat | None = None) -> None:
        """`table` is over, `name` having left it: everyone still at it is told and is back
        in the menu; it waits for no one any more."""
        if table in self.waiting:
            self.waiting.remove(table)
        if table.timer is not None:
            table.timer.cancel()
            table.timer = None
        for k in (*table.players, *sorted(table.watchers)):
            other = self.seats.get(k)
            if other is None or other is seat or other.table is not table:
                continue
            other.table, other.where = None, "menu"
            self._send(other, wire.LEFT, name=name)

    def _away(self, seat: Seat) -> None:
        """`seat`'s connection dropped while it played: its match waits for it (unless the
        other player is away too: then it is over)."""
        table, seat.table = seat.table, None
        side = table.players.index(seat.id)
        table.away.add(side)
        if len(table.away) == 2:
            self._end(table, seat.name, seat)
            return
        if table not in self.waiting:
            self.waiting.append(table)
        if table.timer is not None:
            table.timer.cancel()
        table.timer = asyncio.get_running_loop().call_later(self.resume_wait, self._expire,
                                                            table)
        self._pass_on(table, seat, wire.AWAY, name=seat.name)

    def _expire(self, table: Table) -> None:
        """No one came back in time: the match is over."""
        table.timer = None
        if table in self.waiting:
            self._end(table, " and ".join(table.names[k] for k in sorted(table.away)))
            self._players()

    def _resume(self, seat: Seat) -> None:
        """A game that has just come: back in the match that waits for its player, if any."""
        for table in self.waiting:
            side = next((k for k in sorted(table.away) if table.names[k] == seat.name), None)
            if side is None:
                continue
            table.away.discard(side)
            if not table.away:
                self.waiting.remove(table)
                table.timer.cancel()
                table.timer = None
            table.players[side] = seat.id
            seat.table, seat.where = table, "playing"
            self._send(seat, wire.START, game=table.game, names=table.names, seat=side,
                       moves=table.moves)
            self._pass_on(table, seat, wire.BACK, name=seat.name)
            return

    def gone(self, seat: Seat) -> None:
        self._withdraw(seat)
        if seat.table is not None and seat.where == "playing" and not seat.table.over:
            self._away(seat)
        else:
            self._part(seat)
        self.seats.pop(seat.id, None)
        self._players()
