"""The self-contained HTML page (dynstiff/report/html.py)."""

import base64
from html.parser import HTMLParser

import numpy as np
import pandas as pd
import pytest

from dynstiff.report.html import html_page


class Parse(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tags, self.srcs, self.data = [], [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.srcs += [v for k, v in attrs if k in ("src", "href")]

    def handle_data(self, data):
        self.data.append(data)


def test_page_escapes_text_embeds_images_and_tables():
    png = b"\x89PNG\r\n\x1a\nrest"
    page = html_page("a <b> & c", [("pre", "x < y"), ("table", pd.DataFrame({"f [Hz]": [1.5]})),
                                   ("png", (png, "fig")),
                                   ("checks", [dict(check="c", passed=False, detail="d")])])
    p = Parse()
    p.feed(page)
    assert p.tags.count("table") == 2 and "script" not in p.tags
    (src,) = p.srcs
    assert base64.b64decode(src.split(",", 1)[1]) == png
    text = "".join(p.data)
    assert "a <b> & c" in text and "x < y" in text and "FAIL" in text and "1.5" in text
    assert "&lt;b&gt;" in page
    with pytest.raises(ValueError, match="kind"):
        html_page("t", [("video", None)])


class Tree(HTMLParser):
    """Every element as (path of tags with their classes, attributes, own text); raises on a
    closing tag that does not close the innermost open element."""
    VOID = {"meta", "img"}

    def __init__(self):
        super().__init__()
        self.stack, self.elements, self.stray = [], [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        name = tag + ("." + attrs["class"] if "class" in attrs else "")
        el = ["/".join([e[0] for e in self.stack] + [name]), attrs, ""]
        self.elements.append(el)
        if tag not in self.VOID:
            self.stack.append((name, el))

    def handle_endtag(self, tag):
        assert self.stack and self.stack[-1][0].split(".")[0] == tag, (tag, self.stack)
        self.stack.pop()

    def handle_data(self, data):
        if self.stack:
            self.stack[-1][1][2] += data
        elif data.strip():
            self.stray.append(data)

    def texts(self, suffix):
        return [e[2] for e in self.elements if e[0].endswith(suffix)]


def test_every_block_kind_has_its_markup_and_nothing_else():
    """Each block kind as documented, parsed into elements: balanced tags, no text outside
    an element, headers and cells as stated, verdicts from ``verdict`` or ``passed``."""
    png1, png2 = b"\x89PNG one", b"\x89PNG two"
    rows = [dict(check="tension", passed=True, detail="ok", value=120.5, limit=100.0),
            dict(check="band", passed=False, detail="mode in band"),
            dict(check="margin", verdict="unknown", detail="not computed"),
            dict(check="proximity", verdict="not asked", detail="-"),
            dict(check="custom", verdict="marginal", detail="a verdict not in the list")]
    page = html_page("T", [
        ("h2", "Head"), ("p", "para"), ("note", "careful"), ("ul", ["a", "b < c"]),
        ("kv", [("scene", "cogiro"), ("f", float("nan")), ("g", 9.81)]),
        ("table", pd.DataFrame({"f [Hz]": [1.23456789, np.nan], "n": [2, 3]}, index=[7, 8])),
        ("png", (png1, "one")), ("pngs", [(png1, "left"), (png2, "right")]),
        ("download", ("m.csv", b"x,y\n", "text/csv", "the table")),
        ("checks", rows), ("checks", [dict(check="c", passed=True, detail="d")])])
    t = Tree()
    t.feed(page)
    t.close()
    assert t.stack == [] and t.stray == []
    containers = ("html", "head", "body", "ul", "table", "thead", "tbody", "tr", "div",
                  "figure")
    assert [e for e in t.elements if e[0].rsplit("/", 1)[-1].split(".")[0] in containers
            and e[2].strip()] == []                      # text only in the leaves
    body = "html/body/"
    assert t.texts(body + "h1") == ["T"] and t.texts(body + "h2") == ["Head"]
    assert t.texts(body + "p") == ["para", ""] and t.texts(body + "p.note") == ["careful"]
    assert t.texts(body + "ul") == [""] and t.texts(body + "ul/li") == ["a", "b < c"]
    assert t.texts("table/tr/th.key")[:3] == ["scene", "f", "g"]
    assert t.texts("table/tr/td.text")[:3] == ["cogiro", "", "9.81"]
    # the DataFrame: no index column, floats to 5 significant digits, NaN an empty cell,
    # no border attribute (the page's style draws the rules)
    frame = [e for e in t.elements if e[0].startswith(body + "table.dataframe")]
    assert "border" not in frame[0][1]
    assert [e[2] for e in frame if e[0].endswith("/th")] == ["f [Hz]", "n"]
    assert [e[2] for e in frame if e[0].endswith("/td")] == ["1.2346", "2", "", "3"]
    # one figure alone, two in a grid; each image decodes to its bytes, captioned
    assert t.texts(body + "figure/figcaption") == ["one"]
    assert t.texts(body + "div.grid/figure/figcaption") == ["left", "right"]
    imgs = [e[1] for e in t.elements if e[0].endswith("figure/img")]
    assert [i["alt"] for i in imgs] == ["one", "left", "right"]
    assert [base64.b64decode(i["src"].split(",", 1)[1]) for i in imgs] == [png1, png1, png2]
    (link,) = [e for e in t.elements if e[0] == body + "p/a"]
    assert link[2] == "the table" and link[1]["download"] == "m.csv"
    assert link[1]["href"] == "data:text/csv;base64," + base64.b64encode(b"x,y\n").decode()
    # checks: value and limit columns only in the table where a row has a value
    tables = [e for e in t.elements if e[0] == body + "table"]
    assert len(tables) == 3
    heads = t.texts("table/tr/th") + t.texts("table/tr/th.key")
    assert heads.count("value") == 1 and heads.count("limit") == 1
    assert heads.count("verdict") == 2 and heads.count("reason") == 2
    verdicts = [(e[0].rsplit(".", 1)[1], e[2]) for e in t.elements
                if e[0].endswith(("td.pass", "td.fail", "td.unknown", "td.na"))]
    assert verdicts == [("pass", "PASS"), ("fail", "FAIL"), ("unknown", "UNKNOWN"),
                        ("na", "n/a"), ("fail", "MARGINAL"), ("pass", "PASS")]
    cells = [e[2] for e in t.elements if e[0] == body + "table/tr/td"]
    assert cells == ["120.5", "100"] + [""] * 8                   # value, limit per row


def test_figure_png_is_a_png_at_the_dpi_cropped_when_tight():
    """PNG bytes whatever matplotlib's default save format; a 4 x 2 in figure at 50 dpi is
    200 x 100 pixels, and smaller when cropped to its drawing (tight)."""
    import struct

    import matplotlib
    import matplotlib.pyplot as plt

    from dynstiff.report.html import figure_png

    def size(png):
        assert png[:8] == b"\x89PNG\r\n\x1a\n"
        return struct.unpack(">II", png[16:24])            # IHDR width, height

    fig = plt.figure(figsize=(4.0, 2.0))
    fig.add_axes((0.4, 0.4, 0.2, 0.2)).plot([0, 1], [0, 1])
    with matplotlib.rc_context({"savefig.format": "svg", "savefig.dpi": 80}):
        assert size(figure_png(fig, dpi=50, tight=False)) == (200, 100)
        assert size(figure_png(fig, dpi=100, tight=False)) == (400, 200)
        w, h = size(figure_png(fig, dpi=50))
    assert w < 150 and h < 90
    plt.close(fig)
