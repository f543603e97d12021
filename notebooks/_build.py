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

LAUNCH_MORNING = [
    ("md", "# Launch morning: forecast, ballast, dispersion, maps and the flight card\n\n"
           "Calisto at Spaceport America, launching at 21:00 UTC. On the day the forecast comes from NOAA's RAP "
           "model over the internet; here a local server replays the recorded THREDDS responses bundled in "
           "`tests/data/weather` (the RAP point CSV is *constructed* from recorded numbers: ISA temperatures and "
           "a 12 m/s westerly, see its README), so the notebook runs offline through the very same code."),
    ("code", "import os, tempfile, threading\nfrom functools import partial\n"
             "from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer\nfrom pathlib import Path\n"
             "import matplotlib\nmatplotlib.use('Agg')\n"
             "ROOT = Path.cwd() if (Path.cwd() / 'examples').exists() else Path.cwd().parent\n"
             "W = ROOT / 'tests/data/weather'\nOUT = Path(tempfile.mkdtemp(prefix='launch-morning-'))\n"
             "RAP = '/ncss/grid/grib/NCEP/RAP/CONUS_13km/Best'\n"
             "RECORDED = {RAP + '/dataset.xml': W / 'ncss_RAP_CONUS_13km_20241211_1900_dataset.xml',\n"
             "            RAP: W / 'ncss_rap_point_csv_constructed.csv'}\n\n"
             "class Replay(SimpleHTTPRequestHandler):          # skip this cell on launch morning\n"
             "    def do_GET(self):\n"
             "        body = RECORDED[self.path.split('?')[0]].read_bytes()\n"
             "        self.send_response(200); self.send_header('Content-Length', str(len(body))); self.end_headers()\n"
             "        self.wfile.write(body)\n"
             "    def log_message(self, *args):\n"
             "        pass\n\n"
             "server = ThreadingHTTPServer(('127.0.0.1', 0), Replay)\n"
             "threading.Thread(target=server.serve_forever, daemon=True).start()\n"
             "os.environ.update(IRONBARK_THREDDS_URL=f'http://127.0.0.1:{server.server_port}',\n"
             "                  IRONBARK_FORECAST_SOURCES='thredds', IRONBARK_OFFLINE='0',\n"
             "                  IRONBARK_CACHE_DIR=str(OUT / 'cache'))"),
    ("md", "## 1. The forecast over the site\n\n`forecast_atmosphere` is what `ironbark ballast --forecast rap "
           "--site spaceport_america --time ...` does: the profile replaces the rocket file's atmosphere and "
           "the site's position and ground elevation come with it."),
    ("code", "from ironbark_opt.vehicle import load_setup\nfrom ironbark_opt.cli.optimise import forecast_atmosphere\n"
             "from ironbark_opt.atmosphere.files import describe_flown\n"
             "TIME = '2024-12-11T21:00Z'\n"
             "setup = forecast_atmosphere(load_setup(ROOT / 'examples/calisto/calisto.toml'), 'rap', "
             "'spaceport_america', TIME)\n"
             "atm = describe_flown(setup.atmosphere)\nATM = f\"RAP {atm['valid_time']}\"\nprint(atm)"),
    ("code", "import numpy as np\nimport matplotlib.pyplot as plt\n"
             "h = np.linspace(setup.site_elevation, setup.site_elevation + 4000, 81)\n"
             "we, wn = (np.array([float(c) for c in comp]) for comp in zip(*[setup.atmosphere.wind_l(z) for z in h]))\n"
             "fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 4), sharey=True)\n"
             "a1.plot(we, h, label='toward east'); a1.plot(wn, h, label='toward north')\n"
             "a1.set_xlabel('wind [m/s]'); a1.set_ylabel('altitude ASL [m]'); a1.legend()\n"
             "a2.plot([float(setup.atmosphere.temperature(z)) - 273.15 for z in h], h, 'C3', label='temperature')\n"
             "a2.set_xlabel('temperature [degC]'); a2.legend()\n"
             "fig.suptitle(f'{setup.name} launch site: {ATM} forecast profile')"),
    ("md", "## 2. Ballast for 10,000 ft in that air"),
    ("code", "from ironbark_opt.optimise.ballast import solve_ballast\nfrom ironbark_opt.flight import simulate\n"
             "sol = solve_ballast(setup, '10000ft')\nprint(sol.summary())\n"
             "at = {'ballast_mass': sol.ballast, 'ballast_x': sol.values['ballast_x_m']}\n"
             "flight = simulate(setup, parameters=at, descent=True)\n"
             "assert abs(flight.apogee_agl - 3048.0) < 0.5"),
    ("md", "## 3. What the day's uncertainty does to it\n\nA small Monte Carlo around the ballast (20 flights to "
           "keep the notebook quick; use 1000+ for the real card) with the example's dispersion spec."),
    ("code", "from ironbark_opt.analysis.montecarlo import montecarlo\n"
             "from ironbark_opt.analysis.plots import plot_apogee_histogram, plot_landing_ellipse\n"
             "disp = montecarlo(setup, ROOT / 'examples/calisto/dispersions.toml', 20, parameters=at, descent=True,\n"
             "                  target='10000ft', band=50.0, progress=False)\nprint(disp.summary())\n"
             "fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.5))\n"
             "plot_apogee_histogram(disp, a1); plot_landing_ellipse(disp, a2)\n"
             "a1.set_title(f'{setup.name}: apogee, {disp.samples} flights, {ATM}', fontsize=9)\n"
             "a2.set_title(f'{setup.name}: landing, {disp.samples} flights, {ATM}', fontsize=9)"),
    ("md", "## 4. Maps for Google Earth\n\nThe trajectory (altitude above sea level) and the 1/2/3-sigma landing "
           "ellipses as KML; `ironbark simulate --kml` and `ironbark montecarlo --kml` write the same files."),
    ("code", "from ironbark_opt.report.kml import flight_kml, dispersion_kml\n"
             "(OUT / 'trajectory.kml').write_text(flight_kml(flight, setup.latitude, setup.longitude, atmosphere=ATM))\n"
             "(OUT / 'landing.kml').write_text(dispersion_kml(disp, setup.latitude, setup.longitude, "
             "setup.site_elevation, atmosphere=ATM))\n"
             "print(*(OUT / 'landing.kml').read_text().splitlines()[:12], sep='\\n')"),
    ("md", "## 5. The flight card\n\nOne page for the range safety officer and the ballast bay "
           "(`ironbark ballast ... --card card.pdf --card-spec dispersions.toml`)."),
    ("code", "from IPython.display import Image\n"
             "from ironbark_opt.report.card import apogee_per_100g, build_card, write_flight_card\n"
             "card = build_card(setup, flight, solution=sol, dispersion=disp, apogee_per_100g_m=apogee_per_100g(setup, at),\n"
             "                  launch_time=TIME, site_name='spaceport_america')\n"
             "print('\\n'.join(card.text_lines()))\n"
             "write_flight_card(OUT / 'card.png', card)     # or card.pdf\n"
             "server.shutdown()\nImage(filename=str(OUT / 'card.png'), width=620)"),
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
    build("launch_morning.ipynb", LAUNCH_MORNING)
