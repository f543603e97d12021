"""Motor choice: solve the ballast problem for every candidate motor and rank them.

Every tabulated solid motor flies in a *motor slot*
(:mod:`ironbark_opt.motors.slot`, :mod:`ironbark_opt.dynamics.slot_model`):
its thrust curve, mass model and RK4 grid are numbers in the parameter
vector, so one flight model and one ballast NLP (compiled once per rocket,
cached on disk) serve every candidate, each on the grid its own model would
choose — the same ballast as a solve on the motor's own model.  Other motors
(grain geometry, composite air-start motors) and explicit ``processes`` /
``executor`` requests take one model per motor.

Why enumeration and not a mixed-integer NLP (CasADi's ``bonmin``): a team
chooses among a handful to a few dozen motors, the candidates are
independent, and every candidate gets its own exact, verified answer —
including the infeasible ones, with the reason.  A relaxed formulation would have to blend
thrust curves (a blend of two motors is no motor), and branch-and-bound on
one binary per motor does strictly more work than solving each candidate
once.  Enumeration is exact and simpler; ``bonmin`` pays off only when the
discrete choice interacts with many continuous variables, which a launch-day
decision does not have.
"""
from __future__ import annotations

import dataclasses
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, Sequence


from ironbark_opt.errors import InputError, IronbarkError
from ironbark_opt.optimise.ballast import BallastSolution, solve_ballast

OBJECTIVES = ("least_ballast", "largest_margin", "closest_apogee")
MOTOR_SUFFIXES = (".eng", ".rse", ".csv")


@dataclass(frozen=True)
class Candidate:
    """One motor to try: a file (and a designation inside it) or a ThrustCurve name."""

    label: str
    path: str | None = None
    designation: str | None = None

    def load(self):
        """The Motor (numeric-only; may use the network for ThrustCurve names)."""
        from ironbark_opt.motors import load_motor
        if self.path is not None:
            return load_motor(self.path, self.designation)
        try:
            from ironbark_opt.motors import thrustcurve
        except ImportError:
            raise InputError(f"motor {self.label!r}: not a file, and the ThrustCurve.org client is not "
                             "available", field="motor") from None
        return thrustcurve.load_motor(self.label)


def expand_candidates(items: Sequence) -> list[Candidate]:
    """Files, folders (all motor files in them) and names -> candidates.

    A multi-motor ``.eng`` gives one candidate per motor.
    """
    from ironbark_opt.motors import read_eng, read_rse
    out: list[Candidate] = []
    for item in items:
        if isinstance(item, Candidate):
            out.append(item)
            continue
        path = Path(str(item))
        if path.is_dir():
            files = sorted(f for f in path.iterdir() if f.suffix.lower() in MOTOR_SUFFIXES)
            if not files:
                raise InputError("no motor files (.eng, .rse, .csv) in this folder", source=path)
            out.extend(expand_candidates([str(f) for f in files]))
        elif path.exists():
            if path.suffix.lower() in (".eng", ".rse"):
                motors = read_eng(path) if path.suffix.lower() == ".eng" else read_rse(path)
                if len(motors) == 1:
                    out.append(Candidate(motors[0].designation or path.stem, str(path), None))
                else:
                    out.extend(Candidate(m.designation, str(path), m.designation) for m in motors)
            else:
                out.append(Candidate(path.stem, str(path), None))
        else:
            out.append(Candidate(str(item)))
    if not out:
        raise InputError("no candidate motors given", field="motor")
    return out


