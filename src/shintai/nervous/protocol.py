"""The line protocol of nervous (seed 003 App. C.2.1): how a line is read, never evaluated.

C.2.1: nervous reads its socket (and standard input) one line at a time and

1. "``#`` で始まる → 何もせず" — a comment: nothing;
2. "``(`` で始まる → ``CommandEusNoRet()`` を実行" — an s-expression, which the thesis handed to EusLisp;
3. "最初の 1 単語は登録されているコマンドである → そのコマンドを実行" — a registered command;
4. "最初の1単語は登録されているプラグインモジュール名である → そのプラグインモジュールがなんらかのアクション
   を実行" — the rest goes to the plugin instance of that name;
5. "1. ~ 4. でない → シェルに渡す" — anything else went to the shell.

Here rule 2 is a small s-expression *reader* (:func:`read_sexpr`): the forms a EusLisp client sends
(``(send *ns* :angle-vector #f(…) ms)``, ``:state``, ``:interpolation-method``) are parsed into
lists, symbols, keywords, numbers and float vectors, and the interpreter recognises those forms; nothing is
evaluated. Rule 5 is **refused**: a line that is not a comment, an s-expression, a command or a plugin
instance is an ``error:`` line, never a shell command.

This module holds the reading side (decoding, tokens, vectors, numbers, the ``@ID`` suffix) and the writing
side (one-line replies, state lines); what each command means is :mod:`shintai.nervous.commands`.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

MAX_LINE_BYTES = 65536  # chosen: a 96-DOF vector (Kenta, §6.1) is ~1 KB; anything near 64 KiB is not a command
MAX_TOKENS = 4096  # chosen: far above Kenta's 96 motors in one vector
MAX_DEPTH = 16  # chosen: the thesis's forms nest two deep
ID_PATTERN = re.compile(r"@([A-Za-z0-9_.:-]{1,64})")
NAME_PATTERN = re.compile(r"[A-Za-z][A-Za-z0-9_-]{0,63}")


class ProtocolError(ValueError):
    """A line that cannot be read: its one-line message goes back as ``error: <message>``."""


@dataclass(frozen=True)
class Symbol:
    name: str

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True)
class Keyword:
    """``:name`` (EusLisp keyword), compared case-insensitively like EusLisp's reader."""

    name: str

    def __str__(self) -> str:
        return ":" + self.name


@dataclass(frozen=True)
class Vector:
    """``#f(…)``: EusLisp's float vector, every element finite."""

    values: tuple[float, ...]

    def __str__(self) -> str:
        return "#f(" + " ".join(fmt(v) for v in self.values) + ")"


def decode(raw: bytes) -> str:
    """One received line (without its newline) as text: UTF-8, no control characters but tab, a
    trailing carriage return dropped."""
    if len(raw) > MAX_LINE_BYTES:
        raise ProtocolError(f"line too long ({len(raw)} bytes, the limit is {MAX_LINE_BYTES})")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ProtocolError(f"line is not UTF-8 text (byte {exc.start})") from None
    text = text.removesuffix("\r")
    for i, ch in enumerate(text):
        if (ord(ch) < 32 and ch != "\t") or ord(ch) == 127:
            raise ProtocolError(f"control character U+{ord(ch):04X} at column {i + 1}")
    return text


def is_silent(line: str) -> bool:
    """Rule 1 (and an empty line): no reply."""
    stripped = line.strip()
    return not stripped or stripped.startswith("#")


def split_id(line: str) -> tuple[str, str | None]:
    """The line without a trailing ``@ID`` token, and the id (or None)."""
    match = re.search(r"(?:^|[ \t])(@\S*)[ \t]*$", line)
    if match is None:
        return line, None
    token = match.group(1)
    if ID_PATTERN.fullmatch(token) is None:
        raise ProtocolError(f"bad id {token[:70]!r}: '@' then 1–64 of A-Z a-z 0-9 _ . : -")
    return line[:match.start(1)].rstrip(), token[1:]


# -- tokens --------------------------------------------------------------------------------------

_LP, _RP = "(", ")"


def _tokens(line: str) -> list:
    """Atoms (str), parentheses and float vectors, in order."""
    out: list = []
    i, n = 0, len(line)
    while i < n:
        ch = line[i]
        if ch in " \t":
            i += 1
        elif ch in "()":
            out.append(_LP if ch == "(" else _RP)
            i += 1
        elif line.startswith(("#f(", "#F("), i):
            end = line.find(")", i + 3)
            inner = line[i + 3:end] if end >= 0 else ""
            if end < 0 or "(" in inner:
                raise ProtocolError(f"unbalanced #f( at column {i + 1}: a float vector is #f(n1 n2 …)")
            out.append(Vector(tuple(number(t, f"#f( element {k + 1}") for k, t in enumerate(inner.split()))))
            i = end + 1
        else:
            j = i
            while j < n and line[j] not in " \t()":
                j += 1
            out.append(line[i:j])
            i = j
        if len(out) > MAX_TOKENS:
            raise ProtocolError(f"too many tokens (the limit is {MAX_TOKENS})")
    return out


