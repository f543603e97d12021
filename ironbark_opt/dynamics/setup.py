"""What the equations of motion need to know about one vehicle and site.

A :class:`FlightSetup` is a plain container assembled from a rocket file (or
built by hand in tests); it never simulates.  Everything a user may vary
during a study is *not* here but in the parameter vector ``p``
(:mod:`ironbark_opt.params`); the setup only provides the nominal values of
those parameters through :attr:`FlightSetup.nominal`.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from ironbark_opt import params


@dataclass(frozen=True)
class DryMass:
    """Mass properties of the rocket without motor and ballast.

    Parameters
    ----------
    mass : float [kg]
    cg_x : float [m]
        CG aft of the nose tip.
    inertia : (3, 3) array [kg m^2]
        Inertia tensor about the CG in body axes (x along the rocket axis).
    """

    mass: float
    cg_x: float
    inertia: np.ndarray

    @classmethod
    def from_properties(cls, props: Any) -> "DryMass":
        """From any object with ``mass``, ``cg_x`` and ``inertia`` (3x3)."""
        return cls(float(props.mass), float(props.cg_x), np.asarray(props.inertia, dtype=float).reshape(3, 3))


@dataclass(frozen=True)
class Parachute:
    """A recovery device for the descent phase.

    Parameters
    ----------
    name : str
    cd_area : float [m^2]
        Drag coefficient times reference area.
    deploy_altitude : float or None [m]
        Deploy height above ground during descent; None = at apogee.
    lag : float [s]
        Delay between trigger and full inflation.
    at_ejection : bool
        Opens at the motor's ejection charge (``FlightSetup.ejection_delay``
        after burnout), before or after apogee, instead of at apogee.
    """

    name: str
    cd_area: float
    deploy_altitude: float | None = None
    lag: float = 0.0
    at_ejection: bool = False


@dataclass(frozen=True)
class FlightSetup:
    """Vehicle, motor, aerodynamics, atmosphere and launch site.

    Parameters
    ----------
    motor : Motor
        Any object implementing the ``Motor`` interface (thrust, mass, CG,
        inertia vs time; ``burn_time``).
    nozzle_x : float [m]
        Nozzle exit, aft of the nose tip.
    dry : DryMass
        Rocket without motor and ballast.
    aero : AeroModel
        Assembled aerodynamic model (:mod:`ironbark_opt.aero.model`).
    atmosphere : Atmosphere
        Atmosphere with wind (:mod:`ironbark_opt.atmosphere`).
    site_elevation : float [m]
        Ground level above sea level at the rail.
    latitude : float or None [rad]
        For normal gravity; None uses standard gravity at sea level.
    longitude : float or None [rad]
        East positive; only places the flight on a map (KML, flight card).
    rail_exit_offset : float [m]
        The rocket leaves the rail after travelling ``rail_length -
        rail_exit_offset``; e.g. the distance from the nozzle exit to the
        forward rail button (RocketPy's rule) or 0 (OpenRocket's rule).
    nominal : mapping name -> value
        Nominal values of the parameters in :mod:`ironbark_opt.params`
        (rail length, inclination, heading, ballast position, ...).
    parachutes : tuple of Parachute
    name : str
    gravity : callable h -> g, optional
        Override of the gravity model (e.g. a constant for analytic tests);
        default: WGS-84 normal gravity at ``latitude`` with height.
    ballast_mass_max : float or None [kg]
        Most ballast the bay holds (None: not stated).
    ballast_x_range : (float, float) or None [m]
        Ballast bay, aft of the nose tip (None: not stated).
    source : str or None
        The file the setup was read from.
    airbrakes : BrakeSchedule or None
        Deployable drag device (:mod:`ironbark_opt.aero.airbrakes`), acting
        in the coast.
    body_length : float or None [m]
        Nose tip to the aft end of the body (for plausibility checks).
    ejection_delay : float or None [s]
        The motor's ejection charge fires this long after burnout; parachutes
        with ``at_ejection`` open then (:mod:`ironbark_opt.dynamics.ejection`).
    """

    motor: Any
    nozzle_x: float
    dry: DryMass
    aero: Any
    atmosphere: Any
    site_elevation: float = 0.0
    latitude: float | None = None
    longitude: float | None = None
    rail_exit_offset: float = 0.0
    nominal: Mapping[str, float] = field(default_factory=dict)
    parachutes: tuple = ()
    name: str = "rocket"
    gravity: Any = None
    ballast_mass_max: float | None = None
    ballast_x_range: tuple | None = None
    source: str | None = None
    airbrakes: Any = None
    body_length: float | None = None
    ejection_delay: float | None = None

    def nominal_parameters(self, **overrides) -> np.ndarray:
        """Parameter vector with the case's nominal values and ``overrides``."""
        values = dict(self.nominal)
        values.update(overrides)
        return params.nominal_values(values)
