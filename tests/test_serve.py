"""`termpool serve`: the game over SSH, tried with a real SSH client against a real server
process on this machine's loopback, and the screen read back through a terminal emulator."""

from __future__ import annotations

import asyncio
import os
import re
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

asyncssh = pytest.importorskip("asyncssh")
pyte = pytest.importorskip("pyte")

ROOT = Path(__file__).resolve().parents[1]
MENU = "8-ball vs computer"
WAIT_S = 30.0  # a game process starts in well under a second; the machine may be loaded


class Served:
    """A `termpool serve` process on a free port."""

    def __init__(self, directory: Path, *extra: str) -> None:
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "termpool", "serve", "--port", "0", "--dir",
             str(directory), *extra],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, cwd=ROOT)
        line = self.proc.stdout.readline()
        m = re.search(r"port (\d+)", line)
        assert m, line + self.proc.stderr.read()
        self.port = int(m.group(1))
        self.directory = directory

    def stop(self) -> tuple[int, str]:
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
        try:
            rc = self.proc.wait(WAIT_S)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
        return rc, self.proc.stderr.read()


@pytest.fixture
def served(tmp_path):
    servers = []

    def start(*extra: str) -> Served:
        s = Served(tmp_path / "server", *extra)
        servers.append(s)
        return s

    yield start
    for s in servers:
        s.stop()


def connect(port: int, name: str = "alice", **kw):
    return asyncssh.connect("127.0.0.1", port, username=name, known_hosts=None,
                            client_keys=kw.pop("client_keys", None), **kw)


async def at_menu(conn, cols: int = 80, rows: int = 24, term: str = "xterm-256color"):
    """A session of `conn` on a terminal of this size, its menu on screen: the process and
    what its screen shows."""
    p = await conn.create_process(term_type=term, term_size=(cols, rows), encoding=None)
    seen = Seen(p, cols, rows)
    await seen.until(lambda v: v.shows(MENU))
    return p, seen


class Seen:
    """What a session's screen shows: its output through a terminal emulator."""

    def __init__(self, process, cols: int, rows: int) -> None:
        self.process = process
        self.screen = pyte.Screen(cols, rows)
        self.stream = pyte.ByteStream(self.screen)
        self.raw = b""

    async def until(self, test, timeout: float = WAIT_S) -> None:
        end = time.monotonic() + timeout
        while not test(self):
            left = end - time.monotonic()
            assert left > 0, "timed out; the screen shows:\n" + self.text()
            try:
                data = await asyncio.wait_for(self.process.stdout.read(65536), min(left, 1.0))
            except TimeoutError:
                continue
            if not data:
                return
            self.raw += data
            self.stream.feed(data)

    def text(self) -> str:
        return "\n".join(self.screen.display)

    def shows(self, words: str) -> bool:
        return words in self.text()


def run(coro):
    return asyncio.run(asyncio.wait_for(coro, 3 * WAIT_S))


def test_a_connection_plays_the_game_at_its_own_size_and_quits_cleanly(served):
    s = served()

    async def go():
        async with connect(s.port) as conn:
            p, seen = await at_menu(conn)
            p.stdin.write(b"q")
            await seen.until(lambda v: False, timeout=10)  # to the end of the output
            await p.wait_closed()
            return seen, p.exit_status

    seen, status = run(go())
    assert status == 0
    assert seen.raw.endswith(b"\x1b[?1049l") or b"\x1b[?1049l" in seen.raw[-64:]


def test_a_resize_reaches_the_game(served):
    s = served()

    def right_edge(v: Seen) -> int:
        return max((len(line.rstrip()) for line in v.screen.display), default=0)

    async def go():
        async with connect(s.port) as conn:
            p, seen = await at_menu(conn)
            p.stdin.write(b"\r")  # 8-ball against the computer: the table fills the width
            await seen.until(lambda v: v.shows("alice"))
            narrow = right_edge(seen)
            seen.screen.resize(40, 120)
            p.change_terminal_size(120, 40)
            await seen.until(lambda v: right_edge(v) > 100)
            p.stdin.write(b"q")
            return narrow, right_edge(seen)

    narrow, wide = run(go())
    assert narrow <= 80 < 100 < wide


