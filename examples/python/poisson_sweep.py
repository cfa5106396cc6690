"""A parameter sweep over a material constant: the oscillating plate's period
against Poisson's ratio, each run from the same scene with one value set.
  python3 examples/python/poisson_sweep.py [--coarse]  -> out/examples/plate_period_vs_nu.png"""
import os, sys
import numpy as np
import mfsd

coarse = "--coarse" in sys.argv
here = os.path.dirname(os.path.abspath(__file__))
scene_file = os.path.join(here, "..", "..", "configs", "oscillating_plate_2d.json")
periods = []
for nu in ([0.25, 0.35] if coarse else [0.22, 0.25, 0.3, 0.35, 0.4, 0.45]):
    scene = mfsd.Scene.from_file(scene_file, set={"bodies.plate.material.poisson_ratio": nu,
                                                  "constants.H_over_dp": 6 if coarse else 20,
                                                  "solver.end_time": 0.3 if coarse else 0.62, "output.vtu": False})
    sim = mfsd.Simulation(scene, threads=2, output_dir="out/examples/plate_nu_%g" % nu)
    sim.run()
    t, v = sim.probes["time"], sim.probes["tip.velocity.y"]
    k = np.nonzero(np.sign(v[1:]) * np.sign(v[:-1]) < 0)[0]
    crossing = t[k] - v[k] * (t[k + 1] - t[k]) / (v[k + 1] - v[k])
    periods.append((nu, 2.0 * (crossing[-1] - crossing[0]) / (len(crossing) - 1)))
    print("nu = %.2f: T = %.5f s" % periods[-1])

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    raise SystemExit("matplotlib is not installed: no figure (pip install matplotlib)")
nu, T = map(np.array, zip(*periods))
plt.plot(nu, T, "o-")
plt.xlabel("Poisson's ratio"); plt.ylabel("period T [s]"); plt.title("oscillating plate, E fixed")
plt.savefig("out/examples/plate_period_vs_nu.png", dpi=120)