@dataclass(frozen=True)
class MotorRanking:
    """Result of :func:`choose_motor`: solutions ranked best first."""

    target: str
    objective: str
    solutions: tuple            # of BallastSolution, ranked
    failures: tuple             # of (label, message)

    def __repr__(self) -> str:
        best = self.best
        return (f"MotorRanking({len(self.solutions)} motors, objective {self.objective}, best "
                f"{best.motor if best else 'none'})")

    @property
    def best(self) -> BallastSolution | None:
        """Best feasible solution (None when no candidate can hit the target)."""
        return self.solutions[0] if self.solutions and self.solutions[0].feasible else None

    def to_dataframe(self):
        import pandas as pd   # imported here: 0.4-1 s that the command line does not need

        rows = []
        for rank, sol in enumerate(self.solutions, 1):
            v = sol.values
            rows.append({"rank": rank, "motor": sol.motor, "feasible": sol.feasible, "ballast_kg": v["ballast_kg"],
                         "apogee_agl_m": v["apogee_agl_m"], "zero_ballast_apogee_agl_m": v["zero_ballast_apogee_agl_m"],
                         "rail_exit_speed_mps": v["rail_exit_speed_mps"],
                         "static_margin_rail_exit_cal": v["static_margin_rail_exit_cal"],
                         "status": sol.status})
        return pd.DataFrame(rows)

    def to_dict(self) -> dict:
        best = self.best
        return {"target": self.target, "objective": self.objective,
                "motor": best.motor if best else None,
                "ballast_kg": best.values["ballast_kg"] if best else None,
                "apogee_agl_m": best.values["apogee_agl_m"] if best else None,
                "apogee_time_s": best.values["apogee_time_s"] if best else None,
                "candidates": [s.to_dict() for s in self.solutions],
                "failures": [{"motor": label, "error": msg} for label, msg in self.failures]}

    def summary(self) -> str:
        lines = [f"Motor choice for target {self.target} (objective: {self.objective})",
                 f"  {'rank':>4}  {'motor':<22} {'feasible':<8} {'ballast kg':>10} {'apogee m':>9} "
                 f"{'0-ballast m':>11} {'rail m/s':>8} {'margin cal':>10}"]
        for rank, sol in enumerate(self.solutions, 1):
            v = sol.values
            lines.append(f"  {rank:>4}  {sol.motor[:22]:<22} {'yes' if sol.feasible else 'no':<8} "
                         f"{v['ballast_kg']:10.3f} {v['apogee_agl_m']:9.1f} {v['zero_ballast_apogee_agl_m']:11.1f} "
                         f"{v['rail_exit_speed_mps']:8.2f} {v['static_margin_rail_exit_cal']:10.2f}")
        for label, msg in self.failures:
            lines.append(f"  failed  {label}: {msg}")
        if self.best is None:
            lines.append("  no candidate reaches the target within the ballast and flight constraints")
        return "\n".join(lines)


def _rank_key(objective: str, target_agl: float):
    def key(sol: BallastSolution):
        v = sol.values
        if objective == "least_ballast":
            score = v["ballast_kg"]
        elif objective == "largest_margin":
            score = -v["static_margin_rail_exit_cal"]
        else:
            score = abs(v["zero_ballast_apogee_agl_m"] - target_agl)
        return (not sol.feasible, abs(v["apogee_agl_m"] - target_agl) if not sol.feasible else score)
    return key


#: fewest candidates for which one slotted model beats one model per motor
SLOT_MIN_CANDIDATES = 2


def _round_up(n: int, quantum: int) -> int:
    return quantum * int(math.ceil(n / quantum))


def _solve_slotted(setup, cands, target, kwargs, results, failures) -> list:
    """Solve the candidates that fit a motor slot on one model and one NLP
    (:mod:`ironbark_opt.dynamics.slot_model`), each on the RK4 grid its own
    model would choose, so the ballast is the per-motor answer; returns the
    candidates left for the one-model-per-motor path (and their motors).

    Slot sizes are rounded up (knots to 16, grids to 64 steps) so that other
    candidate lists of the same rocket reuse the cached model.
    """
    from ironbark_opt.dynamics.model import MIN_COAST_STEPS, Steps, initial_boost_steps
    from ironbark_opt.dynamics.setup import FlightSetup
    from ironbark_opt.dynamics.slot_model import SlotFlightModel
    from ironbark_opt.motors import slot

    loaded, rest = [], []
    for c in cands:
        try:
            motor = c.load()
        except IronbarkError as err:
            failures.append((c.label, str(err)))
            continue
        (loaded if slot.fits(motor) else rest).append((c, motor))
    if len(loaded) < SLOT_MIN_CANDIDATES or not isinstance(setup, FlightSetup) \
            or getattr(setup, "airbrakes", None) is not None:
        return [c for c, _ in rest + loaded]
    p_nominal = setup.nominal_parameters()
    jit, steps = "auto", Steps()
    n_knots = _round_up(max(slot.knots(m) for _, m in loaded), 16)
    n_boost = max(initial_boost_steps(m, p_nominal, steps) for _, m in loaded)
    capacity = [_round_up(n_boost + 1, 64), _round_up(MIN_COAST_STEPS + 1, 64)]
    model = SlotFlightModel(setup, n_knots, capacity, steps, jit=jit)
    grids = []
    for c, motor in loaded:
        try:
            grids.append(model.grid_for(motor, p_nominal))
        except IronbarkError as err:
            failures.append((c.label, str(err)))
            grids.append(None)
    need = [max([g[0] for g in grids if g] + [0]) + 1, max([g[1] for g in grids if g] + [0]) + 1]
    if need[0] > capacity[0] or need[1] > capacity[1]:
        capacity = [max(capacity[0], _round_up(need[0], 64)), max(capacity[1], _round_up(need[1], 64))]
        model = SlotFlightModel(setup, n_knots, capacity, steps, jit=jit)
    for (c, motor), grid in zip(loaded, grids):
        if grid is None:
            continue
        try:
            results.append(solve_ballast(dataclasses.replace(setup, motor=motor), target, model=model,
                                         motor_grid=grid, **kwargs))
        except IronbarkError as err:
            failures.append((c.label, str(err)))
    return [c for c, _ in rest]


def _solve_one(setup, candidate: Candidate, target, kwargs):
    motor = candidate.load()
    return solve_ballast(dataclasses.replace(setup, motor=motor), target, **kwargs)


