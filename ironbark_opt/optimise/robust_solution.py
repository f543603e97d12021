"""The result of a robust ballast solve (:func:`~ironbark_opt.optimise.robust.solve_robust_ballast`):
numbers, dictionary and the printed summary."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping


@dataclass(frozen=True)
class RobustBallastSolution:
    """Result of :func:`solve_robust_ballast` (immutable).

    ``values`` holds unit-suffixed numbers: ``ballast_kg``, ``ballast_x_m`` (robust),
    ``nominal_ballast_kg``, ``nominal_ballast_x_m``, ``target_agl_m``, ``band_m``,
    ``kernel_width_m``, the in-sample (SAA) and fresh-check probabilities and
    expected misses of both ballasts with their standard errors, solve times.
    """

    name: str
    motor: str
    objective: str
    samples: int
    seed: int
    check_seed: int
    values: Mapping[str, float]
    nominal: object = field(repr=False)
    design: str = "latin_hypercube"
    kept_nominal: bool = False
    #: why the nominal ballast was kept: "t" (min_gain_t) or "selection" (fresh-sample validation)
    kept_by: str | None = None

    def __repr__(self) -> str:
        v = self.values
        return (f"RobustBallastSolution({self.name!r}: {v['ballast_kg']:.3f} kg (nominal "
                f"{v['nominal_ballast_kg']:.3f}), P(in band) {v['check_probability_in_band']:.3f} vs "
                f"{v['check_nominal_probability_in_band']:.3f})")

    @property
    def ballast(self) -> float:
        """Robust ballast mass [kg]."""
        return self.values["ballast_kg"]

    def to_dict(self) -> dict:
        out = {"rocket": self.name, "motor": self.motor, "robust": True, "objective": self.objective,
               "samples": self.samples, "design": self.design, "seed": self.seed, "check_seed": self.check_seed,
               "kept_nominal": self.kept_nominal, "kept_by": self.kept_by}
        out.update(self.values)
        out["nominal_solution"] = {k: v for k, v in self.nominal.to_dict().items() if k != "parameters"}
        return out

    def summary(self) -> str:
        v = self.values
        b = v["band_m"]
        lines = [f"Robust ballast for {self.name} on {self.motor}: objective {self.objective}, "
                 f"{self.samples} samples ({self.design.replace('_', ' ')}, seed {self.seed}), kernel width "
                 f"{v['kernel_width_m']:.1f} m",
                 f"  target             {v['target_agl_m']:10.1f} m AGL, band +/- {b:.0f} m",
                 f"  {'':18s} {'ballast [kg]':>12s} {'x [m]':>7s} {'P(in band)':>17s} {'E|miss| [m]':>16s}"]
        checked = "check_probability_in_band" in v
        src = "check_" if checked else "saa_"
        for label, pre in (("nominal", "nominal_"), ("robust", "")):
            p_in, miss = v[f"{src}{pre}probability_in_band"], v[f"{src}{pre}expected_abs_miss_m"]
            err = (f" +/- {v[f'check_{pre}probability_in_band_stderr']:.3f}",
                   f" +/- {v[f'check_{pre}expected_abs_miss_stderr_m']:.1f}") if checked else ("", "")
            lines.append(f"  {label:18s} {v[pre + 'ballast_kg']:12.3f} {v[pre + 'ballast_x_m']:7.3f} "
                         f"{p_in:9.3f}{err[0]:8s} {miss:8.1f}{err[1]:7s}")
        lines.append(f"  SAA optimum        {v['saa_optimum_ballast_kg']:.3f} kg, in-sample gain t = {v['saa_gain_t']:.2f}"
                     + (": not significant, the nominal ballast kept" if self.kept_by == "t" else ""))
        if "select_samples" in v:
            lines.append(f"  validation         SAA optimum - nominal on {v['select_samples']} fresh samples (seed "
                         f"{v['select_seed']}): P {v['select_probability_gain']:+.3f} +/- "
                         f"{v['select_probability_gain_stderr']:.3f}, E|miss| "
                         f"{v['select_expected_abs_miss_change_m']:+.1f} m: "
                         + ("not better, the nominal ballast kept" if self.kept_by == "selection" else "accepted"))
        if checked:
            lines += [f"  robust - nominal   P(in band) {v['check_probability_gain']:+.3f} +/- "
                      f"{v['check_probability_gain_stderr']:.3f}, E|miss| "
                      f"{v['check_expected_abs_miss_change_m']:+.1f} +/- "
                      f"{v['check_expected_abs_miss_change_stderr_m']:.1f} m (paired)",
                      f"  check              {v['check_samples']} fresh samples, seed {self.check_seed} "
                      f"(in-sample SAA: P {v['saa_nominal_probability_in_band']:.3f} -> "
                      f"{v['saa_probability_in_band']:.3f})"]
        else:
            lines.append(f"  (in-sample values on the {self.samples} SAA samples: no fresh check asked)")
        for label, pre in (("nominal", "nominal_"), ("robust", "")):
            lines.append(f"  {label + ' flight':18s} apogee {v[pre + 'apogee_agl_m']:.1f} m AGL, rail exit "
                         f"{v[pre + 'rail_exit_speed_mps']:.2f} m/s, margin {v[pre + 'static_margin_rail_exit_cal']:.2f}"
                         f" cal at rail exit ({v[pre + 'static_margin_min_cal']:.2f} min; nominal parameters)")
        limits = [f"{name} >= {v[key]:g} {unit}" for name, key, unit in
                  (("rail-exit speed", "min_rail_speed_mps", "m/s"), ("margin", "min_margin_cal", "cal"))
                  if key in v]
        if limits:
            lines.append(f"  limits             {', '.join(limits)} (on the nominal parameters' flight)")
        lines.append(f"  solve time         {v['solve_time_s']:10.2f} s (nominal solve {v['nominal_solve_time_s']:.2f} "
                     f"s; {v['sample_evaluations']} evaluations of the samples, {v['ipopt_iterations']} IPOPT "
                     f"iterations on their models)")
        return "\n".join(lines)
