"""Speed against error: the oscillating plate's period error (seed 000 Table 1,
T = 0.28201 s) against the run's wall time over resolutions H/dp.
  python3 examples/python/plate_resolution_sweep.py [--coarse]  -> out/examples/plate_speed_vs_error.png"""
import os, sys, time
import numpy as np, mfsd

T_REF = 0.28201  # s, seed 000 Table 1 (nu = 0.3, v_f = 0.05)
coarse = "--coarse" in sys.argv
here = os.path.dirname(os.path.abspath(__file__))
scene_file = os.path.join(here, "..", "..", "configs", "oscillating_plate_2d.json")

def period(t, v):
    """v_y of the tip goes as cos(2 pi t / T): twice the mean time between its zero crossings."""
    k = np.nonzero(np.sign(v[1:]) * np.sign(v[:-1]) < 0)[0]
    crossing = t[k] - v[k] * (t[k + 1] - t[k]) / (v[k + 1] - v[k])
    return 2.0 * (crossing[-1] - crossing[0]) / (len(crossing) - 1)

results = []
for n in ([6, 8] if coarse else [10, 20, 40]):
    scene = mfsd.Scene.from_file(scene_file, set={"constants.H_over_dp": n, "solver.end_time": 0.3 if coarse else 0.62, "output.vtu": False})
    sim = mfsd.Simulation(scene, threads=2, output_dir="out/examples/plate_%d" % n)
    start = time.perf_counter()
    sim.run()
    wall = time.perf_counter() - start
    T = period(sim.probes["time"], sim.probes["tip.velocity.y"])
    results.append((n, wall, 100.0 * abs(T / T_REF - 1.0)))
    print("H/dp %3d: T = %.5f s, error %.2f %%, %.1f s wall" % (n, T, results[-1][2], wall))

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt, matplotlib.ticker
except ImportError:
    raise SystemExit("matplotlib is not installed: no figure (pip install matplotlib)")
n, wall, error = map(np.array, zip(*results))
plt.loglog(wall, error, "o-"); [plt.annotate("H/dp %d" % n[k], (wall[k], error[k])) for k in range(len(n))]
plt.gca().xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter()); plt.xlabel("wall time [s]"); plt.ylabel("period error vs seed 000 [%]"); plt.title("oscillating plate, genog TLSPH")
plt.savefig("out/examples/plate_speed_vs_error.png", dpi=120)
