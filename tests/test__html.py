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
