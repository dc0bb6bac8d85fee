"""Docstrings shown as the package writes them.

* Plain-text mathematics: the docstrings write formulas as plain text, as ``help()`` shows
  them: ``|B - A|`` is a norm, ``|mu|`` a modulus. In reStructuredText ``|...|`` is a
  substitution, so after numpydoc has turned a docstring into reStructuredText every ``|``
  of running text is escaped. Literal text (````...````, ``::`` blocks and directive
  bodies) and tables keep theirs.
* Constants re-exported by a package (``dynstiff.RUNGS``, ``dynstiff.STANDARD_GRAVITY``):
  their ``#:`` comment is in the module that defines them, not in the one that imports
  them; without it autodoc would show the docstring of ``tuple`` or ``float``.
"""

import re
import sys

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


def defining_comment(name, obj):
    """The ``#:`` comment of ``obj`` in the ``dynstiff`` module that defines it, as lines."""
    from sphinx.pycode import ModuleAnalyzer
    attr = name.rsplit(".", 1)[-1]
    for modname, module in sorted(sys.modules.items()):
        if not modname.startswith("dynstiff") or getattr(module, attr, None) is not obj:
            continue
        try:
            docs = ModuleAnalyzer.for_module(modname).find_attr_docs()
        except Exception:              # a module without source (compiled, namespace)
            continue
        if ("", attr) in docs:
            return list(docs[("", attr)])
    return None


def _is_type_docstring(obj, lines):
    """Whether ``lines`` are the docstring of ``obj``'s type (a constant has none)."""
    doc = (type(obj).__doc__ or "").strip()
    text = [line.strip() for line in lines if line.strip()]
    return bool(text and doc) and text[0] == doc.splitlines()[0].strip()


def process(app, what, name, obj, options, lines):
    if what in ("data", "attribute") and _is_type_docstring(obj, lines):
        lines[:] = defining_comment(name, obj) or []
    escape_bars(lines)


def setup(app):
    app.connect("autodoc-process-docstring", process, priority=600)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
