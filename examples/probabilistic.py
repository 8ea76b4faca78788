# %% [markdown]
# # Where would the monolith go? A probabilistic analysis from Python
#
# A notebook-sized walk through slideroute's Python package (`pip install "./python[pandas]"`
# from a checkout; pandas for the tables). Each `# %%` is a cell: run it in Jupyter, VS Code, or as a
# script (`python examples/probabilistic.py`). `SLIDEROUTE_SAMPLES` sets the number of samples
# (400 unless said).

# %%
import os

import numpy as np

import slideroute

SAMPLES = int(os.environ.get("SLIDEROUTE_SAMPLES", "400"))
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# %% [markdown]
# ## The scene and its route
# The paper-like monolith: a 10 m contact frame on a horizontal plane and two planes dipping
# 20° and 25°, 8 MN of water 1 m off the centre of mass, μ = 0.4.

# %%
scene = slideroute.Scene.from_file(os.path.join(ROOT, "scenes", "paper-like-uncertain.toml"))
route = scene.route()
print(route)  # one line: how it ended, when, how far
print(f"{route.reason_text} ({route.reason}) at t = {route.t_end_s:.3f} s after {route.travel_m:.3f} m")
print(f"factor of safety {route.factor_of_safety:.4f}")
last = {k: v[-1] for k, v in route.columns.items()}
print(f"final CM X = {last['x_m']:.3f} m, Z = {last['z_m']:.3f} m, yaw {last['theta_deg']:.2f}°")

# %% [markdown]
# ## What if the friction were lower, or the water acted elsewhere?
# A sweep: every combination, each route on its own core.

# %%
sweep = scene.sweep({"friction.mu_k": [0.30, 0.35, 0.40, 0.45], "loads.eccentricity_m": [0.0, 1.0]})
try:
    print(sweep.to_pandas()[["friction.mu_k", "loads.eccentricity_m", "factor_of_safety", "travel_m", "final_yaw_deg"]])
except ImportError:
    print({k: sweep[k] for k in ("friction.mu_k", "loads.eccentricity_m", "travel_m")})

# %% [markdown]
# ## The probabilistic analysis
# The scene's `[uncertain]` table gives μ, the eccentricity and the dip of plane 2 their
# distributions; a Latin hypercube of `SAMPLES` samples from seed 7.

# %%
print("uncertain:", scene.uncertain)
p = slideroute.probabilistic(scene, samples=SAMPLES, seed=7, travel_limit_m=5.0, rotation_limit_deg=10.0)
s = p.summary
lo, hi = s["probability_of_sliding"]["ci95"]
print(f"probability of sliding {p.probability_of_sliding:.3f} (95 % interval {lo:.3f} to {hi:.3f})")
print(f"travel over 5 m: {s['probability_travel_exceeds_limit']['value']:.3f}")
print(f"yaw over 10°:    {s['probability_rotation_exceeds_limit']['value']:.3f}")
for r in s["rank_correlations"]:
    print(f"  {r['key']:24s} ρ with the factor of safety {r['with_factor_of_safety']:+.2f}, with the travel {r['with_travel']:+.2f}")

# %% [markdown]
# ## Where the block ends
# The final positions of the samples that slid: the anchors belong where they gather.

# %%
slid = p.samples["factor_of_safety"] < 1.0
x, z = p.samples["final_x_m"][slid], p.samples["final_z_m"][slid]
print(f"{slid.sum()} of {len(slid)} slid; final X from {x.min():.2f} to {x.max():.2f} m, Z from {z.min():.2f} to {z.max():.2f} m")
print("median final position:", np.median(x).round(2), np.median(z).round(2))
