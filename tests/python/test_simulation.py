"""mfsd from Python against the CLI and against itself (issue 28)."""
import csv
import gc
import json
import os
import subprocess

import numpy as np
import pytest

import mfsd

PLATE = "oscillating_plate_2d.json"
SHORT = {"solver.end_time": 0.01, "output.interval": 0.005}


def plate(configs, **extra):
    sets = dict(SHORT)
    sets.update(extra)
    return mfsd.Scene.from_file(os.path.join(configs, PLATE), set=sets)


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


def test_run_matches_the_cli_bit_for_bit(configs, out, tmp_path):
    """The same library: the energies.csv and probes.csv of sim.run() and of
    `mfsd run` are the same bytes, and sim.energies holds their numbers."""
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    sim.run()
    assert not sim.running and sim.time == pytest.approx(0.01)
    binary = os.environ.get("MFSD_BINARY")
    if not binary:
        pytest.skip("MFSD_BINARY not set (ctest sets it)")
    cli = str(tmp_path / "cli")
    subprocess.run([binary, "run", os.path.join(configs, PLATE), "-q", "--threads", "1", "-o", cli,
                    "--set", "solver.end_time=0.01", "--set", "output.interval=0.005"], check=True)
    for name in ("energies.csv", "probes.csv"):
        assert open(os.path.join(out, name)).read() == open(os.path.join(cli, name)).read(), name
    columns, rows = read_csv(os.path.join(cli, "energies.csv"))
    e = sim.energies
    assert list(e) == columns
    # the file's rows, at full precision (the CSV prints 10 significant digits)
    np.testing.assert_allclose(e["kinetic"], rows[:, columns.index("kinetic")], rtol=1e-9)


def test_fields_are_zero_copy_read_only_views(configs, out):
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    v = sim.fields["velocity"]
    assert v.shape == (sim.fields["id"].shape[0], 2) and v.dtype == np.float64
    assert not v.flags.writeable
    again = sim.fields["velocity"]
    assert np.shares_memory(v, again)  # the solver's buffer, not a copy
    before = v.copy()
    sim.step(5)
    assert sim.steps == 5
    assert not np.array_equal(before, v)  # the view follows the run
    with pytest.raises(ValueError):
        v[0, 0] = 1.0
    ids = sim.fields["id"]
    assert sorted(ids.tolist()) == list(range(len(ids)))  # each particle once, by its index in the scene
    sim.finish()


def test_an_array_outlives_its_simulation(configs, out):
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    sim.step(2)
    u = sim.fields["displacement"]
    expected = u.copy()
    del sim
    gc.collect()
    np.testing.assert_array_equal(u, expected)  # the array keeps the run's memory alive
    assert float(np.abs(u).sum()) > 0


def test_position_is_reference_plus_displacement(configs, out):
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    sim.step(3)
    x = sim.fields["position"]
    np.testing.assert_array_equal(x, sim.fields["reference_position"] + sim.fields["displacement"])
    assert "velocity" in sim.fields and "position" in sim.fields.keys()
    with pytest.raises(KeyError, match="no particle field 'speed'"):
        sim.fields["speed"]


def test_run_with_a_callback_every_interval(configs, out):
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    seen = []
    sim.run(until=0.008, every=0.002, callback=lambda s: seen.append((s.time, float(np.abs(s.fields["velocity"]).max()))))
    times = [t for t, _ in seen]
    assert len(seen) == 4 and all(b > a for a, b in zip(times, times[1:]))
    for k, t in enumerate(times):  # at the first step at or past each multiple
        assert t >= 0.002 * (k + 1) - 1e-12 and t < 0.002 * (k + 1) + 1e-4
    assert sim.running  # until < end_time
    sim.run()
    assert not sim.running


def test_step_count_and_end(configs, out):
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    assert sim.step(3) == 3 and sim.steps == 3
    taken = sim.step(10**6)  # stops at the end time
    assert not sim.running and sim.time == pytest.approx(0.01) and sim.steps == 3 + taken
    assert sim.step(1) == 0
    result = sim.finish()
    assert result["exit_code"] == 0
    run = json.load(open(os.path.join(out, "run.json")))
    assert run["status"] == "completed" and run["steps"] == sim.steps


