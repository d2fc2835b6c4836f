#!/usr/bin/env python3
"""Regenerates (or checks) the elastic-layer Couette references of tests/data:
couette_elastic_periodic.csv and couette_elastic_startup.csv (docs/references.md,
"Elastic-layer Couette flow": setup, equations and the closed form).

Half channel 0 <= y <= H = a + L_f: neo-Hookean solid (shear modulus G, Kelvin-Voigt viscosity
mu_s) below y = a, fluid (mu_f) above, density rho in both; u(0, t) = 0, u(H, t) = V sin(w t).

* Periodic state: the closed form u = Im[U(y) e^{i w t}] of docs/references.md.
* Start-up from rest: the periodic state plus a transient. The transient is that of a
  second-order finite-difference semi-discretisation (u at the nodes y_i = i h, the shear
  stress at the midpoints, the shear strain gamma of the solid midpoints as a state variable,
  gamma_t = u_y), which is linear with constant coefficients: x' = A x. Starting from rest,
  the discrete transient is x(0) = -x_p(0), x_p the discrete periodic state (solved in complex
  arithmetic), and is integrated exactly in time by the eigen-decomposition of A. Two grids
  (N and 2N cells) and Richardson extrapolation (second order) give the tabulated values.

Usage: /usr/bin/python3 tests/data/couette_elastic_reference.py [--check | OUTDIR]
  --check   compare with the committed files (exit 1 beyond 3e-6, i.e. the 6-decimal rounding
            of the files plus the error of the start-up values)
  OUTDIR    write the two CSV files there (default: print the largest differences only)
Needs numpy and scipy (Debian python3-numpy, python3-scipy); about a minute on one core.
"""
import os
import sys

import numpy as np
import scipy.linalg

V, W, G, MU_F, MU_S, RHO, A_S, L_F = 1.0, np.pi, 5.0, 1.0, 0.0, 1.0, 0.5, 0.5  # docs/references.md
H = A_S + L_F
Y = np.linspace(0.0, H, 41)
T_PERIODIC = [0.2 * k for k in range(10)]
T_STARTUP = [0.5, 1.0, 2.0, 2.8, 4.0, 4.8]


def periodic_amplitude(y):
    """U(y) of u = Im[U e^{i w t}] (closed form)."""
    mu_star = MU_S + G / (1j * W)
    ks, kf = np.sqrt(1j * W * RHO / mu_star), np.sqrt(1j * W * RHO / MU_F)
    beta = mu_star * ks / (MU_F * kf)
    amp = V / (np.sinh(ks * A_S) * np.cosh(kf * L_F) + beta * np.cosh(ks * A_S) * np.sinh(kf * L_F))
    y = np.asarray(y, dtype=float)
    return np.where(y <= A_S, amp * np.sinh(ks * y),
                    amp * (np.sinh(ks * A_S) * np.cosh(kf * (y - A_S)) + beta * np.cosh(ks * A_S) * np.sinh(kf * (y - A_S))))


def periodic(y, t):
    return np.imag(periodic_amplitude(y) * np.exp(1j * W * t))


def discrete_transient(n, times):
    """Transient u at the nodes (0..n) of the n-cell semi-discretisation, at the given times."""
    h = H / n
    ns = int(round(A_S / h))  # solid midpoints 0..ns-1; the interface is node ns
    assert abs(ns * h - A_S) < 1e-12, "the interface must be a node"
    nu = n - 1  # interior nodes 1..n-1
    size = nu + ns
    A = np.zeros((size, size))
    b = np.zeros(size)  # the wall's velocity enters as b * u_wall(t)

    def tau_row(m):
        """Coefficients of the midpoint m+1/2 stress in (u interior, gamma), and of u_wall."""
        c, cw = np.zeros(size), 0.0
        mu = MU_S if m < ns else MU_F
        for node, sign in ((m + 1, 1.0), (m, -1.0)):
            if 1 <= node <= n - 1:
                c[node - 1] += sign * mu / h
            elif node == n:
                cw += sign * mu / h
        if m < ns:
            c[nu + m] += G
        return c, cw

    for i in range(1, n):
        up, upw = tau_row(i)
        dn, dnw = tau_row(i - 1)
        A[i - 1] = (up - dn) / (RHO * h)
        b[i - 1] = (upw - dnw) / (RHO * h)
    for m in range(ns):  # gamma_t = (u_{m+1} - u_m) / h
        for node, sign in ((m + 1, 1.0), (m, -1.0)):
            if 1 <= node <= n - 1:
                A[nu + m, node - 1] += sign / h
            elif node == n:
                b[nu + m] += sign / h
    # discrete periodic state x_p = Im[X e^{iwt}] with u_wall = Im[V e^{iwt}]: (iw - A) X = b V
    X = np.linalg.solve(1j * W * np.eye(size) - A, b * V)
    x0 = -np.imag(X)  # start from rest: transient(0) = -x_p(0)
    lam, vec = scipy.linalg.eig(A)
    coef = np.linalg.solve(vec, x0)
    out = []
    for t in times:
        x = np.real(vec @ (coef * np.exp(lam * t)))
        out.append(np.concatenate(([0.0], x[:nu], [0.0])))  # no transient on the walls
    return np.array(out)


def startup():
    n = 800
    coarse = discrete_transient(n, T_STARTUP)
    fine = discrete_transient(2 * n, T_STARTUP)
    yc, yf = np.linspace(0, H, n + 1), np.linspace(0, H, 2 * n + 1)
    rows = []
    for k, t in enumerate(T_STARTUP):
        c = np.interp(Y, yc, coarse[k])
        f = np.interp(Y, yf, fine[k])
        rows.append(periodic(Y, t) + f + (f - c) / 3.0)  # Richardson, second order
    return np.array(rows)


def write(path, header, cols, fmt):
    with open(path, "w") as f:
        f.write(",".join(header) + "\n")
        for r in range(len(Y)):
            f.write(",".join(fmt % c[r] for c in cols) + "\n")


def read(path):
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    return data[:, 1:].T


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    per = np.array([periodic(Y, t) for t in T_PERIODIC])
    st = startup()
    if len(sys.argv) > 1 and sys.argv[1] != "--check":
        out = sys.argv[1]
        os.makedirs(out, exist_ok=True)
        write(os.path.join(out, "couette_elastic_periodic.csv"), ["y"] + [f"u_t{t:.1f}" for t in T_PERIODIC],
              [Y] + list(per), "%.8f")
        write(os.path.join(out, "couette_elastic_startup.csv"), ["y"] + [f"u_t{t:g}" if t != int(t) else f"u_t{t:.1f}" for t in T_STARTUP],
              [Y] + list(st), "%.6f")
        return 0
    d_per = np.abs(per - read(os.path.join(here, "couette_elastic_periodic.csv"))).max()
    d_st = np.abs(st - read(os.path.join(here, "couette_elastic_startup.csv"))).max()
    print(f"largest difference to the committed files: periodic {d_per:.2e}, start-up {d_st:.2e}")
    return 0 if d_per <= 3e-6 and d_st <= 3e-6 else 1


if __name__ == "__main__":
    sys.exit(main())
