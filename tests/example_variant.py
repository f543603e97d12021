"""A bundled example rocket file with some of its text replaced, written to a temp dir
beside copies of the example's motor and data files (the variant loads as the example
does)."""
import shutil
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def example_variant(tmp_path, example: str, replacements) -> Path:
    """``examples/<example>/<example>.toml`` with each ``(old, new)`` of ``replacements``
    applied (each ``old`` must occur), written to ``tmp_path``; returns its path."""
    src = EXAMPLES / example / f"{example}.toml"
    text = src.read_text()
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    for f in src.parent.iterdir():
        if f.suffix in (".eng", ".csv"):
            shutil.copy(f, tmp_path / f.name)
    path = tmp_path / src.name
    path.write_text(text)
    return path
