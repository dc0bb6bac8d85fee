"""The ``dynstiff-cli`` directive: the command-line reference, read from the parsers.

``.. dynstiff-cli::`` renders every subcommand of :func:`dynstiff.cli.build_parser` with its
one-line help, its usage and each option with its help, choices and default, so the page
follows the command line when an option is added or renamed. ``:summary:`` renders only the
table of subcommands.
"""

import argparse

from docutils import nodes
from docutils.parsers.rst import directives
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

WIDTH = 76


def escape(text):
    """Plain text as reStructuredText (no markup is interpreted)."""
    text = " ".join(str(text).split())
    for ch in "\\*`|_[]":
        text = text.replace(ch, "\\" + ch)
    return text


def subcommands(parser):
    """``[(name, one-line help, parser)]`` of the subcommands, in the parser's order."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {a.dest: a.help for a in action._choices_actions}
            return [(name, helps.get(name) or "", sub) for name, sub in action.choices.items()]
    return []


def _usage(parser):
    fmt = argparse.HelpFormatter(parser.prog, width=WIDTH)
    fmt.add_usage(parser.usage, parser._actions, parser._mutually_exclusive_groups, prefix="")
    return fmt.format_help().rstrip()


def _option(parser, action):
    fmt = argparse.HelpFormatter(parser.prog, width=WIDTH)
    invocation = fmt._format_action_invocation(action)
    text = fmt._expand_help(action) if action.help else ""
    notes = []
    if action.choices is not None and not isinstance(action, argparse._SubParsersAction):
        notes.append("choices: " + ", ".join(str(c) for c in action.choices))
    default = action.default
    if (action.option_strings and default not in (None, False, argparse.SUPPRESS)
            and "%(default)" not in (action.help or "")
            and not isinstance(action, (argparse._HelpAction, argparse._VersionAction))):
        notes.append(f"default: {default}")
    if notes:
        text = f"{text} ({'; '.join(notes)})" if text else "; ".join(notes)
    return invocation, text


def _options(parser):
    lines = []
    for group in parser._action_groups:
        actions = [a for a in group._group_actions if a.help is not argparse.SUPPRESS
                   and not isinstance(a, argparse._SubParsersAction)]
        if not actions:
            continue
        title = group.title or "options"
        lines += [f"*{escape(title)}*", ""]
        for action in actions:
            invocation, text = _option(parser, action)
            lines += [f"``{invocation}``", f"    {escape(text) or '(no description)'}", ""]
    return lines


def summary_lines(parser):
    rows = subcommands(parser)
    lines = [".. list-table::", "   :header-rows: 1", "   :widths: 20 80", "",
             "   * - command", "     - what it does"]
    for name, help_, _ in rows:
        lines += [f"   * - :ref:`dynstiff {name} <cli-{name}>`", f"     - {escape(help_)}"]
    return lines + [""]


def reference_lines(parser):
    lines = [".. _cli-dynstiff:", "", "dynstiff", "-" * 8, "",
             escape(parser.description or ""), "", "::", ""]
    lines += ["    " + line for line in _usage(parser).splitlines()] + [""]
    lines += _options(parser)
    for name, help_, sub in subcommands(parser):
        title = f"dynstiff {name}"
        lines += [f".. _cli-{name}:", "", title, "-" * len(title), "", escape(help_), ""]
        if sub.description:
            lines += [escape(sub.description), ""]
        lines += ["::", ""] + ["    " + line for line in _usage(sub).splitlines()] + [""]
        lines += _options(sub)
        if sub.epilog:
            lines += [escape(sub.epilog), ""]
    return lines


class DynstiffCli(SphinxDirective):
    has_content = False
    option_spec = {"summary": directives.flag}

    def run(self):
        from dynstiff.cli import build_parser
        parser = build_parser()
        lines = summary_lines(parser) if "summary" in self.options else reference_lines(parser)
        container = nodes.section() if "summary" not in self.options else nodes.container()
        content = StringList(lines, source="dynstiff.cli.build_parser()")
        if "summary" in self.options:
            self.state.nested_parse(content, self.content_offset, container)
        else:
            nested_parse_with_titles(self.state, content, container)
        return container.children


def setup(app):
    app.add_directive("dynstiff-cli", DynstiffCli)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
