"""Small HTML tables for the rich display of results in Jupyter (``_repr_html_``): escaped
text, numbers to 5 significant digits, no script and no style sheet."""

import html
from numbers import Real

__all__ = ["html_table", "fmt"]


def fmt(v):
    """A cell's text: a real number to 5 significant digits, anything else as ``str``."""
    if isinstance(v, Real) and not isinstance(v, bool):
        return f"{float(v):.5g}"
    return str(v)


def html_table(title, header, rows, notes=(), limit=20):
    """``<div>`` holding a bold title, a table and notes (escaped).

    Parameters
    ----------
    title : str
    header : sequence of str
    rows : sequence of sequences
        Cells (numbers formatted by :func:`fmt`); beyond ``limit`` rows a note says how many
        are left out.
    notes : sequence of str
        Lines below the table.
    limit : int
        Most rows shown.

    Examples
    --------
    >>> print(html_table("t", ["a"], [[1.0]]))  # doctest: +NORMALIZE_WHITESPACE
    <div><p><b>t</b></p><table><tr><th>a</th></tr><tr><td>1</td></tr></table></div>
    """
    esc = html.escape
    rows = list(rows)
    notes = list(notes)
    if len(rows) > limit:
        notes.insert(0, f"... {len(rows) - limit} more rows (to_frame() holds them all)")
        rows = rows[:limit]
    out = [f"<div><p><b>{esc(title)}</b></p><table>",
           "<tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>"]
    out += ["<tr>" + "".join(f"<td>{esc(fmt(c))}</td>" for c in r) + "</tr>" for r in rows]
    out.append("</table>")
    out += [f"<p>{esc(n)}</p>" for n in notes]
    out.append("</div>")
    return "".join(out)
