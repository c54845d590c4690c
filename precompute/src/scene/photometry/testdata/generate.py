#!/usr/bin/env python3
"""Writes the synthetic photometric files the photometry tests read.

Every file tabulates one of a few closed-form distributions, each with exactly one lateral
symmetry, so that a reduced file (LM-63 horizontal angles 0..90, 0..180, 90..270; EULUMDAT
Isym 1..4) and the full file of the same distribution hold the very same numbers: a value is
always computed at the plane's image in the stored range, then rounded.

    python3 generate.py    # from this folder; rewrites the files in place
"""

import math
from pathlib import Path

HERE = Path(__file__).resolve().parent
GAMMA = [10.0 * k for k in range(19)]  # 0..180 degrees
FULL_C = [30.0 * k for k in range(13)]  # 0..360 degrees


def g(gamma):
    """The γ profile shared by the symmetric distributions, cd (flux 2π·120 lm)."""
    return 60.0 + 30.0 * math.cos(math.radians(gamma))


# symmetry -> (image of C in the LM-63 stored range, C factor of the distribution)
def canon_none(c):
    return c % 360.0


def canon_quadrant(c):
    c = c % 180.0
    return 180.0 - c if c > 90.0 else c


def canon_half(c):
    c = c % 360.0
    return 360.0 - c if c > 180.0 else c


def canon_c90(c):
    c = c % 360.0
    if c < 90.0:
        return 180.0 - c
    if c > 270.0:
        return 540.0 - c
    return c


DISTRIBUTIONS = {
    "rotational": (lambda c: 0.0, lambda c: 1.0),
    "quadrant": (canon_quadrant, lambda c: 1.0 + 0.3 * math.cos(math.radians(2 * c))),
    "half": (
        canon_half,
        lambda c: 1.0 + 0.3 * math.cos(math.radians(c)) + 0.1 * math.cos(math.radians(2 * c)),
    ),
    "c90": (canon_c90, lambda c: 1.0 + 0.3 * math.sin(math.radians(c))),
    "none": (
        canon_none,
        lambda c: 1.0
        + 0.3 * math.cos(math.radians(c))
        + 0.2 * math.sin(math.radians(c))
        + 0.1 * math.sin(math.radians(2 * c)),
    ),
}

STORED = {
    "rotational": [0.0],
    "quadrant": [0.0, 30.0, 60.0, 90.0],
    "half": [30.0 * k for k in range(7)],
    "c90": [90.0 + 30.0 * k for k in range(7)],
    "none": FULL_C,
}


def value(name, c, gamma):
    canon, factor = DISTRIBUTIONS[name]
    return round(g(gamma) * factor(canon(c)), 2)


def fmt(x):
    text = f"{x:.2f}".rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def rows(values, per_line=10):
    """An LM-63 record: values on as many lines as needed."""
    return [" ".join(fmt(v) for v in values[i : i + per_line]) for i in range(0, len(values), per_line)]


def ies(path, version_line, keywords, planes, name, header, ballast, tilt=None, gamma=GAMMA):
    lines = [version_line] if version_line else []
    lines += [f"[{k}] {v}" for k, v in keywords]
    if tilt is None:
        lines.append("TILT=NONE")
    else:
        geometry, angles, factors = tilt
        lines += ["TILT=INCLUDE", str(geometry), str(len(angles))]
        lines += rows(angles, 4) + rows(factors, 4)
    lines.append(header.format(nv=len(gamma), nh=len(planes)))
    lines.append(ballast)
    lines += rows(gamma) + rows(planes)
    for c in planes:
        lines += rows([value(name, c, y) for y in gamma])
    (HERE / path).write_text("\r\n".join(lines) + "\r\n")


def synthetic(what):
    return [
        ("TEST", f"SYNTH-{what}"),
        ("TESTLAB", "none: computed"),
        ("ISSUEDATE", "2024-01-01"),
        ("MANUFAC", "eigenrad test data"),
        ("LUMCAT", f"SYN-{what.upper()}"),
        ("LUMINAIRE", f"synthetic {what} distribution"),
        ("MORE", "from a closed form; not a real luminaire"),
        ("LAMP", "none"),
        ("OTHER", "Synthetic test data written for the eigenrad photometry tests."),
    ]


