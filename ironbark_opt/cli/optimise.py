"""``ironbark ballast ROCKET --target 30000ft``: launch-day ballast and motor choice."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import click

from ironbark_opt.cli.common import (PLOT_SUFFIXES, atmosphere_label, atmosphere_load_kwargs,
                                     atmosphere_options, atmosphere_summary, atomic_write, check_output_path, emit,
                                     handle_errors, json_option, table_option)
from ironbark_opt.optimise.motor_choice import OBJECTIVES
from ironbark_opt.optimise.robust import OBJECTIVES as ROBUST_OBJECTIVES
from ironbark_opt.vehicle import RAIL_EXIT_RULES


def forecast_atmosphere(setup, model: str | None, site: str | None, time: str | None):
    """Replace ``setup``'s atmosphere (and site) by a forecast profile, if asked."""
    if model is None:
        if site is not None or time is not None:
            raise click.UsageError("--site/--time need --forecast rap|gfs")
        return setup
    if time is None:
        raise click.UsageError("--forecast needs --time ISO (UTC launch time)")
    from ironbark_opt.atmosphere.forecast import setup_with_forecast

    if site is None:
        raise click.UsageError("--forecast needs --site NAME (see 'ironbark weather sites')")
    return setup_with_forecast(setup, model, time, site)[0]


@click.command("ballast")
@click.argument("rocket", type=click.Path(dir_okay=False))
@click.option("--target", required=True, help="Target apogee, e.g. 30000ft, 3000m, '10000ft ASL'.")
@click.option("--motor", "motors", multiple=True,
              help="Candidate motor: file, folder of files, or ThrustCurve.org name (repeatable).")
@click.option("--objective", type=click.Choice(OBJECTIVES + ROBUST_OBJECTIVES),
              help="How to rank feasible motors (default least_ballast), or with --robust what to "
                   "optimise: in_band (default, P(|apogee - target| <= band)) or expected_abs_miss.")
@click.option("--robust", is_flag=True,
              help="Choose the ballast that scores best under the --spec dispersions (sample-average "
                   "approximation, IPOPT) and check it against the nominal ballast on fresh samples.")
@click.option("--spec", "spec_path", type=click.Path(dir_okay=False), help="Dispersion spec for --robust.")
@click.option("--band", type=float, default=50.0, show_default=True,
              help="--robust: half-width of the scoring band around the target [m].")
@click.option("--samples", type=int, default=40, show_default=True,
              help="--robust: samples of the sample-average approximation (one fixed set).")
@click.option("--check-samples", type=int, default=1000, show_default=True,
              help="--robust: fresh samples checking both ballasts (another seed; 0: none).")
@click.option("--seed", type=int, help="--robust: seed of the samples (default: the spec's; the check uses seed+1).")
@click.option("--select-samples", type=int, default=200, show_default=True,
              help="--robust: fresh samples on which the SAA optimum must beat the nominal ballast to replace "
                   "it (another seed; 0: no validation).")
@click.option("--min-gain-t", type=float,
              help="--robust: keep the nominal ballast unless the SAA optimum's in-sample improvement has a "
                   "paired t statistic of at least this (its own sampling error; default: take the optimum).")
@atmosphere_options
@click.option("--min-rail-speed", type=float, help="Minimum rail-exit speed [m/s].")
@click.option("--min-margin", type=float, help="Minimum static margin at rail exit [calibers].")
@click.option("--max-ballast", type=float, help="Most ballast the bay holds [kg].")
@click.option("--ballast-x", type=float, help="Ballast position, aft of the nose tip [m].")
@click.option("--free-position", is_flag=True, help="Optimise the position within the ballast bay too.")
@click.option("--rail-exit", type=click.Choice(RAIL_EXIT_RULES), default="forward_button", show_default=True)
@click.option("--solve", "solve_for", type=click.Choice(["ballast", "airbrake_level", "airbrake_start_time"]),
              default="ballast", show_default=True,
              help="What to solve for: ballast mass, or the air brakes' deployment level [-] or start "
                   "time [s] (rocket files with [airbrakes]).")
