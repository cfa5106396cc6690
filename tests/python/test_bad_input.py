"""Wrong types, unknown keys and failures from Python (issue 28, item 6)."""
import json
import os

import pytest

import mfsd


def test_unknown_key_names_its_path(configs):
    with pytest.raises(mfsd.SceneError) as e:
        mfsd.Scene.from_file(os.path.join(configs, "oscillating_plate_2d.json"), set={"solver.hourglas": "genog"})
    assert "hourglas" in str(e.value) and "solver" in e.value.path


def test_bad_value_names_path_and_value(configs):
    with pytest.raises(mfsd.SceneError) as e:
        mfsd.Scene.from_file(os.path.join(configs, "oscillating_plate_2d.json"),
                             set={"bodies.plate.material.poisson_ratio": 0.7})
    assert "0.7" in str(e.value)
    assert e.value.path.startswith("/bodies")


def test_wrong_python_types(configs, tmp_path):
    path = os.path.join(configs, "oscillating_plate_2d.json")
    with pytest.raises(TypeError, match="set"):
        mfsd.Scene.from_file(path, set=["solver.end_time=1"])
    with pytest.raises(TypeError, match="not a JSON value"):
        mfsd.Scene.from_file(path, set={"solver.end_time": object()})
    with pytest.raises(TypeError, match="path"):
        mfsd.Scene.from_file(42)
    with pytest.raises(TypeError, match="dict"):
        mfsd.Scene.from_dict("{}")
    scene = mfsd.Scene.from_file(path, set={"solver.end_time": 0.001})
    with pytest.raises(TypeError, match="threads"):
        mfsd.Simulation(scene, threads="two", output_dir=str(tmp_path / "a"))
    with pytest.raises(ValueError, match="backend"):
        mfsd.Simulation(scene, backend="gpu", output_dir=str(tmp_path / "b"))
    with pytest.raises(TypeError, match="scene"):
        mfsd.Simulation({"name": "x"})
    assert not os.path.exists(str(tmp_path / "a")) and not os.path.exists(str(tmp_path / "b"))


def test_from_dict_round_trip_and_check(configs, tmp_path):
    doc = json.load(open(os.path.join(configs, "oscillating_plate_2d.json")))
    scene = mfsd.Scene.from_dict(doc, set={"constants.H_over_dp": 6})
    summary = scene.check()
    assert "particles" in summary and scene.dimension == 2 and scene.name == doc["name"]
    assert scene.to_dict()["constants"]["H_over_dp"] == 6
    bad = dict(doc)
    bad["bodies"] = []
    with pytest.raises(mfsd.SceneError):
        mfsd.Scene.from_dict(bad)


def test_a_failed_run_raises_numerical_failure(configs, tmp_path):
    """A plate flung far beyond its bounds: the CLI's exit 3 becomes an
    exception with the step, particle, body and field."""
    scene = mfsd.Scene.from_file(os.path.join(configs, "oscillating_plate_2d.json"),
                                 set={"constants.vf": 400.0, "solver.end_time": 0.5})
    sim = mfsd.Simulation(scene, threads=1, output_dir=str(tmp_path / "run"))
    with pytest.raises(mfsd.NumericalFailure) as e:
        sim.run()
    f = e.value
    assert f.step > 0 and f.particle >= 0 and f.body == "plate" and f.field
    assert json.load(open(os.path.join(str(tmp_path / "run"), "run.json")))["status"] == "failed"


def test_fields_of_a_scene_of_several_methods_are_refused_with_a_reason(configs, tmp_path):
    scene = mfsd.Scene.from_file(os.path.join(configs, "colliding_rings_mixed_2d.json"),
                                 set={"solver.end_time": 1e-4})
    sim = mfsd.Simulation(scene, threads=1, output_dir=str(tmp_path / "run"))
    sim.step(1)
    with pytest.raises(NotImplementedError, match="several methods"):
        sim.fields["velocity"]
    assert len(sim.energies["time"]) == 1  # the series are there
    sim.finish()
