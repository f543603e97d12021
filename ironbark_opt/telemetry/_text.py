"""Text plumbing shared by the telemetry readers (numeric-only).

Every reader works on :class:`TextFile` (the decoded lines with their
1-based numbers) and turns cells into numbers through :func:`columns`, so
that a bad cell, a short (truncated) row or a foreign file is always an
:class:`~ironbark_opt.errors.InputError` naming the file and the line.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError

FT = 0.3048  # [m] per international foot (exact, NIST SP 811)


@dataclass(frozen=True)
class TextFile:
    """A decoded text file: ``lines[i]`` is line ``i + 1`` (no line ending)."""

    path: str
    lines: tuple[str, ...]

    def error(self, message: str, line: int | None = None, field: str | None = None) -> InputError:
        return InputError(message, source=self.path, line=line, field=field)


def read_text(path) -> TextFile:
    """Read ``path`` as text (UTF-8, else Latin-1; CRLF/LF/CR; gzip-compressed files too)."""
    path = Path(path)
    if path.is_dir():
        raise InputError("is a directory, not a flight log file", source=str(path))
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise InputError("flight log not found", source=str(path)) from None
    except OSError as err:
        raise InputError(f"cannot read the flight log ({err.strerror})", source=str(path)) from None
    if raw[:2] == b"\x1f\x8b":                      # gzip-compressed log (``.csv.gz``)
        import gzip
        try:
            raw = gzip.decompress(raw)
        except (OSError, EOFError) as err:
            raise InputError(f"damaged gzip file ({err})", source=str(path)) from None
    if b"\x00" in raw[:4096] or raw[:2] == b"PK":
        raise InputError("not a text log (binary content; expected a CSV/text export of a flight log)",
                         source=str(path), line=1)
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    return TextFile(str(path), tuple(text.splitlines()))


@dataclass(frozen=True)
class Rows:
    """Data rows split into cells, with the line number of each row."""

    header: tuple[str, ...]
    cells: list[list[str]]
    line_numbers: list[int]

    def index(self, name: str, file: TextFile, *, occurrence: int = 0) -> int:
        """Column of the ``occurrence``-th (0-based) header cell equal to ``name``."""
        hits = [i for i, h in enumerate(self.header) if h == name]
        if len(hits) <= occurrence:
            raise file.error(f"column '{name}' not found in the header (columns: {', '.join(self.header)})",
                             line=self.header_line, field=name)
        return hits[occurrence]

    header_line: int = 1


def split_rows(file: TextFile, header_line: int, sep: str, *, strip_trailing_sep: bool = False,
               comment: str | None = None) -> Rows:
    """Header at 1-based ``header_line``, data rows after it (blank lines and
    separator-only lines skipped).  A row with fewer cells than the header is a
    truncated row: InputError naming its line."""
    def split(line: str) -> list[str]:
        cells = [c.strip() for c in line.split(sep)] if sep != " " else line.split()
        if strip_trailing_sep and cells and cells[-1] == "":
            cells = cells[:-1]
        return cells

    header = tuple(split(file.lines[header_line - 1].lstrip("#")))
    cells, numbers = [], []
    for k in range(header_line, len(file.lines)):
        line = file.lines[k]
        if not line.strip() or not line.replace(sep, "").strip():
            continue
        if comment and line.lstrip().startswith(comment):
            continue
        row = split(line)
        if len(row) < len(header):
            raise file.error(f"row has {len(row)} of the header's {len(header)} fields "
                             "(truncated file or wrong format)", line=k + 1)
        cells.append(row)
        numbers.append(k + 1)
    if not cells:
        raise file.error("no data rows after the header", line=header_line)
    return Rows(header, cells, numbers, header_line)


def number(text: str, *, decimal_comma: bool = False) -> float:
    """One cell as float (``decimal_comma``: ``2,5E-06`` -> 2.5e-06); ValueError otherwise."""
    if decimal_comma:
        text = text.replace(",", ".")
    return float(text)


def column(rows: Rows, file: TextFile, idx: int, *, decimal_comma: bool = False, scale: float = 1.0,
           strip_suffix: str = "") -> np.ndarray:
    """Column ``idx`` as floats times ``scale``; a bad cell is an InputError with its line."""
    out = np.empty(len(rows.cells))
    name = rows.header[idx] if idx < len(rows.header) else f"#{idx + 1}"
    for i, row in enumerate(rows.cells):
        cell = row[idx]
        if strip_suffix and cell.endswith(strip_suffix):
            cell = cell[: -len(strip_suffix)]
        try:
            out[i] = number(cell, decimal_comma=decimal_comma)
        except ValueError:
            raise file.error(f"expected a number in column '{name}', got {row[idx]!r}",
                             line=rows.line_numbers[i], field=name) from None
        if not np.isfinite(out[i]):       # float() reads 'nan' and 'inf': no logger writes them
            raise file.error(f"expected a finite number in column '{name}', got {row[idx]!r}",
                             line=rows.line_numbers[i], field=name)
    return out * scale


def header_value(file: TextFile, key: str, stop: str | None = None) -> tuple[str, int] | None:
    """Value of a ``Key: value`` header line (before a line starting with ``stop``)."""
    for k, line in enumerate(file.lines):
        if stop and line.startswith(stop):
            return None
        if line.lower().startswith(key.lower() + ":"):
            return line.split(":", 1)[1].strip(), k + 1
    return None
