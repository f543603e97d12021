"""The Calisto example built in the optional peer RocketPy (benchmarks only).

Same inputs as examples/calisto/calisto.toml (../shared/reference/calisto);
the keyword arguments apply our parameter registry's dispersions the way
RocketPy can express them.  Import only when ``rocketpy`` is installed.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

CALISTO = Path(__file__).resolve().parents[1] / "examples" / "calisto"


def build(*, wind_east=0.0, wind_north=0.0, thrust_scale=1.0, burn_time_scale=1.0, dry_mass_offset=0.0,
          dry_inertia_scale=1.0, drag_scale=1.0, dry_cg_offset=0.0, impulse=None, burn_time=3.9):
    """(Environment, Rocket) of Calisto in RocketPy with the given dispersions."""
    from rocketpy import Environment, Function, Rocket, SolidMotor

    env = Environment(latitude=32.990254, longitude=-106.974998, elevation=1400)
    if wind_east or wind_north:
        env.set_atmospheric_model(type="custom_atmosphere", wind_u=float(wind_east), wind_v=float(wind_north))
    reshape = None
    if impulse is not None and (thrust_scale != 1.0 or burn_time_scale != 1.0):
        reshape = (burn_time * burn_time_scale, impulse * thrust_scale)
    motor = SolidMotor(thrust_source=str(CALISTO / "Cesaroni_M1670.eng"), dry_mass=1.815,
                       dry_inertia=(0.125, 0.125, 0.002), nozzle_radius=0.033, grain_number=5,
                       grain_density=1815, grain_outer_radius=0.033, grain_initial_inner_radius=0.015,
                       grain_initial_height=0.120, grain_separation=0.005,
                       grains_center_of_mass_position=0.397, center_of_dry_mass_position=0.317,
                       nozzle_position=0, burn_time=burn_time, throat_radius=0.011, reshape_thrust_curve=reshape,
                       coordinate_system_orientation="nozzle_to_combustion_chamber")
    drag_off = np.loadtxt(CALISTO / "powerOffDragCurve.csv", delimiter=",")
    drag_on = np.loadtxt(CALISTO / "powerOnDragCurve.csv", delimiter=",")
    rocket = Rocket(radius=0.0635, mass=14.426 + dry_mass_offset,
                    inertia=(6.321 * dry_inertia_scale, 6.321 * dry_inertia_scale, 0.034 * dry_inertia_scale),
                    power_off_drag=Function(np.column_stack([drag_off[:, 0], drag_scale * drag_off[:, 1]])),
                    power_on_drag=Function(np.column_stack([drag_on[:, 0], drag_scale * drag_on[:, 1]])),
                    center_of_mass_without_motor=-dry_cg_offset,      # tail_to_nose axis
                    coordinate_system_orientation="tail_to_nose")
    rocket.add_motor(motor, position=-1.255)
    rocket.set_rail_buttons(upper_button_position=0.0818, lower_button_position=-0.6182)
    rocket.add_nose(length=0.55829, kind="vonKarman", position=1.278)
    rocket.add_trapezoidal_fins(n=4, root_chord=0.120, tip_chord=0.060, span=0.110, position=-1.04956, cant_angle=0.5)
    rocket.add_tail(top_radius=0.0635, bottom_radius=0.0435, length=0.060, position=-1.194656)
    return env, rocket


def fly(env, rocket, inclination_deg=84.0, heading_deg=133.0):
    """RocketPy Flight to apogee; returns the Flight."""
    from rocketpy import Flight
    return Flight(rocket=rocket, environment=env, rail_length=5.2, inclination=inclination_deg,
                  heading=heading_deg, terminate_on_apogee=True)
