"""Valid inputs the bad-input work must keep accepting (issue 15), and the
plausibility rules against analytic results."""
from __future__ import annotations

import math
import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.aero.table import AeroTable
from ironbark_opt.errors import InputError
from ironbark_opt.openrocket import read_ork
from ironbark_opt.plausibility import check_flight_inputs, check_inertia

ROOT = Path(__file__).resolve().parents[2]
ORK = ROOT / "tests/data/ork/01.One-stage_OR22.02.ork"


def test_config_matches_designation_as_typed():
    doc = read_ork(ORK)
    cfg = doc.config("[G80T]")                   # the label is "[G80T-10]"
    assert cfg.label() == "[G80T-10]"
    assert doc.config("g74w").label() == "[G74W-9]"
    with pytest.raises(InputError, match="did you mean") as err:
        doc.config("[G80X]")
    print(err.value)


def test_negative_rod_angle_tilts_the_other_way(tmp_path):
    with zipfile.ZipFile(ORK) as zf:
        xml = zf.read("rocket.ork").decode()
    xml = xml.replace("<launchrodangle>0.0</launchrodangle>", "<launchrodangle>-2.0</launchrodangle>", 1)
    out = tmp_path / "tilted.ork"
    with zipfile.ZipFile(out, "w") as zf:
        zf.writestr("rocket.ork", xml)
    sims = read_ork(out).simulations
    inc = [math.degrees(s.launch.inclination) for s in sims]
    head = [math.degrees(s.launch.heading) for s in sims]
    # -2 deg towards 90 deg (east) is +2 deg towards 270 deg: 88 deg above horizontal
    assert inc[0] == pytest.approx(88.0, abs=1e-9) and head[0] == pytest.approx(270.0, abs=1e-9)
    print(f"rod -2 deg @ 90 deg -> inclination {inc[0]:.3f} deg, heading {head[0]:.3f} deg")


def test_table_name_with_dots_round_trips(tmp_path):
    t = AeroTable.load(ROOT / "tables/Kestrel.csv")
    csv_path, json_path = t.save(tmp_path / "01.One-stage_OR22.02")
    assert csv_path.name == "01.One-stage_OR22.02.csv" and json_path.name == "01.One-stage_OR22.02.json"
    back = AeroTable.load(json_path)
    np.testing.assert_array_equal(back.values("CA"), t.values("CA"))
    assert not list(tmp_path.glob("*.tmp*"))


def test_inertia_rules_against_analytic_bodies():
    # solid cylinder, r = 0.05 m, h = 2 m, m = 10 kg: I_axial = m r^2 / 2, I_t = m (3 r^2 + h^2) / 12
    m, r, h = 10.0, 0.05, 2.0
    check_inertia((m * (3 * r * r + h * h) / 12, m * r * r / 2))
    # thin disc: I_axial = 2 I_transverse exactly, the limit of the triangle inequality
    check_inertia((m * r * r / 4, m * r * r / 2))
    with pytest.raises(InputError, match="triangle"):
        check_inertia((25.0, 70.0))               # the published file's 70 vs 25 kg m^2
    with pytest.raises(InputError, match="positive definite"):
        check_inertia([[0.034, 9.0, 0.0], [9.0, 6.321, 0.0], [0.0, 0.0, 6.321]])
    rot = np.array([[1, 0, 0], [0, math.cos(0.3), -math.sin(0.3)], [0, math.sin(0.3), math.cos(0.3)]])
    check_inertia(rot @ np.diag([1.0, 2.0, 2.5]) @ rot.T)      # rotated valid tensor passes


def test_preflight_margin_matches_the_flight_model():
    """The plausibility layer's static margin at launch against the 6-DOF model's output
    at t = 0 (an independent code path: CasADi mass properties and aero outputs)."""
    from ironbark_opt.flight import simulate
    from ironbark_opt.vehicle import load_setup

    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pre = check_flight_inputs(setup, dict(setup.nominal))["static_margin_launch_cal"]
    flown = simulate(setup).summary_values
    err = abs(pre - flown["static_margin_initial_cal"])
    print(f"margin at launch: plausibility {pre:.4f} cal, flight model {flown['static_margin_initial_cal']:.4f} "
          f"cal, |diff| {err:.4f} cal (tolerance 0.05: Mach 0.1 vs ~0)")
    assert err < 0.05
    assert flown["static_margin_min_cal"] <= flown["static_margin_rail_exit_cal"] + 1e-12


def test_descent_table_and_no_recovery_note():
    """Two-stage descent (Kestrel: drogue, then main at 300 m): the time series is in
    time order (the stage-crossing rows were views overwritten by the next stage);
    a file without recovery says so (Calisto: ballistic)."""
    from ironbark_opt.flight import simulate
    from ironbark_opt.vehicle import load_setup

    k = simulate(load_setup(ROOT / "examples/kestrel/kestrel.toml"), descent=True)
    t = k.to_dataframe()["time_s"].to_numpy()
    back = int(np.sum(np.diff(t) < 0))
    print(f"Kestrel descent: {t.size} rows, {back} out of time order, landing {k.summary_values['landing_time_s']:.1f} s")
    assert back == 0
    assert k.summary_values["recovery_devices"] == 2 and "no recovery device" not in k.summary()
    c = simulate(load_setup(ROOT / "examples/calisto/calisto.toml"), descent=True)
    assert c.summary_values["recovery_devices"] == 0
    assert "no recovery device" in c.summary()
    print(c.summary().splitlines()[-1])


