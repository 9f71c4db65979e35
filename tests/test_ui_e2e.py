"""End to end: the real `termpool` in a pseudo-terminal, played with keys, read through pyte.

These tests wait for screens (with generous timeouts) rather than for times: nothing asserts on
wall-clock speed.
"""

from __future__ import annotations

import re
import signal
import sys
import termios

import pytest

pytest.importorskip("pyte")
if sys.platform == "win32":  # pragma: no cover
    pytest.skip("needs a POSIX pty", allow_module_level=True)

from pty_game import PtyGame, restored  # noqa: E402


def cooked(fd: int) -> bool:
    """The terminal is back in its normal (canonical, echoing) mode."""
    lflag = termios.tcgetattr(fd)[3]
    return bool(lflag & termios.ICANON) and bool(lflag & termios.ECHO)


def table_cells(g: PtyGame) -> list:
    """What the table area shows: characters and colours of every cell above the panel."""
    buf = g.screen.buffer
    return [(r, c, buf[r][c].data, buf[r][c].fg, buf[r][c].bg)
            for r in range(g.rows - 6) for c in range(g.cols)]


@pytest.fixture
def game():
    made = []

    def start(*args, **kw):
        g = PtyGame(*args, **kw)
        made.append(g)
        return g

    yield start
    for g in made:
        g.close()


def test_play_a_shot_and_quit_restores_the_terminal(game) -> None:
    g = game("play", "--mode", "practice", cols=100, rows=32)
    assert g.wait_for("You to break"), g.text()
    g.send("\r", pause=0.3)  # practice starts with ball in hand: Enter places it
    before = table_cells(g)
    g.send("\x1b[C" * 3, pause=0.3)  # aim a little to the right of the rack
    g.send(" ", pause=1.2)  # a tap with no auto-repeat: the oscillating meter starts
    g.send(" ", pause=0.2)  # ... and the second tap strikes
    g.send("f")  # fast forward
    assert g.wait_for("You to shoot", timeout=60), g.text()
    assert table_cells(g) != before  # the balls moved
    g.send("q")
    assert g.wait_for("Quit termpool?")
    g.send("y")
    assert g.wait() == 0
    assert restored(g.raw)
    assert cooked(g.fd)


def test_no_arguments_opens_the_menu(game) -> None:
    g = game(cols=90, rows=30)
    assert g.wait_for("8-ball vs computer"), g.text()
    for item in ("8-ball, two players", "9-ball", "Practice", "Help", "Quit"):
        assert item in g.text()
    g.send("5")  # practice
    assert g.wait_for("You to break"), g.text()
    g.send("q")
    g.send("y")
    assert g.wait() == 0 and restored(g.raw)


def test_first_frame_comes_before_any_terminal_query(game) -> None:
    # A pty answers no queries: the table must already be on screen when we ask for kitty
    # keyboard support, so a silent terminal costs a bounded wait after the first frame.
    g = game("play", "--mode", "practice", cols=100, rows=32)
    assert g.wait_for("You to break"), g.text()
    assert g.wait_for_raw(b"\x1b[?u")  # (it follows the frame: a loaded machine may delay it)
    queries = [b"\x1bP+q", b"\x1b[?u", b"\x1b[6n", b"\x1b[>q", b"\x1b[c", b"\x1b]1"]
    first_query = min(g.raw.index(q) for q in queries if q in g.raw)
    assert g.raw.index("▀".encode()) < first_query
    g.send("q")
    g.send("y")
    assert g.wait() == 0


@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 128 + 15), (signal.SIGHUP, 128 + 1),
                                       (signal.SIGQUIT, 128 + 3)])
def test_signals_restore_the_terminal(game, sig, code) -> None:
    g = game("play", "--mode", "8ball", "--opponent", "human", cols=100, rows=32)
    assert g.wait_for("Player 1 to break"), g.text()
    g.kill(sig)
    assert g.wait() == code
    assert restored(g.raw)
    assert cooked(g.fd)


