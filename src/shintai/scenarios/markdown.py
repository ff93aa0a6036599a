"""The small Markdown subset the scenario notes use, as HTML (for the report page).

Paragraphs, ``#`` headings, ``-``/``*``/``1.`` lists, fenced code blocks, ``|`` tables, and inline
`` `code` ``, ``**bold**``, ``*emphasis*`` and ``[links](url)``. Everything else is text, escaped: a note
can never inject markup into the page.
"""

from __future__ import annotations

import html
import re

_INLINE = [  # applied outside code spans, in order
    (re.compile(r"\*\*(?=\S)(.+?)(?<=\S)\*\*"), lambda m: f"<strong>{m.group(1)}</strong>"),
    (re.compile(r"(?<![\w*])\*(?=\S)([^*]+?)(?<=\S)\*(?![\w*])"), lambda m: f"<em>{m.group(1)}</em>"),
    (re.compile(r"\[([^\]]+)\]\(((?:https?://|#)[^)\s]*|[^):\s]+)\)"),  # web or relative links only
     lambda m: f'<a href="{m.group(2)}">{m.group(1)}</a>'),
]


def inline(text: str) -> str:
    """One line of Markdown text as HTML (escaped first; code spans are not formatted further)."""
    parts = re.split(r"(`[^`]+`)", html.escape(text, quote=False))
    out = []
    for part in parts:
        if part.startswith("`") and part.endswith("`") and len(part) > 1:
            out.append(f"<code>{part[1:-1]}</code>")
            continue
        for pattern, repl in _INLINE:
            part = pattern.sub(repl, part)
        out.append(part)
    return "".join(out)


_LIST = re.compile(r"^\s*(?:[-*+]|\d+[.)])\s+")


def to_html(text: str) -> str:
    """The Markdown ``text`` as an HTML fragment."""
    lines = text.replace("\r\n", "\n").split("\n")
    out: list[str] = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line.strip():
            i += 1
            continue
        if line.lstrip().startswith("```"):
            j = i + 1
            while j < len(lines) and not lines[j].lstrip().startswith("```"):
                j += 1
            out.append("<pre><code>" + html.escape("\n".join(lines[i + 1:j]), quote=False) + "</code></pre>")
            i = j + 1
            continue
        heading = re.match(r"^(#{1,6})\s+(.*)$", line)
        if heading:
            level = min(len(heading.group(1)) + 2, 6)  # inside a page whose sections are h2
            out.append(f"<h{level}>{inline(heading.group(2).strip())}</h{level}>")
            i += 1
            continue
        if line.lstrip().startswith("|"):
            j = i
            while j < len(lines) and lines[j].lstrip().startswith("|"):
                j += 1
            out.append(table(lines[i:j]))
            i = j
            continue
        if _LIST.match(line):
            ordered = bool(re.match(r"^\s*\d", line))
            items: list[str] = []
            while i < len(lines) and lines[i].strip():
                if _LIST.match(lines[i]):
                    items.append(_LIST.sub("", lines[i], count=1))
                else:  # a continuation line of the item above
                    items[-1] += " " + lines[i].strip()
                i += 1
            tag = "ol" if ordered else "ul"
            out.append(f"<{tag}>" + "".join(f"<li>{inline(item)}</li>" for item in items) + f"</{tag}>")
            continue
        j = i + 1  # a paragraph holds at least its first line (a "#3" that is no heading, say)
        while (j < len(lines) and lines[j].strip() and not _LIST.match(lines[j])
               and not lines[j].lstrip().startswith(("```", "|", "#"))):
            j += 1
        out.append("<p>" + inline(" ".join(s.strip() for s in lines[i:j])) + "</p>")
        i = j
    return "\n".join(out)


def table(rows: list[str]) -> str:
    cells = [[c.strip() for c in row.strip().strip("|").split("|")] for row in rows]
    if len(cells) > 1 and all(re.fullmatch(r":?-{2,}:?", c) for c in cells[1] if c):
        head, body = cells[0], cells[2:]
    else:
        head, body = None, cells
    parts = ["<table class=\"md\">"]
    if head:
        parts.append("<tr>" + "".join(f"<th>{inline(c)}</th>" for c in head) + "</tr>")
    parts += ["<tr>" + "".join(f"<td>{inline(c)}</td>" for c in row) + "</tr>" for row in body]
    return "".join(parts) + "</table>"
