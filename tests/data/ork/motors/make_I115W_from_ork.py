"""Write AeroTech_I115W.eng from the flight OpenRocket stored in 'Parallel booster staging.ork'.

No I115W motor file is among the shared fixtures.  Simulation 2 of that
design flies the I115W alone (no booster motors), so its stored thrust and
motor-mass columns are the motor OpenRocket flew: the thrust samples up to
burnout (thrust 0 at ignition dropped, as RASP files start after 0), the
loaded mass at t = 0 and the burnt-out mass at the end.  Run from the
repository root:  python tests/data/ork/motors/make_I115W_from_ork.py
"""
from pathlib import Path

from ironbark_opt.openrocket.simdata import simulations
from ironbark_opt.openrocket.xmlread import read_xml

HERE = Path(__file__).parent
data = simulations(read_xml(HERE.parent / "Parallel booster staging.ork"))[1].branches["Sustainer"]
burn = data[data["thrust_n"] > 0]
t_end = float(data["time_s"][data.index[data["time_s"] > burn["time_s"].iloc[-1]][0]])
loaded, spent = float(data["motor_mass_kg"].iloc[0]), float(data["motor_mass_kg"].iloc[-1])
lines = ["; AeroTech I115W as flown by OpenRocket 24.12 in 'Parallel booster staging.ork' (simulation 2),",
         "; thrust and motor mass from its stored flight data (make_I115W_from_ork.py)",
         f"I115W 54 156 10 {loaded - spent:.4f} {loaded:.4f} AeroTech"]
lines += [f"   {t:.3f} {f:.3f}" for t, f in zip(burn["time_s"], burn["thrust_n"])]
lines.append(f"   {t_end:.3f} 0.000")
(HERE / "AeroTech_I115W.eng").write_text("\n".join(lines) + "\n")
