"""The documentation stays in step with the package: the README's command table names every
subcommand of the parser, the API reference lists every public name, the command-line
reference renders every option, and plain-text ``|x|`` in docstrings is shown as written.
The documentation build itself (.ci/run) checks the cross-references and the API pages."""

import argparse
import importlib
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS / "_ext"))


def _subcommands(parser):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return action.choices
    return {}


def test_readme_command_table_names_every_subcommand():
    from dynstiff.cli import build_parser
    text = (ROOT / "README.md").read_text()
    table = re.findall(r"^\| `([a-z-]+)` \|", text, re.MULTILINE)
    assert table == list(_subcommands(build_parser())), table


def _autosummary_names(rst):
    """``{module: [names]}`` listed by the autosummary directives of an .rst file."""
    found, module = {}, None
    lines = rst.splitlines()
    for i, line in enumerate(lines):
        m = re.match(r"\.\. currentmodule:: (\S+)", line)
        if m:
            module = m.group(1)
        if line.startswith(".. autosummary::"):
            for item in lines[i + 1:]:
                if item.strip() and not item.startswith("   "):
                    break
                name = item.strip()
                if name and not name.startswith(":"):
                    found.setdefault(module, []).append(name)
    return found


def test_api_reference_lists_every_public_name():
    from dynstiff_api_check import PACKAGES  # the packages whose __all__ is documented
    listed = {}
    for page in sorted((DOCS / "api").glob("*.rst")):
        for module, names in _autosummary_names(page.read_text()).items():
            listed.setdefault(module, set()).update(names)
    top = set(importlib.import_module("dynstiff").__all__)
    assert top <= listed["dynstiff"], sorted(top - listed["dynstiff"])
    for package in PACKAGES:
        names = set(importlib.import_module(package).__all__) - top
        assert names <= listed.get(package, set()), (package, sorted(names - listed[package]))


def test_the_listing_check_can_fail():
    rst = ".. currentmodule:: dynstiff\n\n.. autosummary::\n   :toctree: generated/\n\n   frf\n"
    assert _autosummary_names(rst) == {"dynstiff": ["frf"]}


def test_cli_reference_renders_every_subcommand_and_option():
    pytest.importorskip("sphinx")
    from dynstiff_cli import reference_lines, summary_lines

    from dynstiff.cli import build_parser
    parser = build_parser()
    text = "\n".join(reference_lines(parser))
    summary = "\n".join(summary_lines(parser))
    for name, sub in _subcommands(parser).items():
        assert f".. _cli-{name}:" in text and f"<cli-{name}>" in summary
        for action in sub._actions:
            for option in action.option_strings:
                assert f"``{option}" in text or f", {option}" in text, (name, option)


def test_plain_text_bars_are_escaped_outside_literals_and_tables():
    from dynstiff_docstrings import escape_bars
    lines = ["The chord |B - A| and ``|x|`` and `a|b`_.",
             "",
             "Formula::",
             "",
             "    |mu| > 1",
             "",
             "| a line block",
             "+---+---+",
             "| a | b |",
             "After ||K||."]
    escape_bars(lines)
    assert lines[0] == r"The chord \|B - A\| and ``|x|`` and `a|b`_."
    assert lines[4] == "    |mu| > 1"
    assert lines[6:9] == ["| a line block", "+---+---+", "| a | b |"]
    assert lines[9] == r"After \|\|K\|\|."


def test_reexported_constants_show_their_own_comment():
    pytest.importorskip("sphinx")
    from dynstiff_docstrings import _is_type_docstring, defining_comment

    import dynstiff
    assert "cheapest first" in " ".join(defining_comment("dynstiff.RUNGS", dynstiff.RUNGS))
    assert "gravity" in " ".join(defining_comment("dynstiff.STANDARD_GRAVITY",
                                                  dynstiff.STANDARD_GRAVITY))
    assert _is_type_docstring(dynstiff.RUNGS, ["", "Built-in immutable sequence.", ""])
    assert not _is_type_docstring(dynstiff.RUNGS, ["The rungs, cheapest first."])
