"""Text from outside (files, names, network) made safe to print on a terminal.

A file's text can hold control characters: ESC starts sequences that clear the screen, retitle
the window or remap keys, BEL rings, a carriage return hides what came before, and bidirectional
overrides reorder what is read. `shown` writes each of them escaped, the way Python writes them
in a string ("\\x1b", "\\n", "\\u202e"), so the text is printed as it is, never obeyed.
"""

from __future__ import annotations

import sys
import unicodedata

PROG = "termpool"  # the command's name, first on every line it says

_NAMED = {"\t": "\\t", "\n": "\\n", "\r": "\\r"}
_CONTROLS = [*range(0x20), *range(0x7F, 0xA0),  # C0, DEL and C1 (0x9b is an 8-bit CSI)
             0x2028, 0x2029,  # line and paragraph separators
             *range(0x200E, 0x2010), *range(0x202A, 0x202F), *range(0x2066, 0x206A)]  # bidi
_TABLE = {c: _NAMED.get(chr(c)) or (f"\\x{c:02x}" if c < 0x100 else f"\\u{c:04x}")
          for c in _CONTROLS}


def shown(text: object) -> str:
    """`text` (made a string) with every control character written as an escape."""
    return str(text).translate(_TABLE)


def one_column(ch: str) -> bool:
    """Whether a printable character takes one column of a terminal: not a wide one (CJK,
    most emoji), which takes two, nor a combining mark or variation selector, which takes
    none. (The screen is drawn a character a cell.)"""
    return (unicodedata.east_asian_width(ch) not in ("W", "F")
            and unicodedata.category(ch) not in ("Mn", "Me"))


def say(message: object) -> None:
    """One line on stderr, "termpool: message": whitespace runs become one space, control
    characters are shown escaped, and a terminal that went away (SIGHUP) is not an error."""
    line = f"{PROG}: {' '.join(shown(message).split())}\n"
    try:
        sys.stderr.write(line)
        sys.stderr.flush()
    except (OSError, ValueError):  # gone (EIO), or stderr closed
        pass
