"""Fits ortho9 problems with scipy.optimize.least_squares(method='lm'), for scipy_compare.rs.

Reads {"problems": [[[x, y, z], ...], ...], "tol": t, "repeats": r} (readings in g) on stdin; prints
{"seconds": median CPU time (time.process_time) for all problems, "iterations": mean Jacobian evaluations,
"costs": [sum of squared residuals per problem]}. The stopping rule is shared::ortho9's: a step of at most
tol (|x| + tol) (xtol); ftol and gtol sit at the smallest value MINPACK accepts.
"""
import json
import sys
import time

import numpy as np
from scipy.optimize import least_squares


def model(p):
    a_yz, a_zy, a_zx, s_x, s_y, s_z, o_x, o_y, o_z = p
    m = np.array([[s_x, a_yz * s_y, a_zy * s_z], [0.0, s_y, a_zx * s_z], [0.0, 0.0, s_z]])
    return m, np.array([o_x, o_y, o_z])


def residuals(p, readings):
    m, o = model(p)
    return np.linalg.norm((readings - o) @ m.T, axis=1) - 1.0


def jacobian(p, readings):
    a_yz, a_zy, a_zx, s_x, s_y, s_z, _, _, _ = p
    m, o = model(p)
    centered = readings - o
    a = centered @ m.T
    u = a / np.linalg.norm(a, axis=1)[:, None]
    x, y, z = centered[:, 0], centered[:, 1], centered[:, 2]
    jac = np.empty((len(readings), 9))
    jac[:, 0] = u[:, 0] * s_y * y
    jac[:, 1] = u[:, 0] * s_z * z
    jac[:, 2] = u[:, 1] * s_z * z
    jac[:, 3] = u[:, 0] * x
    jac[:, 4] = u[:, 0] * a_yz * y + u[:, 1] * y
    jac[:, 5] = u[:, 0] * a_zy * z + u[:, 1] * a_zx * z + u[:, 2] * z
    jac[:, 6:9] = -(u @ m)
    return jac


def main():
    request = json.load(sys.stdin)
    problems = [np.array(p) for p in request["problems"]]
    start = np.array([0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    floor = 1e-15  # MINPACK refuses tolerances below the machine epsilon
    seconds = []
    for _ in range(request["repeats"]):
        began = time.process_time()
        results = [
            least_squares(
                residuals, start, jac=jacobian, args=(r,), method="lm", xtol=request["tol"], ftol=floor, gtol=floor
            )
            for r in problems
        ]
        seconds.append(time.process_time() - began)
    costs = [float(np.sum(result.fun**2)) for result in results]
    iterations = sum(result.njev for result in results) / len(results)
    json.dump({"seconds": sorted(seconds)[len(seconds) // 2], "iterations": iterations, "costs": costs}, sys.stdout)


if __name__ == "__main__":
    main()