def test_ctrl_c_restores_the_terminal(game) -> None:
    g = game("play", "--mode", "practice", cols=100, rows=32)
    assert g.wait_for("You to break"), g.text()
    g.send("\x03")
    assert g.wait() == 130
    assert restored(g.raw) and cooked(g.fd)


def test_ctrl_z_puts_the_terminal_back_then_redraws(game) -> None:
    g = game("play", "--mode", "practice", cols=100, rows=32)
    assert g.wait_for("You to break"), g.text()
    mark = len(g.raw)
    g.send("\x1a", pause=0.5)
    g.kill(signal.SIGCONT)  # a job-control shell's `fg` (here the child may not stop at all)
    g.pump(0.5)
    after = g.raw[mark:]
    assert b"\x1b[?1049l" in after and b"\x1b[?1049h" in after
    assert after.index(b"\x1b[?1049l") < after.rindex(b"\x1b[?1049h")
    assert g.wait_for("You to break")
    g.send("q")
    g.send("y")
    assert g.wait() == 0


def test_resize_relays_out_and_tiny_windows_get_a_message(game) -> None:
    g = game("play", "--mode", "practice", cols=100, rows=32)
    assert g.wait_for("You to break"), g.text()
    g.resize(30, 10)
    assert g.wait_for("make the window at least"), g.text()
    g.resize(120, 40)
    assert g.wait_for("You to break"), g.text()
    rows = g.text().splitlines()
    assert "make the window" not in g.text()
    assert len(rows) == 40 and len(rows[0]) == 120
    g.send("q")
    g.send("y")
    assert g.wait() == 0 and restored(g.raw)


def test_an_exception_inside_the_app_restores_the_terminal(game) -> None:
    code = (
        "import sys\n"
        "from termpool.ui import term\n"
        "class Boom:\n"
        "    done = False\n"
        "    dirty = True\n"
        "    depth = 'truecolor'\n"
        "    n = 0\n"
        "    def key(self, k, t): pass\n"
        "    def wake_in(self, t): return 0.0\n"
        "    def cells(self, c, r):\n"
        "        from termpool.ui.panel import blank_cells\n"
        "        return blank_cells(c, r, False)\n"
        "    def tick(self, t):\n"
        "        self.n += 1\n"
        "        if self.n > 3: raise RuntimeError('boom')\n"
        "term.run(Boom(), 'truecolor')\n"
    )
    g = game("-c", code, cols=80, rows=24, python_args=True)
    g.wait()
    assert g.status == 1
    assert restored(g.raw) and cooked(g.fd)
    assert b"RuntimeError: boom" in g.raw


def test_a_timed_wake_is_slept_not_spun(game) -> None:
    """An app that needs a tick every 0.2 s (a lobby polling its server) is ticked about five
    times a second, not in a loop, and draws only what changed."""
    code = (
        "import time\n"
        "from termpool.ui import term\n"
        "class Poll:\n"
        "    done = False\n"
        "    dirty = True\n"
        "    depth = 'truecolor'\n"
        "    ticks = 0\n"
        "    def key(self, k, t): pass\n"
        "    def wake_in(self, t): return 0.2\n"
        "    def cells(self, c, r):\n"
        "        from termpool.ui.panel import blank_cells\n"
        "        self.dirty = False\n"
        "        return blank_cells(c, r, False)\n"
        "    def tick(self, t):\n"
        "        self.ticks += 1\n"
        "        self.done = self.ticks >= 1000 or time.monotonic() > self.end\n"
        "app = Poll()\n"
        "app.end = time.monotonic() + 1.5\n"
        "term.run(app, 'truecolor', kitty=False)\n"
        "print('ticks', app.ticks)\n"
    )
    g = game("-c", code, cols=80, rows=24, python_args=True)
    g.wait()
    ticks = int(re.search(rb"ticks (\d+)", g.raw).group(1))
    assert 5 <= ticks <= 12  # 1.5 s at a tick every 0.2 s; a spin would reach 1000


