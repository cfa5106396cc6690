"""examples/python at their coarse settings (issue 28, item 3): each runs,
prints its numbers and draws its figure."""
import os
import subprocess
import sys

import pytest

EXAMPLES = ["plate_resolution_sweep.py", "field_callback.py", "poisson_sweep.py"]
FIGURES = {"plate_resolution_sweep.py": "plate_speed_vs_error.png", "field_callback.py": "plate_fields.png",
           "poisson_sweep.py": "plate_period_vs_nu.png"}


@pytest.mark.parametrize("example", EXAMPLES)
def test_example_runs_coarse(example, tmp_path):
    root = os.environ.get("MFSD_SOURCE_DIR") or os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    r = subprocess.run([sys.executable, os.path.join(root, "examples", "python", example), "--coarse"],
                       cwd=str(tmp_path), capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.strip(), "the example printed nothing"
    assert os.path.getsize(str(tmp_path / "out" / "examples" / FIGURES[example])) > 1000
    assert len(open(os.path.join(root, "examples", "python", example)).read().splitlines()) < 40
