"""Test-wide settings.

Hypothesis runs derandomized by default, so that the suite (and CI) is reproducible: the same
examples every run. Set HYPOTHESIS_PROFILE=explore to search new random examples instead.
"""

import os
import signal
from pathlib import Path

import pytest
from contact_check import checked_handle
from hypothesis import settings

from termpool.physics.engine import Engine

# A suite started in the background by a non-interactive shell inherits SIGINT ignored, and
# so would every game it starts: the tests that press Ctrl-C need it as a terminal gives it
# (a handled signal is back to its default in a child after exec; an ignored one is not).
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

settings.register_profile("repeatable", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))


@pytest.fixture(autouse=True)
def _contacts_are_checked(monkeypatch):
    """Every contact the engine applies in any test must be between touching bodies."""
    monkeypatch.setattr(Engine, "_handle", checked_handle(Engine._handle))


@pytest.fixture(autouse=True)
def _own_config_and_data(monkeypatch, tmp_path_factory):
    """No test reads the user's settings or keys, or writes to their history: the config and
    data directories are fresh temporary ones (a test that needs them sets its own)."""
    base = tmp_path_factory.mktemp("xdg")
    monkeypatch.setenv("XDG_CONFIG_HOME", str(base / "config"))
    monkeypatch.setenv("XDG_DATA_HOME", str(base / "data"))


# The user's own directories, as the environment names them before any test changes it (a
# child process started with a bare environment falls back to these).
USER_DIRS = [Path(os.environ.get(var) or Path.home() / rest) / "termpool"
             for var, rest in (("XDG_DATA_HOME", ".local/share"), ("XDG_CONFIG_HOME", ".config"))]


def _files(dirs: list[Path]) -> dict[str, tuple[int, int]]:
    return {str(f): (f.stat().st_mtime_ns, f.stat().st_size)
            for d in dirs if d.is_dir() for f in d.rglob("*") if f.is_file()}


@pytest.fixture(autouse=True, scope="session")
def _the_user_s_files_are_untouched():
    """However a test starts the game (a subprocess with an environment of its own
    included), the suite writes nothing to the user's history, records or settings."""
    before = _files(USER_DIRS)
    yield
    assert _files(USER_DIRS) == before, "a test wrote to the user's own termpool files"
