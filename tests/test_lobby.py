"""The lobby of `termpool serve`: its messages (the server's side), and online matches between
two apps, each with its own copy of the match, over a real socket."""

from __future__ import annotations

import asyncio
import json
import socket
import threading
import time
from dataclasses import replace

import pytest

from termpool import wire
from termpool.lobby import Lobby
from termpool.ui.app import App
from termpool.ui.headless import screen_text
from termpool.ui.keys import Key
from termpool.ui.link import Link, digest
from termpool.ui.phases import remote
from termpool.ui.phases.turn import shoot
from termpool.ui.state import Options, Over, Phase, Waiting, menu_entries
from termpool.ui.stats import stats_lines

WAIT_S = 20.0


@pytest.fixture
def lobby(tmp_path):
    """A Lobby listening on a socket, its loop in a thread of its own."""
    lob = Lobby()
    path = str(tmp_path / "lobby")
    loop = asyncio.new_event_loop()
    ready = threading.Event()
    holder = {}

    async def main():
        holder["server"] = await asyncio.start_unix_server(lob.connection, path,
                                                           limit=wire.MAX_LINE)
        ready.set()

    loop.run_until_complete(main())
    thread = threading.Thread(target=loop.run_forever, daemon=True)
    thread.start()
    ready.wait()
    lob.path = path
    yield lob

    async def shutdown():
        holder["server"].close()
        for task in asyncio.all_tasks():
            if task is not asyncio.current_task():
                task.cancel()
        await asyncio.sleep(0.01)

    asyncio.run_coroutine_threadsafe(shutdown(), loop).result(5)
    loop.call_soon_threadsafe(loop.stop)
    thread.join(5)
    loop.close()


class Raw:
    """A game's side of the lobby, by hand: messages out, messages in."""

    def __init__(self, lob: Lobby, name: str | None, token: str | None = None) -> None:
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.connect(lob.path)
        self.sock.settimeout(WAIT_S)
        self.file = self.sock.makefile("rb")
        self.send(wire.HELLO, token=token if token is not None else lob.admit(name))

    def close(self) -> None:
        self.file.close()  # the socket closes with the last of its users
        self.sock.close()

    def send(self, kind: str, **fields) -> None:
        self.sock.sendall(wire.encode(kind, **fields))

    def next(self, kind: str) -> dict:
        """The next message of this kind (the others before it skipped)."""
        while True:
            line = self.file.readline()
            assert line, f"closed before a {kind!r}"
            msg = json.loads(line)
            if msg["t"] == kind:
                return msg

    def players(self, test) -> dict:
        """The first list of players that passes `test`."""
        while True:
            msg = self.next(wire.PLAYERS)
            if test(msg["players"]):
                return msg


GAME = {"mode": "8ball", "table": "9ft", "frames": 1, "seed": 7, "three_foul": False,
        "eight_break": "respot", "theme": "standard"}


def where(players, name):
    return next((p["where"] for p in players if p["name"] == name), None)


def in_lobby_raw(lobby, *names: str) -> tuple[list[Raw], dict[str, int]]:
    """Games of `names` by hand, each with the lobby open, once the first sees them all
    there; and everyone's id by name."""
    raws = [Raw(lobby, n) for n in names]
    for r in raws:
        r.send(wire.WHERE, lobby=True)
    seen = raws[0].players(lambda ps: all(where(ps, n) == "lobby" for n in names))
    return raws, {p["name"]: p["id"] for p in seen["players"]}


def matched(lobby, *names: str) -> tuple[list[Raw], dict[str, int]]:
    """`in_lobby_raw`, then the first challenges the second, who accepts: both started."""
    raws, ids = in_lobby_raw(lobby, *names)
    raws[0].send(wire.CHALLENGE, to=ids[names[1]], game=GAME)
    raws[1].send(wire.ANSWER, to=raws[1].next(wire.CHALLENGED)["by"], yes=True)
    raws[0].next(wire.START)
    return raws, ids


def test_a_challenge_accepted_starts_one_match_for_both(lobby):
    (ann, bob), ids = in_lobby_raw(lobby, "ann", "bob")
    ann.send(wire.CHALLENGE, to=ids["bob"], game=GAME)
    got = bob.next(wire.CHALLENGED)
    assert got["name"] == "ann" and got["game"] == GAME
    bob.send(wire.ANSWER, to=got["by"], yes=True)
    a, b = ann.next(wire.START), bob.next(wire.START)
    assert a["game"] == b["game"] == GAME
    assert a["names"] == b["names"] == ["ann", "bob"]  # the challenger first
    assert (a["seat"], b["seat"]) == (0, 1)
    # A move goes to the other player only, as it was sent.
    move = {"kind": "shot", "at": "x", "speed": 0.1 + 0.2, "angle": 1e-300}
    ann.send(wire.MOVE, move=move)
    assert bob.next(wire.MOVE)["move"] == move
    ann.send(wire.LEAVE)
    assert bob.next(wire.LEFT)["name"] == "ann"
    after = bob.players(lambda ps: where(ps, "bob") == "menu")
    assert where(after["players"], "ann") == "menu"


