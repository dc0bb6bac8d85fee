"""Plain-text mathematics in the docstrings, shown as written.

The docstrings write formulas as plain text, as ``help()`` shows them: ``|B - A|`` is a
norm, ``|mu|`` a modulus. In reStructuredText ``|...|`` is a substitution, so after numpydoc
has turned a docstring into reStructuredText every ``|`` of running text is escaped. Literal
text (````...````, ``::`` blocks and directive bodies) and tables keep theirs.
"""

import re

_LITERAL = re.compile(r"(``.*?``|`[^`]*`_?)")
_LINE_BLOCK = re.compile(r"\s*\|( |$)")             # "| text": a line block
_GRID_ROW = re.compile(r"\s*[+|].*[+|]\s*$")         # a row or border of a grid table


def _escape_text(line):
    parts = _LITERAL.split(line)
    return "".join(p if i % 2 else re.sub(r"(?<!\\)\|", r"\\|", p) for i, p in enumerate(parts))


def _indent(line):
    return len(line) - len(line.lstrip())


def escape_bars(lines):
    """Escape the ``|`` of running text in reStructuredText ``lines`` (in place)."""
    block = None                 # indentation of the line that opened a literal block
    for i, line in enumerate(lines):
        stripped = line.strip()
        if block is not None:
            if not stripped or _indent(line) > block:
                continue
            block = None
        if stripped.endswith("::") or stripped.startswith(".. "):
            block = _indent(line)
        if "|" not in line or _LINE_BLOCK.match(line) or _GRID_ROW.match(line):
            continue
        lines[i] = _escape_text(line)


def process(app, what, name, obj, options, lines):
    escape_bars(lines)


def setup(app):
    app.connect("autodoc-process-docstring", process, priority=600)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