@table_option
@click.option("--calibration", "calibration_path", type=click.Path(dir_okay=False),
              help="Apply a calibration file (from 'ironbark calibrate --output').")
@click.option("--processes", type=int, help="Worker processes for several motors.")
@click.option("--executor", metavar="local|local:N|dask://HOST:PORT",
              help="Where several motors are solved (replaces --processes): this process, N local "
                   "processes, or a Dask scheduler.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False, writable=True),
              help="Write the flight at the optimum (PNG/PDF/SVG).")
@click.option("--card", "card_path", type=click.Path(dir_okay=False, writable=True),
              help="Write the flight card at the optimum: one page (PDF/PNG/SVG) for the range safety "
                   "officer and the ballast bay.")
@click.option("--card-spec", "card_spec", type=click.Path(dir_okay=False),
              help="Dispersion spec (as for 'montecarlo --spec') for the card's 5-95 % apogee band and "
                   "landing ellipse: a Monte Carlo at the optimum.")
@click.option("--card-samples", type=click.IntRange(min=2, max=100_000), default=500, show_default=True,
              help="Monte Carlo flights behind the card's band.")
@click.option("--allow-unstable", is_flag=True,
              help="Accept a rocket whose static margin falls below zero (at launch or on the solved ascent).")
@json_option
@handle_errors
def ballast_command(rocket, target, motors, objective, robust, spec_path, band, samples, check_samples, seed,
                    select_samples, min_gain_t,
                    atmosphere, atmosphere_time, forecast, site, time,
                    min_rail_speed, min_margin, max_ballast, ballast_x, free_position, rail_exit, solve_for,
                    table, calibration_path, processes, executor, plot_path, card_path, card_spec, card_samples,
                    allow_unstable, as_json):
    """Ballast (and motor), or the air-brake deployment, that put ROCKET's apogee on --target."""
    from ironbark_opt.optimise.ballast import solve_ballast
    from ironbark_opt.optimise.motor_choice import choose_motor
    from ironbark_opt.errors import InputError
    from ironbark_opt.optimise.target import parse_target
    from ironbark_opt.plausibility import check_ascent_stability, check_flight_inputs, option_overrides
    from ironbark_opt.validate import number
    from ironbark_opt.vehicle import load_setup

    check_output_path(plot_path, "--plot", PLOT_SUFFIXES)
    from ironbark_opt.report.card import CARD_SUFFIXES
    check_output_path(card_path, "--card", CARD_SUFFIXES)
    if card_spec is not None and card_path is None:
        raise click.UsageError("--card-spec needs --card FILE")
    objective = _check_robust_options(robust, objective, spec_path, motors, solve_for, card_spec)
    if processes is not None and processes < 1:
        raise InputError(f"must be >= 1, got {processes}", field="--processes")
    for value, option in ((min_margin, "--min-margin"), (min_rail_speed, "--min-rail-speed")):
        if value is not None:
            try:
                number(value, option)
            except InputError as err:
                raise InputError(err.message, field=option) from None
    if min_rail_speed is not None and min_rail_speed < 0:
        raise InputError(f"must be >= 0 m/s, got {min_rail_speed}", field="--min-rail-speed")
    for item in motors:
        looks_like_path = any(ch in item for ch in "/\\") or item.lower().endswith((".eng", ".rse", ".csv"))
        if looks_like_path and not Path(item).exists():
            raise InputError("motor file not found (a path, so not looked up on ThrustCurve.org)",
                             source=item, field="--motor")
    parse_target(target)
    weather = atmosphere_load_kwargs(atmosphere, atmosphere_time, forecast, site, time)
    setup = forecast_atmosphere(load_setup(rocket, rail_exit=rail_exit, table=table, **weather),
                                forecast, site, time)
    flown, flown_line = atmosphere_summary(setup)
    if calibration_path is not None:
        from ironbark_opt.telemetry.calibration_file import apply_calibration
        setup = apply_calibration(setup, calibration_path)
    opts = option_overrides(setup, ballast_x_m=ballast_x, max_ballast=max_ballast, body_length=setup.body_length)
    check_flight_inputs(setup, {**setup.nominal, **opts["parameters"]}, allow_unstable=allow_unstable)
    if card_spec is not None:
        from ironbark_opt.analysis.distributions import load_spec
        card_spec = load_spec(card_spec)                 # a bad spec fails before the solve
    card = dict(path=card_path, spec=card_spec, samples=card_samples, time=time or atmosphere_time, site=site)
    if solve_for != "ballast":
        if motors or free_position or max_ballast is not None or ballast_x is not None:
            raise click.UsageError(f"--solve {solve_for} takes no ballast or motor options")
        from ironbark_opt.optimise.airbrakes import solve_airbrakes
        solution = solve_airbrakes(setup, target, variable=solve_for)
        check_ascent_stability(setup, allow_unstable=allow_unstable, summary=solution.values)
        _report(setup, solution, plot_path, card, flown, flown_line, as_json)
        return
    kwargs = dict(mass_max=max_ballast, ballast_x=ballast_x, free_position=free_position,
                  min_rail_speed=min_rail_speed, min_margin=min_margin)
    if executor is not None and not motors:
        raise click.UsageError("--executor spreads several --motor candidates; a single ballast solve runs here")
    if motors:
        if forecast is not None:
            processes = 1          # the forecast profile lives in this process only (an executor ships it)
        ranking = choose_motor(setup, motors, target, objective=objective, processes=processes,
                               load_kwargs={"rail_exit": rail_exit, "table": table, **weather},
                               executor=executor,
                               **kwargs)
        best = ranking.best or (ranking.solutions[0] if ranking.solutions else None)
        if best is not None:
            check_ascent_stability(setup, allow_unstable=allow_unstable, summary=best.values)
        result = ranking.to_dict()
        if best is not None:
            result.update({k: v for k, v in best.to_dict().items() if k not in ("parameters",)})
            result["motor"] = best.motor
        result["feasible"] = ranking.best is not None
        for label, message in ranking.failures:
            click.echo(f"warning: motor {label}: {message}", err=True)
        if best is not None and (plot_path or card_path):
            from ironbark_opt.optimise.motor_choice import expand_candidates
            for cand in expand_candidates(motors):
                motor = cand.load()
                if motor.designation == best.motor:
                    best_setup = dataclasses.replace(setup, motor=motor)
                    _plot(best_setup, best, plot_path)
                    _card(best_setup, best, result, **card)
                    break
        result["atmosphere"] = flown
        if ranking.solutions or as_json:     # nothing solved: the failures are on stderr (and in JSON)
            emit(result, as_json, ranking.summary() + "\n" + flown_line)
        if not ranking.solutions:
            from ironbark_opt.errors import SolverError
            label, message = ranking.failures[0] if ranking.failures else ("?", "")
            raise SolverError(f"no candidate motor could be solved ({len(ranking.failures)} failed, "
                              f"listed above); first: {label}: {message[:160]}")
        return
    if robust:
        from ironbark_opt.optimise.robust import solve_robust_ballast
        from ironbark_opt.analysis.distributions import load_spec
        spec = load_spec(spec_path)
        solution = solve_robust_ballast(setup, target, spec, objective=objective, band=band, samples=samples,
                                        seed=seed, check_samples=check_samples, select_samples=select_samples,
                                        min_gain_t=None if min_gain_t is None else
                                        number(min_gain_t, "--min-gain-t"),
                                        **kwargs)
        check_ascent_stability(setup, {"ballast_mass": solution.values["ballast_kg"],
                                       "ballast_x": solution.values["ballast_x_m"]},
                               allow_unstable=allow_unstable)
        # the card's Monte Carlo is the solver's check (same spec, samples and seed): its P(in band) is the JSON's
        card.update(spec=spec, samples=check_samples or card_samples, seed=solution.check_seed, band=band)
        _report(setup, solution, plot_path, card, flown, flown_line, as_json)
        return
    solution = solve_ballast(setup, target, **kwargs)
    check_ascent_stability(setup, allow_unstable=allow_unstable, summary=solution.values)
    _report(setup, solution, plot_path, card, flown, flown_line, as_json)


