"""Ctrl-C in Python ends the run through the CLI's interruption path (issue 28)."""
import json
import os
import subprocess
import sys
import textwrap


def test_sigint_during_steps_checkpoints_and_raises(configs, tmp_path):
    out = str(tmp_path / "run")
    script = textwrap.dedent("""
        import os, signal, sys, threading
        import mfsd
        scene = mfsd.Scene.from_file(sys.argv[1], set={"solver.end_time": 10.0})
        sim = mfsd.Simulation(scene, threads=1, output_dir=sys.argv[2])
        threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        try:
            sim.run()
        except KeyboardInterrupt as e:
            print("interrupted", sim.steps, e)
            sys.exit(7)
        sys.exit(1)
    """)
    r = subprocess.run([sys.executable, "-c", script, os.path.join(configs, "oscillating_plate_2d.json"), out],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 7, r.stdout + r.stderr
    run = json.load(open(os.path.join(out, "run.json")))
    assert run["status"] == "interrupted"
    assert os.path.isdir(os.path.join(out, "checkpoint"))
    steps = int(r.stdout.split()[1])
    assert run["steps"] == steps > 0
