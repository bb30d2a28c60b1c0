#!/usr/bin/env python3
"""Continuum reference for the static bar of Bobaru et al. (2009), sections 2 and 5.

Solves the linear bond-based peridynamic bar (E = A = 1, infinite length, unit point loads
+1 at x = a and -1 at x = -a) by Fourier transform, independently of PeriAdapt's discrete solver:

    L u + b = 0,   (L u)(x) = int c(xi) (u(x + xi) - u(x)) / |xi| dxi over |xi| < delta
    u(x) - x / E = (1/pi) int_0^inf [cos k(a - x) - cos k(a + x)] (1/|L(k)| - 1/(E k^2)) dk

with |L(k)| = 2 c0 Cin(k delta) for the constant micromodulus (c0 = 2E/delta^2) and
2 c0 [Cin(k delta) - 1 + sin(k delta)/(k delta)] for the triangular one (c0 = 6E/delta^2),
Cin(z) = gamma + ln z - Ci(z). Prints the relative error of u at the probe (default x = 0.5)
for the horizons of Table II (delta = 1, 0.75, 2/3, 0.625). Needs python3-scipy (Debian).
Usage: scripts/bobaru_bar_fourier.py [probe]
"""
import sys
import warnings

import numpy as np
from scipy.integrate import IntegrationWarning, quad
from scipy.special import sici

E, A_LOAD = 1.0, 1.0


def cin(z):
    return np.euler_gamma + np.log(z) - sici(z)[1]


def symbol(k, delta, shape):
    """|L(k)|, with its small-k series where the closed form cancels badly."""
    z = k * delta
    if shape == "constant":
        return E * k * k * (1 - z * z / 24) if z < 1e-3 else 2 * (2 * E / delta**2) * cin(z)
    return (E * k * k * (1 - z * z / 60) if z < 1e-2
            else 2 * (6 * E / delta**2) * (cin(z) - 1 + np.sin(z) / z))


def relative_error(delta, shape, x):
    small_k = delta * delta / (24 if shape == "constant" else 60)  # limit of the bracket at k = 0
    f = lambda k: 1 / symbol(k, delta, shape) - 1 / (E * k * k) if k > 0 else small_k
    total = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)  # QAWF's cycle extrapolation
        for w, sign in ((A_LOAD - x, 1), (A_LOAD + x, -1)):
            total += sign * quad(f, 0, np.inf, weight="cos", wvar=w, limlst=200)[0]
    return total / np.pi / x


if __name__ == "__main__":
    probe = float(sys.argv[1]) if len(sys.argv) > 1 else 0.5
    print(f"continuum bond-based bar, loads at +-{A_LOAD}: relative error of u at x = {probe} (signed, %)")
    print(f"{'delta':>8} {'constant':>10} {'triangular':>11}")
    for delta in (1.0, 0.75, 2 / 3, 0.625):
        print(f"{delta:8.4f} {100 * relative_error(delta, 'constant', probe):+10.4f} "
              f"{100 * relative_error(delta, 'triangular', probe):+11.4f}")
