"""Start-up of the ``ironbark`` command: ``simulate`` imports only what it uses.

Not a timing test: it checks *which* modules a fresh ``simulate`` process has
imported (SciPy's interpolate 0.7 s, pandas 0.4 s, requests/ssl, matplotlib and
the other sub-command modules were all loaded before commands were registered
lazily), and that the JSON it prints is the same as an in-process simulate.
"""
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = str(ROOT / "examples/calisto/calisto.toml")
HEAVY = ("scipy.interpolate", "pandas", "requests", "ssl", "matplotlib", "ironbark_opt.cli.motor",
         "ironbark_opt.cli.weather", "ironbark_opt.cli.aero", "ironbark_opt.cli.optimise",
         "ironbark_opt.cli.analysis", "ironbark_opt.cli.ork", "ironbark_opt.cli.window", "panair")

PROBE = """
import json, sys
from ironbark_opt.cli import main
try:
    main(["simulate", sys.argv[1], "--json"])
except SystemExit:
    pass
print(json.dumps(sorted(m for m in sys.modules)), file=sys.stderr)
"""


def test_simulate_does_not_import_heavy_modules(tmp_path):
    proc = subprocess.run([sys.executable, "-c", PROBE, EXAMPLE], capture_output=True, text=True,
                          cwd=tmp_path, timeout=120)
    assert proc.returncode == 0, proc.stderr
    loaded = set(json.loads(proc.stderr.strip().splitlines()[-1]))
    found = sorted(m for m in HEAVY if m in loaded)
    print(f"{len(loaded)} modules loaded; heavy ones: {found}")
    assert not found
    from ironbark_opt.flight import simulate
    from ironbark_opt.vehicle import load_setup
    out = json.loads(proc.stdout)
    assert out["apogee_agl_m"] == simulate(load_setup(EXAMPLE)).apogee_agl


def test_native_writes_to_stdout_go_to_stderr():
    """A native library writing to file descriptor 1 while a command runs (the reference
    BLAS's XERBLA under SuperLU, which corrupted ``aero build --json``) lands on stderr;
    what the command prints through ``sys.stdout`` stays on stdout, and descriptor 1 is
    restored afterwards."""
    code = ("import os, sys\n"
            "from ironbark_opt.cli.common import native_stdout_to_stderr\n"
            "with native_stdout_to_stderr():\n"
            "    os.write(1, b' ** On entry to DTRSV  parameter number  6\\n')\n"
            "    print('{\"ok\": 1}')\n"
            "os.write(1, b'after\\n')\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout == '{"ok": 1}\nafter\n'
    assert "DTRSV" in out.stderr
