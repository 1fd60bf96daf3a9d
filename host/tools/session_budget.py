#!/usr/bin/env python3
"""What a minute allows the adaptive session (host/src/procedure/stop_rule.rs, docs/guide.md).

The linear model of host/tools/drift_order.py, with each capture weighed by its length (a mean over T s
errs by N / sqrt(T) per axis, N = 283 ug/sqrt(Hz), the simulated MPU-6050's two-sided white noise) and the
die warming as the realistic simulated sensor does (5 degC, a 240 s time constant, from power-on). Prints:
- the true error's 95th percentile over its rms at the mean temperature (TAIL_OVER_RMS) and its
  effective degrees of freedom, for the order of procedure/drift.rs with captures of equal length;
- the rms at the mean and at the end temperature when every second of a minute averages (no turns, no
  verification): the floor of one minute's session on this sensor.

Usage: python3 host/tools/session_budget.py
"""
import math

import numpy as np

import drift_order as d

N_MG = 0.283  # mg sqrt(s): a mean's standard error per axis after one second of averaging
ORDER = ["+Z", "+X-Y+Z", "+X+Y+Z", "+X+Y-Z", "-X+Y-Z", "-X-Y-Z", "-X-Y+Z", "+X-Y-Z", "-Z", "-X", "-Y", "+X", "+Y",
         "-X+Y+Z"]


def die_c(t):
    return 5.0 * (1.0 - np.exp(-t / 240.0))


def covariance(lengths, gaps_s):
    """The twelve parameters' covariance (mg units) and the captures' temperatures less their mean."""
    captures = ORDER + [ORDER[0]]
    clock, centres = 0.0, []
    for i, name in enumerate(captures):
        if i:
            clock += gaps_s(captures[i - 1], name)
        centres.append(clock + lengths[i] / 2)
        clock += lengths[i]
    temps = die_c(np.array(centres))
    rows = np.array([d.design_row(d.UPS[n], t) for n, t in zip(captures, temps - temps.mean())])
    information = (rows * (np.array(lengths) / N_MG**2)[:, None]).T @ rows
    information[9:, 9:] += np.eye(3) / d.PRIOR_MG_PER_C**2
    return np.linalg.inv(information), clock, temps.mean()


def error_form(covariance_mg, t):
    """Eigenvalues of the true error's square (mean over fresh orientations) as a form in unit normals."""
    g = np.array([d.design_row(u, t) for u in d.FRESH])
    root = np.linalg.cholesky(covariance_mg)
    return np.linalg.eigvalsh(root.T @ (g.T @ g / len(g)) @ root)


def main():
    cov, _, _ = covariance([1.6] * 15, lambda a, b: d.turn_s(a, b) + 0.25)
    weights = error_form(cov, 0.0)
    draws = np.sqrt((np.random.default_rng(0).normal(size=(200_000, 12)) ** 2) @ weights)
    rms = math.sqrt(weights.sum())
    dof = weights.sum() ** 2 / (weights**2).sum()
    print(f"at the mean temperature: 95th percentile {np.quantile(draws, 0.95) / rms:.2f} x the rms, {dof:.1f} dof")
    lengths = [60.0 / 15] * 15
    cov, clock, mean_c = covariance(lengths, lambda a, b: 0.0)
    at = [math.sqrt(error_form(cov, t).sum()) for t in (0.0, die_c(clock) - mean_c)]
    print(f"a minute of averaging alone: {at[0]:.3f} mg rms at the mean temperature, {at[1]:.3f} mg at the end")


if __name__ == "__main__":
    main()