def test_a_dropped_connection_hangs_up_the_game_which_keeps_its_history(served):
    s = served()
    history = s.directory / "players" / "bob" / "data" / "termpool" / "history.jsonl"

    async def go():
        conn = await connect(s.port, "bob")
        p, seen = await at_menu(conn, 100, 30)
        p.stdin.write(b"\r")
        await seen.until(lambda v: v.shows("bob to break"))
        p.stdin.write(b"\r")  # the cue ball placed where it is offered
        await seen.until(lambda v: not v.shows("ball in hand"))
        p.stdin.write(b" ")  # a press starts the charge, the next strikes (no releases)
        await asyncio.sleep(0.3)
        p.stdin.write(b" ")
        # The break played: the verdict, or the computer's turn.
        await seen.until(lambda v: any(v.shows(w) for w in ("bob's turn", "thinking", "foul")))
        conn.abort()  # the network goes: no quit, no goodbye

    run(go())
    rc, log = s.stop()
    assert rc == 0
    assert "bob left (hung up)" in log
    # The game saved the match on the hang-up, under bob's own directory.
    assert history.exists()
    assert '"bob"' in history.read_text()


def test_without_a_terminal_it_says_how_to_connect(served):
    s = served()

    async def go():
        async with connect(s.port) as conn:
            return await conn.run(encoding=None)

    r = run(go())
    assert r.exit_status == 1
    assert b"ssh -t" in r.stdout


def test_a_name_that_cannot_be_a_player_is_refused(served):
    s = served()

    async def go(name):
        async with connect(s.port, name) as conn:
            return await conn.run(term_type="xterm", encoding=None)

    assert run(go("a" * 17)).exit_status == 2  # longer than the game's names may be
    r = run(go("../etc"))
    assert r.exit_status == 2
    assert b"name" in r.stdout
    assert not (s.directory / "players" / ".." / "etc").exists()
    assert not (s.directory / "etc").exists()


def test_past_the_most_sessions_a_player_is_told_the_server_is_full(served):
    s = served("--max-sessions", "1")

    async def go():
        async with connect(s.port) as first:
            p, _ = await at_menu(first, term="xterm")
            async with connect(s.port, "carol") as second:
                r = await second.run(term_type="xterm", term_size=(80, 24), encoding=None)
            p.stdin.write(b"q")
            return r

    r = run(go())
    assert r.exit_status == 1
    assert b"full" in r.stdout


def test_the_host_key_is_made_once_private_and_kept(served, tmp_path):
    first = served()
    key = first.directory / "ssh_host_ed25519_key"
    assert stat.S_IMODE(key.stat().st_mode) == 0o600
    text = key.read_bytes()
    first.stop()
    served()
    assert key.read_bytes() == text


def test_with_authorized_keys_only_those_keys_get_in(served, tmp_path):
    allowed = asyncssh.generate_private_key("ssh-ed25519")
    other = asyncssh.generate_private_key("ssh-ed25519")
    keys = tmp_path / "authorized_keys"
    keys.write_bytes(allowed.export_public_key())
    s = served("--authorized-keys", str(keys))

    async def attempt(key):
        try:
            async with connect(s.port, client_keys=[key]) as conn:
                r = await conn.run(encoding=None)  # no terminal: let in, then told so
                return r.exit_status
        except asyncssh.PermissionDenied:
            return "denied"

    assert run(attempt(other)) == "denied"
    assert run(attempt(allowed)) == 1


def test_stopping_the_server_hangs_up_every_game(served):
    s = served()

    async def go():
        async with connect(s.port, "dave") as conn:
            p, seen = await at_menu(conn, term="xterm")
            s.proc.send_signal(signal.SIGTERM)
            await seen.until(lambda v: False, timeout=WAIT_S)  # to the end of the output
            await p.wait_closed()

    run(go())
    rc = s.proc.wait(WAIT_S)  # it stops by itself once its games have gone
    log = s.proc.stderr.read()
    assert rc == 0
    assert "dave left" in log and "stopped" in log


