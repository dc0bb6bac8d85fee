"""CSV tables read strictly: a header line, ``#`` comment and metadata lines skipped, every
number parsed on its own with the file, line and column of a bad one in the error (a decimal
comma is refused, never read as "not measured"), empty files and tables refused.

The tables dynstiff writes (``# key: value`` metadata lines, then a header with units in the
column names) read back through :func:`read_table`.
"""

import csv
import math
from dataclasses import dataclass

import numpy as np

from dynstiff.errors import InvalidParameterError
from dynstiff.io.files import input_file

__all__ = ["Table", "read_table"]


@dataclass(frozen=True)
class Table:
    """The text of a CSV table.

    Attributes
    ----------
    path : str
    columns : tuple of str
        Header names, stripped.
    rows : tuple of (int, tuple of str)
        File line number (1-based) and cells of every data row.
    """

    path: str
    columns: tuple
    rows: tuple

    def __len__(self):
        return len(self.rows)

    def numbers(self, column, empty=None):
        """The column as floats, shape (n_rows,).

        Parameters
        ----------
        column : str
        empty : float, optional
            The value of an empty cell (e.g. NaN for "not measured"); None: an empty cell
            is an error.

        Raises
        ------
        InvalidParameterError
            A cell that is not a number (naming file, line, column and text), or an empty
            one where none is allowed.
        """
        k = self.columns.index(column)
        out = np.empty(len(self.rows))
        for i, (line, cells) in enumerate(self.rows):
            text = cells[k].strip() if k < len(cells) else ""
            if not text:
                if empty is None:
                    raise InvalidParameterError(
                        f"{self.path}: line {line}, column {column!r}: empty, a number is "
                        f"needed")
                out[i] = empty
                continue
            try:
                v = float(text)
            except ValueError:
                hint = " (write the decimal point as '.', not ',')" if "," in text else ""
                raise InvalidParameterError(
                    f"{self.path}: line {line}, column {column!r}: {text!r} is not a "
                    f"number{hint}") from None
            if math.isnan(v) and empty is None:
                raise InvalidParameterError(
                    f"{self.path}: line {line}, column {column!r}: {text!r} is not a number")
            out[i] = v
        return out

    def text(self, column):
        """The column as stripped strings."""
        k = self.columns.index(column)
        return [cells[k].strip() if k < len(cells) else "" for _, cells in self.rows]


def read_table(path):
    """Read a CSV table (module notes).

    Parameters
    ----------
    path : str or path-like

    Returns
    -------
    Table

    Raises
    ------
    InvalidParameterError
        An empty file, a header without data rows, a row with more cells than the header,
        or a file that is not text (each naming the file and, for a row, its line).
    """
    path = input_file(path)
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    except UnicodeDecodeError:
        raise InvalidParameterError(f"{path}: not a text (UTF-8) file") from None
    numbered = [(k, ln) for k, ln in enumerate(lines, start=1)
                if ln.strip() and not ln.lstrip().startswith("#")]
    if not numbered:
        raise InvalidParameterError(f"{path}: empty (no header and no data)")
    parsed = list(csv.reader([ln for _, ln in numbered], skipinitialspace=True))
    header = tuple(c.strip() for c in parsed[0])
    if len(set(header)) != len(header):
        raise InvalidParameterError(f"{path}: line {numbered[0][0]}: a column name appears "
                                    f"twice in {list(header)}")
    rows = []
    for (line, _), cells in zip(numbered[1:], parsed[1:]):
        if len(cells) > len(header):
            raise InvalidParameterError(
                f"{path}: line {line}: {len(cells)} cells for {len(header)} columns "
                f"{list(header)} (a decimal comma splits a number in two: use '.')")
        rows.append((line, tuple(cells)))
    if not rows:
        raise InvalidParameterError(f"{path}: a header ({list(header)}) but no data rows")
    return Table(path=path, columns=header, rows=tuple(rows))
