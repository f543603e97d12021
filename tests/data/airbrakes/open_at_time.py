"""Test controller: command full deployment from 5.525 s after ignition."""


def open_late(time_s, state):
    return 1.0 if time_s >= 5.525 - 1e-9 else 0.0


def broken(time_s, state):
    return state["no_such_key"]
