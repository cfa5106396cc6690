#!/usr/bin/env python3
"""Tutorial: plot the beam's tip deflection (out/beam/probes.csv) against
Euler-Bernoulli theory. Usage: python3 docs/tutorial/plot_tip.py [out/beam]"""
import csv
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "out/beam"
rows = list(csv.DictReader(open(f"{out}/probes.csv")))
t = [float(r["time"]) for r in rows]
uy = [1000 * float(r["tip.displacement.y"]) for r in rows]

# Euler-Bernoulli, first mode: omega = kw^2 sqrt(E' I / (rho A)), plane strain E' = E / (1 - nu^2).
E, nu, rho, H, kw, v_tip = 2.0e6, 0.3975, 1000.0, 0.02, 9.375, 0.57
omega = kw ** 2 * math.sqrt(E / (1 - nu ** 2) * H ** 3 / 12 / (rho * H))
theory = [1000 * v_tip / omega * math.sin(omega * x) for x in t]

plt.plot(t, uy, label="mfsd")
plt.plot(t, theory, "k--", label=f"Euler-Bernoulli (period {2 * math.pi / omega:.3f} s)")
plt.xlabel("t [s]")
plt.ylabel("tip deflection [mm]")
plt.legend()
plt.savefig(f"{out}/tip.png", dpi=100)
print(f"wrote {out}/tip.png")