def test_a_match_can_be_watched_from_its_start_and_its_moves_follow(lobby):
    (ann, bob, cy), ids = matched(lobby, "ann", "bob", "cy")
    first = {"kind": "place", "at": "a", "x": 0.5, "y": 0.6}
    ann.send(wire.MOVE, move=first)
    assert bob.next(wire.MOVE)["move"] == first
    cy.send(wire.WATCH, to=ids["bob"])
    start = cy.next(wire.START)
    assert start["seat"] is None and start["names"] == ["ann", "bob"]
    assert start["game"] == GAME and start["moves"] == [first]
    second = {"kind": "shot", "at": "b", "speed": 3.0}
    ann.send(wire.MOVE, move=second)
    assert cy.next(wire.MOVE)["move"] == second
    assert bob.next(wire.MOVE)["move"] == second
    cy.send(wire.MOVE, move=second)  # a watcher makes no moves
    assert cy.next(wire.REFUSED)["why"] == wire.BAD
    cy.send(wire.LEAVE)  # a watcher going ends nothing
    third = {"kind": "shot", "at": "c", "speed": 2.0}
    bob.send(wire.MOVE, move=third)
    assert ann.next(wire.MOVE)["move"] == third
    cy.send(wire.WHERE, lobby=True)
    cy.send(wire.WATCH, to=ids["ann"])
    assert cy.next(wire.START)["moves"] == [first, second, third]
    ann.send(wire.LEAVE)  # a player going ends it for everyone
    assert bob.next(wire.LEFT)["name"] == "ann"
    assert cy.next(wire.LEFT)["name"] == "ann"
    cy.send(wire.WHERE, lobby=True)
    cy.send(wire.WATCH, to=ids["bob"])  # no match now
    assert cy.next(wire.REFUSED)["why"] == wire.GONE


def test_a_declined_challenge_says_so_and_starts_nothing(lobby):
    (ann, bob), ids = in_lobby_raw(lobby, "ann", "bob")
    ann.send(wire.CHALLENGE, to=ids["bob"], game=GAME)
    got = bob.next(wire.CHALLENGED)
    bob.send(wire.ANSWER, to=got["by"], yes=False)
    assert ann.next(wire.DECLINED)["name"] == "bob"
    bob.send(wire.ANSWER, to=got["by"], yes=True)  # too late: nothing is open
    assert bob.next(wire.REFUSED)["why"] == wire.GONE


def test_a_challenger_who_leaves_the_lobby_withdraws_the_challenge(lobby, tmp_path):
    (ann, bob), ids = in_lobby_raw(lobby, "ann", "bob")
    ann.send(wire.CHALLENGE, to=ids["bob"], game=GAME)
    by = bob.next(wire.CHALLENGED)["by"]
    ann.send(wire.WHERE, lobby=False)
    got = bob.next(wire.WITHDRAWN)
    assert got["by"] == by and got["name"] == "ann"


def test_a_withdrawn_challenge_leaves_the_screen(lobby):
    from termpool.ui.phases.lobby import tick

    app = in_lobby(lobby, "bob")
    link = app.state.link
    link.challenged = {"t": wire.CHALLENGED, "by": 5, "name": "ann", "game": GAME}
    link._take({"t": wire.WITHDRAWN, "by": 5, "name": "ann"})
    app.state = tick(app.state, time.monotonic())
    assert link.challenged is None
    text = screen(app, 80, 24)
    assert "ann withdrew the challenge" in text and "challenges you" not in text


def test_one_player_on_two_screens_cannot_challenge_themselves(lobby):
    (ann, _bob), _ = in_lobby_raw(lobby, "ann", "bob")
    other = Raw(lobby, "ann")
    other.send(wire.WHERE, lobby=True)
    seen = ann.players(lambda ps: [p["name"] for p in ps].count("ann") == 2
                       and all(p["where"] == "lobby" for p in ps))
    me = next(p["id"] for p in seen["players"] if p["name"] == "ann" and p["id"] != seen["you"])
    ann.send(wire.CHALLENGE, to=me, game=GAME)
    assert ann.next(wire.REFUSED)["why"] == wire.SELF


def test_who_may_be_challenged(lobby):
    ann, bob = Raw(lobby, "ann"), Raw(lobby, "bob")
    ann.send(wire.WHERE, lobby=True)
    seen = ann.players(lambda ps: where(ps, "bob") == "menu")
    ids = {p["name"]: p["id"] for p in seen["players"]}
    ann.send(wire.CHALLENGE, to=ids["bob"], game=GAME)  # bob is in the menu
    assert ann.next(wire.REFUSED)["why"] == wire.BUSY
    ann.send(wire.CHALLENGE, to=ids["ann"], game=GAME)  # oneself
    assert ann.next(wire.REFUSED)["why"] == wire.SELF
    ann.send(wire.CHALLENGE, to=999, game=GAME)
    assert ann.next(wire.REFUSED)["why"] == wire.GONE
    ann.send(wire.CHALLENGE, to=ids["bob"], game={"mode": "8ball"})  # not a whole game
    assert ann.next(wire.REFUSED)["why"] == wire.BAD
    bob.send(wire.CHALLENGE, to=ids["ann"], game=GAME)  # from outside the lobby
    assert bob.next(wire.REFUSED)["why"] == wire.BAD


def test_a_player_who_drops_is_away_and_the_match_ends_if_they_do_not_come_back(lobby):
    lobby.resume_wait = 0.3
    (ann, bob), _ = matched(lobby, "ann", "bob")
    bob.close()
    assert ann.next(wire.AWAY)["name"] == "bob"
    ann.players(lambda ps: [p["name"] for p in ps] == ["ann"])
    t0 = time.monotonic()
    assert ann.next(wire.LEFT)["name"] == "bob"  # the wait is over
    assert time.monotonic() - t0 > 0.2
    assert lobby.waiting == []
    late = Raw(lobby, "bob")  # too late: no match to be back in (not "playing")
    assert where(late.next(wire.PLAYERS)["players"], "bob") == "menu"
    assert where(ann.players(lambda ps: len(ps) == 2)["players"], "ann") == "menu"


