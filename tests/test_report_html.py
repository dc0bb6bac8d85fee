"""The self-contained HTML page (dynstiff/report/html.py)."""

import base64
from html.parser import HTMLParser

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