def test_bad_arguments_are_one_line_and_exit_2(tmp_path):
    r = subprocess.run([sys.executable, "-m", "termpool", "serve", "--port", "70000"],
                       capture_output=True, text=True, cwd=ROOT,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "--port" in r.stderr
    r = subprocess.run([sys.executable, "-m", "termpool", "serve", "--authorized-keys",
                        str(tmp_path / "none")], capture_output=True, text=True, cwd=ROOT,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "--authorized-keys" in r.stderr


def test_without_asyncssh_it_says_what_to_install(monkeypatch, capsys):
    from termpool import serve
    from termpool.cli import _parser

    monkeypatch.setitem(sys.modules, "asyncssh", None)
    args = _parser(["serve"]).parse_args(["serve"])
    assert serve.run(args) == 2
    assert "pip install" in capsys.readouterr().err


def test_two_players_meet_in_the_lobby_and_play_one_match_on_two_screens(served):
    s = served()

    async def go():
        async with connect(s.port, "ann") as c1, connect(s.port, "bob") as c2:
            (p1, ann), (p2, bob) = await at_menu(c1, 100, 30), await at_menu(c2)
            assert ann.shows("Play someone online") and bob.shows("Play someone online")
            p2.stdin.write(b"6")
            await bob.until(lambda v: v.shows("Players online"))
            p1.stdin.write(b"6")
            await ann.until(lambda v: v.shows("bob  in the lobby"))
            p1.stdin.write(b"\r")  # challenge bob to 8-ball
            await bob.until(lambda v: v.shows("ann challenges you to 8-ball"))
            p2.stdin.write(b"y")
            await ann.until(lambda v: v.shows("ann to break"))
            await bob.until(lambda v: v.shows("ann is placing the cue ball"))
            await asyncio.sleep(0.6)  # an Enter soon after the last one would be its repeat
            p1.stdin.write(b"\r")  # ann puts the cue ball down
            await bob.until(lambda v: v.shows("ann is aiming"))
            p1.stdin.write(b"9")  # 90% ...
            await asyncio.sleep(0.2)
            p1.stdin.write(b" ")  # ... struck at once
            # The same verdict on both screens, each at its own size.
            # (Any break: the match's seed is drawn afresh, and a scratch's verdict is "Your
            # foul: ..." on one screen and "ann's foul: ..." on the other: read from "foul".)
            verdict = re.compile(r"(legal break|illegal break|foul)[^\n]*", re.IGNORECASE)
            await ann.until(lambda v: verdict.search(v.text()) is not None)
            await bob.until(lambda v: verdict.search(v.text()) is not None)
            said = verdict.search(ann.text()).group(0).strip()
            assert said[:40] in bob.text()
            p1.stdin.write(b"qy")
            await bob.until(lambda v: v.shows("ann has left the match"))
            p2.stdin.write(b"q")

    run(go())


def test_a_connection_that_takes_no_bytes_pauses_its_game_not_the_server(tmp_path):
    """A game writes faster than its player's connection takes the bytes: the server stops
    reading that game's screen at MAX_BUFFER waiting (the game then waits on its own
    terminal) and goes on once the connection drains; nothing is lost."""
    from termpool import serve

    total = 6 * serve.MAX_BUFFER
    game = [sys.executable, "-c",
            f"import os\nfor _ in range({total // 65536}): os.write(1, b'x' * 65536)\n"]

    class Channel:
        def __init__(self, out):
            self.out = out

        def get_write_buffer_size(self):
            return len(self.out.data) - self.out.sent

    class Out:
        def __init__(self):
            self.data, self.sent, self.most = b"", 0, 0
            self.go = asyncio.Event()

        def write(self, data):
            self.data += data
            self.most = max(self.most, len(self.data) - self.sent)

        async def drain(self):
            await self.go.wait()
            self.sent = len(self.data)

    class Keys:
        async def read(self, n):
            await asyncio.sleep(3600)

    class Process:
        def __init__(self):
            self.stdout, self.stdin = Out(), Keys()
            self.channel = Channel(self.stdout)

        def get_terminal_size(self):
            return (80, 24, 0, 0)

        def get_terminal_type(self):
            return "xterm"

    async def go():
        server = serve.Server(tmp_path, command=game)
        p = Process()
        run = asyncio.ensure_future(server._run_game(p, "ann"))
        await asyncio.sleep(1.0)
        stalled = len(p.stdout.data)
        p.stdout.go.set()  # the connection takes bytes again
        status = await asyncio.wait_for(run, WAIT_S)
        return stalled, p, status

    stalled, p, status = asyncio.run(go())
    assert serve.MAX_BUFFER < stalled < serve.MAX_BUFFER + 2 * 65536  # it paused there
    assert status == 0
    assert p.stdout.data.count(b"x") == total  # every byte, once the connection drained
