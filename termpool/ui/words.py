"""What the screen says about the options a player may be offered (an illegal 8-ball break,
a 9-ball push-out): the question's box, the letters that answer it, and the answer in words
("Player 2 chose to pass the shot back") for the game and for a watched match."""

from __future__ import annotations

OPTION_WORDS = {"rerack": "re-rack and break", "accept": "accept the table",
                "shoot": "shoot", "pass": "pass the shot back"}
OPTION_KEYS = {
    "rerack_or_accept": {"r": "rerack", "a": "accept"},
    "shoot_or_pass": {"s": "shoot", "p": "pass"},
}
OPTION_TEXT = {
    "rerack_or_accept": ["The break was illegal.", "", "r: re-rack and break yourself",
                         "a: accept the table and shoot"],
    "shoot_or_pass": ["Your opponent pushed out.", "", "s: shoot from here",
                      "p: pass the shot back"],
}


def chose(who: str, choice: str) -> str:
    """A player's answer in words."""
    return f"{who} chose to {OPTION_WORDS[choice]}"
