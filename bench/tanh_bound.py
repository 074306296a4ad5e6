#!/usr/bin/env python3
"""The coefficients and the error bound of bounded_tanh (src/core/vector_math.hpp).

    python3 bench/tanh_bound.py --fit     # the (3, 3) minimax fit on [0, 0.85²]
    python3 bench/tanh_bound.py [N]       # the bound of the shipped function, N points a branch

Needs mpmath (Debian: python3-mpmath). All arithmetic at 90 digits.

--fit: Remez's algorithm for R(z) = P(z)/Q(z), Q(0) = 1, approximating
f(z) = (tanh(√z)/√z − 1)/z in relative error on [0, 0.85²], started from the
Padé approximant; prints the levelled error and the coefficients rounded to
doubles (as written in vector_math.hpp).

The bound, for the doubles in the header, in units of ulp(tanh a), to first
order in 2⁻⁵³:
  rational branch (a < 0.77): |y − (tanh a − a)| for y = a·z·P/Q computed
    exactly with the double coefficients (the approximation), plus, for every
    operation v of the evaluation as written, ulp(v)/2·|∂y/∂v| (its rounding
    carried to y; the derivative by a 1e-20 relative perturbation), plus 1/2
    for the final a + y;
  exp branch (a ≥ 0.77), E = e^(2a), s = E + 1, q = 2/s: 0.511·ulp(E)·2/s²
    (glibc's exp), ulp(s)/2·2/s² (rounding s), ulp(q)/2, plus 1/2 for 1 − q.
Each maximised over N points of the branch, its ends and both sides of
tanh a = 1/2 (where ulp(tanh a) halves). Below 2⁻²⁷ the function returns x,
the correctly rounded value (the header says why).
"""
import sys

import mpmath as mp

mp.mp.dps = 90
U = mp.mpf(2) ** -53
CUT = mp.mpf("0.77")
COEFFS = {  # the doubles of bounded_tanh, as in the header
    "p": ["-0x1.5555555555555p-2", "-0x1.5ed88403e05cap-6", "-0x1.fea3333b76333p-13",
          "-0x1.29ea01f3b3aa6p-26"],
    "q": ["0x1.0p0", "0x1.db62325a53aaep-2", "0x1.91c67e4c09ce4p-6", "0x1.0ae56587bc992p-12"],
}
P = [mp.mpf(float.fromhex(c)) for c in COEFFS["p"]]
Q = [mp.mpf(float.fromhex(c)) for c in COEFFS["q"]]


def f(z):
    if z == 0:
        return mp.mpf(-1) / 3
    s = mp.sqrt(z)
    return (mp.tanh(s) / s - 1) / z


def ulp(v):
    """ulp of the binade of |v|, the larger one if v is within 1e-14 of a power of 2."""
    v = abs(v)
    return max(mp.mpf(2) ** (mp.floor(mp.log(v * (1 + k * mp.mpf(10) ** -14), 2)) - 52)
               for k in (-1, 1))


def remez(m, n, zmax, iterations=30):
    count = m + n + 2
    points = [zmax * (1 - mp.cos(mp.pi * i / (count - 1))) / 2 for i in range(count)]
    taylor = mp.taylor(mp.tanh, 0, 45)
    _, q_pade = mp.pade([taylor[2 * k + 1] for k in range(1, 22)], m, n)
    q_old = [q_pade[j] * zmax**j for j in range(n + 1)]  # in s = z/zmax
    for _ in range(iterations):
        for _ in range(20):  # the levelled error E enters through Q: iterate
            a = mp.matrix(count, count)
            b = mp.matrix(count, 1)
            for i, z in enumerate(points):
                s, fi = z / zmax, f(z)
                q_prev = sum(q_old[j] * s**j for j in range(n + 1))
                for j in range(m + 1):
                    a[i, j] = s**j
                for j in range(1, n + 1):
                    a[i, m + j] = -fi * s**j
                a[i, m + n + 1] = -((-1) ** i) * fi * q_prev
                b[i] = fi
            x = mp.lu_solve(a, b)
            p = [x[j] for j in range(m + 1)]
            q = [mp.mpf(1)] + [x[m + j] for j in range(1, n + 1)]
            level = x[m + n + 1]
            done = max(abs(q[j] - q_old[j]) for j in range(n + 1)) < mp.mpf(10) ** -80
            q_old = q
            if done:
                break

        def err(z):
            s = z / zmax
            return mp.polyval(p[::-1], s) / mp.polyval(q[::-1], s) / f(z) - 1

        grid = [zmax * i / 4000 for i in range(4001)]
        values = [err(z) for z in grid]
        extrema = [grid[0]]
        for i in range(1, 4000):
            if (values[i] - values[i - 1]) * (values[i + 1] - values[i]) <= 0:
                try:
                    z = mp.findroot(lambda t: mp.diff(err, t), grid[i])
                    extrema.append(z if 0 <= z <= zmax else grid[i])
                except Exception:  # complex or no convergence: the grid point  # noqa: BLE001
                    extrema.append(grid[i])
        extrema.append(grid[-1])
        if len(extrema) != count:  # keep an alternating set, the largest of each sign run
            chosen = []
            for z in sorted(extrema):
                if chosen and mp.sign(err(chosen[-1])) == mp.sign(err(z)):
                    if abs(err(z)) > abs(err(chosen[-1])):
                        chosen[-1] = z
                else:
                    chosen.append(z)
            while len(chosen) > count:
                chosen.pop(0 if abs(err(chosen[0])) < abs(err(chosen[-1])) else -1)
            extrema = chosen
        if len(extrema) != count:
            break
        points = extrema
        if abs(max(abs(err(z)) for z in points) / abs(level) - 1) < mp.mpf(10) ** -6:
            break
    return ([p[j] / zmax**j for j in range(m + 1)], [q[j] / zmax**j for j in range(n + 1)],
            level)


