"""A small Markdown-to-HTML renderer for the reports (offline: images embedded as base64).

It understands the subset the reports write, and nothing else:

- ATX headings ``#`` … ``######``;
- paragraphs (consecutive non-blank lines);
- unordered lists (lines starting with ``- `` or ``* ``);
- fenced code blocks (lines between two lines starting with three backticks; the content is
  escaped verbatim);
- tables (a header row ``| a | b |``, a separator row ``|---|---|``, then rows);
- images on a line of their own, ``![caption](file.png)``: the PNG is read from ``folder`` and
  embedded as a ``data:`` URI, so the page needs no other file;
- inline: code spans ```text```, ``**bold**`` and links ``[text](url)``.

Everything else is text and is HTML-escaped.  The renderer is deterministic (same Markdown, same
images, same bytes out).
"""
from __future__ import annotations

import base64
import html
import os
import re

_IMAGE = re.compile(r"^!\[(?P<alt>[^\]]*)\]\((?P<src>[^)\s]+)\)\s*$")
_HEADING = re.compile(r"^(?P<hashes>#{1,6})\s+(?P<text>.*?)\s*#*\s*$")
_ROW = re.compile(r"^\s*\|.*\|\s*$")
_SEPARATOR = re.compile(r"^\s*\|?\s*:?-{3,}:?\s*(\|\s*:?-{3,}:?\s*)*\|?\s*$")
_ITEM = re.compile(r"^\s*[-*]\s+(?P<text>.*)$")

STYLE = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;"
         "line-height:1.4}table{border-collapse:collapse;font-size:0.85em;margin:1em 0}"
         "td,th{border:1px solid #bbb;padding:2px 6px;text-align:right}"
         "th{background:#f0f0f0}img{max-width:100%}figcaption{font-size:0.85em;color:#444}"
         "pre{background:#f6f6f6;padding:0.6em;overflow-x:auto}code{font-size:0.95em}"
         ".fail{color:#b00020;font-weight:bold}.pass{color:#1b5e20}")


def inline(text: str) -> str:
    """Escape ``text`` and render code spans, bold and links (code spans are taken first, so
    nothing inside them is interpreted)."""
    out = []
    for i, part in enumerate(re.split(r"(`[^`]*`)", text)):
        if i % 2 == 1:
            out.append(f"<code>{html.escape(part[1:-1])}</code>")
            continue
        esc = html.escape(part)
        esc = re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", esc)
        esc = re.sub(r"\[([^\]]+)\]\(([^)\s]+)\)", r'<a href="\2">\1</a>', esc)
        # verdict words stand out in the reports' tables
        esc = re.sub(r"\b(FAIL)\b", r'<span class="fail">\1</span>', esc)
        esc = re.sub(r"\b(PASS)\b", r'<span class="pass">\1</span>', esc)
        out.append(esc)
    return "".join(out)


def _cells(line: str) -> list[str]:
    s = line.strip()
    if s.startswith("|"):
        s = s[1:]
    if s.endswith("|") and not s.endswith("\\|"):
        s = s[:-1]
    return [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", s)]


def _image(src: str, alt: str, folder) -> str:
    path = src if folder is None else os.path.join(folder, src)
    with open(path, "rb") as fh:
        data = base64.b64encode(fh.read()).decode("ascii")
    return (f'<figure><img src="data:image/png;base64,{data}" alt="{html.escape(alt)}">'
            f"<figcaption>{inline(alt)}</figcaption></figure>")


def render(markdown: str, folder=None, title: str = "report") -> str:
    """The whole HTML page for ``markdown``.

    Parameters
    ----------
    markdown : str
        The Markdown text (the subset described in the module docstring).
    folder : str or path, optional
        Where the images named in ``markdown`` are (default: the current directory).
    title : str
        The page title.

    Returns
    -------
    str
        A complete, self-contained HTML document.

    Raises
    ------
    OSError
        When an image named in the Markdown cannot be read.
    """
    return (f"<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>{html.escape(title)}"
            f"</title><style>{STYLE}</style></head><body>\n{body(markdown, folder)}\n"
            "</body></html>\n")


def body(markdown: str, folder=None) -> str:
    """The HTML of ``markdown`` without the page around it."""
    lines = markdown.splitlines()
    out: list[str] = []
    para: list[str] = []
    i = 0

    def flush():
        if para:
            out.append(f"<p>{inline(' '.join(s.strip() for s in para))}</p>")
            para.clear()

    while i < len(lines):
        line = lines[i]
        if line.lstrip().startswith("```"):
            flush()
            j = i + 1
            while j < len(lines) and not lines[j].lstrip().startswith("```"):
                j += 1
            out.append("<pre><code>" + html.escape("\n".join(lines[i + 1:j])) + "</code></pre>")
            i = j + 1
            continue
        if not line.strip():
            flush()
            i += 1
            continue
        m = _HEADING.match(line)
        if m:
            flush()
            n = len(m.group("hashes"))
            out.append(f"<h{n}>{inline(m.group('text'))}</h{n}>")
            i += 1
            continue
        m = _IMAGE.match(line.strip())
        if m:
            flush()
            out.append(_image(m.group("src"), m.group("alt"), folder))
            i += 1
            continue
        if _ROW.match(line) and i + 1 < len(lines) and _SEPARATOR.match(lines[i + 1]):
            flush()
            head = _cells(line)
            rows = []
            j = i + 2
            while j < len(lines) and _ROW.match(lines[j]):
                rows.append(_cells(lines[j]))
                j += 1
            th = "".join(f"<th>{inline(c)}</th>" for c in head)
            trs = "".join("<tr>" + "".join(f"<td>{inline(c)}</td>" for c in r) + "</tr>"
                          for r in rows)
            out.append(f"<table><thead><tr>{th}</tr></thead><tbody>{trs}</tbody></table>")
            i = j
            continue
        if _ITEM.match(line):
            flush()
            items = []
            while i < len(lines) and _ITEM.match(lines[i]):
                items.append(_ITEM.match(lines[i]).group("text"))
                i += 1
                # continuation lines of an item are indented
                while i < len(lines) and lines[i].startswith("  ") and lines[i].strip() \
                        and not _ITEM.match(lines[i]):
                    items[-1] += " " + lines[i].strip()
                    i += 1
            out.append("<ul>" + "".join(f"<li>{inline(t)}</li>" for t in items) + "</ul>")
            continue
        para.append(line)
        i += 1
    flush()
    return "\n".join(out)


def table(head, rows) -> str:
    """A Markdown table (the cells are written as given; ``|`` in a cell is escaped)."""
    esc = lambda c: str(c).replace("|", "\\|")  # noqa: E731
    lines = ["| " + " | ".join(esc(c) for c in head) + " |",
             "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(esc(c) for c in r) + " |" for r in rows]
    return "\n".join(lines) + "\n"