def _report(setup, solution, plot_path, card, flown, flown_line, as_json):
    """Plot, flight card (``card``: the ``_card`` options, or None) and the printed or
    JSON result of one solution."""
    _plot(setup, solution, plot_path)
    result = solution.to_dict()
    if card is not None:
        _card(setup, solution, result, **card)
    result["atmosphere"] = flown
    emit(result, as_json, solution.summary() + "\n" + flown_line)


def _at_optimum(solution) -> dict:
    """The parameters [SI] a solution flies (ballast, or the air brakes' setting)."""
    if hasattr(solution, "variable"):                 # an AirbrakeSolution
        return dict(solution.parameters)
    return {"ballast_mass": solution.values["ballast_kg"], "ballast_x": solution.values["ballast_x_m"]}


def _check_robust_options(robust, objective, spec_path, motors, solve_for, card_spec):
    """The objective to use; usage errors for option combinations --robust does not take."""
    if not robust:
        if objective in ROBUST_OBJECTIVES or spec_path is not None:
            raise click.UsageError(f"--objective {objective or ''} / --spec belong to --robust".replace("  ", " "))
        return objective or "least_ballast"
    if spec_path is None:
        raise click.UsageError("--robust needs --spec dispersions.toml")
    if motors or solve_for != "ballast":
        raise click.UsageError("--robust solves the ballast of one motor (no --motor, no --solve)")
    if card_spec is not None:
        raise click.UsageError("--robust: the card's Monte Carlo is the solver's check (--spec, --check-samples, "
                               "seed + 1); no --card-spec")
    if objective is not None and objective not in ROBUST_OBJECTIVES:
        raise click.UsageError(f"--robust optimises {' or '.join(ROBUST_OBJECTIVES)}, not {objective}")
    return objective or "in_band"