def words(line: str) -> list:
    """A command line (rules 3 and 4) as words: atoms (str) and float vectors; parentheses other than a
    vector's are an error."""
    toks = _tokens(line)
    for t in toks:
        if t is _LP or t is _RP:
            raise ProtocolError("unexpected parenthesis in a command line (a float vector is #f(n1 n2 …); "
                                "a line that starts with '(' is an s-expression)")
    return toks


def read_sexpr(line: str):
    """Rule 2: one s-expression, read into nested lists of :class:`Symbol`, :class:`Keyword`, numbers
    (int or float), :class:`Vector` and ``t``/``nil`` (True/None). Nothing is evaluated."""
    toks = _tokens(line)
    stack: list[list] = []
    result = None
    for k, t in enumerate(toks):
        if result is not None:
            raise ProtocolError("text after the closing parenthesis of the s-expression")
        if t is _LP:
            if len(stack) >= MAX_DEPTH:
                raise ProtocolError(f"s-expression nested deeper than {MAX_DEPTH}")
            stack.append([])
        elif t is _RP:
            if not stack:
                raise ProtocolError("unbalanced ')' in the s-expression")
            done = stack.pop()
            if stack:
                stack[-1].append(done)
            else:
                result = done
        elif not stack:
            raise ProtocolError("an s-expression line must start with '('")
        else:
            stack[-1].append(t if isinstance(t, Vector) else _atom(t))
    if stack or result is None:
        raise ProtocolError(f"unbalanced '(' in the s-expression ({len(stack)} not closed)")
    return result


def _atom(text: str):
    low = text.lower()
    if low == "t":
        return True
    if low == "nil":
        return None
    if text.startswith(":") and len(text) > 1:
        return Keyword(low[1:])
    if re.fullmatch(r"[-+]?\d+", text):
        return int(text)
    if re.fullmatch(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", text):
        return number(text, "number")
    if text.startswith(("'", "`", ",", "#")):
        raise ProtocolError(f"{text[:40]!r}: quoting and reader macros are not understood (only #f(…))")
    return Symbol(low)


# -- numbers and vectors -------------------------------------------------------------------------

def number(text, what: str, lo: float = -math.inf, hi: float = math.inf) -> float:
    """A finite number in [lo, hi] from a token; a :class:`ProtocolError` naming ``what`` otherwise."""
    if isinstance(text, Vector) or isinstance(text, (list, Symbol, Keyword)) or text is None:
        raise ProtocolError(f"{what}: expected a number, got {str(text)[:40]!r}")
    if isinstance(text, bool):
        raise ProtocolError(f"{what}: expected a number, got {'t' if text else 'nil'}")
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise ProtocolError(f"{what}: expected a number, got {str(text)[:40]!r}") from None
    if not math.isfinite(value):
        raise ProtocolError(f"{what}: {str(text)[:40]!r} is not a finite number")
    if not lo <= value <= hi:
        raise ProtocolError(f"{what}: {fmt(value)} is outside [{fmt(lo)}, {fmt(hi)}]")
    return value


def integer(text, what: str, lo: int, hi: int) -> int:
    value = number(text, what, lo, hi)
    if value != int(value):
        raise ProtocolError(f"{what}: expected a whole number, got {text}")
    return int(value)


def name(text, what: str) -> str:
    """An instance or plugin name: a letter then up to 63 of letters, digits, '_', '-'."""
    if not isinstance(text, str) or NAME_PATTERN.fullmatch(text) is None:
        raise ProtocolError(f"{what}: {str(text)[:40]!r} is not a name (a letter, then letters, digits, _ or -)")
    return text


# -- writing -------------------------------------------------------------------------------------

def fmt(x: float) -> str:
    """A number as the protocol writes it (6 significant digits; integers plainly)."""
    x = float(x)
    if not math.isfinite(x):
        return str(x)
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return f"{x:.6g}"


def fmt_vector(values) -> str:
    return ",".join(fmt(v) for v in values)


def one_line(text: str) -> str:
    """Replies are one line: newlines and control characters become spaces."""
    return "".join(ch if ch >= " " or ch == "\t" else " " for ch in str(text)).strip()


def ok(payload: str = "") -> str:
    payload = one_line(payload)
    return "ok " + payload if payload else "ok"


def error(message: str) -> str:
    return "error: " + (one_line(message) or "error")