def test_a_player_who_comes_back_is_put_back_in_the_match_with_its_moves(lobby):
    (ann, bob, cy), ids = in_lobby_raw(lobby, "ann", "bob", "cy")
    ann.send(wire.CHALLENGE, to=ids["bob"], game=GAME)
    bob.send(wire.ANSWER, to=bob.next(wire.CHALLENGED)["by"], yes=True)
    ann.next(wire.START)
    bob.next(wire.START)
    cy.send(wire.WATCH, to=ids["ann"])
    cy.next(wire.START)
    first, second = {"kind": "place", "x": 0.5, "y": 0.6, "at": "a"}, \
        {"kind": "shot", "n": 2, "at": "b"}
    ann.send(wire.MOVE, move=first)
    assert bob.next(wire.MOVE)["move"] == first
    bob.close()
    assert ann.next(wire.AWAY)["name"] == "bob" and cy.next(wire.AWAY)["name"] == "bob"
    ann.send(wire.MOVE, move=second)  # ann's turn goes on; the move waits for bob too
    assert cy.next(wire.MOVE)["move"] == second
    back = Raw(lobby, "bob")
    start = back.next(wire.START)
    assert (start["seat"], start["names"], start["game"]) == (1, ["ann", "bob"], GAME)
    assert start["moves"] == [first, second]
    assert ann.next(wire.BACK)["name"] == "bob" and cy.next(wire.BACK)["name"] == "bob"
    assert lobby.waiting == []
    ann.players(lambda ps: where(ps, "bob") == "playing" and where(ps, "ann") == "playing")
    back.send(wire.MOVE, move={"kind": "shot", "n": 3})
    assert ann.next(wire.MOVE)["move"] == {"kind": "shot", "n": 3}


def test_leaving_a_match_that_waits_ends_it_and_a_player_away_on_both_sides_too(lobby):
    (ann, bob), _ = matched(lobby, "ann", "bob")
    bob.close()
    ann.next(wire.AWAY)
    ann.send(wire.LEAVE)
    ann.players(lambda ps: where(ps, "ann") == "menu")
    assert lobby.waiting == []
    # Both dropped: nobody is left to wait, so the match is over.
    (cy, dee), _ = matched(lobby, "cy", "dee")
    cy.close()
    dee.close()
    Raw(lobby, "ann").players(lambda ps: "cy" not in [p["name"] for p in ps]
                              and "dee" not in [p["name"] for p in ps])
    assert lobby.waiting == []


def test_a_drop_after_the_match_is_over_is_a_leaving_with_no_wait(lobby):
    (ann, bob), _ = matched(lobby, "ann", "bob")
    bob.next(wire.START)
    bob.send(wire.OVER)  # bob's screen has shown the match's end
    # (Read before bob's drop: a socket closed with lines unread in it may reach the
    # lobby as a reset before the lines it had sent.)
    end = time.monotonic() + WAIT_S
    while not any(s.table is not None and s.table.over for s in list(lobby.seats.values())):
        assert time.monotonic() < end, "the lobby never read OVER"
        time.sleep(0.005)
    bob.close()
    assert ann.next(wire.LEFT)["name"] == "bob"  # at once: no AWAY, no wait
    assert lobby.waiting == []
    back = Raw(lobby, "bob")  # bob again: in the menu, not back in a finished match
    assert where(back.next(wire.PLAYERS)["players"], "bob") == "menu"


def test_over_from_a_watcher_changes_nothing(lobby):
    lobby.resume_wait = 30.0
    (ann, bob, cy), ids = in_lobby_raw(lobby, "ann", "bob", "cy")
    ann.send(wire.CHALLENGE, to=ids["bob"], game=GAME)
    bob.send(wire.ANSWER, to=bob.next(wire.CHALLENGED)["by"], yes=True)
    ann.next(wire.START)
    cy.send(wire.WATCH, to=ids["ann"])
    cy.next(wire.START)
    cy.send(wire.OVER)  # not cy's match to end
    bob.close()
    assert ann.next(wire.AWAY)["name"] == "bob"  # the match waits for bob as before
    assert len(lobby.waiting) == 1 and not lobby.waiting[0].over


def test_a_game_without_a_good_token_or_with_garbage_is_refused(lobby):
    stranger = Raw(lobby, None, token="not-a-token")
    assert stranger.next(wire.REFUSED)["why"] == wire.BAD
    assert stranger.file.readline() == b""  # and the connection is closed
    ann = Raw(lobby, "ann")
    ann.sock.sendall(b"{not json\n")
    assert ann.next(wire.REFUSED)["why"] == wire.BAD
    ann.sock.sendall(b"x" * (wire.MAX_LINE + 10))  # no line at all: the connection goes
    with pytest.raises((AssertionError, ConnectionError)):
        ann.next(wire.PLAYERS)
        ann.next(wire.PLAYERS)


def test_a_token_is_one_players_and_is_forgotten_with_the_session(lobby):
    token = lobby.admit("ann")
    lobby.forget(token)
    assert Raw(lobby, None, token=token).next(wire.REFUSED)["why"] == wire.BAD


# --------------------------------------------------------------------- two apps, one match
def until(apps, test, what: str) -> None:
    end = time.monotonic() + WAIT_S
    while not test():
        assert time.monotonic() < end, f"timed out waiting for {what}"
        for app in apps:
            app.tick(time.monotonic())
        time.sleep(0.005)


