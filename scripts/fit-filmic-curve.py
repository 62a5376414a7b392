#!/usr/bin/env python3
"""Fit the curve of Blender's Filmic "Base Contrast" look for core/ViewTransform.cpp.

    scripts/fit-filmic-curve.py [SPI1D]

Reads the 1D LUT filmic_to_0-70_1-03.spi1d of Blender's OpenColorIO
configuration (default: Debian's blender package's copy), whose input is
Filmic's log encoding in [0, 1] and output the sRGB-encoded display value,
and prints the least-squares Chebyshev coefficients (degree 10, on t = 2x - 1)
with the largest and RMS error in 8-bit codes. Pure Python, no NumPy.
"""
import math
import sys

DEFAULT = "/usr/share/blender/datafiles/colormanagement/filmic/filmic_to_0-70_1-03.spi1d"
DEGREE = 10


def read_lut(path):
    text = open(path).read()
    return [float(v) for v in text.split("{")[1].split("}")[0].split()]


def chebyshev(t, degree):
    values = [1.0, t]
    for _ in range(2, degree + 1):
        values.append(2.0 * t * values[-1] - values[-2])
    return values[: degree + 1]


def solve(matrix, rhs):
    """Gaussian elimination with partial pivoting."""
    m = len(rhs)
    a = [row[:] + [rhs[i]] for i, row in enumerate(matrix)]
    for c in range(m):
        p = max(range(c, m), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        for r in range(m):
            if r != c:
                f = a[r][c] / a[c][c]
                for k in range(c, m + 1):
                    a[r][k] -= f * a[c][k]
    return [a[i][m] / a[i][i] for i in range(m)]


def main():
    lut = read_lut(sys.argv[1] if len(sys.argv) > 1 else DEFAULT)
    n = len(lut)
    rows = [chebyshev(2.0 * i / (n - 1) - 1.0, DEGREE) for i in range(n)]
    normal = [[sum(r[i] * r[j] for r in rows) for j in range(DEGREE + 1)] for i in range(DEGREE + 1)]
    rhs = [sum(r[i] * lut[k] for k, r in enumerate(rows)) for i in range(DEGREE + 1)]
    coefficients = solve(normal, rhs)
    errors = [sum(c * v for c, v in zip(coefficients, r)) - lut[k] for k, r in enumerate(rows)]
    print("coefficients:", ", ".join(repr(c) for c in coefficients))
    print("max error %.3f codes, rms %.3f codes" % (max(abs(e) for e in errors) * 255,
                                                  math.sqrt(sum(e * e for e in errors) / n) * 255))


if __name__ == "__main__":
    main()