def test_kitty_terminal_hold_space_and_release_to_shoot(game) -> None:
    # A terminal that answers the kitty keyboard query gets the protocol (flags pushed, popped
    # on exit) and reports releases: Space shoots when it is let go.
    g = game("play", "--mode", "practice", cols=100, rows=32, kitty=True)
    assert g.wait_for("You to break"), g.text()
    g.pump(0.5)
    assert b"\x1b[>11u" in g.raw  # disambiguate + event types + all keys as escapes
    g.send("\x1b[13u", pause=0.3)  # Enter (as kitty reports it): place the cue ball
    assert g.wait_for("Space:hold "), g.text()  # the power mode, in the key help (short)
    g.send("\x1b[32u", pause=0.2)  # Space pressed ...
    g.send("\x1b[32;1:2u" * 3, pause=0.4)  # ... held (repeats) ...
    g.send("\x1b[32;1:3u", pause=0.2)  # ... released: the shot goes
    g.send("\x1b[102u")  # f: fast forward
    assert g.wait_for("You to shoot", timeout=60), g.text()
    g.send("\x1b[113u")  # q
    assert g.wait_for("Quit termpool?")
    g.send("\x1b[121u")  # y
    assert g.wait() == 0
    assert restored(g.raw) and cooked(g.fd)
    assert g.raw.rindex(b"\x1b[<u") > g.raw.rindex(b"\x1b[>11u")  # flags popped on the way out


def test_kitty_terminal_ctrl_c_still_quits_and_restores(game) -> None:
    # With all keys reported as escapes, Ctrl-C is a key (CSI 99;5u), not a signal.
    g = game("play", "--mode", "practice", cols=100, rows=32, kitty=True)
    assert g.wait_for("You to break"), g.text()
    g.pump(0.5)
    g.send("\x1b[99;5u")
    assert g.wait() == 130
    assert restored(g.raw) and cooked(g.fd) and b"\x1b[<u" in g.raw


def test_mouse_click_moves_the_ball_in_hand_and_mouse_mode_is_switched_off(game) -> None:
    g = game("play", "--mode", "practice", cols=100, rows=32)
    assert g.wait_for("You to break"), g.text()
    assert b"\x1b[?1002h" in g.raw and b"\x1b[?1006h" in g.raw
    before = table_cells(g)
    g.send("\x1b[<0;30;8M\x1b[<0;30;8m", pause=0.5)  # click at column 30, row 8 (1-based)
    assert table_cells(g) != before  # the cue ball followed the click
    g.send("q")
    g.send("y")
    assert g.wait() == 0 and restored(g.raw)
    assert g.raw.rindex(b"\x1b[?1002l") > g.raw.rindex(b"\x1b[?1002h")


def test_a_key_right_after_a_frame_is_drawn_without_waiting_for_the_idle_timeout(game) -> None:
    # The app animates until a key stops it (as Q does to a shot): the key lands between two
    # frames, and its change must be drawn at the next frame, not at the end of the idle
    # wait (60 s here, so a late frame would never come in time).
    code = (
        "from termpool.ui import term\n"
        "from termpool.ui.panel import blank_cells\n"
        "from termpool.ui.canvas import put_text\n"
        "class Keys:\n"
        "    done = False\n"
        "    dirty = True\n"
        "    n = 0\n"
        "    moving = True  # frames back to back, like a shot, until the first key\n"
        "    def key(self, k, t):\n"
        "        self.n += 1\n"
        "        self.moving = False\n"
        "        self.dirty = True\n"
        "        self.done = k.name == 'x'\n"
        "    def mouse(self, ev, t): pass\n"
        "    def wake_in(self, t): return 0.0 if self.moving else None\n"
        "    def tick(self, t): self.dirty = self.dirty or self.moving\n"
        "    def cells(self, c, r):\n"
        "        self.dirty = False\n"
        "        cells = blank_cells(c, r, False)\n"
        "        put_text(cells, 0, 0, f'keys seen {self.n}', (200, 200, 200), (0, 0, 0))\n"
        "        return cells\n"
        "term.run(Keys(), 'truecolor', kitty=False, idle=60.0)\n"
    )
    g = game("-c", code, cols=40, rows=10, python_args=True)
    assert g.wait_for("keys seen 0", timeout=10), g.text()
    for k in range(1, 4):
        g.send("a", pause=0.0)
        assert g.wait_for(f"keys seen {k}", timeout=10), g.text()
    g.send("x")
    assert g.wait(timeout=10) == 0