def in_lobby(lobby, name: str, history=None) -> App:
    """`name`'s app with the lobby open (and its history in the file `history`, if given)."""
    from termpool.game.history import Recorder

    app = App(Options(colors="mono", player1=name), link=Link(lobby.path, lobby.admit(name)),
              history=None if history is None else Recorder(history))
    entries = [e[1] for e in menu_entries(app.state)]
    app.key(Key(str(entries.index("online") + 1)), time.monotonic())
    assert app.state.phase is Phase.LOBBY
    return app


def screen(app: App, cols: int = 80, rows: int = 24) -> str:
    return screen_text(app.cells(cols, rows)[0])


def break_online(ann: App, bob: App) -> None:
    """Ann puts the cue ball down and breaks; both screens until the balls stop."""
    ann.key(Key("enter"), time.monotonic())
    ann.state = shoot(ann.state, 8.0, 0.5, 0.0, 0.0)
    until([ann, bob], lambda: bob.state.phase is not Phase.RUN and bob.state.match.history
          and ann.state.phase is not Phase.RUN, "the break")


def online(lobby, tmp_path) -> tuple[App, App]:
    """Two apps (ann's, bob's) in an online 9-ball match that ann challenged bob to."""
    apps = [in_lobby(lobby, name, tmp_path / f"{name}.jsonl") for name in ("ann", "bob")]
    ann, bob = apps
    until(apps, lambda: len(ann.state.link.others()) == 1
          and ann.state.link.others()[0]["where"] == "lobby", "bob in ann's lobby")
    ann.key(Key("right"), time.monotonic())  # 9-ball
    ann.key(Key("enter"), time.monotonic())
    until(apps, lambda: bob.state.link.challenged is not None, "the challenge")
    text = screen(bob, 80, 24)
    assert "ann challenges you to 9-ball" in text
    bob.key(Key("y"), time.monotonic())
    until(apps, lambda: ann.state.match is not None and bob.state.match is not None,
          "the match")
    return ann, bob


