#!/usr/bin/env python3
"""The SRAM macro model's coefficients (scripts/sram_model.txt) from the
published macros in scripts/sram_macros.tsv (docs/physical.md, "SRAM
macros"):

  area:   least squares over the two-port macros (every kdrt memory is read
          and written in the same cycle), area = fixed + per_bit * bits;
  access: piecewise linear in log2(words) through the slowest
          clock-to-data-out published at each word count (one or two ports),
          made non-decreasing in the words: flat below the smallest macro,
          beyond the largest the slope from the smallest to the largest; no
          published macro is faster than the model;
  both scaled from the macros' 130 nm at 1.20 V to 180 nm at 1.8 V (the OSU
  cells' node and supply) by Stillmaker & Baas, Integration 58 (2017): the
  area factor 0.34 (their table, 180 nm row, 130 nm column) and the ratio of
  their fitted delay polynomials (180 nm at 1.8 V over 130 nm at 1.2 V).

Usage: scripts/sram_fit.py            print the coefficients
       scripts/sram_fit.py --write    write them into scripts/sram_model.txt
       scripts/sram_fit.py --check    exit 1 when sram_model.txt differs"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
MACROS = os.path.join(HERE, "sram_macros.tsv")
MODEL = os.path.join(HERE, "sram_model.txt")

AREA_130_FROM_180 = 0.34
# Stillmaker & Baas's delay polynomials a3 V^3 + a2 V^2 + a1 V + a0 (the 180 nm
# one is also sim/phys.cpp's).
DELAY_POLY = {180: (0.0, 97.09, -356.7, 406.5), 130: (-76.65, 334.9, -493.4, 275.8)}


def delay_poly(nm, v):
    a3, a2, a1, a0 = DELAY_POLY[nm]
    return ((a3 * v + a2) * v + a1) * v + a0


DELAY_180_FROM_130 = delay_poly(180, 1.8) / delay_poly(130, 1.2)


def read_macros(path=MACROS):
    rows, header = [], None
    with open(path) as f:
        for n, line in enumerate(f, 1):
            if line.startswith("#") or not line.strip():
                continue
            cols = line.rstrip("\n").split("\t")
            if header is None:
                header = cols
                continue
            if len(cols) != len(header):
                sys.exit(f"{path}:{n}: {len(cols)} columns, the header has {len(header)}")
            r = dict(zip(header, cols))
            try:
                rows.append({"name": r["name"], "ports": int(r["ports"]), "words": int(r["words"]),
                             "width": int(r["width"]), "area": float(r["area_um2"]),
                             "access": float(r["clk_to_dout_ns"])})
            except (KeyError, ValueError) as e:
                sys.exit(f"{path}:{n}: {e}")
    return rows


def fit(rows):
    two = [r for r in rows if r["ports"] == 2]
    xs = [r["words"] * r["width"] for r in two]
    ys = [r["area"] for r in two]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    per_bit = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    fixed = my - per_bit * mx
    slowest = {}
    for r in rows:
        slowest[r["words"]] = max(slowest.get(r["words"], 0.0), r["access"])
    points, top = [], 0.0
    for words in sorted(slowest):
        top = max(top, slowest[words])
        points.append((words, top))
    (w0, a0), (w1, a1) = points[0], points[-1]
    beyond = (a1 - a0) / (math.log2(w1) - math.log2(w0))
    return {"area_fixed_um2": round(fixed / AREA_130_FROM_180, 1),
            "area_per_bit_um2": round(per_bit / AREA_130_FROM_180, 4),
            "access": [(w, round(a * DELAY_180_FROM_130, 4)) for w, a in points],
            "access_beyond_per_log2_word_ns": round(beyond * DELAY_180_FROM_130, 4)}


def text(c, rows):
    two = sum(r["ports"] == 2 for r in rows)
    points = "".join(f"access_ns_at_words_{w} {a}\n" for w, a in c["access"])
    return f"""# SRAM macro model at 180 nm: the area and read access time of a two-port
# synchronous SRAM macro (one read and one write a cycle, the read registered
# inside) of WORDS words of WIDTH bits, as an SRAM compiler would make it.
# Read by scripts/sram_model.py (scripts/synth-core.sh) and by anything else
# that needs the same figures; docs/physical.md, "SRAM macros", gives the
# sources. One "key value" a line, # comments. Written by scripts/sram_fit.py
# from scripts/sram_macros.tsv ({len(rows)} macros of IHP's SG13G2 130 nm SRAM
# compiler, typical corner 1.20 V 25 C); do not edit by hand.
#
#   area_um2  = area_fixed_um2 + area_per_bit_um2 * WORDS * WIDTH
#   access_ns = piecewise linear in log2(WORDS) through the points
#               access_ns_at_words_W (the value of the first point below it,
#               access_beyond_per_log2_word_ns a doubling beyond the last)
#
# area: least squares over the {two} two-port macros; access: through the
# slowest clock to data out published at each word count, made non-decreasing;
# both scaled to 180 nm at 1.8 V by Stillmaker & Baas 2017 (area / {AREA_130_FROM_180},
# delay x {DELAY_180_FROM_130:.4f}).
model ihp_sg13g2_2p_to_180nm
area_fixed_um2 {c['area_fixed_um2']}
area_per_bit_um2 {c['area_per_bit_um2']}
{points}access_beyond_per_log2_word_ns {c['access_beyond_per_log2_word_ns']}
"""


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] not in ("--write", "--check", "-h", "--help")):
        print("usage: sram_fit.py [--write | --check]   (--help)", file=sys.stderr)
        return 2
    if len(argv) == 2 and argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    rows = read_macros()
    t = text(fit(rows), rows)
    if len(argv) == 1:
        sys.stdout.write(t)
    elif argv[1] == "--write":
        with open(MODEL, "w") as f:
            f.write(t)
    elif open(MODEL).read() != t:
        print(f"{MODEL}: not what scripts/sram_fit.py makes of {MACROS} (scripts/sram_fit.py --write)",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
