"""Camoes's air-brake deployment against time, as RocketPy's docs/examples/camoes_flight_sim.ipynb
gives it ("for privacy reasons ... just describes the actuation with time of the algorithm
developed by the team"; RocketPy clamps the level to [0, 1])."""


def deployment(time_s, state):
    t = time_s
    if t < 3.8 or t > 19.6:
        return 0.0
    if t <= 11.4:
        return 1.0
    level = -0.002906 * t ** 3 + 0.1497 * t ** 2 - 2.563 * t + 14.96
    return min(max(level, 0.0), 1.0)
