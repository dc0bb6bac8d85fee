"""One self-contained HTML page: a title block, headings, paragraphs, tables, verdicts, PNG
figures embedded as base64 data URIs and files to download as data URIs; no external asset
(no script, no style sheet, no image file)."""

import base64
import html

__all__ = ["html_page", "figure_png"]

_STYLE = ("body{font-family:sans-serif;max-width:72em;margin:2em auto;padding:0 1em;"
          "color:#222;line-height:1.4}h1{margin-bottom:.2em}h2{border-bottom:1px solid #ccc;"
          "margin-top:1.6em}table{border-collapse:collapse;font-size:85%;margin:.4em 0}"
          "td,th{border:1px solid #bbb;padding:2px 6px;text-align:right;vertical-align:top}"
          "th{background:#eee}td.text,th.key{text-align:left}pre{background:#f6f6f6;"
          "padding:.6em;overflow-x:auto}.fail,.unknown{color:#b00;font-weight:bold}"
          ".pass{color:#070}.na{color:#777}.note{background:#fff6dd;border-left:4px solid "
          "#e0a800;padding:.4em .8em}figure{margin:1em 0}img{max-width:100%;height:auto}"
          "figcaption{font-size:90%;color:#444}.grid{display:flex;flex-wrap:wrap;gap:1%}"
          ".grid figure{flex:0 0 49%;margin:.5em 0}")
_VERDICT = {"pass": ("PASS", "pass"), "fail": ("FAIL", "fail"),
            "unknown": ("UNKNOWN", "unknown"), "not asked": ("n/a", "na")}


def figure_png(fig, dpi=110, tight=True):
    """PNG bytes of a matplotlib figure (``tight``: cropped to its drawn content, which costs
    a second drawing pass)."""
    import io
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight" if tight else None)
    return buf.getvalue()


def _uri(data, mime):
    return f"data:{mime};base64,{base64.b64encode(data).decode('ascii')}"


def _cell(v):
    if isinstance(v, float):
        return "" if v != v else f"{v:.5g}"          # NaN: no value
    return str(v)


def html_page(title, blocks):
    """The page as a string.

    Parameters
    ----------
    title : str
    blocks : list of (kind, content)
        ``("h2", text)``, ``("p", text)``, ``("note", text)`` (a highlighted paragraph),
        ``("pre", text)``, ``("ul", [text, ...])``, ``("kv", [(key, value), ...])`` (a
        two-column table), ``("table", DataFrame)``, ``("png", (bytes, caption))``,
        ``("pngs", [(bytes, caption), ...])`` (figures side by side),
        ``("download", (file name, bytes, MIME type, label))`` (a link holding the file as
        a data URI) or ``("checks", rows)`` (dicts with ``check``, ``detail`` and
        ``verdict`` ("pass", "fail", "unknown", "not asked") or ``passed``; ``value`` and
        ``limit`` shown when present).

    Examples
    --------
    >>> page = html_page("t", [("kv", [("scene", "cogiro")]), ("p", "a < b")])
    >>> "<th class=\\"key\\">scene</th>" in page and "a &lt; b" in page
    True
    """
    esc = html.escape
    out = ["<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
           f"<title>{esc(title)}</title><style>{_STYLE}</style></head><body>",
           f"<h1>{esc(title)}</h1>"]
    for kind, content in blocks:
        if kind in ("h2", "p"):
            out.append(f"<{kind}>{esc(str(content))}</{kind}>")
        elif kind == "note":
            out.append(f"<p class=\"note\">{esc(str(content))}</p>")
        elif kind == "pre":
            out.append(f"<pre>{esc(str(content))}</pre>")
        elif kind == "ul":
            out.append("<ul>" + "".join(f"<li>{esc(str(x))}</li>" for x in content) + "</ul>")
        elif kind == "kv":
            out.append("<table>" + "".join(
                f"<tr><th class=\"key\">{esc(str(k))}</th><td class=\"text\">"
                f"{esc(_cell(v))}</td></tr>" for k, v in content) + "</table>")
        elif kind == "table":
            out.append(content.to_html(index=False, float_format=lambda x: f"{x:.5g}",
                                       border=0, na_rep=""))
        elif kind in ("png", "pngs"):
            grid = kind == "pngs"
            out += ["<div class=\"grid\">"] if grid else []
            for data, caption in (content if grid else [content]):
                out.append(f"<figure><img alt=\"{esc(caption)}\" src=\""
                           f"{_uri(data, 'image/png')}\"><figcaption>{esc(caption)}"
                           "</figcaption></figure>")
            out += ["</div>"] if grid else []
        elif kind == "download":
            name, data, mime, label = content
            out.append(f"<p><a download=\"{esc(name)}\" href=\"{_uri(data, mime)}\">"
                       f"{esc(label)}</a></p>")
        elif kind == "checks":
            extra = any("value" in r for r in content)
            out.append("<table><tr><th>verdict</th><th class=\"key\">check</th>"
                       + ("<th>value</th><th>limit</th>" if extra else "")
                       + "<th class=\"key\">reason</th></tr>")
            for r in content:
                v = r.get("verdict") or ("pass" if r["passed"] else "fail")
                word, cls = _VERDICT.get(v, (v.upper(), "fail"))
                vals = (f"<td>{esc(_cell(r.get('value', '')))}</td>"
                        f"<td>{esc(_cell(r.get('limit', '')))}</td>") if extra else ""
                out.append(f"<tr><td class=\"{cls}\">{word}</td><td class=\"text\">"
                           f"{esc(r['check'])}</td>{vals}<td class=\"text\">"
                           f"{esc(r['detail'])}</td></tr>")
            out.append("</table>")
        else:
            raise ValueError(f"unknown block kind {kind!r}")
    out.append("</body></html>")
    return "\n".join(out) + "\n"
