"""Write the notebooks from their cell sources (keeps them reviewable as code).

Run: ``python notebooks/_build.py``; the tests execute the .ipynb files.
"""
from pathlib import Path

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

HERE = Path(__file__).parent

BALLAST = [
    ("md", "# Launch-day ballast solve\n\nThe job a team runs on launch day: the rocket, the conditions, a target "
           "apogee — how much ballast, on which motor? This notebook runs offline on the bundled Calisto example."),
    ("code", "from pathlib import Path\nimport matplotlib\nmatplotlib.use('Agg')\n"
             "from ironbark_opt.vehicle import load_setup\nfrom ironbark_opt.flight import simulate\n"
             "from ironbark_opt.optimise.ballast import solve_ballast\n"
             "from ironbark_opt.optimise.motor_choice import choose_motor\n"
             "from ironbark_opt.plots import plot_flight\n"
             "ROOT = Path.cwd() if (Path.cwd() / 'examples').exists() else Path.cwd().parent\n"
             "setup = load_setup(ROOT / 'examples/calisto/calisto.toml')"),
    ("md", "## 1. Fly it as it is"),
    ("code", "flight = simulate(setup)\nprint(flight.summary())"),
    ("md", "## 2. Ballast for a 10,000 ft target\n\nIPOPT solves for the ballast mass with the apogee time as a "
           "free variable constrained by v_z = 0; we ask for at least 24 m/s off the rail."),
    ("code", "sol = solve_ballast(setup, '10000ft', min_rail_speed=24.0)\nprint(sol.summary())\n"
             "assert sol.feasible and abs(sol.values['resimulated_apogee_agl_m'] - 3048.0) < 0.5"),
    ("md", "## 3. Re-fly the answer"),
    ("code", "flown = simulate(setup, parameters={'ballast_mass': sol.ballast, 'ballast_x': sol.values['ballast_x_m']})\n"
             "print(flown)\nfig = plot_flight(flown)"),
    ("md", "## 4. Which motor?\n\nEvery candidate gets its own ballast solve; feasible ones are ranked by the "
           "least ballast."),
    ("code", "motors = [ROOT / 'examples/calisto/Cesaroni_M1670.eng', ROOT / 'tests/data/motors/Cesaroni_7579M1520-P.eng',\n"
             "          ROOT / 'tests/data/motors/AeroTech_M1340W.eng']\n"
             "ranking = choose_motor(setup, motors, '10000ft', processes=1)\nprint(ranking.summary())\nranking.to_dataframe()"),
]

SENSITIVITY = [
    ("md", "# Sensitivity sweep\n\nExact derivatives (CasADi AD through the whole trajectory, rail-exit and "
           "apogee roots included) of apogee and friends with respect to every named parameter."),
    ("code", "from pathlib import Path\nimport matplotlib\nmatplotlib.use('Agg')\n"
             "from ironbark_opt.vehicle import load_setup\nfrom ironbark_opt.analysis.sensitivity import sensitivities\n"
             "ROOT = Path.cwd() if (Path.cwd() / 'examples').exists() else Path.cwd().parent\n"
             "setup = load_setup(ROOT / 'examples/calisto/calisto.toml')"),
    ("code", "sens = sensitivities(setup, target='10000ft')\nprint(sens.summary())"),
    ("code", "sens.to_dataframe()"),
    ("md", "## A sweep: apogee vs drag scale, and the tangent from AD"),
    ("code", "import numpy as np\nimport matplotlib.pyplot as plt\nfrom ironbark_opt.flight import simulate\n"
             "scales = np.linspace(0.8, 1.2, 9)\napogee = [simulate(setup, parameters={'drag_scale': s}).apogee_agl for s in scales]\n"
             "df = sens.to_dataframe().set_index('parameter')\nslope = df.loc['drag_scale', 'd_apogee_agl_m']\n"
             "fig, ax = plt.subplots()\nax.plot(scales, apogee, 'o', label='simulate')\n"
             "ax.plot(scales, apogee[4] + slope * (scales - 1), label='AD tangent')\n"
             "ax.set_xlabel('drag scale [-]'); ax.set_ylabel('apogee AGL [m]'); ax.legend()"),
]