def test_ctrl_backslash_restores_the_terminal(game) -> None:
    g = game("play", "--mode", "practice", cols=100, rows=32)
    assert g.wait_for("You to break"), g.text()
    g.send("\x1c")  # Ctrl-\: the terminal sends SIGQUIT
    assert g.wait() == 128 + 3
    assert restored(g.raw) and cooked(g.fd)
    assert b"Traceback" not in g.raw and b"core dumped" not in g.raw


def test_kitty_terminal_ctrl_backslash_quits_like_sigquit(game) -> None:
    # With all keys reported as escapes, Ctrl-\ is a key (CSI 92;5u), not a signal.
    g = game("play", "--mode", "practice", cols=100, rows=32, kitty=True)
    assert g.wait_for("You to break"), g.text()
    g.pump(0.5)
    g.send("\x1b[92;5u")
    assert g.wait() == 128 + 3
    assert restored(g.raw) and cooked(g.fd) and b"\x1b[<u" in g.raw


def flow_control(fd: int) -> bool:
    return bool(termios.tcgetattr(fd)[0] & termios.IXON)


def test_ctrl_s_cannot_freeze_the_game(game) -> None:
    g = game("play", "--mode", "practice", cols=100, rows=32)
    assert flow_control(g.fd)  # a terminal starts with it on
    assert g.wait_for("You to break"), g.text()
    assert not flow_control(g.fd)  # off while playing
    g.send("\x13", pause=0.2)  # Ctrl-S: with flow control on, all output would stop here
    g.send("h")
    assert g.wait_for("this help", timeout=10), g.text()  # the help box is drawn
    g.kill(signal.SIGTERM)
    assert g.wait() == 128 + 15
    assert restored(g.raw) and cooked(g.fd) and flow_control(g.fd)  # and back on at the end


def break_shot(g) -> None:
    """Practice: place the cue ball and break (the balls then roll for seconds)."""
    assert g.wait_for("You to break"), g.text()
    g.send("\r", pause=0.3)
    g.send(" ", pause=1.2)  # no auto-repeat in a pty: the swinging meter starts ...
    g.send(" ", pause=0.3)  # ... and the second tap strikes


@pytest.mark.parametrize("how, code", [("qy", 0), ("\x03", 130), (signal.SIGTERM, 143),
                                       (signal.SIGHUP, 129)])
def test_leaving_while_the_balls_roll_keeps_the_record(game, tmp_path, capsys, how,
                                                       code) -> None:
    from termpool import cli

    rec = tmp_path / "match.json"
    g = game("play", "--mode", "practice", "--record", str(rec), cols=100, rows=32)
    break_shot(g)
    if isinstance(how, str):
        for ch in how:
            g.send(ch, pause=0.1)
    else:
        g.kill(how)
    assert g.wait() == code
    assert restored(g.raw)
    assert b"Traceback" not in g.raw
    assert f"record saved to {rec} (1 shot)".encode() in g.raw
    assert cli.main(["replay", str(rec)]) == 0  # the shot, played out, replays identically
    assert capsys.readouterr().out.endswith("1 shot: all identical\n")


def test_a_terminal_without_an_alternate_screen_is_left_clean(game) -> None:
    # The Linux console (TERM=linux) has no alternate screen: the game's last frame, quit box
    # and all, would stay under the shell's prompt unless leaving clears it.
    g = game("play", "--mode", "practice", cols=100, rows=32, env={"TERM": "linux"})
    assert g.wait_for("You to break"), g.text()
    assert b"\x1b[?1049h" not in g.raw  # no alternate screen was asked for
    g.send("q", pause=0.3)
    assert "Quit termpool?" in g.text()
    g.send("y")
    assert g.wait() == 0
    assert g.text().strip() == "", g.text()
    assert b"\x1b[?25h" in g.raw[-16:] and cooked(g.fd)  # the cursor is back
