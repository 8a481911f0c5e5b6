#!/usr/bin/env python3
"""The front's normal direction in 1-D (docs/adapt.md): P1 interpolation of
u = tanh(50 s) on [-0.1, 0.1] with n intervals. Prints, for each n, the L2
error times n^2 (constant in the asymptotic regime) of the grid that
equidistributes |u''|^(2/5) (the L2-optimal density of the continuous-mesh
theory, which the anisotropic metric asks for across the front) and, for a
few n, of that grid after a coordinate descent on the error itself.

    bench/aniso_1d.py
"""
import math

A, L = 50.0, 0.1


def u(s):
    return math.tanh(A * s)


def u2(s):
    t = math.tanh(A * s)
    return abs(2 * A * A * t * (1 - t * t))


def err2(xs):
    """Squared L2 error: 16 sub-intervals per interval, 2-point Gauss on each."""
    tot = 0.0
    for a, b in zip(xs, xs[1:]):
        ua, ub = u(a), u(b)
        for i in range(16):
            for g in (-0.5773502691896257, 0.5773502691896257):
                t = (i + 0.5 + 0.5 * g) / 16
                e = u(a + t * (b - a)) - (ua + t * (ub - ua))
                tot += e * e * (b - a) / 32
    return tot


def equidistributed(n, q=0.4, m=4000):
    xs = [-L + 2 * L * i / m for i in range(m + 1)]
    d = [u2(x) ** q + 1e-9 for x in xs]
    c = [0.0]
    for i in range(m):
        c.append(c[-1] + 0.5 * (d[i] + d[i + 1]) * (xs[i + 1] - xs[i]))
    out, j = [-L], 0
    for k in range(1, n):
        target = c[-1] * k / n
        while c[j + 1] < target:
            j += 1
        out.append(xs[j] + (target - c[j]) / (c[j + 1] - c[j]) * (xs[j + 1] - xs[j]))
    return out + [L]


def descend(xs, sweeps=60):
    xs, e = xs[:], err2(xs)
    for _ in range(sweeps):
        for i in range(1, len(xs) - 1):
            for step in (0.3, 0.1, 0.03):
                for sign in (1, -1):
                    y = xs[:]
                    y[i] += sign * step * min(xs[i + 1] - xs[i], xs[i] - xs[i - 1])
                    ey = err2(y)
                    if ey < e:
                        xs, e = y, ey
    return xs, e


if __name__ == "__main__":
    print("n, equidistributed L2 error * n^2 * 1e3, after descent * n^2 * 1e3")
    for n in (8, 10, 12, 13, 14, 16, 20, 24, 32, 48, 64, 128, 256):
        g = equidistributed(n)
        row = f"{n}, {math.sqrt(err2(g)) * n * n * 1e3:.1f}"
        if n in (12, 16, 24, 48):
            row += f", {math.sqrt(descend(g)[1]) * n * n * 1e3:.1f}"
        print(row)
