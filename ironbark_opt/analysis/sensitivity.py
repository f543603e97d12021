"""Exact sensitivities: ``sensitivities(setup) -> Sensitivities``.

Derivatives of apogee, apogee time, maximum speed and rail-exit speed with
respect to every named parameter (:mod:`ironbark_opt.params`), by CasADi
algorithmic differentiation of the apogee ``simulate`` reports: the same
phased trajectory on the same steps, apogee inside its coast step
(:func:`ironbark_opt.dynamics.flown_apogee.flown_apogee_function`).  The
event times (rail exit, apogee) are roots, so AD through the ``rootfinder``
gives the implicit-function derivatives (Griewank & Walther, *Evaluating
Derivatives*, 2nd ed., SIAM 2008, ch. 15).  Staged rockets and a flight whose
charge fires before apogee use the ballast NLP's formulation instead
(:func:`ironbark_opt.dynamics.model.apogee_functions`, coast grid ending at
apogee; centimetres from ``simulate``).

With a ``target``, the ballast that hits it is solved first, as ``ballast``
solves it (:func:`ironbark_opt.optimise.ballast.solve_ballast`), and the
sensitivities are taken at that optimum, together with the parametric
sensitivity of the optimal ballast itself, on the apogee that solve put on
the target: ``run``'s for the one-variable root, as ``ballast`` solves it;
with flight constraints, a free position, a staged rocket or an ejection
before apogee the NLP solves it and its formulation is differentiated.  At the optimum the apogee constraint
``z(m*, p) = target`` holds, so by the implicit-function theorem (Fiacco,
*Introduction to Sensitivity and Stability Analysis in Nonlinear
Programming*, Academic Press 1983, ch. 3, the basic sensitivity theorem,
for an optimum fixed by the equality constraint with no active bound)::

    dm*/dp = -(dz/dp) / (dz/dm)

Numeric-only (results are numbers; the symbolic work is inside).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.errors import InputError

#: (key [unit-suffixed], label, unit) of each differentiated output, in the
#: order of ``apogee_functions(...)["apogee"]``.
OUTPUTS = (("apogee_agl_m", "apogee", "m"), ("apogee_time_s", "apogee time", "s"),
           ("rail_exit_speed_mps", "rail exit speed", "m/s"), ("max_speed_mps", "max speed", "m/s"))

#: Natural step per parameter: (size [SI], or for factors (unit "-") the
#: fraction of the nominal value; label).
STEPS = {
    "ballast_mass": (1.0, "+1 kg ballast"),
    "ballast_x": (0.01, "+1 cm ballast aft"),
    "dry_mass_offset": (1.0, "+1 kg dry mass"),
    "dry_cg_offset": (0.01, "+1 cm dry CG aft"),
    "dry_inertia_scale": (0.10, "+10 % dry inertia"),
    "thrust_scale": (0.01, "+1 % thrust"),
    "burn_time_scale": (0.01, "+1 % burn time"),
    "drag_scale": (0.10, "+10 % drag"),
    "normal_force_scale": (0.10, "+10 % normal force"),
    "wind_scale": (0.10, "+10 % profile wind"),
    "wind_east": (1.0, "+1 m/s wind toward east"),
    "wind_north": (1.0, "+1 m/s wind toward north"),
    "rail_length": (0.1, "+10 cm rail"),
    "inclination": (math.radians(1.0), "+1 deg launch angle"),
    "heading": (math.radians(1.0), "+1 deg heading"),
    "temperature_offset": (1.0, "+1 K air temperature"),
    "airbrake_level": (0.1, "+10 % air-brake deployment"),
    "airbrake_start_time": (1.0, "+1 s later air brakes"),
}


def natural_step(name: str, value: float) -> tuple[float, str]:
    """(step [SI], label) of parameter ``name`` at ``value`` [SI]; numeric-only.

    Dimensionless factors step by a fraction of their value (``+10 % drag``
    is 0.1 x the nominal drag factor; 0.1 absolute if the value is 0).
    """
    params.index(name)
    size, label = STEPS.get(name, (1.0, f"+1 {params.INFO[name].unit} {name}"))
    if params.INFO[name].unit == "-" and value != 0:
        size = size * abs(value)
    return size, label


def apogee_function(model, p_nominal, *, flown: bool = True) -> ca.Function:
    """``p -> (y_0, ..., y_3)``, the four :data:`OUTPUTS` as the MX Function that is
    differentiated: with ``flown``, the apogee of ``FlightModel.run``
    (:func:`~ironbark_opt.dynamics.flown_apogee.flown_apogee_function`) where it
    applies, else (and with ``flown=False``) the ballast NLP's
    (:func:`~ironbark_opt.dynamics.model.apogee_functions`)."""
    from ironbark_opt.dynamics.flown_apogee import flown_apogee_function
    from ironbark_opt.dynamics.model import apogee_functions

    p_nominal = np.asarray(p_nominal, dtype=float)
    fn = flown_apogee_function(model, p_nominal) if flown else None
    return fn if fn is not None else apogee_functions(model, p_nominal)["apogee"]


def jacobian_function(model, p_nominal, *, flown: bool = True) -> ca.Function:
    """CasADi Function ``p -> (y, dy/dp)`` of the four :data:`OUTPUTS`.

    Builds a symbolic (MX) Function; call it with a numeric ``p`` (or embed
    it in a larger CasADi graph).

    Parameters
    ----------
    model : FlightModel
    p_nominal : array [mixed SI]
        The point the event rootfinders start from.
    flown : bool
        Differentiate ``simulate``'s apogee (see :func:`apogee_function`).
    """
    fn = apogee_function(model, p_nominal, flown=flown)
    p = ca.MX.sym("p", params.SIZE)
    y = ca.vertcat(*fn(p))
    return ca.Function("apogee_jacobian", [p], [y, ca.jacobian(y, p)], ["p"], ["y", "dy_dp"])


@dataclass(frozen=True)
class Sensitivities:
    """Result of :func:`sensitivities` (immutable).

    Attributes
    ----------
    name : str
        Rocket name.
    names : tuple of str
        Parameters reported (registry names).
    point : mapping name -> float
        The full parameter vector the derivatives are taken at [SI].
    values : mapping output key -> float
        The outputs at ``point`` (``apogee_agl_m``, ...), from the
        differentiated apogee Function: ``simulate``'s values (staged rockets,
        an ejection before apogee and a ballast from the NLP: the NLP's
        formulation, centimetres from ``simulate``).
    jacobian : array (len(OUTPUTS), len(names))
        d output / d parameter [output unit per parameter SI unit].
    ballast : mapping name -> float or None, or None
        dm*/dp [kg per parameter SI unit] when a target was given and the
        optimum is interior; None for ``ballast_mass`` itself.
    target_agl : float or None [m]
    note : str
        How the point was chosen (and why ballast sensitivities are missing).
    """

    name: str
    names: tuple
    point: Mapping[str, float]
    values: Mapping[str, float]
    jacobian: np.ndarray = field(repr=False)
    ballast: Mapping[str, float | None] | None = None
    target_agl: float | None = None
    note: str = ""

    def __post_init__(self):
        self.jacobian.setflags(write=False)

    def __repr__(self) -> str:
        return (f"Sensitivities({self.name!r}: {len(self.names)} parameters at apogee "
                f"{self.values['apogee_agl_m']:.1f} m AGL; d apogee / d ballast_mass = "
                f"{self.derivative('apogee_agl_m', 'ballast_mass'):.2f} m/kg)"
                if "ballast_mass" in self.names else
                f"Sensitivities({self.name!r}: {len(self.names)} parameters at apogee "
                f"{self.values['apogee_agl_m']:.1f} m AGL)")

    def derivative(self, output: str, name: str) -> float:
        """d ``output`` / d ``name`` [output unit per parameter SI unit]."""
        keys = [o[0] for o in OUTPUTS]
        if output not in keys:
            raise InputError(f"unknown output {output!r}; expected one of {', '.join(keys)}", field="output")
        if name not in self.names:
            raise InputError(f"parameter {name!r} was not differentiated (have: {', '.join(self.names)})",
                             field=name)
        return float(self.jacobian[keys.index(output), self.names.index(name)])

    def step(self, name: str) -> tuple[float, str]:
        """Natural step (size [SI], label) of ``name`` at this point."""
        return natural_step(name, self.point[name])

    def change(self, output: str, name: str) -> float:
        """Linearised change of ``output`` for the natural step of ``name`` [output unit]."""
        return self.derivative(output, name) * self.step(name)[0]

    def ballast_change(self, name: str) -> float | None:
        """Change of the optimal ballast [kg] for the natural step of ``name`` (None if unavailable)."""
        if self.ballast is None or self.ballast.get(name) is None:
            return None
        return self.ballast[name] * self.step(name)[0]

    def to_dict(self) -> dict:
        """Unit-suffixed values; per parameter its step, change per step and derivative."""
        out = {"rocket": self.name, **dict(self.values), "note": self.note}
        if self.target_agl is not None:
            out["target_agl_m"] = self.target_agl
            out["ballast_kg"] = self.point["ballast_mass"]
        table = {}
        for name in self.names:
            size, label = self.step(name)
            entry = {"unit": params.INFO[name].unit, "value": self.point[name], "step": size, "step_label": label,
                     "change_per_step": {k: self.change(k, name) for k, _, _ in OUTPUTS},
                     "derivative": {k: self.derivative(k, name) for k, _, _ in OUTPUTS}}
            if self.ballast is not None:
                entry["change_per_step"]["ballast_kg"] = self.ballast_change(name)
                entry["derivative"]["ballast_kg"] = self.ballast.get(name)
            table[name] = entry
        out["parameters"] = table
        return out

    def to_dataframe(self):
        """One row per parameter: value, step, derivatives (``d_<output>``,
        per SI unit of the parameter) and changes per step (``<output>``)."""
        import pandas as pd   # imported here: 0.4-1 s that the command line does not need

        rows = []
        for name in self.names:
            size, label = self.step(name)
            row = {"parameter": name, "unit": params.INFO[name].unit, "value": self.point[name],
                   "step": size, "step_label": label}
            for k, _, _ in OUTPUTS:
                row[f"d_{k}"] = self.derivative(k, name)
            if self.ballast is not None:
                row["d_ballast_kg"] = np.nan if self.ballast.get(name) is None else self.ballast[name]
            for k, _, _ in OUTPUTS:
                row[k] = self.change(k, name)
            if self.ballast is not None:
                change = self.ballast_change(name)
                row["ballast_kg"] = np.nan if change is None else change
            rows.append(row)
        return pd.DataFrame(rows)

    def summary(self) -> str:
        """The readable table: change of each output per natural step (a string)."""
        v = self.values
        lines = [f"Sensitivities of {self.name} at apogee {v['apogee_agl_m']:.1f} m AGL ({v['apogee_time_s']:.2f} s), "
                 f"max speed {v['max_speed_mps']:.1f} m/s, rail exit {v['rail_exit_speed_mps']:.2f} m/s"]
        if self.note:
            lines.append(f"  {self.note}")
        head = f"  {'step':26s} {'apogee [m]':>11s} {'t_apogee [s]':>12s} {'rail exit [m/s]':>15s} " \
               f"{'max speed [m/s]':>15s}"
        if self.ballast is not None:
            head += f" {'ballast* [kg]':>13s}"
        lines += ["  linearised change per step (exact derivatives by CasADi AD):", head]
        order = sorted(self.names, key=lambda n: -abs(self.change("apogee_agl_m", n)))
        for name in order:
            label = self.step(name)[1]
            dz, dt = self.change("apogee_agl_m", name), self.change("apogee_time_s", name)
            dv_rail, dv_max = self.change("rail_exit_speed_mps", name), self.change("max_speed_mps", name)
            row = f"  {label:26s} {dz:+11.2f} {dt:+12.3f} {dv_rail:+15.3f} {dv_max:+15.2f}"
            if self.ballast is not None:
                b = self.ballast_change(name)
                row += f" {'-':>13s}" if b is None else f" {b:+13.4f}"
            lines.append(row)
        if self.ballast is not None:
            lines.append(f"  ballast*: change of the ballast that keeps apogee on {self.target_agl:.1f} m AGL")
        return "\n".join(lines)


def _names(names) -> tuple:
    if names is None:
        return params.NAMES
    if isinstance(names, str):
        names = [names]
    out = []
    for name in names:
        params.index(name)
        if name not in out:
            out.append(name)
    if not out:
        raise InputError("no parameters to differentiate", field="names")
    return tuple(out)


def sensitivities(setup, *, parameters: Mapping[str, float] | None = None, names=None, target=None,
                  model=None, **ballast_options) -> Sensitivities:
    """Exact derivatives of apogee, apogee time, rail-exit and maximum speed (numeric-only).

    Parameters
    ----------
    setup : FlightSetup
    parameters : mapping name -> value, optional
        Overrides of the nominal parameters [SI] (the point of the derivatives).
    names : sequence of str, optional
        Parameters to report (default: all of :data:`ironbark_opt.params.NAMES`).
    target : str or float, optional
        Apogee target (``"3000m"``, ``"10000 ft"``, ...): solve the ballast
        first (as ``solve_ballast`` with ``ballast_options`` does), take the
        derivatives at the optimum and add dm*/dp.
    model : FlightModel, optional
        Reuse an already built (VM) model.
    ballast_options
        Passed to :func:`solve_ballast` (``mass_max``, ``ballast_x``, ...).

    Returns
    -------
    Sensitivities
    """
    from ironbark_opt.flight import flight_model

    names = _names(names)
    if ballast_options and target is None:
        raise InputError(f"{', '.join(ballast_options)} need(s) a target", field=next(iter(ballast_options)))
    model = model or flight_model(setup)
    p0 = setup.nominal_parameters(**dict(parameters or {}))
    note, target_agl, solution, flown = "at the nominal parameters", None, None, True
    if target is not None:
        from ironbark_opt.dynamics.flown_apogee import applies
        from ironbark_opt.optimise.ballast import solve_ballast, solved_by_root

        # the implicit-function ballast derivatives need the apogee the solve put on the
        # target: run's (the one-variable root, as `ballast` solves it) where it is
        # differentiated, else the NLP's (constraints, a free position, staged rockets,
        # an ejection before apogee: apogee_functions' formulation)
        flown = solved_by_root(**ballast_options) and applies(model, model.run(p0))
        solution = solve_ballast(setup, target, parameters=parameters,
                                 **{**ballast_options, "method": "auto" if flown else "ipopt"})
        target_agl = float(solution.values["target_agl_m"])
        p0 = np.array([solution.parameters[n] for n in params.NAMES])
        note = f"at the optimal ballast {solution.ballast:.4f} kg for {target_agl:.1f} m AGL ({solution.status})"
    y, J = (np.array(v) for v in jacobian_function(model, p0, flown=flown)(p0))
    y = y.ravel()
    cols = [params.index(n) for n in names]
    values = {k: float(y[i]) for i, (k, _, _) in enumerate(OUTPUTS)}
    ballast = None
    if solution is not None:
        if solution.feasible and not solution.active:
            dz_dm = J[0, params.index("ballast_mass")]
            ballast = {n: (None if n == "ballast_mass" else float(-J[0, params.index(n)] / dz_dm)) for n in names}
        else:
            note += "; the ballast is at a bound or the target is unreachable, so it does not follow small " \
                    "changes: no ballast sensitivities"
    return Sensitivities(name=setup.name, names=names, point=params.to_dict(p0), values=values,
                         jacobian=np.array(J[:, cols], dtype=float), ballast=ballast, target_agl=target_agl,
                         note=note)
