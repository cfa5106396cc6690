"""mfsd from Python: scenes, runs stepped from a script, fields as NumPy arrays.

The module wraps the library that `mfsd run` uses (docs/python.md): a
Simulation is the CLI's run, set up, stepped and finished the same way, with
the same output folder (VTU/PVD snapshots, the CSV series, run.json,
timing.json, checkpoints).

    import mfsd
    scene = mfsd.Scene.from_file("configs/oscillating_plate_2d.json",
                                 set={"constants.H_over_dp": 20})
    sim = mfsd.Simulation(scene, threads=2)
    sim.run(until=0.1)
    v = sim.fields["velocity"]          # (n, 2) read-only view, no copy (CPU)
    ke = sim.energies["kinetic"]        # the energies.csv column so far
"""
from __future__ import annotations

import json
import numbers
import os
import weakref

import numpy as np

from . import _mfsd

__all__ = ["Scene", "Simulation", "SceneError", "NumericalFailure", "__version__"]
__version__ = _mfsd.__version__


class SceneError(ValueError):
    """A problem with a scene. `path` is the JSON path of the value
    ("/bodies/0/material/density"), the message says what was found and what
    was expected."""

    def __init__(self, message, path=""):
        super().__init__(message)
        self.message = message
        self.path = path


class NumericalFailure(RuntimeError):
    """A run stopped by a numerical failure (a non-finite value, a particle
    leaving the bounds, ...): the step, time, particle (its index in the
    scene), body and field; the run's folder keeps the last good snapshot."""

    def __init__(self, message, step, time, particle, body, field, detail):
        super().__init__(message)
        self.step, self.time, self.particle = step, time, particle
        self.body, self.field, self.detail = body, field, detail


def _native(call, *args):
    """Calls the native layer, its scene errors raised as SceneError."""
    try:
        return call(*args)
    except _mfsd.NativeSceneError as e:
        message, path = e.args
        raise SceneError(message, path) from None


def _overrides(values):
    """{"constants.H_over_dp": 20} -> ["constants.H_over_dp=20"] (JSON values)."""
    if values is None:
        return []
    if not isinstance(values, dict):
        raise TypeError("set: expected a dict of dotted paths to values, got %s" % type(values).__name__)
    out = []
    for key, value in values.items():
        if not isinstance(key, str) or not key:
            raise TypeError("set: keys are dotted scene paths such as 'solver.end_time', got %r" % (key,))
        try:
            text = json.dumps(value)
        except (TypeError, ValueError):
            raise TypeError("set[%r]: %r is not a JSON value" % (key, value)) from None
        out.append("%s=%s" % (key, text))
    return out


class Scene:
    """A scene as read: overrides applied and every default resolved. Reading
    checks it; nothing is written until a Simulation runs it."""

    def __init__(self, native):
        self._native = native

    @classmethod
    def from_file(cls, path, set=None):
        """Reads a JSON scene file; set={"dotted.path": value} overrides values."""
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError("path: expected a file name, got %s" % type(path).__name__)
        return cls(_native(_mfsd.scene_from_file, os.fspath(path), _overrides(set)))

    @classmethod
    def from_dict(cls, scene, set=None, name="<dict>"):
        """A scene from a dict of the JSON scene format."""
        if not isinstance(scene, dict):
            raise TypeError("scene: expected a dict, got %s" % type(scene).__name__)
        try:
            text = json.dumps(scene)
        except (TypeError, ValueError) as e:
            raise TypeError("scene: not a JSON document (%s)" % e) from None
        return cls(_native(_mfsd.scene_from_text, text, name, _overrides(set)))

    def check(self):
        """Generates the particles and returns what `mfsd check` prints;
        raises SceneError for a scene that cannot run. Writes nothing."""
        return _native(self._native.summary)

    @property
    def name(self):
        return self._native.name

    @property
    def dimension(self):
        return self._native.dimension

    @property
    def end_time(self):
        return self._native.end_time

    def to_dict(self):
        """The resolved scene: every key with its value or default."""
        return json.loads(self._native.resolved_json())

    def __repr__(self):
        return "mfsd.Scene(%r, %dD, end_time=%g)" % (self.name, self.dimension, self.end_time)