def test_an_online_match_is_the_same_on_both_screens(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    a, b = ann.state.match, bob.state.match
    assert a.players == b.players == ("ann", "bob") and a.mode == "9ball"
    assert (ann.state.remote, bob.state.remote) == ((1,), (0,))
    assert bob.state.phase is Phase.REMOTE  # ann breaks; bob watches her move
    # Ann puts the cue ball down and breaks with her keys.
    ann.key(Key("up"), time.monotonic())
    ann.key(Key("enter"), time.monotonic())
    assert ann.state.phase is Phase.AIM
    until([bob], lambda: bob.state.part == Waiting(placed=True), "bob to see her place it")
    assert digest(a) == digest(b)
    text = screen(bob, 100, 30)
    assert "ann is aiming, on their own screen" in text
    ann.state = shoot(ann.state, 7.0, 1.5, 0.1, -0.2)
    until([ann, bob], lambda: ann.state.phase not in (Phase.RUN,)
          and bob.state.phase not in (Phase.RUN, Phase.REMOTE), "the break on both screens")
    assert len(a.history) == len(b.history) == 1
    assert json.dumps(a.to_json(), sort_keys=True) == json.dumps(b.to_json(), sort_keys=True)
    assert digest(a) == digest(b)
    # Whoever is to shoot now moves on their screen and the other waits.
    mover, watcher = (ann, bob) if a.shooter == 0 else (bob, ann)
    assert watcher.state.phase is Phase.REMOTE
    assert mover.state.phase in (Phase.AIM, Phase.PLACE, Phase.OPTION)
    # Ann leaves (the quit box says what it costs): bob is told, wins the match by her
    # leaving, is back in the menu, and keeps only his own line.
    ann.key(Key("q"), time.monotonic())
    assert "leaving gives bob the match" in screen(ann, 100, 30)
    ann.key(Key("m"), time.monotonic())
    until([bob], lambda: bob.state.phase is Phase.MENU, "bob told")
    text = screen(bob, 100, 30)
    assert "ann has left the match: you win it" in text
    lines = [json.loads(x) for x in (tmp_path / "bob.jsonl").read_text().splitlines()]
    assert [x["player"] for x in lines] == ["bob"] and lines[0]["opponent"] == "ann"
    assert (lines[0]["result"], lines[0]["forfeit"]) == ("won", True)
    (hers,) = [json.loads(x) for x in (tmp_path / "ann.jsonl").read_text().splitlines()]
    assert (hers["result"], hers["forfeit"]) == ("lost", True)
    # Bob was the second player, yet his Stats count the match, as one against someone
    # online.
    from termpool.game.history import read_history, summary

    got = summary(read_history(tmp_path / "bob.jsonl")[0])
    assert got["all"]["matches"] == 1 and list(got["per_opponent"]) == ["online"]
    assert "someone online" in "\n".join(stats_lines(got))
    assert [json.loads(x)["player"] for x in
            (tmp_path / "ann.jsonl").read_text().splitlines()] == ["ann"]


def play_a_shot(apps, power: float = 2.0, angle: float = 100.0) -> None:
    """Whoever is to shoot shoots (the cue ball put down first if in hand); every screen
    until the balls stop."""
    n = len(apps[0].state.match.history)
    mover = next(a for a in apps if a.state.phase in (Phase.AIM, Phase.PLACE))
    if mover.state.phase is Phase.PLACE:
        mover.key(Key("enter"), time.monotonic())
    mover.state = shoot(mover.state, power, angle, 0.0, 0.0)
    until(apps, lambda: all(len(a.state.match.history) == n + 1
                            and a.state.phase is not Phase.RUN for a in apps), "the shot")


def test_a_player_whose_connection_drops_is_back_in_the_match_when_they_return(lobby,
                                                                             tmp_path):
    from termpool.game.history import Recorder, read_history, summary
    from termpool.ui.phases.turn import log_match

    ann, bob = online(lobby, tmp_path)
    break_online(ann, bob)
    play_a_shot([ann, bob])
    # Bob's connection drops: his game is gone (as a SIGHUP ends it: the match kept, his
    # history's line "unfinished"); ann is told, and the match waits.
    log_match(bob.state)
    bob.state.link.close()
    until([ann], lambda: ann.state.link.away == "bob", "ann told")
    assert "bob's connection dropped: the match waits for them" in screen(ann, 100, 30)
    if ann.state.phase in (Phase.AIM, Phase.PLACE):  # ann's turn: she may play on
        play_a_shot([ann])
    # Bob comes back (a new session, at its menu): he is in the match at once, its moves
    # made, and plays his side again.
    back = App(Options(colors="mono", player1="bob"), link=Link(lobby.path, lobby.admit("bob")),
               history=Recorder(tmp_path / "bob.jsonl"))
    until([ann, back], lambda: back.state.match is not None and back.state.link.resume is None
          and back.state.phase is not Phase.RUN, "bob back in his match")
    a, b = ann.state.match, back.state.match
    assert len(b.history) == len(a.history) >= 2 and digest(a) == digest(b)
    assert back.state.remote == (0,) and ann.state.remote == (1,)
    assert "back in your match against ann" in screen(back, 100, 30)
    until([ann], lambda: ann.state.link.away is None, "ann told he is back")
    assert "bob is back" in screen(ann, 100, 30)
    assert (back.state.phase is Phase.REMOTE) == (a.shooter == 0)
    play_a_shot([ann, back], 3.0, 250.0)  # the match goes on, whoever is to shoot
    assert digest(ann.state.match) == digest(back.state.match)
    # Ann leaves; bob's history has both his lines, and counts the match once.
    ann.key(Key("q"), time.monotonic())
    ann.key(Key("m"), time.monotonic())
    until([back], lambda: back.state.phase is Phase.MENU, "bob told")
    lines = read_history(tmp_path / "bob.jsonl")[0]
    assert len(lines) == 2 and lines[0]["match"] == lines[1]["match"]
    assert lines[1]["shots"] >= lines[0]["shots"]
    got = summary(lines)
    assert got["all"]["matches"] == 1 and got["last"] == [lines[1]]


def drop_after_own_shot(lobby, tmp_path, bob_records=None) -> tuple[App, App]:
    """Ann and bob in a match, bob's connection dropping right after a shot of his own (his
    game ending as a SIGHUP ends it: its match kept); then bob back, a new session, in
    his match again. Returns (ann, bob's new app)."""
    from termpool.ui.phases.turn import log_match

    ann, bob = online(lobby, tmp_path)
    if bob_records is not None:
        bob.state = replace(bob.state, files=replace(bob.state.files, records=bob_records()))
    break_online(ann, bob)
    play_a_shot([ann, bob])
    while bob.state.match.history[-1]["player"] != 1:
        play_a_shot([ann, bob])
    log_match(bob.state)
    bob.state.link.close()
    until([ann], lambda: ann.state.link.away == "bob", "ann told")
    back = App(Options(colors="mono", player1="bob"), link=Link(lobby.path, lobby.admit("bob")),
               records=None if bob_records is None else bob_records())
    until([ann, back], lambda: back.state.match is not None and back.state.link.resume is None
          and back.state.phase is not Phase.RUN, "bob back in his match")
    return ann, back


def test_a_player_back_after_their_own_shot_does_not_send_it_again(lobby, tmp_path,
                                                                   monkeypatch):
    """Bob's last move before his connection dropped was his shot: back in the match, his
    new session makes it as it makes the others, and sends no move, so ann's copy (which
    has that shot already) is not thrown out of step; the match goes on."""
    sent = []
    real = Link.send

    def send(self, kind, **fields):
        sent.append((self, kind))
        real(self, kind, **fields)

    monkeypatch.setattr(Link, "send", send)
    ann, back = drop_after_own_shot(lobby, tmp_path)
    assert not [k for link, k in sent if link is back.state.link and k == wire.MOVE]
    assert digest(ann.state.match) == digest(back.state.match)
    for _ in range(2):  # whoever is to shoot, twice over
        play_a_shot([ann, back], 3.0, 250.0)
        assert ann.state.match is not None and back.state.match is not None, \
            (ann.state.message, back.state.message)
        assert digest(ann.state.match) == digest(back.state.match)


def test_a_player_back_in_their_match_goes_on_in_its_record_from_before_the_drop(lobby,
                                                                                 tmp_path):
    """Bob's game ends as his connection drops (its record kept); back in the match, his new
    session writes the whole match into that file, not into a second one, and never with
    fewer shots than that file holds."""
    from termpool.files import kept_records
    from termpool.game.record import read_replay
    from termpool.ui.records import Records

    folder = tmp_path / "bob-records"
    written = []

    class Counted(Records):
        def _write(self, k, kept):
            written.append((self, len(kept.match.history)))
            super()._write(k, kept)

    ann, back = drop_after_own_shot(lobby, tmp_path, lambda: Counted(None, folder=folder))
    (first,) = kept_records(folder)
    dropped = len(back.state.match.history)
    before = read_replay(first)["shots"]
    assert len(before) == dropped
    play_a_shot([ann, back], 3.0, 250.0)
    assert kept_records(folder) == [first]  # one file for the match
    after = read_replay(first)["shots"]
    assert after[:dropped] == before and len(after) == dropped + 1
    # The new session's writes, its catch-up's included: never fewer shots than the file had.
    mine = [n for who, n in written if who is back.state.files.records]
    assert mine and min(mine) >= dropped


def test_leaving_while_the_other_player_is_away_gives_them_nothing(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    break_online(ann, bob)
    bob.state.link.close()
    until([ann], lambda: ann.state.link.away == "bob", "ann told")
    ann.key(Key("q"), time.monotonic())
    assert "Quit termpool?" in screen(ann, 100, 30)
    assert "leaving gives" not in screen(ann, 100, 30)
    ann.key(Key("m"), time.monotonic())
    (hers,) = [json.loads(x) for x in (tmp_path / "ann.jsonl").read_text().splitlines()]
    assert hers["result"] == "unfinished" and "forfeit" not in hers


def test_a_screen_that_comes_to_watch_catches_up_and_follows(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    break_online(ann, bob)
    cy = in_lobby(lobby, "cy", tmp_path / "cy.jsonl")
    until([cy], lambda: any(p["where"] == "playing" for p in cy.state.link.others()),
          "the players in cy's lobby")
    cy.key(Key("enter"), time.monotonic())  # the first player listed: playing, so watched
    until([ann, bob, cy], lambda: cy.state.match is not None
          and cy.state.phase is Phase.REMOTE and len(cy.state.match.history) == 1,
          "cy caught up")
    assert cy.state.remote == (0, 1)
    assert digest(cy.state.match) == digest(ann.state.match) == digest(bob.state.match)
    # The next shot, whoever plays it, reaches cy's screen too.
    mover = ann if ann.state.match.shooter == 0 else bob
    if mover.state.phase is Phase.PLACE:
        mover.key(Key("enter"), time.monotonic())
    mover.state = shoot(mover.state, 2.0, 100.0, 0.0, 0.0)
    until([ann, bob, cy], lambda: all(len(a.state.match.history) == 2
                                      and a.state.phase is not Phase.RUN
                                      for a in (ann, bob, cy)), "the second shot")
    assert digest(cy.state.match) == digest(ann.state.match) == digest(bob.state.match)
    text = screen(cy, 80, 24)
    assert "ann" in text and "bob" in text
    cy.key(Key("q"), time.monotonic())
    cy.key(Key("m"), time.monotonic())  # cy goes; the match goes on
    until([ann, bob], lambda: True, "a tick")
    assert ann.state.match is not None and bob.state.match is not None
    assert not (tmp_path / "cy.jsonl").exists()  # a watcher's history has no one's line


def test_the_other_screen_follows_the_ball_in_hand_and_the_stick(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    for _ in range(3):
        ann.key(Key("up"), time.monotonic())
        time.sleep(0.12)  # the aim goes out at most every AIM_EVERY_S
        ann.tick(time.monotonic())
    until([ann, bob], lambda: bob.state.part.cursor == ann.state.part.cursor,
          "bob to see the ball in hand where ann has it")
    text = screen(bob, 100, 30)
    assert "ann is placing the cue ball" in text
    ann.key(Key("enter"), time.monotonic())
    for _ in range(3):
        ann.key(Key("left"), time.monotonic())
        time.sleep(0.12)
        ann.tick(time.monotonic())
    ann.key(Key("w"), time.monotonic())  # top spin
    until([ann, bob], lambda: bob.state.part.stick
          and (bob.state.stroke.angle, bob.state.stroke.top)
          == (ann.state.stroke.angle, ann.state.stroke.top), "bob to see ann's stick")
    assert ann.state.stroke.top != 0.0
    assert len(bob.state.match.history) == 0  # aiming is not a move
    # The stick is drawn on bob's screen (in colour): cells differ from a screen without it.
    import numpy as np

    bob.state = replace(bob.state, depth="truecolor")
    with_stick = bob.cells(100, 30)
    bob.state = replace(bob.state, part=replace(bob.state.part, stick=False))
    without = bob.cells(100, 30)
    assert not all(np.array_equal(a, b) for a, b in zip(with_stick, without, strict=True))


def test_the_other_screen_shows_the_aid_of_the_shot_being_aimed(lobby, tmp_path):
    from termpool.ui import aid

    ann, bob = online(lobby, tmp_path)
    ann.key(Key("enter"), time.monotonic())  # the cue ball down where it is
    assert ann.state.phase is Phase.AIM
    ann.key(Key("5"), time.monotonic())  # power 50%
    time.sleep(0.12)
    ann.key(Key("left"), time.monotonic())
    until([ann, bob], lambda: bob.state.part.stick and bob.state.part.power == 0.5
          and bob.state.stroke.angle == ann.state.stroke.angle, "bob to see ann's power")
    for app in ann, bob:
        app.cells(100, 30)  # a screen drawn starts its aid (the driver draws after a move)
    until([ann, bob], lambda: not (aid.running(bob.state) or aid.running(ann.state)),
          "the aids")
    mine, theirs = aid.prediction(ann.state), aid.prediction(bob.state)
    assert theirs is not None and theirs.ball == mine.ball  # the same shot, foreseen alike
    assert "ann's aid at 50% power · first ball: the" in screen(bob, 100, 30)
    # The watcher's own setting still rules: with the aid off, none of it shows.
    bob.state = replace(bob.state, opts=replace(bob.state.opts, aid="off"))
    assert aid.prediction(bob.state) is None and "ann's aid" not in screen(bob, 100, 30)


def test_the_other_screen_is_told_when_the_player_to_move_pauses(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    ann.key(Key("enter"), time.monotonic())  # the cue ball down: ann aims
    ann.key(Key("p"), time.monotonic())
    until([ann, bob], lambda: "ann has paused the game" in screen(bob, 100, 30), "bob told")
    ann.key(Key("space"), time.monotonic())  # on again, and aiming
    time.sleep(0.12)
    ann.key(Key("left"), time.monotonic())
    until([ann, bob], lambda: "ann is aiming" in screen(bob, 100, 30), "bob sees her aim")


def test_aims_go_to_the_match_only_and_are_not_kept(lobby):
    (ann, bob, cy), ids = matched(lobby, "ann", "bob", "cy")
    cy.send(wire.WATCH, to=ids["ann"])
    assert cy.next(wire.START)["moves"] == []
    aim = {"kind": "stick", "values": [10.0, 0.0, 0.1]}
    ann.send(wire.AIM, aim=aim)
    assert bob.next(wire.AIM)["aim"] == aim
    assert cy.next(wire.AIM)["aim"] == aim
    cy.send(wire.LEAVE)
    cy.send(wire.WHERE, lobby=True)
    cy.send(wire.WATCH, to=ids["ann"])
    assert cy.next(wire.START)["moves"] == []


def test_copies_that_differ_end_the_match_instead_of_playing_on_apart(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    bob.state.match.pos[3, 0] += 1e-12  # one ball a picometre out on bob's copy
    ann.key(Key("enter"), time.monotonic())  # ann places: the move carries her digest
    until([bob], lambda: bob.state.phase is Phase.MENU, "bob's copy to notice")
    assert bob.state.message[0][0] == remote.OUT_OF_STEP


@pytest.mark.parametrize("move", [
    {"kind": "shot", "speed": "fast"}, {"kind": "place", "x": 1e9, "y": 0.0},
    {"kind": "choose", "choice": "dance"}, {"kind": "jump"},
    {"kind": "place", "x": float("nan"), "y": 0.5}])
def test_a_move_that_cannot_be_made_ends_the_match(lobby, tmp_path, move):
    ann, bob = online(lobby, tmp_path)
    bob.state.link.moves.append({"at": digest(bob.state.match), **move})
    bob.state = remote.tick(bob.state, time.monotonic())
    assert bob.state.phase is Phase.MENU
    assert bob.state.message[0][0] == remote.UNREADABLE


def test_the_waiting_screen_says_who_is_moving_and_takes_no_shot_keys(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    text = screen(bob, 100, 30)
    assert "ann is placing the cue ball, on their own screen" in text
    before = bob.state.match.to_json()
    for k in ("space", "enter", "left", "1"):
        bob.key(Key(k), time.monotonic())
    assert isinstance(bob.state.part, Waiting)
    assert bob.state.match.to_json() == before


def test_the_server_going_ends_the_match(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    bob.state.link.sock.shutdown(socket.SHUT_RDWR)
    bob.state = replace(bob.state)
    until([bob], lambda: bob.state.phase is Phase.MENU, "bob to notice")
    assert "the server has gone" in bob.state.message[0][0]


@pytest.mark.parametrize("bad", [{"frames": 0}, {"frames": 2.5}, {"mode": "practice"},
                                 {"table": "99ft"}, {"table": ["9ft"]}, {"seed": -1},
                                 {"theme": None}, {"eight_break": "again"}])
def test_a_match_that_cannot_be_built_is_said_and_left(lobby, bad):
    from termpool.ui.phases.lobby import start_online

    app = in_lobby(lobby, "ann")
    s = start_online(app.state, {"game": {**GAME, **bad}, "names": ["ann", "bob"], "seat": 1})
    assert s.phase is Phase.LOBBY and s.match is None
    assert "could not start" in s.message[0][0]


def test_without_a_server_the_menu_has_no_online_entry():
    app = App(Options(colors="mono"))
    assert "online" not in [e[1] for e in menu_entries(app.state)]
    assert Link.open(None) is None
    assert Link.open(("/nonexistent/lobby", "t")) is None


# ------------------------------------------------------------------ the lobby's own keys
def challenge(by: App, to: App) -> None:
    """`by` (in the lobby with `to`, and no one else) challenges `to`, who sees it."""
    name = to.state.opts.player1
    until([by, to], lambda: [p["where"] for p in by.state.link.others()] == ["lobby"],
          f"{name} in the lobby")
    by.key(Key("enter"), time.monotonic())
    until([by, to], lambda: to.state.link.challenged is not None, "the challenge")


def test_n_declines_a_challenge_and_esc_takes_one_back_or_leaves(lobby):
    ann, bob = in_lobby(lobby, "ann"), in_lobby(lobby, "bob")
    challenge(ann, bob)
    bell = bob.state.opts.bell
    bob.key(Key("n"), time.monotonic())  # N answers the challenge, not the bell
    assert bob.state.opts.bell == bell and bob.state.link.challenged is None
    until([ann, bob], lambda: "bob declined" in screen(ann), "ann told")
    ann.key(Key("enter"), time.monotonic())  # again, then taken back with Esc
    until([ann, bob], lambda: bob.state.link.challenged is not None, "the second challenge")
    assert "waiting for bob (8-ball) to answer" in screen(ann)
    ann.key(Key("esc"), time.monotonic())
    assert ann.state.phase is Phase.LOBBY and ann.state.part.waiting is None
    until([ann, bob], lambda: bob.state.link.challenged is None, "bob's challenge gone")
    assert "ann withdrew the challenge" in screen(bob)
    bob.key(Key("esc"), time.monotonic())  # nothing open: Esc leaves the lobby
    assert bob.state.phase is Phase.MENU


def test_leaving_the_lobby_by_the_quit_box_takes_ones_challenge_with_one(lobby):
    ann, bob = in_lobby(lobby, "ann"), in_lobby(lobby, "bob")
    challenge(bob, ann)
    bob.key(Key("q"), time.monotonic())
    bob.key(Key("m"), time.monotonic())  # Q, then M: the menu
    assert bob.state.phase is Phase.MENU
    until([ann, bob], lambda: ann.state.link.challenged is None
          and [p["where"] for p in ann.state.link.others()] == ["menu"], "ann told")
    ann.key(Key("y"), time.monotonic())  # nothing to accept: no match with nobody
    until([ann, bob], lambda: True, "a tick")
    assert ann.state.match is None and bob.state.match is None


def test_the_choice_follows_the_player_as_others_come(lobby):
    ann, cy = in_lobby(lobby, "ann"), in_lobby(lobby, "cy")
    until([ann, cy], lambda: len(ann.state.link.others()) == 1, "cy in ann's lobby")
    ann.key(Key("down"), time.monotonic())
    assert ann.state.part.chosen == ann.state.link.others()[0]["id"]
    bob = in_lobby(lobby, "bob")  # comes before cy by name
    until([ann, bob, cy], lambda: len(ann.state.link.others()) == 2, "bob in ann's lobby")
    assert [p["name"] for p in ann.state.link.others()] == ["bob", "cy"]
    ann.key(Key("enter"), time.monotonic())
    until([ann, bob, cy], lambda: cy.state.link.challenged is not None, "cy challenged")
    assert bob.state.link.challenged is None


def test_no_one_in_a_challenge_can_be_challenged_or_challenge(lobby):
    (ann, bob, cy), ids = in_lobby_raw(lobby, "ann", "bob", "cy")
    ann.send(wire.CHALLENGE, to=ids["bob"], game=GAME)
    bob.next(wire.CHALLENGED)
    cy.send(wire.CHALLENGE, to=ids["ann"], game=GAME)  # ann waits for bob's answer
    assert cy.next(wire.REFUSED)["why"] == wire.BUSY
    bob.send(wire.CHALLENGE, to=ids["cy"], game=GAME)  # bob has ann's to answer first
    assert bob.next(wire.REFUSED)["why"] == wire.BUSY


def test_the_lobby_says_whom_each_player_plays(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    cy = in_lobby(lobby, "cy")
    until([ann, bob, cy], lambda: "playing" in screen(cy), "cy's list")
    assert "ann  playing bob (Enter: watch)" in screen(cy)
    assert "bob  playing ann" in screen(cy)


def test_a_match_over_stays_on_show_when_the_other_player_goes(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    for app in (ann, bob):
        app.state.match.winner = 0  # the match won, on both screens
        app.state = replace(app.state, part=Over())
    assert "N: the lobby" in screen(ann, 100, 30)
    bob.key(Key("m"), time.monotonic())  # bob goes back to the menu
    until([ann, bob], lambda: "bob has left" in screen(ann, 100, 30), "ann told")
    assert ann.state.phase is Phase.OVER  # the end, the W to watch it, stay hers


def test_a_screen_that_shows_the_match_over_frees_the_server_from_waiting(lobby, tmp_path):
    from termpool.ui.phases.turn import start_turn

    ann, bob = online(lobby, tmp_path)
    for app in (ann, bob):
        app.state.match.winner = 0  # the match won, on both screens, as a shot ends it
        app.state = start_turn(app.state)
        assert app.state.phase is Phase.OVER
    bob.state.link.close()  # bob's connection drops at the game-over box
    until([ann], lambda: "bob has left" in screen(ann, 100, 30), "ann told")
    assert ann.state.phase is Phase.OVER and ann.state.link.away is None
    assert lobby.waiting == []


def test_a_watcher_joining_late_sees_the_table_as_it_is_not_old_shots(lobby, tmp_path):
    ann, bob = online(lobby, tmp_path)
    break_online(ann, bob)
    cy = in_lobby(lobby, "cy")
    until([cy], lambda: any(p["where"] == "playing" for p in cy.state.link.others()),
          "the players in cy's lobby")
    cy.key(Key("enter"), time.monotonic())
    until([ann, bob, cy], lambda: cy.state.match is not None
          and len(cy.state.match.history) == 1, "cy caught up")
    assert cy.state.phase is not Phase.RUN  # the break is over: not shown again
    assert "watching" in screen(cy)
    assert digest(cy.state.match) == digest(ann.state.match)


def test_the_lobby_shows_who_is_in_a_challenge(lobby):
    ann, bob, cy = in_lobby(lobby, "ann"), in_lobby(lobby, "bob"), in_lobby(lobby, "cy")
    until([ann, bob, cy], lambda: len(ann.state.link.others()) == 2
          and all(p["where"] == "lobby" for p in ann.state.link.others()), "all in the lobby")
    ann.key(Key("enter"), time.monotonic())  # bob, first by name
    until([ann, bob, cy], lambda: "a challenge from ann" in screen(cy), "cy's list")
    assert "ann  in the lobby, a challenge to bob" in screen(cy)
    # Each of the two sees themselves as "you"; bob, answering, sees no game of his own.
    until([ann, bob], lambda: "bob  in the lobby, a challenge from you" in screen(ann)
          and "ann  in the lobby, a challenge to you" in screen(bob), "the two lists")
    assert "ann challenges you to 8-ball" in screen(bob) and "game: ◀" not in screen(bob)
    assert "game: ◀" in screen(ann)
    bob.key(Key("n"), time.monotonic())
    until([ann, bob, cy], lambda: "a challenge" not in screen(cy), "the challenge gone")
