"""Air-brake drag table, deployment schedule and the [airbrakes] TOML section."""
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero.airbrakes import BrakeSchedule, read_brake_drag, smoothstep
from ironbark_opt.errors import InputError
from ironbark_opt.rocket.toml_io import loads_rocket_toml

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "calisto_airbrakes"
TABLE = EXAMPLE / "drag_airbrakes.csv"          # the camoes team's table (RocketPy example data)


def _rows():
    data = np.genfromtxt(TABLE, delimiter=",", skip_header=1)
    return {(round(d, 6), round(mach, 6)): cd for d, mach, cd in data}


def test_total_table_is_the_increment_over_the_stowed_row():
    rows = _rows()
    drag = read_brake_drag(TABLE, meaning="total")
    assert drag.delta_cd.shape == (11, 11)
    for (d, mach), cd in rows.items():
        i, j = np.searchsorted(drag.deployment, d), np.searchsorted(drag.mach, mach)
        assert drag.delta_cd[i, j] == pytest.approx(cd - rows[(0.0, mach)], abs=1e-12)
    # The cubic B-spline interpolates the grid values (numeric and symbolic alike).
    d_s, m_s = ca.SX.sym("d"), ca.SX.sym("m")
    f = ca.Function("f", [d_s, m_s], [drag.evaluate(d_s, m_s)])
    for d, mach in ((1.0, 0.5), (0.3, 0.8), (0.7, 1.1)):
        want = rows[(d, mach)] - rows[(0.0, mach)]
        got_num, got_sym = float(drag.evaluate(d, mach)), float(f(d, mach))
        print(f"d={d} M={mach}: table {want:.4f}, spline {got_num:.6f}")
        assert got_num == pytest.approx(want, abs=1e-9)
        assert got_sym == pytest.approx(want, abs=1e-9)
    # Clamped outside the grid: Mach 2 reads the Mach 1.1 column.
    assert float(drag.evaluate(1.0, 2.0)) == pytest.approx(rows[(1.0, 1.1)] - rows[(0.0, 1.1)], abs=1e-9)


def test_increment_meaning_keeps_the_values(tmp_path):
    path = tmp_path / "brake.csv"
    path.write_text("mach,deployment,cd\n0,0,0\n0,1,0.5\n1,0,0\n1,1,0.7\n")
    drag = read_brake_drag(path)
    assert float(drag.evaluate(1.0, 1.0)) == pytest.approx(0.7)
    assert float(drag.evaluate(0.0, 0.3)) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("text, message", [
    ("deployment_level,mach,cd\n0,0.1,0.5\n1,0.1,0.6\n0,0.2,0.5\n", "incomplete grid"),
    ("deployment_level,mach,cd\n0,0.1,0.5\n1.5,0.1,0.6\n0,0.2,0.5\n1.5,0.2,0.6\n", "must lie in [0, 1]"),
    ("deployment_level,mach,cd\n0,0.1,0.5\n1,0.1,abc\n", "expected three numbers"),
    ("a,b,c\n0,0.1,0.5\n", "header must name"),
    ("deployment_level,mach,cd\n0,0.1,0.5\n0,0.1,0.6\n1,0.2,0.5\n", "given twice"),
])
def test_bad_tables(tmp_path, text, message):
    path = tmp_path / "brake.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=message.replace("[", r"\[").replace("]", r"\]")) as err:
        read_brake_drag(path)
    assert str(path) in str(err.value)


def test_time_schedule_honours_the_rate_limit_exactly():
    drag = read_brake_drag(TABLE, meaning="total")
    for level, rate in ((1.0, 2.0), (0.4, 0.5)):
        sched = BrakeSchedule(drag, trigger="time", start=5.0, level=level, rate=rate)
        t = np.linspace(4.0, 10.0, 600001)
        d = sched.deployment(t, 0.0, 0.0, 0.0, {"airbrake_level": level, "airbrake_start_time": 5.0})
        slope = np.diff(d) / np.diff(t)
        print(f"level {level}, rate {rate}/s: max slope {slope.max():.6f}/s, final {d[-1]}")
        assert slope.max() == pytest.approx(rate, rel=1e-6)
        assert d[t <= 5.0].max() == 0.0 and d[-1] == pytest.approx(level)
    assert smoothstep(0.5) == 0.5 and smoothstep(-1.0) == 0.0 and smoothstep(2.0) == 1.0


def test_schedule_needs_its_keys():
    drag = read_brake_drag(TABLE, meaning="total")
    with pytest.raises(InputError, match="rate limit"):
        BrakeSchedule(drag, trigger="time", start=5.0)
    with pytest.raises(InputError, match="ramp"):
        BrakeSchedule(drag, trigger="altitude", start=500.0, rate=1.0)
    with pytest.raises(InputError, match="level"):
        BrakeSchedule(drag, trigger="time", start=5.0, rate=1.0, level=1.5)


def _toml(section: str) -> str:
    text = (EXAMPLE / "calisto_airbrakes.toml").read_text()
    return text[: text.index("\n[airbrakes]") + 1] + section


def test_toml_section_reads_and_errors_name_the_line():
    rf = loads_rocket_toml((EXAMPLE / "calisto_airbrakes.toml").read_text(), EXAMPLE / "calisto_airbrakes.toml")
    spec = rf.airbrakes
    assert (spec.trigger, spec.start, spec.level, spec.rate, spec.drag_is) == ("time", 5.4, 1.0, 2.0, "total")
    path = EXAMPLE / "x.toml"
    cases = [
        ('[airbrakes]\ndrag = "drag_airbrakes.csv"\nstart = 5.0\nrate = 2.0\nspeed = 3\n', "unknown key 'speed'",
         "airbrakes.speed"),
        ('[airbrakes]\ndrag = "drag_airbrakes.csv"\nstart = 5.0\n', "missing required key 'rate'", "airbrakes"),
        ('[airbrakes]\ndrag = "drag_airbrakes.csv"\nstart = 5.0\nrate = 2.0\nlevel = 1.2\n', "in (0, 1]",
         "airbrakes.level"),
        ('[airbrakes]\ndrag = "drag_airbrakes.csv"\ntrigger = "pressure"\n', "expected one of", "airbrakes.trigger"),
        ('[airbrakes]\ndrag = "nothere.csv"\n', "file not found", "airbrakes.drag"),
        ('[airbrakes]\ndrag = "drag_airbrakes.csv"\ntrigger = "altitude"\nstart = 800.0\n',
         "missing required key 'ramp'", "airbrakes"),
    ]
    for section, message, field in cases:
        text = _toml(section)
        with pytest.raises(InputError) as err:
            loads_rocket_toml(text, path)
        print(err.value)
        assert message in err.value.message and err.value.field == field
        assert err.value.line is not None and err.value.line >= text[: text.index("\n[airbrakes]")].count("\n") + 2
