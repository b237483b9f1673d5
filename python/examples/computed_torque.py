"""Computed-torque control of the Panda arm: τ = M(q) (a_d + Kp e + Kd ė) + C(q, v) v + g(q),
which is the inverse dynamics at the commanded acceleration (one `rnea` call per step), with
the arm simulated by its forward dynamics (`aba`) and semi-implicit Euler steps.

    python python/examples/computed_torque.py
"""
import numpy as np

import rne

model = rne.load("panda-arm", kernels=["inverse_dynamics", "forward_dynamics"])
dt, steps = 1e-3, 3000
kp, kd = 400.0, 40.0  # critically damped: kd = 2 sqrt(kp)
w = 2 * np.pi * 0.5


def desired(t):
    """A sine about a bent pose for every joint: position, velocity, acceleration."""
    amplitude = np.linspace(0.4, 0.1, model.nv)
    home = np.array([0.0, -0.5, 0.0, -2.0, 0.0, 1.6, 0.8])
    return home + amplitude * np.sin(w * t), amplitude * w * np.cos(w * t), -amplitude * w**2 * np.sin(w * t)


q, v = desired(0.0)[0] + 0.05, np.zeros(model.nv)  # start 0.05 rad off the trajectory
worst = 0.0
for k in range(steps):
    qd, vd, ad = desired(k * dt)
    if k * dt > 1.0:
        worst = max(worst, np.max(np.abs(qd - q)))
    a_command = ad + kp * (qd - q) + kd * (vd - v)
    tau = model.rnea(q, v, a_command)  # M a_command + C v + g
    a = model.aba(q, v, tau)
    v = v + dt * a
    q = q + dt * v

print(f"{model.name}: largest tracking error after 1 s: {worst:.2e} rad")
assert worst < 1e-3, "computed-torque control should track the trajectory"
