#!/usr/bin/env python3
"""SRAM macro model at 180 nm: area (um^2) and read access time (ns) of a
two-port synchronous SRAM macro (one read and one write a cycle), from the
coefficients in scripts/sram_model.txt (written by scripts/sram_fit.py;
docs/physical.md, "SRAM macros").

Usage: scripts/sram_model.py WORDS WIDTH   prints {"words", "width",
       "area_um2", "access_ns", "source": "model"} as JSON."""
import json
import math
import os
import sys

COEFFS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sram_model.txt")
KEYS = ("area_fixed_um2", "area_per_bit_um2", "access_beyond_per_log2_word_ns")
POINT = "access_ns_at_words_"


def load(path=COEFFS):
    """The coefficients of PATH: {key: value}; exits with file:line on a bad line."""
    coeffs = {"access": []}
    with open(path) as f:
        for n, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            parts = line.split()
            if len(parts) != 2:
                sys.exit(f"{path}:{n}: expected 'key value', got '{line}'")
            if parts[0] == "model":
                coeffs["model"] = parts[1]
                continue
            try:
                value = float(parts[1])
            except ValueError:
                sys.exit(f"{path}:{n}: {parts[0]}: '{parts[1]}' is not a number")
            if parts[0].startswith(POINT):
                words = parts[0][len(POINT):]
                if not words.isdigit() or int(words) < 1:
                    sys.exit(f"{path}:{n}: {parts[0]}: '{words}' is not a number of words")
                if coeffs["access"] and (int(words) <= coeffs["access"][-1][0] or value < coeffs["access"][-1][1]):
                    sys.exit(f"{path}:{n}: {parts[0]}: the points must grow in words and not fall in time")
                coeffs["access"].append((int(words), value))
            else:
                coeffs[parts[0]] = value
    missing = [k for k in KEYS if k not in coeffs] + ([POINT + "W"] if not coeffs["access"] else [])
    if missing:
        sys.exit(f"{path}: missing {', '.join(missing)}")
    return coeffs


def access_ns(words, coeffs):
    """The access time of a macro of WORDS words: piecewise linear in
    log2(words) through the points, flat below the first, the beyond slope
    after the last."""
    pts = coeffs["access"]
    x = math.log2(words)
    if words <= pts[0][0]:
        return pts[0][1]
    for (w0, a0), (w1, a1) in zip(pts, pts[1:]):
        if words <= w1:
            x0, x1 = math.log2(w0), math.log2(w1)
            return a0 + (a1 - a0) * (x - x0) / (x1 - x0)
    return pts[-1][1] + coeffs["access_beyond_per_log2_word_ns"] * (x - math.log2(pts[-1][0]))


def macro(words, width, coeffs):
    """Area and access time of a WORDS x WIDTH macro."""
    if words < 1 or width < 1:
        raise ValueError(f"an SRAM macro of {words} x {width} bits")
    area = coeffs["area_fixed_um2"] + coeffs["area_per_bit_um2"] * words * width
    access = access_ns(words, coeffs)
    return {"words": words, "width": width, "area_um2": round(area),
            "access_ns": round(access, 3), "source": "model"}


def main(argv):
    if len(argv) == 2 and argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    if len(argv) != 3 or not all(a.isdigit() and int(a) > 0 for a in argv[1:]):
        print("usage: sram_model.py WORDS WIDTH   (positive integers; --help)", file=sys.stderr)
        return 2
    print(json.dumps(macro(int(argv[1]), int(argv[2]), load())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
