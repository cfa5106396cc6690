"""Observers through the whole code (issue 28, item 2): a linear observer
reproduces the positions of the initial configuration, a frozen observer's
row is the hand-computed weighted average of the particles' own values."""
import os

import numpy as np
import pytest

import mfsd


def plate_with(configs, observers, **extra):
    sets = {"solver.end_time": 0.004, "output.interval": 0.002, "observers": observers}
    sets.update(extra)
    return mfsd.Scene.from_file(os.path.join(configs, "oscillating_plate_2d.json"), set=sets)


def test_linear_observer_reproduces_the_positions(configs, out):
    points = [[0.1, 0.0], [0.15, 0.006], [0.199, 0.0095]]  # inside, and at the free corner
    scene = plate_with(configs, [{"name": "p", "points": points, "fields": ["reference_position"],
                                  "interpolation": "linear"}])
    sim = mfsd.Simulation(scene, threads=1, output_dir=out)
    o = sim.observers
    for k, x in enumerate(points):
        assert o["p.%d.reference_position.x" % k][0] == pytest.approx(x[0], abs=1e-12)
        assert o["p.%d.reference_position.y" % k][0] == pytest.approx(x[1], abs=1e-12)
    sim.finish()


def test_frozen_observer_is_the_weighted_average_of_its_particles(configs, out):
    point, radius = np.array([0.12, 0.003]), 0.005
    scene = plate_with(configs, [{"name": "f", "points": [point.tolist()], "fields": ["velocity"], "freeze": True,
                                  "radius": radius}])
    sim = mfsd.Simulation(scene, threads=1, output_dir=out)
    X, V = sim.fields["reference_position"], sim.fields["volume"]
    q = np.linalg.norm(X - point, axis=1) / radius
    w = np.where(q < 1, (1 - q) ** 4 * (1 + 4 * q), 0.0) * V  # Wendland C2 times volume, at t = 0
    assert (w > 0).sum() >= 3
    sim.step(40)
    sim.write_snapshot()  # a row now
    v = sim.fields["velocity"]
    expected = (w[:, None] * v).sum(axis=0) / w.sum()
    o = sim.observers
    assert o["f.velocity.x"][-1] == pytest.approx(expected[0], rel=1e-12, abs=1e-15)
    assert o["f.velocity.y"][-1] == pytest.approx(expected[1], rel=1e-12)
    assert abs(expected[1]) > 0.01  # the plate moves there
    sim.finish()
    with open(os.path.join(out, "observers.csv")) as f:
        assert f.readline().strip() == "time,f.velocity.x,f.velocity.y"


def test_observer_errors_name_their_path(configs, tmp_path):
    scene = plate_with(configs, [{"name": "bad", "points": [[0.1, 0.0]], "fields": ["speed"]}])
    with pytest.raises(mfsd.SceneError) as e:
        mfsd.Simulation(scene, threads=1, output_dir=str(tmp_path / "run"))
    assert e.value.path == "/observers/0/fields/0" and "velocity" in str(e.value)
    written = [f for _, _, files in os.walk(str(tmp_path)) for f in files]
    assert written == []  # no file for a scene that fails
    with pytest.raises(mfsd.SceneError) as e:
        plate_with(configs, [{"name": "both", "points": [[0, 0]], "line": {"from": [0, 0], "to": [1, 0]},
                              "fields": ["velocity"]}])
    assert e.value.path == "/observers/0"
    with pytest.raises(mfsd.SceneError) as e:
        plate_with(configs, [{"name": "x", "points": [[0, 0, 0]], "fields": ["velocity"]}])
    assert "2 coordinates" in str(e.value)
