"""The user's `ironbark aero build` on a generated rocket TOML, and what the
generated-rocket tests read from the table (tests: test_random_rockets.py,
test_odd_rockets_aero_build.py)."""
from __future__ import annotations

import json
from types import SimpleNamespace

import numpy as np
from click.testing import CliRunner


def build_generated(text: str, tmp_path, name: str) -> SimpleNamespace:
    """Build the table of rocket TOML ``text`` with the CLI's default grid and return
    ``table``, ``rocket``, ``d`` (reference diameter [m]), ``ia`` (the 2 deg column),
    ``i3`` (the Mach 0.3 row), ``cn`` (CN at 2 deg per Mach), ``ca0`` (zero-lift pressure
    + base CA per Mach) and ``steps`` (relative change of CN(2 deg) per 0.1 of Mach
    number between neighbouring solved supersonic grid Mach numbers)."""
    from ironbark_opt.aero.table import AeroTable
    from ironbark_opt.cli import main
    from ironbark_opt.vehicle import load_rocket_geometry
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    res = CliRunner().invoke(main, ["aero", "build", str(path), "--out", str(tmp_path / "t"), "--no-progress",
                                    "--no-resume", "--json"])
    assert res.exit_code == 0, res.output
    t = AeroTable.load(json.loads(res.stdout)["table_csv"])
    rk, _ = load_rocket_geometry(path)
    ia = int(np.argmin(np.abs(np.degrees(t.alpha) - 2.0)))
    cn = t.values("CN")[:, ia]
    md = t.metadata
    sup = np.nonzero((t.mach > 1.0) & ~np.isin(t.mach, md["mach_bridged"]))[0]     # solved ones
    steps = (np.abs(cn[sup[1:]] / cn[sup[:-1]] - 1.0) / (np.diff(t.mach[sup]) / 0.1)
             if len(sup) > 1 else np.zeros(0))
    return SimpleNamespace(table=t, rocket=rk, d=2 * rk.reference_radius(), ia=ia,
                           i3=int(np.argmin(np.abs(t.mach - 0.3))), cn=cn, steps=steps,
                           ca0=t.values("CA_pressure")[:, 0] + t.values("CA_base")[:, 0])