def _solve_from_file(source: str, load_kwargs: dict, candidate: Candidate, target, kwargs):
    """Process-pool worker: rebuild the setup from its file (picklable inputs only)."""
    from ironbark_opt.vehicle import load_setup
    return _solve_one(load_setup(source, **load_kwargs), candidate, target, kwargs)


def _solve_shipped(payload, motor, target, kwargs):
    """Executor task: one candidate on a shipped setup -> ("ok", solution) or ("error", message)."""
    try:
        return "ok", solve_ballast(dataclasses.replace(payload.load(), motor=motor), target, **kwargs)
    except IronbarkError as err:
        return "error", str(err)


def _solve_on_executor(executor, setup, cands, target, kwargs, results, failures):
    """Load each motor here, solve the candidates on ``executor`` (see :mod:`ironbark_opt.executors`)."""
    from ironbark_opt.executors import SetupPayload, run_chunks, use_executor

    with use_executor(executor) as ex:
        if ex.in_process:
            for c in cands:
                try:
                    results.append(_solve_one(setup, c, target, kwargs))
                except IronbarkError as err:
                    failures.append((c.label, str(err)))
            return
        payload, tasks, labels = SetupPayload.of(setup), [], []
        for c in cands:
            try:
                tasks.append((payload, c.load(), target, kwargs))
                labels.append(c.label)
            except IronbarkError as err:
                failures.append((c.label, str(err)))
        for label, (status, value) in zip(labels, run_chunks(ex, _solve_shipped, tasks, label="motor")):
            if status == "ok":
                results.append(value)
            else:
                failures.append((label, value))


def choose_motor(setup, candidates: Sequence, target, *, objective: str = "least_ballast",
                 processes: int | None = None, load_kwargs: Mapping | None = None,
                 progress: bool = False, executor=None, **ballast_kwargs) -> MotorRanking:
    """Solve the ballast problem for each candidate motor and rank the results.

    Parameters
    ----------
    setup : FlightSetup
        The rocket; its motor is replaced by each candidate (same nozzle position).
    candidates : sequence
        Motor files, folders of motor files, ThrustCurve.org names or :class:`Candidate`.
    target : str or float
        As in :func:`~ironbark_opt.optimise.ballast.solve_ballast`.
    objective : {'least_ballast', 'largest_margin', 'closest_apogee'}
        Order among feasible candidates (infeasible ones follow, closest first).
    processes : int, optional
        Default (None) or 1: slotted candidates in this process (one model, one
        NLP); the remaining ones in up to the CPU count of worker processes
        (None) or here (1).  N > 1: every candidate in N workers, one model per
        motor (each worker rebuilds the setup from ``setup.source``).
    load_kwargs : mapping, optional
        Keyword arguments ``load_setup`` used for ``setup`` (rail_exit, ...).
    executor : None, "local", "local:N", "dask://HOST:PORT", distributed.Client or Executor
        Where candidates are solved (:func:`ironbark_opt.executors.get_executor`);
        given, it replaces ``processes``: motors are loaded here and the
        setup itself (forecast atmosphere included) is shipped to workers.
    ballast_kwargs
        Passed to :func:`solve_ballast` (mass_max, min_rail_speed, min_margin, ...).
    """
    if objective not in OBJECTIVES:
        raise InputError(f"objective must be one of {', '.join(OBJECTIVES)}, got {objective!r}", field="objective")
    cands = expand_candidates(candidates)
    results: list = []
    failures: list = []
    if executor is None and processes in (None, 1):
        # one model and one NLP for every tabulated solid motor (in this process:
        # a worker would pay the imports and the model again); the others below
        cands = _solve_slotted(setup, cands, target, ballast_kwargs, results, failures)
    n_proc = processes if processes is not None else min(len(cands), os.cpu_count() or 1)
    if executor is not None:
        _solve_on_executor(executor, setup, cands, target, ballast_kwargs, results, failures)
    elif n_proc > 1 and setup.source is not None and len(cands) > 1:
        from concurrent.futures import ProcessPoolExecutor   # here: multiprocessing costs ~20 ms to import
        with ProcessPoolExecutor(max_workers=n_proc) as pool:
            futures = [(c, pool.submit(_solve_from_file, setup.source, dict(load_kwargs or {}), c, target,
                                       ballast_kwargs)) for c in cands]
            for c, fut in futures:
                try:
                    results.append(fut.result())
                except IronbarkError as err:
                    failures.append((c.label, str(err)))
    else:
        for c in cands:
            try:
                results.append(_solve_one(setup, c, target, ballast_kwargs))
            except IronbarkError as err:
                failures.append((c.label, str(err)))
    if results:
        target_agl = results[0].values["target_agl_m"]
        results.sort(key=_rank_key(objective, target_agl))
    return MotorRanking(str(target), objective, tuple(results), tuple(failures))
