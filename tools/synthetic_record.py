#!/usr/bin/env python3
"""Write the synthetic rock-outcrop accelerogram that the examples use, in PEER NGA format.

It is not a recording: no real record's licence is in question, and the command makes it again
bit for bit. It is built the classical way (Kramer 1996, section 3.6; Clough & Penzien 1993):

* Gaussian white noise (numpy's PCG64, seed 2026), filtered in the frequency domain by
  - the Kanai-Tajimi filter of a rock site, f_g = 5 Hz, zeta_g = 0.6, which gives the spectrum
    its hump between 2 and 10 Hz,
  - the Clough-Penzien high-pass, f_f = 0.5 Hz, zeta_f = 0.6, which takes out the long periods
    white noise would give the velocity and displacement,
  - a 4-pole Butterworth low-pass at 25 Hz, the cut-off of a processed strong-motion record;
* shaped by the Jennings, Housner & Tsai (1968) envelope: a quadratic rise over 1.5 s, strong
  motion to 5 s, then exp(-0.5 (t - 5)) to the end at 15 s;
* scaled to a PGA of 0.25 g, sampled every 0.005 s (200 samples per second).

    /usr/bin/python3 tools/synthetic_record.py [OUTPUT]   # examples/records/synthetic_rock.AT2
"""
import pathlib
import sys

import numpy as np

DT = 0.005  # s
DURATION = 15.0  # s
SEED = 2026
PGA_G = 0.25
F_G, ZETA_G = 5.0, 0.6  # Kanai-Tajimi, rock
F_F, ZETA_F = 0.5, 0.6  # Clough-Penzien high-pass
F_LOW_PASS, POLES = 25.0, 4


def filter_gain(f):
    """|H(f)| of the Kanai-Tajimi x Clough-Penzien x Butterworth filter."""
    r = f / F_G
    kanai_tajimi = (1 + 4 * ZETA_G**2 * r**2) / ((1 - r**2) ** 2 + 4 * ZETA_G**2 * r**2)
    q = f / F_F
    clough_penzien = q**4 / ((1 - q**2) ** 2 + 4 * ZETA_F**2 * q**2)
    butterworth = 1.0 / (1.0 + (f / F_LOW_PASS) ** (2 * POLES))
    return np.sqrt(kanai_tajimi * clough_penzien * butterworth)


def envelope(t):
    """Jennings, Housner & Tsai (1968): rise to 1.5 s, strong to 5 s, exponential decay."""
    return np.where(t < 1.5, (t / 1.5) ** 2, np.where(t <= 5.0, 1.0, np.exp(-0.5 * (t - 5.0))))


def accelerogram():
    n = int(round(DURATION / DT)) + 1
    noise = np.random.Generator(np.random.PCG64(SEED)).standard_normal(n)
    spectrum = np.fft.rfft(noise)
    f = np.fft.rfftfreq(n, DT)
    a = np.fft.irfft(spectrum * filter_gain(f), n) * envelope(np.arange(n) * DT)
    a -= np.linspace(a[0], a[-1], n)  # start and end at exactly 0
    return a * (PGA_G / np.max(np.abs(a)))


def write_peer(path, a_g):
    lines = [
        "SYNTHETIC ROCK-OUTCROP ACCELEROGRAM (NOT A RECORDING), DDAFEM tools/synthetic_record.py",
        f"KANAI-TAJIMI FG={F_G} HZ ZETA={ZETA_G}, CLOUGH-PENZIEN FF={F_F} HZ, LP {F_LOW_PASS} HZ,"
        f" JENNINGS ENVELOPE, SEED {SEED}",
        "ACCELERATION TIME SERIES IN UNITS OF G",
        f"NPTS= {len(a_g):6d}, DT= {DT:.4f} SEC",
    ]
    for i in range(0, len(a_g), 5):
        lines.append("".join(f"{x:15.7E}" for x in a_g[i : i + 5]))
    path.write_text("\n".join(lines) + "\n")


def main():
    top = pathlib.Path(__file__).resolve().parent.parent
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else top / "examples/records/synthetic_rock.AT2"
    out.parent.mkdir(parents=True, exist_ok=True)
    write_peer(out, accelerogram())
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
