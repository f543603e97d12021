"""The compiled side of :class:`~ironbark_opt.dynamics.model.FlightModel`: C libraries,
JIT, the background compile and the library twin.

``jit=True`` compiles the phase trajectories, the apogee event, the output rows and the
fused ascent (:mod:`~ironbark_opt.dynamics.ascent`) into one library named by the model
cache key (:func:`~ironbark_opt.dynamics.model_cache.library_key`); ``jit="auto"`` loads
it when cached, else flies the VM and compiles in a detached child
(:func:`~ironbark_opt.dynamics.model_cache.compile_detached`).
"""
from __future__ import annotations

import casadi as ca

from ironbark_opt.dynamics import model_cache
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.integrator import cached_library, compile_function, library_member, rk4_step


class LibraryMixin:
    """Compiled libraries of a :class:`~ironbark_opt.dynamics.model.FlightModel` (mixin)."""

    def _library_key(self) -> str | None:
        return model_cache.library_key(self)

    def _compiled(self, func: ca.Function) -> ca.Function:
        """``func`` compiled as ``self.jit`` asks (the VM Function itself when it says no);
        ``"auto"``: the cached library, else the VM and :meth:`_compile_in_background`."""
        if not self.jit:
            return func
        key = self._library_key()
        if self.jit == "auto" and key is not None:
            lib = cached_library(func.name(), key)
            if lib is None:
                self._compile_in_background()
                return func
            return lib
        return compile_function(func, key=key, background=self.jit == "auto")

    def _compile_in_background(self) -> None:
        """Start (once per model and grid) the detached process that rebuilds this model from its
        setup and the model cache and compiles its libraries for the next run
        (:func:`~ironbark_opt.dynamics.model_cache.compile_detached`): this process pays
        neither the C code generation nor the compiler."""
        started = self.__dict__.setdefault("_background_started", set())
        if self._library_key() not in started:             # once per grid (set_discretisation)
            started.add(self._library_key())
            model_cache.compile_detached(self)

    def _rebuild_args(self) -> tuple:
        """Positional arguments that rebuild this model (with ``jit=``) in another process."""
        return (self.setup, self.steps)

    def _compile_libraries(self, discretisation) -> None:
        """Compile, now, every library ``jit="auto"`` looks for (the background child)."""
        self.set_discretisation(*discretisation)
        self.jit = True
        self._compile_phases()

    #: the Functions compiled into the model's one library with the ascent
    _LIBRARY = ("ascent_batch", "traj_rail", "traj_boost", "traj_coast", "apogee_event", "outputs_rail",
                "outputs_boost", "outputs_coast")

    def _compile_phases(self) -> None:
        """Compile as ``self.jit`` asks: the ascent (:mod:`~ironbark_opt.dynamics.ascent`),
        the phase trajectories, the apogee event and the phases' output rows, all in
        one library (their RK4 steps generated and compiled once), loaded from the
        cache when it has it.  Without a cache key: one library per Function."""
        self.__dict__.pop("_ascent_cache", None)
        self.__dict__.pop("_out_cache", None)
        # the mapped ascents of run_batch were built on the old grid's ascent
        for k in [k for k in self.__dict__.get("_map_cache", {}) if k[0] == "ascent_batch"]:
            del self._map_cache[k]
        self._lib = {}
        key = self._library_key()
        self._one_library = bool(self.jit) and key is not None and self._FUSED
        if not self._one_library:
            for ph in ("rail", "boost", "coast"):
                self._run[ph] = self._compiled(self.trajectory[ph])
            self._apogee_run = self._compiled(self._apogee_event)
            return
        lib = cached_library("ascent", key)
        if lib is None and self.jit == "auto":  # the VM now, the library for the next run
            self._compile_in_background()
        elif lib is None:
            vm, members = self._library_functions()
            lib = compile_function(vm, key=key, extra=lambda: [members[n] for n in self._LIBRARY])
            if lib is vm:                       # no compiler, or compiling failed
                lib = None
        if lib is None:                         # the VM (meanwhile)
            for ph in ("rail", "boost", "coast"):
                self._run[ph] = self.trajectory[ph]
            self._apogee_run = self._apogee_event
            return
        self._lib = {"ascent": lib, **{name: library_member(name, "ascent", key) for name in self._LIBRARY}}
        for ph in ("rail", "boost", "coast"):
            self._run[ph] = self._lib[f"traj_{ph}"]
        self._apogee_run = self._lib["apogee_event"]

    def _library_twin(self) -> "FlightModel":
        """This model built again with the Mach tables in piecewise-polynomial form
        (:func:`~ironbark_opt.aero.mach_splines.table_form`: the same splines to ~1e-15,
        ~1/6 of the B-splines' cost in C; the VM keeps the B-splines, whose tables are
        no per-call copy): the right-hand sides, their RK4 steps, the phase trajectories
        on this grid and the events (~0.3 s, only where a library is compiled).  What the
        compiled library holds comes from it (:meth:`_library_functions`, and the robust
        ballast's derivative Function), so compiled flights agree with each other to the
        bit, and with the VM's to ~1e-15."""
        cached = self.__dict__.get("_twin")
        if cached is not None and cached.discretisation() == self.discretisation():
            return cached
        from ironbark_opt.aero.mach_splines import table_form
        twin = object.__new__(type(self))
        keep = ("setup", "steps", "jit", "_key", "n_boost", "n_coast", "coast_grading")
        twin.__dict__.update({k: self.__dict__[k] for k in keep})
        with table_form("pp"):
            twin.rhs = {ph: rhs_mod.build(self.setup, ph) for ph in ("rail", "boost", "coast")}
        twin.step = {ph: rk4_step(f, f"step_{ph}") for ph, f in twin.rhs.items()}
        twin.trajectory, twin._run = {}, {}
        for ph, n in (("rail", self.steps.n_rail), ("boost", self.n_boost), ("coast", self.n_coast)):
            twin._set_trajectory(ph, n)
        twin._build_events()
        self.__dict__["_twin"] = twin
        return twin

    def _library_functions(self) -> tuple[ca.Function, dict]:
        """``(ascent, {name: Function})``: what the model's library compiles, from
        :meth:`_library_twin`: the ascent, the phase trajectories, the apogee event and
        the output rows."""
        twin = self._library_twin()
        vm, vm_batch = twin._ascent_vm()
        return vm, {"ascent_batch": vm_batch,
                    "traj_rail": twin.trajectory["rail"], "traj_boost": twin.trajectory["boost"],
                    "traj_coast": twin.trajectory["coast"], "apogee_event": twin._apogee_event,
                    **{f"outputs_{ph}": twin._outputs_base(ph) for ph in ("rail", "boost", "coast")}}

    def _ascent_runner(self):
        """The :class:`~ironbark_opt.dynamics.ascent.AscentRunner` of this model's grid
        (built on first use; compiled as ``self.jit`` asks, like the phase Functions)."""
        cache = self.__dict__.setdefault("_ascent_cache", {})
        key = self.discretisation()
        if key not in cache:
            from ironbark_opt.dynamics.ascent import AscentRunner
            cache.clear()
            func = self._lib.get("ascent")
            if func is None:
                func = self._ascent_vm()[0] if self._one_library else self._compiled(self._ascent_vm()[0])
            cache[key] = AscentRunner(func)
        return cache[key]

    def _ascent_vm(self) -> tuple[ca.Function, ca.Function]:
        """``(ascent, ascent_batch)`` of :func:`~ironbark_opt.dynamics.ascent.ascent_functions`
        in the VM, built once per grid."""
        grid, funcs = self.__dict__.get("_ascent_vm_funcs", (None, None))
        if grid != self.discretisation():
            from ironbark_opt.dynamics.ascent import ascent_functions
            funcs = ascent_functions(self)
            self.__dict__["_ascent_vm_funcs"] = (self.discretisation(), funcs)
        return funcs
