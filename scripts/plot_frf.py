#!/usr/bin/python3
"""Plot the frequency response functions of a beamfea "frf" analysis (its <id>.csv): magnitude
(log-log) and phase (degrees) against frequency (Hz), one curve per output.

    /usr/bin/python3 scripts/plot_frf.py OUT/h.csv [--out h.png]

Needs matplotlib (Debian: python3-matplotlib). Without --out the figure is shown on screen.
"""
import argparse
import csv


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], [[float(x) for x in r] for r in rows[1:] if r]
    columns = {name: [r[i] for r in data] for i, name in enumerate(header)}
    labels = [name[: -len("_magnitude")] for name in header if name.endswith("_magnitude")]
    return columns, labels


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", help="the <id>.csv of an frf analysis")
    parser.add_argument("--out", help="write the figure to this file (png, pdf, svg) instead of showing it")
    args = parser.parse_args()
    import matplotlib

    if args.out:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    columns, labels = read(args.csv)
    hz = columns["frequency_hz"]
    fig, (mag, phase) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    for label in labels:
        mag.loglog(hz, columns[label + "_magnitude"], label=label)
        phase.semilogx(hz, columns[label + "_phase_deg"], label=label)
    mag.set_ylabel("|H| (displacement / force)")
    mag.grid(True, which="both", alpha=0.3)
    mag.legend(fontsize="small")
    phase.set_ylabel("phase (deg)")
    phase.set_xlabel("frequency (Hz)")
    phase.set_yticks([-180, -90, 0, 90, 180])
    phase.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    if args.out:
        fig.savefig(args.out, dpi=150)
    else:
        plt.show()


if __name__ == "__main__":
    main()