def _plot(setup, solution, path):
    """Overview figure of the flight at the optimum."""
    if not path or solution is None:
        return
    import matplotlib
    matplotlib.use("Agg")
    from ironbark_opt.flight import simulate
    from ironbark_opt.plots import plot_flight
    flight = simulate(setup, parameters=_at_optimum(solution))
    atomic_write(path, lambda tmp: plot_flight(flight, filename=tmp, atmosphere=atmosphere_label(setup)))


def _card(setup, solution, result, *, path, spec, samples, time=None, site=None, seed=None, band=None):
    """Fly the optimum to landing (and ``spec``'s Monte Carlo around it: ``samples`` flights,
    ``seed`` (default the spec's), P(in ``band``)), write the flight card to ``path`` and add
    its numbers to ``result["flight_card"]``."""
    if not path or solution is None:
        return
    import matplotlib
    matplotlib.use("Agg")
    from ironbark_opt.flight import simulate
    from ironbark_opt.report.card import apogee_per_100g, build_card, write_flight_card
    at = _at_optimum(solution)
    flight = simulate(setup, parameters=at, descent=True)
    disp = None
    if spec is not None:
        from ironbark_opt.analysis.montecarlo import montecarlo
        disp = montecarlo(setup, spec, samples, seed=seed, descent=True, target=solution.values["target_agl_m"],
                          band=band, parameters=at, progress=False)
    card = build_card(setup, flight, solution=solution, dispersion=disp,
                      apogee_per_100g_m=apogee_per_100g(setup, at), launch_time=time, site_name=site)
    atomic_write(path, lambda tmp: write_flight_card(tmp, card))
    result["flight_card"] = card.to_dict()


COMMANDS = [ballast_command]
