#!/usr/bin/env python3
"""Regenerates the scenes under scenes/ (committed, so users need not run this).

Plain Python (no numpy here). Shapes are drawn with 4x4 supersampling so that edges carry
the partial grey levels a real optical image would.
"""
import math
import random
import os
import struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")
SS = 4  # supersampling per axis


def write_pgm(path, width, height, values, maxval=255):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n%d\n" % (width, height, maxval))
        if maxval < 256:
            f.write(bytes(values))
        else:
            f.write(b"".join(struct.pack(">H", v) for v in values))


def write_pfm(path, width, height, values):
    """Grey PFM, little-endian (negative scale), rows stored bottom to top."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(b"Pf\n%d %d\n-1.0\n" % (width, height))
        for y in reversed(range(height)):
            f.write(struct.pack("<%df" % width, *values[y * width:(y + 1) * width]))


def render(width, height, inside):
    """Coverage in [0, 1] of each pixel by the shape `inside(u, v)`, u and v in pixel units."""
    out = []
    for y in range(height):
        for x in range(width):
            hits = sum(inside(x + (i + 0.5) / SS, y + (j + 0.5) / SS) for j in range(SS) for i in range(SS))
            out.append(hits / (SS * SS))
    return out


def to8(coverage, lo=0, hi=255):
    return [int(round(lo + (hi - lo) * c)) for c in coverage]


def segment_distance(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    t = max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)))
    return math.hypot(px - (ax + t * dx), py - (ay + t * dy))


STROKE = 2.2  # half-width of a letter stroke, pixels


def letter_a(u, v):
    return (segment_distance(u, v, 16, 4, 6.5, 28) < STROKE or segment_distance(u, v, 16, 4, 25.5, 28) < STROKE
            or (abs(v - 19) < STROKE * 0.8 and 9.5 < u < 22.5))


def ring(u, v, cx=16, cy=16, rx=10.5, ry=10.5):
    # Distance to an ellipse, approximated by scaling to a circle: exact for a circle.
    return abs(math.hypot((u - cx) * ry / rx, v - cy) - ry) < STROKE


# As in a typeface, the round letters differ beyond their distinguishing strokes: C is narrower
# than O, Q's bowl sits higher and flatter. Nested shapes (C inside O inside Q) would make the
# rank-weighted recogniser's scores tie over a full pass.
def letter_c(u, v):
    angle = math.degrees(math.atan2(v - 16, u - 17))
    return ring(u, v, cx=17, rx=9.0, ry=10.5) and not (-45 < angle < 45)


def letter_o(u, v):
    return ring(u, v)


def letter_q(u, v):
    return ring(u, v, cy=15, rx=10.5, ry=9.0) or segment_distance(u, v, 19, 18, 27, 28) < STROKE


def natural(n, seed=7):
    """A landscape-like scene: fractal value noise (octaves of bilinearly interpolated random
    grids, amplitude halving per octave) for clouds and ground, a bright sky toward the top,
    and a darker hill whose ridge is itself fractal. Seeded, so it regenerates identically."""
    rng = random.Random(seed)

    def octave(cells):
        grid = [[rng.random() for _ in range(cells + 1)] for _ in range(cells + 1)]

        def sample(u, v):
            gx, gy = u * cells / n, v * cells / n
            x0, y0 = int(gx), int(gy)
            fx, fy = gx - x0, gy - y0
            top = grid[y0][x0] * (1 - fx) + grid[y0][x0 + 1] * fx
            bottom = grid[y0 + 1][x0] * (1 - fx) + grid[y0 + 1][x0 + 1] * fx
            return top * (1 - fy) + bottom * fy
        return sample

    octaves = [(octave(2 ** k), 0.5 ** k) for k in range(1, 6)]
    ridge = [octave(2 ** k) for k in range(1, 5)]
    values = []
    for y in range(n):
        for x in range(n):
            noise = sum(a * f(x, y) for f, a in octaves) / sum(a for _, a in octaves)
            height = n * (0.55 + 0.25 * (sum(0.5 ** k * r(x, 0) for k, r in enumerate(ridge)) - 0.6))
            if y < height:
                value = 0.55 + 0.35 * (1 - y / n) + 0.25 * (noise - 0.5)
            else:
                value = 0.12 + 0.3 * noise
            values.append(int(round(255 * min(1.0, max(0.0, value)))))
    return values


def union(*shapes):
    return lambda u, v: any(s(u, v) for s in shapes)


def finger(x, top, width=3.0, bottom=17, tilt=0.0):
    """A finger from `bottom` up to `top`, leaning by `tilt` pixels per pixel of height."""
    def inside(u, v):
        if not (top <= v < bottom + 1):
            return False
        centre = x + tilt * (bottom - v)
        return abs(u - centre) < width / 2 or math.hypot(u - centre, v - top) < width / 2
    return inside


def rounded_rect(x0, y0, x1, y1, r):
    """The rectangle [x0, x1) x [y0, y1) with corners rounded to radius r."""
    def inside(u, v):
        if not (x0 <= u < x1 and y0 <= v < y1):
            return False
        cx = min(max(u, x0 + r), x1 - r)
        cy = min(max(v, y0 + r), y1 - r)
        return math.hypot(u - cx, v - cy) <= r
    return inside


def side_finger(y, tip, knuckle, width=3.0):
    """A finger pointing left, along row y, from `knuckle` out to a rounded tip at `tip`."""
    return lambda u, v: (tip <= u < knuckle and abs(v - y) < width / 2) or math.hypot(u - tip, v - y) < width / 2


# Six hand signs that the rank rule can tell apart. Under ranks (r = b_max / b) a template lying
# almost wholly inside another ties it over every full pass of events, so no sign may be another
# plus extra fingers: the fist is wider and squatter than every hand's body, the flat palm holds
# its fingers together as one block, victory spreads its two fingers wider than that block, rock's
# horns leave the body's edges wider still, point aims sideways from a tall narrow hand and the
# thumbs-up hand lies on its side. Centred on their centroids no sign has more than 87 % of its
# pixels inside another (`scripts/paper_table1` checks 10 distorted instances of each).
HAND_BODY = rounded_rect(11, 15, 22, 27, 2.5)
HAND_SIGNS = {
    "fist": rounded_rect(6, 12, 26, 25, 5),
    "palm": union(rounded_rect(11, 15, 22, 28, 2), rounded_rect(11, 4, 22, 16, 1.5),
                  finger(9, 14, tilt=0.9, bottom=24, width=3.2)),
    "point": union(rounded_rect(16, 5, 26, 28, 3), side_finger(13, 1, 17, width=4.0)),
    "victory": union(HAND_BODY, finger(14.5, 3, bottom=15, tilt=-0.45), finger(18.5, 3, bottom=15, tilt=0.45)),
    "thumbs_up": union(rounded_rect(8, 16, 26, 27, 3), finger(11, 3, width=4.0, bottom=17)),
    "rock": union(HAND_BODY, finger(12.5, 3, bottom=15, tilt=-0.7, width=3.4),
                  finger(20.5, 4, bottom=15, tilt=0.7, width=3.4)),
}


def binary(coverage):
    return [255 if c >= 0.5 else 0 for c in coverage]


def main():
    for name, shape in (("A", letter_a), ("C", letter_c), ("O", letter_o), ("Q", letter_q)):
        coverage = render(32, 32, shape)
        write_pgm(os.path.join(ROOT, "letters", name + ".pgm"), 32, 32, to8(coverage))
        # The recogniser's template: the letter's pixels at least half covered.
        write_pgm(os.path.join(ROOT, "templates", "letters", name + ".pgm"), 32, 32, binary(coverage))
    for name, shape in HAND_SIGNS.items():
        coverage = render(32, 32, shape)
        write_pgm(os.path.join(ROOT, "hand_signs", name + ".pgm"), 32, 32, to8(coverage))
        write_pgm(os.path.join(ROOT, "templates", "hand_signs", name + ".pgm"), 32, 32, binary(coverage))

    n = 64
    write_pgm(os.path.join(ROOT, "uniform.pgm"), n, n, [255] * (n * n))
    write_pgm(os.path.join(ROOT, "gradient.pgm"), n, n,
              [int(round(65535 * x / (n - 1))) for y in range(n) for x in range(n)], maxval=65535)
    write_pgm(os.path.join(ROOT, "checkerboard.pgm"), n, n,
              [255 if ((x // 8) + (y // 8)) % 2 == 0 else 0 for y in range(n) for x in range(n)])

    write_pgm(os.path.join(ROOT, "natural.pgm"), n, n, natural(n))

    # A dim room (1e-4 .. 1e-3 of full scale, log ramp), a window (0.3 .. 1) and the sun (20):
    # 5.3 decades in one frame.
    hdr = []
    for y in range(n):
        for x in range(n):
            value = 1e-4 * 10 ** (x / (n - 1))
            if 36 <= x < 60 and 6 <= y < 30:
                value = 0.3 + 0.7 * (y - 6) / 23
            if math.hypot(x - 50, y - 14) < 4:
                value = 20.0
            hdr.append(value)
    write_pfm(os.path.join(ROOT, "hdr", "window.pfm"), n, n, hdr)

    # A bright disc (radius 8) crossing a dark background (2 % of full scale), 2 px per frame.
    folder = os.path.join(ROOT, "moving_disc")
    for k in range(24):
        cx = 8 + 2 * k
        coverage = render(n, n, lambda u, v: math.hypot(u - cx, v - 32) < 8)
        write_pgm(os.path.join(folder, "frame_%03d.pgm" % k), n, n, to8(coverage, lo=5, hi=255))
    with open(os.path.join(folder, "scene.toml"), "w") as f:
        f.write("# 24 frames at 10 Hz: the disc crosses the field in 2.4 s, then the last frame holds.\n")
        f.write('frame_rate = "10Hz"\nloop = false\n')


if __name__ == "__main__":
    main()
