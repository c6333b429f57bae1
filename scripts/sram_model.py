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
KEYS = ("area_fixed_um2", "area_per_bit_um2", "access_base_ns", "access_per_log2_word_ns")


def load(path=COEFFS):
    """The coefficients of PATH: {key: value}; exits with file:line on a bad line."""
    coeffs = {}
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
                coeffs[parts[0]] = float(parts[1])
            except ValueError:
                sys.exit(f"{path}:{n}: {parts[0]}: '{parts[1]}' is not a number")
    missing = [k for k in KEYS if k not in coeffs]
    if missing:
        sys.exit(f"{path}: missing {', '.join(missing)}")
    return coeffs


def macro(words, width, coeffs):
    """Area and access time of a WORDS x WIDTH macro."""
    if words < 1 or width < 1:
        raise ValueError(f"an SRAM macro of {words} x {width} bits")
    area = coeffs["area_fixed_um2"] + coeffs["area_per_bit_um2"] * words * width
    access = coeffs["access_base_ns"] + coeffs["access_per_log2_word_ns"] * math.log2(words)
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
