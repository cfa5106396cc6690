"""Fields mid-run: a callback every 10 ms reads the plate's velocity and von
Mises arrays (views of the solver's memory, no copy) and keeps their maxima.
  python3 examples/python/field_callback.py [--coarse]  -> out/examples/plate_fields.png"""
import os, sys
import numpy as np
import mfsd

coarse = "--coarse" in sys.argv
here = os.path.dirname(os.path.abspath(__file__))
scene = mfsd.Scene.from_file(os.path.join(here, "..", "..", "configs", "oscillating_plate_2d.json"),
                             set={"constants.H_over_dp": 6 if coarse else 20, "solver.end_time": 0.1 if coarse else 0.6})
sim = mfsd.Simulation(scene, threads=2, output_dir="out/examples/plate_fields")
history = []

def watch(s):
    speed = np.linalg.norm(s.fields["velocity"], axis=1)
    history.append((s.time, speed.max(), s.fields["von_mises"].max()))

sim.run(every=0.01, callback=watch)
x = sim.fields["position"]
tip = np.argmax(x[:, 0])  # the particle furthest along the plate
print("tip particle %d (scene index %d) at %s" % (tip, sim.fields["id"][tip], x[tip]))
np.save("out/examples/plate_fields/final_velocity.npy", sim.fields["velocity"])

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    raise SystemExit("matplotlib is not installed: no figure (pip install matplotlib)")
t, vmax, smax = map(np.array, zip(*history))
fig, ax = plt.subplots(2, 1, sharex=True)
ax[0].plot(t, vmax); ax[0].set_ylabel("max |v| [m/s]")
ax[1].plot(t, smax / 1e3); ax[1].set_ylabel("max von Mises [kPa]"); ax[1].set_xlabel("t [s]")
fig.savefig("out/examples/plate_fields.png", dpi=120)