def test_unstable_rocket_flies_only_with_the_flag(tmp_path):
    """CG moved to 2.40 m (CP about 1.7 m): refused (exit 2) without --allow-unstable;
    with it the flight runs and the JSON carries the minimum static margin (< 0)."""
    import json
    import shutil

    from click.testing import CliRunner

    from ironbark_opt.cli import main

    shutil.copytree(ROOT / "examples/calisto", tmp_path / "c")
    toml = tmp_path / "c/calisto.toml"
    toml.write_text(toml.read_text().replace("cg_x = 1.278", "cg_x = 2.40"))
    refused = CliRunner().invoke(main, ["simulate", str(toml), "--json"])
    assert refused.exit_code == 2 and "--allow-unstable" in refused.stderr and not refused.stdout
    flown = CliRunner().invoke(main, ["simulate", str(toml), "--json", "--allow-unstable"])
    assert flown.exit_code == 0, flown.stderr
    data = json.loads(flown.stdout)
    print(f"unstable Calisto: min margin {data['static_margin_min_cal']:.2f} cal at "
          f"{data['static_margin_min_time_s']:.2f} s; stderr: {flown.stderr.strip()}")
    assert data["static_margin_min_cal"] < 0 and "static margin" in flown.stderr


def test_ascent_stability_is_one_rule_for_every_command(tmp_path):
    """Calisto with its motor moved forward (nozzle at 1.50 m) and its dry CG aft (1.90 m):
    0.54 cal at launch, but the CG moves aft as the propellant burns and the margin falls
    below zero on the coast. simulate, ballast, sensitivity and montecarlo all refuse it
    (exit 2, 'static margin', no output file) unless --allow-unstable; with the flag the
    three commands flying the nominal flight report the same minimum margin (< 0)."""
    import json
    import shutil

    from click.testing import CliRunner

    from ironbark_opt.cli import main

    shutil.copytree(ROOT / "examples/calisto", tmp_path / "c")
    toml = tmp_path / "c/calisto.toml"
    text = toml.read_text()
    toml.write_text(text.replace("cg_x = 1.278 ", "cg_x = 1.90 ").replace("nozzle_x = 2.533 ", "nozzle_x = 1.500 "))
    spec = str(tmp_path / "c/dispersions.toml")
    out = tmp_path / "out.csv"
    commands = {"simulate": ["simulate", str(toml), "--csv", str(out)],
                "sensitivity": ["sensitivity", str(toml), "--csv", str(out)],
                "montecarlo": ["montecarlo", str(toml), "--spec", spec, "--samples", "8", "--no-progress",
                               "--csv", str(out)],
                "ballast": ["ballast", str(toml), "--target", "1500m", "--plot", str(tmp_path / "b.png")]}
    runner = CliRunner()
    for name, args in commands.items():
        refused = runner.invoke(main, args)
        print(f"{name}: exit {refused.exit_code}: {refused.stderr.strip().splitlines()[-1]}")
        assert refused.exit_code == 2, refused.stderr
        assert "static margin falls to -" in refused.stderr and "--allow-unstable" in refused.stderr
        assert "Traceback" not in refused.output and not out.exists() and not (tmp_path / "b.png").exists()
    minima = {}
    for name in ("simulate", "sensitivity", "montecarlo"):
        flown = runner.invoke(main, commands[name] + ["--allow-unstable", "--json"])
        assert flown.exit_code == 0, flown.stderr
        data = json.loads(flown.stdout)
        minima[name] = data.get("static_margin_min_cal", data.get("nominal_static_margin_min_cal"))
        out.unlink()
    print("minimum margins with --allow-unstable:", minima)
    assert minima["simulate"] < 0
    assert minima["sensitivity"] == pytest.approx(minima["simulate"], abs=1e-9)
    assert minima["montecarlo"] == pytest.approx(minima["simulate"], abs=1e-9)


def test_slow_rail_exit_warns():
    """Calisto off a 2.3 m rod (0.96 m of travel past its rail guide): the rail-exit speed
    falls under 15 m/s and ``simulate`` warns (plausibility.MIN_RAIL_EXIT_SPEED_MPS); off its
    own 5.2 m rail (26 m/s) it does not.  The two speeds against uniform acceleration,
    v = sqrt(2 a d) over the travel d with the same a: ratio sqrt(d_5.2 / d_2.3) within 10 %
    (the thrust curve's rise makes the short travel's mean acceleration lower)."""
    import json

    from click.testing import CliRunner

    from ironbark_opt import load_setup
    from ironbark_opt.cli import main

    toml = str(ROOT / "examples/calisto/calisto.toml")
    offset = load_setup(toml).rail_exit_offset
    short = CliRunner().invoke(main, ["simulate", toml, "--json", "--rail-length", "2.3"])
    full = CliRunner().invoke(main, ["simulate", toml, "--json"])
    assert short.exit_code == 0 and full.exit_code == 0, short.stderr + full.stderr
    v_short = json.loads(short.stdout)["rail_exit_speed_mps"]
    v_full = json.loads(full.stdout)["rail_exit_speed_mps"]
    uniform = math.sqrt((5.2 - offset) / (2.3 - offset))
    print(f"rail exit: 2.3 m rod {v_short:.2f} m/s, 5.2 m rail {v_full:.2f} m/s, ratio "
          f"{v_full / v_short:.3f} (uniform acceleration {uniform:.3f})")
    assert v_short < 15.0 and "rail exit speed" in short.stderr
    assert v_full > 15.0 and "rail exit speed" not in full.stderr
    assert v_full / v_short == pytest.approx(uniform, rel=0.10)