MONTECARLO = [
    ("md", "# Monte Carlo dispersion\n\nThe same trajectory Function mapped over parameter samples; seeded and "
           "reproducible."),
    ("code", "from pathlib import Path\nimport matplotlib\nmatplotlib.use('Agg')\n"
             "from ironbark_opt.vehicle import load_setup\nfrom ironbark_opt.analysis.montecarlo import montecarlo\n"
             "from ironbark_opt.analysis.distributions import load_spec\n"
             "from ironbark_opt.analysis.plots import plot_apogee_histogram, plot_landing_ellipse\n"
             "ROOT = Path.cwd() if (Path.cwd() / 'examples').exists() else Path.cwd().parent\n"
             "setup = load_setup(ROOT / 'examples/calisto/calisto.toml')\n"
             "spec = load_spec(ROOT / 'examples/calisto/dispersions.toml')"),
    ("code", "disp = montecarlo(setup, spec, 200, seed=1, target='10800ft', band=100.0, progress=False)\nprint(disp.summary())"),
    ("code", "fig = plot_apogee_histogram(disp)"),
    ("code", "fig = plot_landing_ellipse(disp)"),
]

FLIGHT_LOG = [
    ("md", "# Learn from the last flight\n\nImport the altimeter log of NUSTARS' test flight FT1 (TeleMega), "
           "compare it with the team's OpenRocket design, calibrate drag and thrust on the first 60 % of the "
           "climb, and re-solve the ballast for the next flight with what was learned."),
    ("code", "from pathlib import Path\nimport matplotlib\nmatplotlib.use('Agg')\n"
             "from ironbark_opt.vehicle import load_setup\nfrom ironbark_opt.flight import simulate\n"
             "from ironbark_opt.telemetry import read_log\nfrom ironbark_opt.telemetry.compare import compare_flight\n"
             "from ironbark_opt.telemetry.calibrate import calibrate\n"
             "from ironbark_opt.telemetry.calibration_file import write_calibration, apply_calibration\n"
             "from ironbark_opt.telemetry.plots import plot_comparison, plot_residuals\n"
             "from ironbark_opt.optimise.ballast import solve_ballast\n"
             "ROOT = Path.cwd() if (Path.cwd() / 'examples').exists() else Path.cwd().parent\n"
             "DATA = ROOT / 'tests/data/telemetry'\n"
             "setup = load_setup(DATA / 'nustars-2026-ft1-telemega.ork')\n"
             "log = read_log(DATA / 'nustars-2026-ft1-telemega.csv.gz')\nprint(log.summary())"),
    ("md", "## 1. The model against the flight"),
    ("code", "comparison = compare_flight(setup, log)\nprint(comparison.summary())\nfig = plot_comparison(comparison)"),
    ("md", "## 2. Calibrate on the first 60 % of the climb\n\nGauss-Newton on the exact Jacobian of the "
           "trajectory; the log's time shift and the static-port pressure error of the baro are fitted too."),
    ("code", "cal = calibrate(setup, log, until_fraction=0.6)\nprint(cal.summary())\nfig = plot_residuals(cal)\ncal.to_dataframe()"),
    ("code", "import tempfile\npath = write_calibration(cal, Path(tempfile.mkdtemp()) / 'ft1-calibration.toml')\n"
             "calibrated = apply_calibration(setup, path)\n"
             "before, after = simulate(setup).apogee_agl, simulate(calibrated).apogee_agl\n"
             "print(f'logged apogee {log.apogee_agl:.1f} m; model {before:.1f} m ({before - log.apogee_agl:+.1f}), '\n"
             "      f'calibrated {after:.1f} m ({after - log.apogee_agl:+.1f})')\n"
             "assert abs(after - log.apogee_agl) * 3 <= abs(before - log.apogee_agl)"),
    ("md", "## 3. Next flight: ballast for 7,000 ft with and without the calibration"),
    ("code", "for label, s in (('design model', setup), ('calibrated', calibrated)):\n"
             "    sol = solve_ballast(s, '7000ft')\n"
             "    print(f\"{label:>12}: ballast {sol.ballast:.3f} kg, re-simulated apogee \"\n"
             "          f\"{sol.values['resimulated_apogee_agl_m']:.1f} m\")"),
]


def build(name, cells):
    nb = new_notebook()
    nb.cells = [new_markdown_cell(src) if kind == "md" else new_code_cell(src) for kind, src in cells]
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(nb, HERE / name)


if __name__ == "__main__":
    build("launch_day_ballast.ipynb", BALLAST)
    build("sensitivity_sweep.ipynb", SENSITIVITY)
    build("monte_carlo.ipynb", MONTECARLO)
    build("flight_log_calibration.ipynb", FLIGHT_LOG)
