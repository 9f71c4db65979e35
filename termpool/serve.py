"""`termpool serve`: the game over SSH. Anyone who connects with `ssh -p PORT NAME@HOST` gets
the whole game (menu, matches, settings, stats) at their own terminal's size, as NAME.

Each connection runs the ordinary game (`termpool play`) in a process of its own on a
pseudo-terminal, so that it behaves exactly as on a local terminal: its own size and resizes,
its own key decoding, the terminal restored when it ends, and a slow computer opponent on one
connection never holds up another. The server only carries bytes, window sizes and hang-ups
between the SSH channel and that process. A dropped connection is a hang-up (SIGHUP): the
game saves its record and settings on the way out, as it does on a local terminal.

Every player has their own settings, history and records under DIR/players/NAME (the
server's directory, by default the data directory's `server`). The host key is made once,
on the first start, as DIR/ssh_host_ed25519_key (mode 0600).

asyncssh is an optional dependency (`pip install termpool[ssh]`); nothing else imports this
module.
"""

from __future__ import annotations

import argparse
import asyncio
import fcntl
import os
import re
import shutil
import signal
import struct
import sys
import tempfile
import termios
import warnings
from pathlib import Path

from termpool import wire
from termpool.files import data_dir, write_atomic
from termpool.lobby import Lobby
from termpool.text import say
from termpool.ui.play import whole_number
from termpool.ui.settings import MAX_NAME

# A player's name: the game's own limit (it must fit the panel), and a directory's name.
NAME = re.compile(rf"[A-Za-z0-9][A-Za-z0-9_.-]{{0,{MAX_NAME - 1}}}\Z")
MAX_SESSIONS = 16
MAX_BUFFER = 1 << 20  # bytes of screen a connection may have waiting to be sent
HANG_UP_S = 5.0  # a game told to hang up gets this long to save and leave before SIGKILL
DEFAULT_TERM = "xterm-256color"  # a client that names no terminal type
KEY_NAME = "ssh_host_ed25519_key"
NEEDS_PTY = "termpool: the game needs a terminal: connect with ssh -t\r\n"
FULL = "termpool: the server is full ({n} playing); try again later\r\n"
BAD_NAME = (f"termpool: a player's name is 1 to {MAX_NAME} letters, digits, '_', '-' or "
            "'.', beginning with a letter or digit (ssh NAME@host)\r\n")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--host", default="127.0.0.1",
                   help="the address to listen on (default 127.0.0.1: this machine only; "
                        "0.0.0.0 for every network)")
    p.add_argument("--port", type=whole_number(0, 65535), default=2222,
                   help="the port (default 2222; 0 picks a free one, printed on start)")
    p.add_argument("--dir", metavar="DIR", default=None,
                   help="the server's host key and players' files (default: the data "
                        "directory's server/)")
    p.add_argument("--authorized-keys", metavar="FILE", default=None,
                   help="let in only the keys in this file (OpenSSH authorized_keys form); "
                        "without it anyone who can reach the port may play, under any name")
    p.add_argument("--max-sessions", type=whole_number(1, 1000),
                   default=MAX_SESSIONS,
                   help=f"the most players at once (default {MAX_SESSIONS})")


