"""CSV tables read strictly (dynstiff/io/table.py) and the measured-modes reader on top of
it: a decimal comma, text in a number column, an empty file or a header without rows are
refused naming the file, line and column; an empty shape cell is "not measured"; damping
ratios outside [0, 1) are refused."""

import numpy as np
import pytest

from dynstiff.analyses.measured import read_measured_modes
from dynstiff.errors import InvalidParameterError
from dynstiff.io.table import read_table


def _write(tmp_path, text, name="t.csv"):
    p = tmp_path / name
    p.write_text(text)
    return p


@pytest.mark.parametrize("text, match", [
    ("", "empty"), ("# only a comment\n\n", "empty"),
    ("freq [Hz],x\n", r"a header \(\['freq \[Hz\]', 'x'\]\) but no data rows"),
    ('freq [Hz],x\n4.2,"0,5"\n', r"line 2, column 'x': '0,5' is not a number \(write the "
                                 r"decimal point as '.'"),
    ("freq [Hz],x\n4.2,0,5\n", r"line 2: 3 cells for 2 columns .*decimal comma"),
    ("freq [Hz]\n4.2\nabc\n", r"line 3, column 'freq \[Hz\]': 'abc' is not a number"),
    ("freq [Hz]\n\n4.2\nnan\n", r"line 4, column 'freq \[Hz\]': 'nan' is not a number"),
    ("freq [Hz],damping ratio [-]\n4.2,1.0\n", r"damping_ratio must be in \[0, 1\)"),
    ("freq [Hz],freq [Hz]\n4.2,4.2\n", "appears twice"),
])
def test_bad_measured_tables_are_refused_with_line_and_column(tmp_path, text, match):
    with pytest.raises(InvalidParameterError, match=match):
        read_measured_modes(_write(tmp_path, text))


def test_not_measured_shape_cells_and_metadata_lines(tmp_path):
    p = _write(tmp_path, "# scene: \"x\"\nfreq [Hz], z [m], rx\n4.25,1e-3,\n5.0,,-0.5\n")
    m = read_measured_modes(p)
    np.testing.assert_array_equal(m.freq_hz, [4.25, 5.0])
    assert m.shapes[0, 2] == 1e-3 and np.isnan(m.shapes[0, 3]) and m.shapes[1, 3] == -0.5
    assert np.isnan(m.shapes[1, 2]) and np.all(np.isnan(m.shapes[:, :2]))
    t = read_table(p)
    assert t.rows[0][0] == 3 and t.text("rx") == ["", "-0.5"]
    with pytest.raises(InvalidParameterError, match="line 4, column 'z \\[m\\]': empty"):
        t.numbers("z [m]")
    with pytest.raises(InvalidParameterError, match="not a text"):
        read_table(tmp_path / "b.csv") if (tmp_path / "b.csv").write_bytes(b"\xff\xfe\x00")\
            else None


def test_short_rows_indented_comments_and_quoted_cells(tmp_path):
    """A row with fewer cells than the header reads its missing cells as empty (a number
    where an empty value is given, text ""); an indented '#' line is a comment; a quoted
    cell after a space is one cell (a quoted decimal comma is named as such); the line of a
    repeated header is the file's."""
    t = read_table(_write(tmp_path, "a,b,c\n  # an indented note\n1,2\n3, 4,5\n"))
    assert t.columns == ("a", "b", "c") and [r[0] for r in t.rows] == [3, 4]
    np.testing.assert_array_equal(t.numbers("c", empty=-1.0), [-1.0, 5.0])
    assert t.text("c") == ["", "5"] and t.text("b") == ["2", "4"]
    with pytest.raises(InvalidParameterError, match=r"^\S+t.csv: line 3, column 'c': empty, "
                                                    r"a number is needed$"):
        t.numbers("c")
    q = read_table(_write(tmp_path, 'a,b\n1, "2,5"\n', "q.csv"))
    with pytest.raises(InvalidParameterError, match=r"line 2, column 'b': '2,5' is not a "
                                                    r"number \(write the decimal point"):
        q.numbers("b")
    with pytest.raises(InvalidParameterError, match=r"'--1.5' is not a number$"):
        read_table(_write(tmp_path, "a\n--1.5\n", "s.csv")).numbers("a")
    with pytest.raises(InvalidParameterError, match=r"d.csv: line 2: a column name appears"):
        read_table(_write(tmp_path, "# meta\na,a\n1,2\n", "d.csv"))