def write_lm63():
    metres = "1 -1 1 {nv} {nh} 1 2 0.6 1.2 0"
    # Full equivalents of the reduced files: the same numbers on all planes 0..360.
    for name in ["rotational", "quadrant", "half", "c90"]:
        ies(f"lm63-full-{name}.ies", "IESNA:LM-63-2002", synthetic(f"{name}-full"), FULL_C,
            name, metres, "1 1 40")
    ies("lm63-2002-rotational.ies", "IESNA:LM-63-2002", synthetic("rotational"), [0.0],
        "rotational", metres, "1 1 40")
    # Feet, a negative width and zero length: LM-63-1995's circular opening, 1 ft across.
    ies("lm63-1995-quadrant.ies", "IESNA:LM-63-1995", synthetic("quadrant"), STORED["quadrant"],
        "quadrant", "1 -1 1 {nv} {nh} 1 1 -1 0 0", "1 1 40")
    ies("lm63-2002-half.ies", "IESNA:LM-63-2002", synthetic("half"), STORED["half"], "half",
        metres, "1 1 40")
    # 2019's second ballast field is the file generation type, no factor.
    ies("lm63-2019-c90.ies", "IES:LM-63-2019", synthetic("c90"), STORED["c90"], "c90",
        metres, "1 1.10000 40")
    ies("lm63-2019-none.ies", "IES:LM-63-2019", synthetic("none"), FULL_C, "none",
        metres, "1 1.00001 40")
    # LM-63-1991: multiplier 2, ballast factor 0.9, ballast-lamp photometric factor 0.95,
    # relative photometry of two 400 lm lamps.
    ies("lm63-1991-factors.ies", "IESNA91", synthetic("factors"), [0.0], "rotational",
        "2 400 2 {nv} {nh} 1 2 0 0 0", "0.9 0.95 40")
    ies("lm63-2002-tilt.ies", "IESNA:LM-63-2002", synthetic("tilt"), [0.0], "rotational",
        metres, "1 1 40",
        tilt=(1, [0, 15, 30, 45, 60, 75, 90], [1, 0.98, 0.95, 0.9, 0.84, 0.77, 0.7]))
    # Isotropic, 100 cd: relative photometry of one lamp of 4π·100 lm.
    gamma = [22.5 * k for k in range(9)]
    lines = ["IESNA:LM-63-2002"] + [f"[{k}] {v}" for k, v in synthetic("isotropic")]
    lines += ["TILT=NONE", f"1 {4 * math.pi * 100:.2f} 1 9 1 1 2 0 0 0", "1 1 10"]
    lines += rows(gamma) + ["0"] + rows([100.0] * 9)
    (HERE / "isotropic.ies").write_text("\r\n".join(lines) + "\r\n")


def ldt(path, isym, name, dff, lorl, gamma=GAMMA, values=None, mc=12):
    dc = 360.0 / mc
    c_all = [dc * k for k in range(mc)]
    stored = {
        0: list(range(mc)),
        1: [0],
        2: list(range(mc // 2 + 1)),
        3: [(3 * mc // 4 + k) % mc for k in range(mc // 2 + 1)],
        4: list(range(mc // 4 + 1)),
    }[isym]
    lines = [
        "eigenrad synthetic test data: not a real luminaire",
        "1" if isym == 1 else "3",
        str(isym),
        str(mc),
        fmt(dc),
        str(len(gamma)),
        fmt(gamma[1] - gamma[0]),
        f"SYNTH-{name}",
        f"synthetic {name} distribution",
        f"SYN-{name.upper()}",
        path,
        "2024-01-01 / computed",
        "620", "310", "80",  # luminaire, mm
        "600", "300",  # luminous area, mm
        "0", "0", "0", "0",
        fmt(dff),
        fmt(lorl),
        "1",
        "0",
        "1",
        "2",
        "synthetic lamp",
        "1000",
        "4000K",
        "1B",
        "40",
    ]
    lines += ["0.5"] * 10
    lines += [fmt(c) for c in c_all] + [fmt(y) for y in gamma]
    for k in stored:
        for j, y in enumerate(gamma):
            v = values(c_all[k], y) if values else value(name, c_all[k], y)
            lines.append(fmt(v))
    (HERE / path).write_text("\r\n".join(lines) + "\r\n")


def write_eulumdat():
    # The symmetric distributions emit 2π·120 lm, 2π·75 lm of it downward: with lamps of
    # 1000 lm, LORL 75.40 % and DFF 62.5 % (closed forms, not the tabulated values).
    lorl = 2 * math.pi * 120 / 10
    for isym, name in [(0, "none"), (1, "rotational"), (2, "half"), (3, "c90"), (4, "quadrant")]:
        ldt(f"eulumdat-isym{isym}.ldt", isym, name, 62.5, lorl)
    # Lambertian, I = (1000/π) cos γ cd/klm over 0..90: all of 1000 lm, downward.
    gamma = [5.0 * k for k in range(19)]
    ldt("lambertian.ldt", 1, "lambertian", 100, 100, gamma=gamma,
        values=lambda c, y: 1000 / math.pi * math.cos(math.radians(y)))


if __name__ == "__main__":
    write_lm63()
    write_eulumdat()