def rational(a, perturbed=None, h=mp.mpf(0)):
    """y = a·z·P/Q evaluated as bounded_tanh writes it; operation `perturbed` × (1 + h)."""
    ops = []

    def r(v):
        ops.append(v)
        return v * (1 + h) if perturbed == len(ops) - 1 else v

    z = r(a * a)
    z2 = r(z * z)
    p = r(r(P[0] + r(P[1] * z)) + r(z2 * r(P[2] + r(P[3] * z))))
    q = r(r(Q[0] + r(Q[1] * z)) + r(z2 * r(Q[2] + r(Q[3] * z))))
    y = r(r(r(a * z) * p) / q)
    return y, ops


def rational_bound(a):
    t = mp.tanh(a)
    y, ops = rational(a)
    h = mp.mpf(10) ** -20
    rounding = 0
    for i, v in enumerate(ops):
        if v != 0:
            rounding += abs((rational(a, i, h)[0] - y) / (h * v)) * ulp(v) / 2
    approximation = abs(y - (t - a))
    return (approximation + rounding) / ulp(t) + mp.mpf(0.5), approximation / ulp(t), rounding / ulp(t)


def exp_bound(a):
    t, e = mp.tanh(a), mp.exp(2 * a)
    s = e + 1
    q = 2 / s
    total = mp.mpf("0.511") * ulp(e) * 2 / s**2 + ulp(s) / 2 * 2 / s**2 + ulp(q) / 2
    return total / ulp(t) + mp.mpf(0.5)


def main():
    if "--fit" in sys.argv:
        p, q, level = remez(3, 3, mp.mpf("0.85") ** 2)
        print("levelled relative error", mp.nstr(level, 5))
        for name, cs in (("p", p), ("q", q)):
            for j, c in enumerate(cs):
                print(f"{name}{j} = {float(c).hex()}  ({mp.nstr(c, 20)})")
        return
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 2000
    half = mp.atanh(mp.mpf(0.5))
    points = [CUT * i / n for i in range(1, n)] + [CUT * (1 - mp.mpf(10) ** -15)]
    points += [half * (1 - mp.mpf(10) ** -12), half * (1 + mp.mpf(10) ** -12)]
    points += [mp.mpf(2) ** -k for k in range(1, 60)]
    worst = max((rational_bound(a) + (a,) for a in points), key=lambda w: w[0])
    print(f"rational branch, a < {CUT}: bound {mp.nstr(worst[0], 5)} ULP at a = "
          f"{mp.nstr(worst[3], 6)} (approximation {mp.nstr(worst[1], 3)}, roundings "
          f"{mp.nstr(worst[2], 3)}, final add 0.5)")
    points = [CUT + (22 - CUT) * (mp.mpf(i) / n) ** 3 for i in range(n + 1)]
    worst = max((exp_bound(a), a) for a in points)
    print(f"exp branch, a >= {CUT}: bound {mp.nstr(worst[0], 5)} ULP at a = {mp.nstr(worst[1], 6)}")


if __name__ == "__main__":
    main()
