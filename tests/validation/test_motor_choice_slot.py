"""One NLP for all candidate motors gives each motor's own ballast.

The README's three Calisto motors are ranked through one motor-slot model and
one NLP (``choose_motor``, in this process) and solved one by one on their own
models (``solve_ballast``); the ballast must agree within 1e-6 kg (the slot
flies the same RK4 steps on the same numbers, so it is round-off in practice).
The compiled ballast NLP (slow: a C compile) must agree with the VM to 1e-9.
"""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.motors import load_motor
from ironbark_opt.optimise.ballast import solve_ballast
from ironbark_opt.optimise.motor_choice import choose_motor
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples/calisto/calisto.toml"
MOTORS = [ROOT / "examples/calisto/Cesaroni_M1670.eng", ROOT / "tests/data/motors/Cesaroni_7579M1520-P.eng",
          ROOT / "tests/data/motors/AeroTech_M1340W.eng"]


def test_one_nlp_ranking_equals_per_motor_solves():
    setup = load_setup(CALISTO)
    ranking = choose_motor(setup, [str(m) for m in MOTORS], "3000m", processes=1)
    assert not ranking.failures
    slotted = {s.motor: s for s in ranking.solutions}
    for path in MOTORS:
        motor = load_motor(path)
        own = solve_ballast(dataclasses.replace(setup, motor=motor), "3000m")
        one = slotted[own.motor]
        diff = one.ballast - own.ballast
        print(f"{own.motor}: own model {own.ballast:.9f} kg, one NLP {one.ballast:.9f} kg (diff {diff:+.2e} kg), "
              f"re-simulated apogee {own.values['resimulated_apogee_agl_m']:.6f} / "
              f"{one.values['resimulated_apogee_agl_m']:.6f} m")
        assert one.feasible == own.feasible
        assert abs(diff) < 1e-6                                             # tolerance 1e-6 kg
        for k in ("apogee_agl_m", "resimulated_apogee_agl_m", "rail_exit_speed_mps", "launch_mass_kg",
                  "static_margin_rail_exit_cal", "max_speed_mps"):
            assert one.values[k] == pytest.approx(own.values[k], rel=1e-9, abs=1e-9), k


@pytest.mark.slow
def test_compiled_ballast_nlp_equals_vm(tmp_path):
    import casadi as ca

    from ironbark_opt.dynamics.integrator import compile_function, compiler_available
    from ironbark_opt.flight import flight_model
    from ironbark_opt.optimise import ballast

    if not compiler_available():
        pytest.skip("no C compiler")
    setup = load_setup(CALISTO)
    oracle = ballast._nlp_graph(flight_model(setup, jit=False), False, False, False)[0]
    compiled = compile_function(oracle, tmp_path, extra=lambda: (ballast._jacobian_in_x(oracle),))
    assert compiled.is_a("External")
    w = ca.DM([1.5, 0.3811, 25.0])
    p = np.r_[setup.nominal_parameters(), 3000.0, setup.dry.mass, 0.3]
    x = ca.MX.sym("x", 3)
    jac_vm, jac_c = (ca.Function("j", [x], [ca.jacobian(f(x, p)[1], x)]) for f in (oracle, compiled))
    for a, b in ((oracle(w, p)[1], compiled(w, p)[1]), (jac_vm(w), jac_c(w))):
        a, b = np.array(a).ravel(), np.array(b).ravel()
        print(a, b)
        np.testing.assert_allclose(b, a, rtol=1e-9, atol=1e-9 * np.max(np.abs(a)))   # 1e-9 relative
    vm = ca.nlpsol("vm", "ipopt", oracle, {"print_time": False, "ipopt.print_level": 0, "ipopt.sb": "yes",
                                           "ipopt.hessian_approximation": "limited-memory", "ipopt.tol": 1e-10})
    c = ca.nlpsol("c", "ipopt", compiled, {"print_time": False, "ipopt.print_level": 0, "ipopt.sb": "yes",
                                           "ipopt.hessian_approximation": "limited-memory", "ipopt.tol": 1e-10})
    args = dict(x0=w, p=p, lbx=[0, 0, 5], ubx=[setup.dry.mass, 3, 60], lbg=0, ubg=0)
    x_vm, x_c = np.array(vm(**args)["x"]).ravel(), np.array(c(**args)["x"]).ravel()
    print("ballast, rail exit, apogee time: VM", x_vm, "compiled", x_c)
    np.testing.assert_allclose(x_c, x_vm, rtol=1e-9)