def player_env(base: dict, home: Path, term: str) -> dict:
    """The environment of one player's game: their own directories, the client's terminal
    type, UTF-8 text. Nothing of the server's own settings or history leaks in."""
    env = {k: v for k, v in base.items()
           if k in ("PATH", "PYTHONPATH", "PYTHONHASHSEED", "TZ", "OPENBLAS_NUM_THREADS",
                    "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
    env.update(HOME=str(home), XDG_DATA_HOME=str(home / "data"),
               XDG_CONFIG_HOME=str(home / "config"), TERM=term or DEFAULT_TERM,
               LANG="C.UTF-8", LC_ALL="C.UTF-8")
    return env


def set_size(fd: int, cols: int, rows: int) -> None:
    """Give the pseudo-terminal `fd` a window size; the kernel tells its game (SIGWINCH)."""
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", max(rows, 1), max(cols, 1), 0, 0))


def _take_terminal() -> None:
    # In the child, after setsid: its standard input (the pty) becomes its controlling
    # terminal, so that a hang-up and resizes reach it.
    fcntl.ioctl(0, termios.TIOCSCTTY, 0)


def host_key(directory: Path):
    """The server's host key: read, or made and written (mode 0600) on the first start."""
    import asyncssh

    path = directory / KEY_NAME
    if path.exists():
        return asyncssh.read_private_key(str(path))
    key = asyncssh.generate_private_key("ssh-ed25519")
    directory.mkdir(parents=True, exist_ok=True)
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)  # private from the start
    os.close(fd)
    write_atomic(path, key.export_private_key())
    return key


class Server:
    """The listening server: sessions in, one game process each."""

    def __init__(self, directory: Path, max_sessions: int = MAX_SESSIONS,
                 command: list[str] | None = None) -> None:
        self.directory = directory
        self.max_sessions = max_sessions
        # The game as each player runs it; its name on screen is the SSH user name.
        self.command = command or [sys.executable, "-m", "termpool", "play"]
        self.games: set[asyncio.subprocess.Process] = set()
        self.sessions = 0
        self.lobby = Lobby()
        self.socket: str | None = None  # the lobby's socket, once it listens

    def log(self, text: str) -> None:
        sys.stderr.write(f"termpool serve: {text}\n")
        sys.stderr.flush()

    async def session(self, process) -> None:
        """One connection, start to end."""
        name = process.get_extra_info("username") or ""
        peer = (process.get_extra_info("peername") or ("?",))[0]
        if not NAME.match(name):
            process.stdout.write(BAD_NAME.encode())
            process.exit(2)
            return
        if process.get_terminal_type() is None:
            process.stdout.write(NEEDS_PTY.encode())
            process.exit(1)
            return
        if self.sessions >= self.max_sessions:
            process.stdout.write(FULL.format(n=self.sessions).encode())
            process.exit(1)
            return
        self.sessions += 1
        self.log(f"{name} connected from {peer} ({self.sessions} playing)")
        status = None
        try:
            status = await self._run_game(process, name)
        finally:
            self.sessions -= 1
            self.log(f"{name} left ({'hung up' if status is None else f'exit {status}'})")
        if status is not None:
            process.exit(status)

    async def _run_game(self, process, name: str) -> int | None:
        """Run `name`'s game on a pseudo-terminal and carry bytes both ways until the game
        ends (its exit status) or the connection drops (None: the game was hung up)."""
        home = self.directory / "players" / name
        home.mkdir(parents=True, exist_ok=True)
        cols, rows = process.get_terminal_size()[:2]
        env = player_env(dict(os.environ), home, process.get_terminal_type())
        token = self.lobby.admit(name)
        if self.socket is not None:
            env.update({wire.ENV_SOCKET: self.socket, wire.ENV_TOKEN: token})
        try:
            return await self._carry(process, home, env, cols, rows)
        finally:
            self.lobby.forget(token)

    async def _carry(self, process, home: Path, env: dict, cols: int, rows: int) -> int | None:
        master, slave = os.openpty()
        set_size(master, cols or 80, rows or 24)
        try:
            game = await asyncio.create_subprocess_exec(
                *self.command, "--player1", home.name,
                stdin=slave, stdout=slave, stderr=slave, start_new_session=True,
                preexec_fn=_take_terminal, cwd=str(home), env=env)
        finally:
            os.close(slave)
        self.games.add(game)
        os.set_blocking(master, False)
        loop = asyncio.get_running_loop()
        output_done = loop.create_future()

        def readable() -> None:
            try:
                data = os.read(master, 65536)
            except BlockingIOError:
                return
            except OSError:  # EIO: the game has closed its terminal
                data = b""
            if data:
                try:
                    process.stdout.write(data)
                except (BrokenPipeError, ConnectionError):  # the player has gone: the
                    return  # game is being hung up
                if process.channel.get_write_buffer_size() > MAX_BUFFER:
                    # A player whose connection takes no bytes: stop reading the game's
                    # screen until it drains (their game then waits on its own terminal).
                    loop.remove_reader(master)
                    asyncio.ensure_future(resume())
            else:
                loop.remove_reader(master)
                if not output_done.done():
                    output_done.set_result(None)

        async def resume() -> None:
            try:
                await process.stdout.drain()
            except (BrokenPipeError, ConnectionError):
                return
            if not output_done.done() and master in open_fds:
                loop.add_reader(master, readable)

        open_fds = {master}
        loop.add_reader(master, readable)
        keys = asyncio.ensure_future(self._carry_input(process, master))
        ended = asyncio.ensure_future(game.wait())
        try:
            await asyncio.wait({keys, ended}, return_when=asyncio.FIRST_COMPLETED)
            if ended.done():
                # Whatever the game wrote last (restoring the terminal) goes out first.
                await asyncio.wait({output_done}, timeout=1.0)
                return game.returncode
            await self.hang_up(game)
            return None
        finally:
            keys.cancel()
            loop.remove_reader(master)
            open_fds.discard(master)
            os.close(master)
            self.games.discard(game)

    async def _carry_input(self, process, master: int) -> None:
        """The player's keys to the game, and window changes to its terminal, until the
        connection ends."""
        import asyncssh

        while True:
            try:
                data = await process.stdin.read(4096)
            except asyncssh.TerminalSizeChanged as e:
                set_size(master, e.width, e.height)
                continue
            except (asyncssh.Error, ConnectionError, BrokenPipeError):
                return
            if not data:
                return
            view = memoryview(data)
            while view:
                try:
                    view = view[os.write(master, view):]
                except BlockingIOError:  # the game is not reading yet: wait a little
                    await asyncio.sleep(0.01)
                except OSError:
                    return

    async def hang_up(self, game) -> None:
        """Hang the game up (it saves and leaves), and kill it if it has not within
        HANG_UP_S."""
        if game.returncode is not None:
            return
        try:
            os.killpg(game.pid, signal.SIGHUP)
        except ProcessLookupError:
            return
        try:
            await asyncio.wait_for(game.wait(), HANG_UP_S)
        except TimeoutError:
            try:
                os.killpg(game.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            await game.wait()

    async def close(self) -> None:
        """Hang up every game (each saves on its way out)."""
        await asyncio.gather(*(self.hang_up(g) for g in list(self.games)))


async def _serve(args: argparse.Namespace, directory: Path) -> int:
    import asyncssh

    key = host_key(directory)
    server = Server(directory, args.max_sessions)
    # The lobby's socket, in a directory of the server's own (a socket's path must be short).
    private = tempfile.mkdtemp(prefix="termpool-")
    server.socket = os.path.join(private, "lobby")
    lobby = await asyncio.start_unix_server(server.lobby.connection, server.socket,
                                            limit=wire.MAX_LINE)
    auth = args.authorized_keys

    class Gate(asyncssh.SSHServer):
        def begin_auth(self, username: str) -> bool:
            return auth is not None  # without a keys file: no authentication

    listener = await asyncssh.create_server(
        Gate, args.host, args.port, server_host_keys=[key], process_factory=server.session,
        encoding=None, line_editor=False, authorized_client_keys=auth,
        password_auth=False, kbdint_auth=False)
    port = listener.sockets[0].getsockname()[1]
    print(f"termpool serve: listening on {args.host} port {port} "
          f"(ssh -t -p {port} NAME@{args.host}); host key {directory / KEY_NAME}", flush=True)
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        loop.add_signal_handler(sig, stop.set)
    try:
        await stop.wait()
    finally:
        listener.close()
        await server.close()
        lobby.close()
        shutil.rmtree(private, ignore_errors=True)
    server.log("stopped")
    return 0


def run(args: argparse.Namespace) -> int:
    """`termpool serve`: listen until SIGINT, SIGTERM or SIGHUP, then hang up every game."""
    try:
        with warnings.catch_warnings():
            # asyncssh names DSA keys at import, which newer cryptography warns about (some
            # ten lines on stderr): nothing the server's operator can act on.
            warnings.simplefilter("ignore")
            import asyncssh  # noqa: F401
    except ImportError:
        say("serve: needs asyncssh (pip install 'termpool[ssh]')")
        return 2
    directory = Path(args.dir) if args.dir else data_dir() / "server"
    if args.authorized_keys is not None and not os.path.isfile(args.authorized_keys):
        say(f"serve: --authorized-keys: no such file: {args.authorized_keys}")
        return 2
    try:
        return asyncio.run(_serve(args, directory))
    except OSError as e:
        say(f"serve: {e.strerror or e}")
        return 1

