#!/usr/bin/env python3
"""Searches the order of the adaptive session's fourteen positions (host/src/procedure/drift.rs).

A linear model of the session: the reading at up u_i is (I + E) u_i + o + c t_i, with E the six
terms of an upper-triangular matrix, o the offset and c its drift per degree, t_i the die temperature
of capture i less the session's mean. The twelve parameters are fitted from |a| - 1 ~ u^T (E u + o +
c t), with each mean known to SIGMA_MG and the drift prior of 1 mg/degC; the error predicted at
fresh orientations is that design's. The order is scored by that error at the end temperature
(after three verifications), of all fourteen positions and of the first thirteen (where a session
may stop), by the error at the mean temperature, and by its length (turns at a hand's pace).

Usage: python3 host/tools/drift_order.py [restarts]   (about 30 s a restart)
"""
import itertools
import math
import random
import sys

import numpy as np

SIGMA_MG = 0.21  # a mean's standard error per axis (the stop rule's goal)
PRIOR_MG_PER_C = 1.0  # drift.rs SLOPE_PRIOR_G_PER_C
WARMING_C_PER_S = 1.0 / 60  # a board just powered on (the realistic simulated sensor)
CAPTURE_S = 1.9  # a capture to that goal at 400 ug/sqrt(Hz)
DETECT_S = 0.43  # from the end of a turn to the capture's start (live windows)
VERIFY_S = 12.0  # three verifications after the last capture
TURN_BASE_S, TURN_DPS = 0.6, 150.0  # the simulated hand (simulated_hand.rs)


def positions():
    ups = {}
    for axis, name in enumerate("XYZ"):
        for sign in (1, -1):
            up = [0.0, 0.0, 0.0]
            up[axis] = sign
            ups[("+" if sign > 0 else "-") + name] = np.array(up)
    for signs in itertools.product((1, -1), repeat=3):
        name = "".join(("+" if s > 0 else "-") + a for s, a in zip(signs, "XYZ"))
        ups[name] = np.array(signs, float) / math.sqrt(3)
    return ups


UPS = positions()
FRESH = np.random.default_rng(0).normal(size=(400, 3))
FRESH /= np.linalg.norm(FRESH, axis=1)[:, None]


def turn_s(a, b):
    degrees = math.degrees(math.acos(float(np.clip(UPS[a] @ UPS[b], -1, 1))))
    return TURN_BASE_S + degrees / TURN_DPS


def design_row(u, t):
    x, y, z = u
    return np.array([x * x, y * y, z * z, x * y, x * z, y * z, x, y, z, x * t, y * t, z * t])


def score(order):
    """(seconds, error at the mean temperature, error at the end temperature), in s and mg."""
    captures = order + [order[0]]  # the closing capture
    clock, centres = 0.0, []
    for i, name in enumerate(captures):
        if i:
            clock += turn_s(captures[i - 1], name) + DETECT_S
        centres.append(clock + CAPTURE_S / 2)
        clock += CAPTURE_S
    temps = np.array(centres) * WARMING_C_PER_S
    rows = np.array([design_row(UPS[n], t) for n, t in zip(captures, temps - temps.mean())])
    information = rows.T @ rows / SIGMA_MG**2
    information[9:, 9:] += np.eye(3) / PRIOR_MG_PER_C**2
    covariance = np.linalg.inv(information)

    def predicted(t):
        g = np.array([design_row(u, t) for u in FRESH])
        return math.sqrt(np.mean(np.einsum("ij,jk,ik->i", g, covariance, g)))

    end = (clock + VERIFY_S) * WARMING_C_PER_S - temps.mean()
    return clock, predicted(0.0), predicted(end)


def objective(order):
    seconds, at_mean, at_end = score(order)
    _, at_mean13, at_end13 = score(order[:13])
    return at_end + at_end13 + 0.5 * (at_mean + at_mean13) + seconds / 60


def anneal(rng, steps=6000):
    rest = [n for n in UPS if n != "+Z"]
    rng.shuffle(rest)
    order = ["+Z"] + rest
    value = objective(order)
    best, best_value, temperature = order[:], value, 0.3
    for _ in range(steps):
        i, j = sorted(rng.sample(range(1, 14), 2))
        candidate = order[:]
        if rng.random() < 0.5:
            candidate[i], candidate[j] = candidate[j], candidate[i]
        else:
            candidate[i : j + 1] = candidate[i : j + 1][::-1]
        v = objective(candidate)
        if v < value or rng.random() < math.exp((value - v) / temperature):
            order, value = candidate, v
            if v < best_value:
                best, best_value = candidate[:], v
        temperature *= 0.999
    return best_value, best


def main():
    restarts = int(sys.argv[1]) if len(sys.argv) > 1 else 12
    rng = random.Random(1)
    found = sorted(anneal(rng) for _ in range(restarts))
    for value, order in found[:3]:
        seconds, at_mean, at_end = score(order)
        print(f"{value:.3f}  {seconds:.1f} s  {at_mean:.3f} / {at_end:.3f} mg  " + ",".join(order))


if __name__ == "__main__":
    main()
