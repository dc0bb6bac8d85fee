"""The rich-display tables (dynstiff/_html.py): escaped, balanced, numbers to 5 digits, long
tables cut with a note."""

from conftest import assert_valid_html

from dynstiff._html import html_table


def test_cells_are_escaped_and_numbers_rounded():
    s = html_table("<a & b>", ["x <y>"], [["</table><script>"], [1 / 3], [True]])
    text = assert_valid_html(s)
    assert "<script>" not in s and "</table><script>" in text
    assert "0.33333" in text and "0.333333" not in text and "True" in text


def test_rows_beyond_the_limit_are_counted():
    text = assert_valid_html(html_table("t", ["k"], [[k] for k in range(25)], limit=20))
    assert " 19 " in f" {text} " and " 20 " not in f" {text} " and "5 more rows" in text


def test_exact_table_with_special_characters_and_cut_rows():
    """Title, header, cells and notes escaped (& < > " '); cut-rows note first, then notes."""
    s = html_table("R&D <x>", ['a "q"', "b"], [[1 / 3, "<i>"], [2, "it's"]],
                   notes=["n & m"], limit=1)
    assert s == ("<div><p><b>R&amp;D &lt;x&gt;</b></p><table>"
                 "<tr><th>a &quot;q&quot;</th><th>b</th></tr>"
                 "<tr><td>0.33333</td><td>&lt;i&gt;</td></tr>"
                 "</table>"
                 "<p>... 1 more rows (to_frame() holds them all)</p>"
                 "<p>n &amp; m</p>"
                 "</div>")


def test_exactly_limit_rows_are_shown_without_note():
    """limit rows: all shown, no 'more rows' note; apostrophes escaped."""
    s = html_table("t", ["k"], [[1], ["it's"]], limit=2)
    assert s == ("<div><p><b>t</b></p><table><tr><th>k</th></tr>"
                 "<tr><td>1</td></tr><tr><td>it&#x27;s</td></tr></table></div>")
