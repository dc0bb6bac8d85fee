"""One self-contained HTML page: headings, preformatted text, tables and PNG figures embedded
as base64 data URIs; no external asset (no script, no style sheet, no image file)."""

import base64
import html

__all__ = ["html_page", "figure_png"]

_STYLE = ("body{font-family:sans-serif;max-width:70em;margin:2em auto;color:#222}"
          "table{border-collapse:collapse;font-size:85%}td,th{border:1px solid #bbb;"
          "padding:2px 6px;text-align:right}th{background:#eee}pre{background:#f6f6f6;"
          "padding:.6em;overflow-x:auto}.fail{color:#b00;font-weight:bold}"
          ".pass{color:#070}img{max-width:100%}")


def figure_png(fig, dpi=110):
    """PNG bytes of a matplotlib figure."""
    import io
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
    return buf.getvalue()


def html_page(title, blocks):
    """The page as a string.

    Parameters
    ----------
    title : str
    blocks : list of (kind, content)
        ``("h2", text)``, ``("p", text)``, ``("pre", text)``, ``("table", DataFrame)``,
        ``("png", (bytes, caption))`` or ``("checks", rows)`` (dicts with ``check``,
        ``passed``, ``detail``).
    """
    esc = html.escape
    out = ["<!DOCTYPE html>", "<html><head><meta charset=\"utf-8\">",
           f"<title>{esc(title)}</title><style>{_STYLE}</style></head><body>",
           f"<h1>{esc(title)}</h1>"]
    for kind, content in blocks:
        if kind in ("h2", "p"):
            out.append(f"<{kind}>{esc(str(content))}</{kind}>")
        elif kind == "pre":
            out.append(f"<pre>{esc(str(content))}</pre>")
        elif kind == "table":
            out.append(content.to_html(index=False, float_format=lambda x: f"{x:.5g}",
                                       border=0))
        elif kind == "png":
            data, caption = content
            b64 = base64.b64encode(data).decode("ascii")
            out.append(f"<figure><img alt=\"{esc(caption)}\" src=\"data:image/png;base64,"
                       f"{b64}\"><figcaption>{esc(caption)}</figcaption></figure>")
        elif kind == "checks":
            out.append("<table><tr><th>verdict</th><th>check</th><th>detail</th></tr>")
            for r in content:
                v = "PASS" if r["passed"] else "FAIL"
                out.append(f"<tr><td class=\"{v.lower()}\">{v}</td><td>{esc(r['check'])}</td>"
                           f"<td style=\"text-align:left\">{esc(r['detail'])}</td></tr>")
            out.append("</table>")
        else:
            raise ValueError(f"unknown block kind {kind!r}")
    out.append("</body></html>")
    return "\n".join(out) + "\n"