class _Fields:
    """sim.fields[name]: a registered particle field in the solver's particle
    order (fields["id"] is each particle's index in the scene). On the CPU a
    read-only view of the solver's memory, without a copy, that follows the
    run as it steps; from a GPU a copy. "position" (X + u) is computed."""

    def __init__(self, sim):
        self._sim = sim

    def keys(self):
        return sorted(self._sim._native.field_names() + ["position"])

    def __iter__(self):
        return iter(self.keys())

    def __len__(self):
        return len(self.keys())

    def __contains__(self, name):
        return name in self.keys()

    def _native_for(self, name):
        if not isinstance(name, str):
            raise TypeError("field names are strings, got %r" % (name,))
        native = self._sim._native
        if not native.field_names():
            raise NotImplementedError("sim.fields: a scene of several methods does not show its solvers' fields "
                                      "yet (docs/python.md); sim.series and the snapshots have its results")
        return native

    def _unknown(self, name):
        return KeyError("no particle field %r; this run has: %s" % (name, ", ".join(self.keys())))

    def __getitem__(self, name):
        native = self._native_for(name)
        if name == "position":
            return native.field("reference_position", native) + native.field("displacement", native)
        try:
            return native.field(name, native)
        except KeyError:
            raise self._unknown(name) from None

    def dlpack(self, name):
        """The field where it lies (the GPU's memory with backend="cuda"),
        without a copy, for DLPack consumers:
        np.from_dlpack(sim.fields.dlpack("velocity")) on the CPU,
        torch.from_dlpack(...) or cupy.from_dlpack(...) on either. Writing
        through such an array changes the run: leave it read-only."""
        native = self._native_for(name)
        try:
            native.dlpack(name, native)  # the name checked now
            return _DLPackField(native, name)
        except KeyError:
            raise self._unknown(name) from None

    def __repr__(self):
        return "mfsd fields: " + ", ".join(self.keys())


class _DLPackField:
    """A field for DLPack consumers: each __dlpack__ call hands out a new
    capsule over the same memory (a capsule is consumed once)."""

    def __init__(self, native, name):
        self._native, self._name = native, name

    def __dlpack__(self, stream=None, **kwargs):
        return self._native.dlpack(self._name, self._native)[0]

    def __dlpack_device__(self):
        _, device, device_id = self._native.dlpack(self._name, self._native)
        return (device, device_id)


def _columns(series):
    columns, rows = series
    data = np.array(rows, dtype=float).reshape(len(rows), len(columns))
    return {c: data[:, k].copy() for k, c in enumerate(columns)}


def _finish_dropped(native):
    """Finishes the run of a Simulation that was garbage-collected (or alive at
    the interpreter's exit) without finish(): run.json and timing.json."""
    try:
        native.finish()
    except Exception as e:  # noqa: BLE001 - a finaliser must not raise
        import sys
        print("mfsd: a dropped Simulation could not finish its run: %s" % e, file=sys.stderr)