def test_snapshot_and_checkpoint_continue_with_the_cli(configs, out, tmp_path):
    """A snapshot and a checkpoint taken from Python after 4 steps; `mfsd run
    --restart` then ends where the uninterrupted run ends: energies.csv and
    probes.csv hold the uninterrupted run's rows, byte for byte, and the one
    row the snapshot added at its time."""
    binary = os.environ.get("MFSD_BINARY")
    if not binary:
        pytest.skip("MFSD_BINARY not set (ctest sets it)")
    whole = str(tmp_path / "whole")
    mfsd.Simulation(plate(configs), threads=1, output_dir=whole).run().finish()
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    sim.step(4)
    snapshot_time = sim.time
    sim.write_snapshot()
    folder = sim.checkpoint()
    assert os.path.isdir(folder)
    pvd = open(os.path.join(out, "snapshots.pvd")).read()
    assert pvd.count("<DataSet") == 2  # t = 0 and the one asked for
    sim.finish()
    subprocess.run([binary, "run", os.path.join(configs, PLATE), "-q", "--threads", "1", "--set",
                    "solver.end_time=0.01", "--set", "output.interval=0.005", "--restart", out], check=True)
    assert json.load(open(os.path.join(out, "run.json")))["status"] == "completed"
    for name in ("energies.csv", "probes.csv"):
        cut = open(os.path.join(out, name)).read().splitlines()
        uninterrupted = open(os.path.join(whole, name)).read().splitlines()
        extra = [line for line in cut if line not in uninterrupted]
        assert [line for line in cut if line in uninterrupted] == uninterrupted, name
        assert len(extra) == 1 and float(extra[0].split(",")[0]) == pytest.approx(snapshot_time, rel=1e-9), extra


def test_checkpoint_in_a_folder_continues_with_the_cli(configs, out, tmp_path):
    """sim.checkpoint(dir) copies the outputs so far beside the checkpoint:
    `mfsd run --restart dir` ends where the uninterrupted run ends, with the
    same energies.csv and probes.csv bytes."""
    binary = os.environ.get("MFSD_BINARY")
    if not binary:
        pytest.skip("MFSD_BINARY not set (ctest sets it)")
    whole = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    whole.run()
    branch = str(tmp_path / "branch")
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=str(tmp_path / "cut"))
    sim.step(7)
    assert sim.checkpoint(branch) == os.path.join(branch, "checkpoint")
    sim.finish()
    subprocess.run([binary, "run", os.path.join(configs, PLATE), "-q", "--threads", "1", "--set",
                    "solver.end_time=0.01", "--set", "output.interval=0.005", "--restart", branch], check=True)
    for name in ("energies.csv", "probes.csv", "snapshots.pvd"):
        assert open(os.path.join(branch, name)).read() == open(os.path.join(out, name)).read(), name
    with pytest.raises(mfsd.SceneError, match="empty"):
        sim2 = mfsd.Simulation(plate(configs), threads=1, output_dir=str(tmp_path / "again"))
        sim2.checkpoint(branch)


def test_timing_report(configs, out):
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    sim.step(5)
    t = sim.timing
    assert t["steps"] == 5 and "force" in t["stages"] and t["stage_seconds"] > 0


def test_dlpack_view_shares_the_solver_memory(configs, out):
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    d = np.from_dlpack(sim.fields.dlpack("velocity"))
    assert np.shares_memory(d, sim.fields["velocity"]) and d.shape == sim.fields["velocity"].shape
    before = d.copy()
    sim.step(3)
    assert not np.array_equal(before, d)
    assert sim.fields.dlpack("velocity").__dlpack_device__()[0] == 1  # kDLCPU
    sim.finish()


def test_a_dropped_simulation_finishes_its_run(configs, out):
    """A Simulation garbage-collected before finish() (the README's five lines
    without it) writes run.json and timing.json: its run is not left
    "running"; run.json says it stopped before the end time."""
    sim = mfsd.Simulation(plate(configs), threads=1, output_dir=out)
    sim.step(5)
    del sim
    gc.collect()
    run = json.load(open(os.path.join(out, "run.json")))
    assert run["status"] == "stopped" and run["steps"] == 5
    assert "finished before end_time" in run["message"]
    assert os.path.exists(os.path.join(out, "timing.json"))
