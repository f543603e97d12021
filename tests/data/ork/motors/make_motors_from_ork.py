"""Write a motor file from the flight OpenRocket stored in one of the .ork fixtures.

No file of these motors as OpenRocket flew them is among the shared fixtures:

- AeroTech I115W ('Parallel booster staging.ork', simulation 2 flies it alone);
(The G80T of '01.One-stage_OR22.02.ork' is OpenRocket's own file, AeroTech_G80_1.eng,
found by its digest; see tests/data/ork/README.md.)

Each simulation's stored thrust and motor-mass columns are the motor
OpenRocket flew: the thrust samples up to burnout (the zero at ignition
dropped, as RASP files start after 0), the loaded mass at t = 0 and the
burnt-out mass at the end.  Run from the repository root:
    python tests/data/ork/motors/make_motors_from_ork.py
"""
from pathlib import Path

from ironbark_opt.openrocket.simdata import simulations
from ironbark_opt.openrocket.xmlread import read_xml

HERE = Path(__file__).parent
#: (output file, .ork fixture, simulation index, RASP header: name, diameter [mm], length [mm], delays, maker)
MOTORS = [("AeroTech_I115W.eng", "Parallel booster staging.ork", 1, ("I115W", 54, 156, "10", "AeroTech"))]

for out, ork, index, (name, dia, length, delays, maker) in MOTORS:
    sim = simulations(read_xml(HERE.parent / ork))[index]
    data = sim.data()
    burn = data[data["thrust_n"] > 0]
    t_end = float(data["time_s"][data.index[data["time_s"] > burn["time_s"].iloc[-1]][0]])
    loaded, spent = float(data["motor_mass_kg"].iloc[0]), float(data["motor_mass_kg"].iloc[-1])
    lines = [f"; {maker} {name} as flown by OpenRocket in '{ork}' ({sim.name}),",
             "; thrust and motor mass from its stored flight data (make_motors_from_ork.py)",
             f"{name} {dia} {length} {delays} {loaded - spent:.4f} {loaded:.4f} {maker}"]
    lines += [f"   {t:.3f} {f:.3f}" for t, f in zip(burn["time_s"], burn["thrust_n"])]
    lines.append(f"   {t_end:.3f} 0.000")
    (HERE / out).write_text("\n".join(lines) + "\n")