class Simulation:
    """One run of a scene, as `mfsd run` does it, stepped from Python.

    backend "cpu" or "cuda"; threads 0 (the CPU default) or N; precision None
    (the scene's), "float" or "double"; output_dir None (out/<scene name>);
    quiet False prints the CLI's progress and summary.
    """

    def __init__(self, scene, backend="cpu", threads=0, precision=None, output_dir=None, quiet=True, max_steps=0):
        if not isinstance(scene, Scene):
            raise TypeError("scene: expected an mfsd.Scene, got %s" % type(scene).__name__)
        if not isinstance(backend, str):
            raise TypeError("backend: expected \"cpu\" or \"cuda\", got %r" % (backend,))
        if isinstance(threads, bool) or not isinstance(threads, numbers.Integral):
            raise TypeError("threads: expected an int, got %r" % (threads,))
        if precision is not None and not isinstance(precision, str):
            raise TypeError("precision: expected None, \"float\" or \"double\", got %r" % (precision,))
        if output_dir is not None and not isinstance(output_dir, (str, os.PathLike)):
            raise TypeError("output_dir: expected a folder name, got %r" % (output_dir,))
        if isinstance(max_steps, bool) or not isinstance(max_steps, numbers.Integral) or max_steps < 0:
            raise TypeError("max_steps: expected an int >= 0, got %r" % (max_steps,))
        self.scene = scene
        self._result = None
        self._native = _native(_mfsd.NativeSession, scene._native, backend, int(threads), precision or "",
                               os.fspath(output_dir) if output_dir is not None else "", bool(quiet),
                               int(max_steps), "python")
        self.fields = _Fields(self)
        # A Simulation dropped (or alive at exit) before finish(): the run
        # finishes itself, so run.json never stays "running" and timing.json
        # is written; run.json says where it stopped.
        self._finalizer = weakref.finalize(self, _finish_dropped, self._native)

    # -- stepping ---------------------------------------------------------
    def step(self, n=1):
        """n steps (fewer when the run reaches its end); returns the steps taken."""
        if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 1:
            raise TypeError("n: expected an int >= 1, got %r" % (n,))
        done = self._native.step(int(n))
        self._check()
        return done

    def run(self, until=None, every=None, callback=None):
        """Steps to time `until` (the scene's end time by default). With
        `every` and `callback`, callback(sim) is called each time the run
        passes a multiple of `every` seconds, and at the end."""
        until = self.end_time if until is None else until
        if not isinstance(until, numbers.Real):
            raise TypeError("until: expected a time in seconds, got %r" % (until,))
        if every is not None and (not isinstance(every, numbers.Real) or not every > 0):
            raise TypeError("every: expected a positive time in seconds, got %r" % (every,))
        if callback is not None and not callable(callback):
            raise TypeError("callback: expected a callable, got %r" % (callback,))
        if every is None:
            self._native.advance_to(float(until))
            self._check()
            if callback is not None:
                callback(self)
            return self
        k = int(self.time / every) + 1
        while self.running and self.time < until:
            self._native.advance_to(min(k * every, float(until)))
            self._check()
            k = int(self.time / every) + 1
            if callback is not None:
                callback(self)
        return self

    def _check(self):
        """After steps: Ctrl-C ends the run as the CLI's does; a failure raises."""
        if self._native.interrupted:
            result = self.finish()
            raise KeyboardInterrupt("mfsd run interrupted at t = %g s; checkpoint in %s" %
                                    (result["time"], result["output_dir"]))
        if not self._native.running and self._result is None:
            result = self.finish()
            if "failure_message" in result:
                raise NumericalFailure(result["failure_message"], result["failure_step"], result["failure_time"],
                                       result["failure_particle"], result["failure_body"], result["failure_field"],
                                       result["failure_detail"])

    def finish(self):
        """Ends the run (run.json, timing.json, the last snapshot); returns
        its result. Called by the steps that reach the end, by close() and
        on leaving a `with` block."""
        if self._result is None:
            self._finalizer.detach()
            self._result = dict(self._native.finish())
        return self._result

    close = finish

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.finish()
        return False

    # -- state --------------------------------------------------------------
    @property
    def time(self):
        return self._native.time

    @property
    def steps(self):
        return self._native.steps

    @property
    def end_time(self):
        return self._native.end_time

    @property
    def running(self):
        return self._native.running and self._result is None

    @property
    def output_dir(self):
        return self._native.output_dir

    def series(self, name):
        """A CSV series of this run as written so far ("energies", "probes",
        "boundary_forces", "measure_<plane>", "crack_<body>"): a dict of
        column name -> array."""
        s = self._native.series()
        key = name if name.endswith(".csv") else name + ".csv"
        if key not in s:
            raise KeyError("no series %r; this run writes: %s" % (name, ", ".join(sorted(k[:-4] for k in s))))
        return _columns(s[key])

    @property
    def energies(self):
        """energies.csv so far: time, kinetic, strain, ... per column."""
        return self.series("energies")

    @property
    def probes(self):
        """probes.csv so far (an empty dict for a scene without probes)."""
        s = self._native.series()
        return _columns(s["probes.csv"]) if "probes.csv" in s and len(s["probes.csv"][0]) > 1 else {}

    @property
    def observers(self):
        """observers.csv so far: the scene's observers' interpolated fields
        (an empty dict for a scene without observers)."""
        s = self._native.series()
        return _columns(s["observers.csv"]) if "observers.csv" in s else {}

    @property
    def timing(self):
        """Seconds spent in each stage of the steps so far, with the steps
        and the particle-steps per second of those stages."""
        stages = dict(self._native.timing())
        return {"stages": stages, "steps": self.steps, "stage_seconds": sum(stages.values())}

    def write_snapshot(self):
        """A snapshot and the series' rows of the current time, now."""
        self._native.write_snapshot()

    def checkpoint(self, dir=None):
        """A checkpoint of the current state; returns its folder. Without
        `dir` in the run's output folder (`mfsd run --restart OUTPUT`
        continues it); with `dir` (new or empty) a copy of the outputs so far
        and the checkpoint go there, and `mfsd run --restart dir` continues
        the run in that folder, a branch of this one."""
        if dir is not None and not isinstance(dir, (str, os.PathLike)):
            raise TypeError("dir: expected a folder name, got %r" % (dir,))
        return _native(self._native.checkpoint, os.fspath(dir) if dir is not None else "")

    def __repr__(self):
        return "mfsd.Simulation(%r, t = %g s, step %d%s)" % (self.scene.name, self.time, self.steps,
                                                             "" if self.running else ", stopped")
