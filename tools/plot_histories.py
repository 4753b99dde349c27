#!/usr/bin/python3
"""Plot the time histories that a ddafem run writes to RUN_DIR/histories.h5.

Sample command lines:

    /usr/bin/python3 tools/plot_histories.py runs/wave/histories.h5
    /usr/bin/python3 tools/plot_histories.py runs/wave/histories.h5 -o sxx.png \\
        --quantity stress --component xx --monitors M1 M2
    /usr/bin/python3 tools/plot_histories.py runs/wave/histories.h5 --quantity velocity

Writes two figures:
  OUT.png         one subplot per monitor: the chosen quantity against time [ms]
                  (stress [MPa], tension positive; displacement [mm]; velocity [mm/s]);
  OUT_energy.png  every dataset under /energy against time [ms], in J (and, for coupled runs,
                  those under /far_field/energy beside it).
Default OUT: histories_<quantity>.png next to the HDF5 file.

HDF5 layout read (as written by the engine; extra datasets are ignored):
  /time                            (n)     [s]
  /monitors/<NAME>/displacement    (n, 2)  [m]    (ux, uy)
  /monitors/<NAME>/velocity        (n, 2)  [m/s]  (vx, vy)
  /monitors/<NAME>/stress          (n, 3)  [Pa]   (sxx, syy, sxy), tension positive
  /energy/<quantity>               (n)     [J]    kinetic, strain, work_of_loads, dissipated, ...
A dataset's "unit" attribute, when present, overrides the unit assumed above.
"""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402

try:
    import h5py  # noqa: E402
except ImportError:  # pragma: no cover - depends on the installation
    sys.exit("plot_histories.py: needs h5py (Debian package python3-h5py); run it with "
             "/usr/bin/python3")

# Per quantity: the unit the engine writes and the names of its components.
QUANTITIES = {
    "stress": ("Pa", ["xx", "yy", "xy"]),
    "displacement": ("m", ["x", "y"]),
    "velocity": ("m/s", ["x", "y"]),
}
SYMBOLS = {"stress": "\N{GREEK SMALL LETTER SIGMA}", "displacement": "u", "velocity": "v"}

# Stored unit -> (factor, unit shown in the plots).
DISPLAY_UNITS = {
    "s": (1.0e3, "ms"),
    "Pa": (1.0e-6, "MPa"),
    "m": (1.0e3, "mm"),
    "m/s": (1.0e3, "mm/s"),
    "J": (1.0, "J"),
}


def text_attribute(obj, name, default):
    """A string attribute (fixed- or variable-length, bytes or str), or `default`."""
    if name not in obj.attrs:
        return default
    value = obj.attrs[name]
    if isinstance(value, np.ndarray):
        value = value.flat[0] if value.size else default
    if isinstance(value, (bytes, np.bytes_)):
        value = value.decode("utf-8", errors="replace")
    return str(value).rstrip("\0")


def scaled(dataset, assumed_unit):
    """Values of `dataset` as float array in display units, and the display unit."""
    unit = text_attribute(dataset, "unit", assumed_unit)
    factor, shown = DISPLAY_UNITS.get(unit, (1.0, unit))
    return np.asarray(dataset[...], dtype=float) * factor, shown


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        description="Plot monitor and energy histories of a ddafem run (histories.h5).",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="HDF5 layout read" + __doc__.split("HDF5 layout read", 1)[1],
    )
    parser.add_argument("histories", help="RUN_DIR/histories.h5")
    parser.add_argument("-o", "--output", help="monitor figure (PNG); the energy figure goes "
                        "to OUTPUT_energy.png. Default: histories_<quantity>.png next to the "
                        "HDF5 file")
    parser.add_argument("--quantity", choices=sorted(QUANTITIES), default="stress",
                        help="monitor quantity to plot (default: stress)")
    parser.add_argument("--component", choices=["xx", "yy", "xy", "x", "y"],
                        help="one component (xx|yy|xy for stress, x|y otherwise); "
                             "default: all components")
    parser.add_argument("--monitors", nargs="+", metavar="NAME",
                        help="monitors to plot (default: all)")
    args = parser.parse_args(argv)
    components = QUANTITIES[args.quantity][1]
    if args.component is not None and args.component not in components:
        parser.error("--component %s does not apply to --quantity %s; use one of: %s"
                     % (args.component, args.quantity, " ".join(components)))
    return args


def output_paths(args):
    if args.output:
        monitor_path = args.output
    else:
        directory = os.path.dirname(os.path.abspath(args.histories))
        stem = os.path.splitext(os.path.basename(args.histories))[0]
        monitor_path = os.path.join(directory, "%s_%s.png" % (stem, args.quantity))
    root, extension = os.path.splitext(monitor_path)
    return monitor_path, root + "_energy" + (extension or ".png")


def plot_monitors(h5, time_ms, args, path):
    """One subplot per monitor; returns False if there is nothing to plot."""
    monitors = h5.get("monitors")
    available = sorted(name for name in monitors
                       if isinstance(monitors[name], h5py.Group)) if monitors else []
    names = args.monitors if args.monitors else available
    unknown = [name for name in names if name not in available]
    if unknown:
        sys.exit("plot_histories.py: %s: no monitor(s) %s; the file has: %s"
                 % (args.histories, " ".join(unknown), " ".join(available) or "none"))
    if not names:
        print("plot_histories.py: %s has no /monitors; monitor figure skipped" % args.histories)
        return False

    assumed_unit, components = QUANTITIES[args.quantity]
    selected = [args.component] if args.component else components
    figure, axes = plt.subplots(len(names), 1, sharex=True, squeeze=False,
                                figsize=(8.0, 1.0 + 2.4 * len(names)))
    for ax, name in zip(axes[:, 0], names):
        group = monitors[name]
        ax.set_title(name, fontsize="medium")
        ax.grid(True, alpha=0.3)
        if args.quantity not in group or not isinstance(group[args.quantity], h5py.Dataset):
            ax.text(0.5, 0.5, "no %s" % args.quantity, ha="center", va="center",
                    transform=ax.transAxes)
            continue
        values, unit = scaled(group[args.quantity], assumed_unit)
        if values.ndim == 1:
            values = values[:, np.newaxis]
        n = min(len(time_ms), values.shape[0])
        for component in selected:
            column = components.index(component)
            if column < values.shape[1]:
                ax.plot(time_ms[:n], values[:n, column],
                        label="%s%s" % (SYMBOLS[args.quantity], component))
        ylabel = "%s [%s]" % (args.quantity, unit)
        if args.quantity == "stress":
            ylabel += "\n(tension +)"
        ax.set_ylabel(ylabel)
        ax.legend(loc="best", fontsize="small")
    axes[-1, 0].set_xlabel("time [ms]")
    figure.suptitle("%s: monitor %s" % (os.path.basename(args.histories), args.quantity))
    figure.tight_layout()
    figure.savefig(path, dpi=150)
    plt.close(figure)
    return True


def plot_energy(h5, time_ms, args, path):
    """Every dataset under /energy in one axes, and beside it those under /far_field/energy
    (coupled runs: the far field's balance; its work_of_ties is the energy that crossed the
    interface); returns False if there is none."""
    groups = [(title, h5.get(group)) for title, group in
              (("blocks", "energy"), ("far field", "far_field/energy"))]
    groups = [(title, g, sorted(n for n in g if isinstance(g[n], h5py.Dataset)))
              for title, g in groups if g is not None]
    groups = [group for group in groups if group[2]]
    if not groups:
        print("plot_histories.py: %s has no /energy datasets; energy figure skipped"
              % args.histories)
        return False
    figure, axes = plt.subplots(1, len(groups), figsize=(8.0 * len(groups), 4.5), squeeze=False)
    for ax, (title, group, names) in zip(axes[0], groups):
        units = set()
        for name in names:
            values, unit = scaled(group[name], "J")
            units.add(unit)
            if values.ndim != 1:
                values = values.reshape(values.shape[0], -1)[:, 0]
            n = min(len(time_ms), values.shape[0])
            ax.plot(time_ms[:n], values[:n], label=name)
        ax.set_xlabel("time [ms]")
        ax.set_ylabel("energy [%s]" % ", ".join(sorted(units)))
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize="small")
        ax.set_title("%s: energy of the %s" % (os.path.basename(args.histories), title)
                     if len(groups) > 1 else "%s: energy" % os.path.basename(args.histories))
    figure.tight_layout()
    figure.savefig(path, dpi=150)
    plt.close(figure)
    return True


def open_histories(path, fail):
    """(histories.h5 open for reading, whether a run held its lock). A running simulation holds
    HDF5's write lock; it flushes every few hundred rows, so reading without the lock shows the
    rows written so far. `fail(message)` does not return."""
    try:
        return h5py.File(path, "r"), False
    except OSError as error:
        if "lock" not in str(error):
            fail("cannot open %s: %s" % (path, error))
    try:
        return h5py.File(path, "r", locking=False), True
    except (OSError, TypeError, ValueError) as error:
        fail("cannot open %s: %s" % (path, error))


def main(argv):
    args = parse_arguments(argv)
    monitor_path, energy_path = output_paths(args)
    if not os.path.isfile(args.histories):
        sys.exit("plot_histories.py: no file %s" % args.histories)
    h5, locked = open_histories(args.histories, lambda m: sys.exit("plot_histories.py: " + m))
    if locked:
        print("plot_histories.py: %s is locked (run in progress?); reading it unlocked"
              % args.histories)
    with h5:
        if "time" not in h5 or not isinstance(h5["time"], h5py.Dataset):
            sys.exit("plot_histories.py: %s has no /time dataset" % args.histories)
        time_ms, _ = scaled(h5["time"], "s")
        time_ms = time_ms.reshape(-1)
        written = []
        if plot_monitors(h5, time_ms, args, monitor_path):
            written.append(monitor_path)
        if plot_energy(h5, time_ms, args, energy_path):
            written.append(energy_path)
    if not written:
        sys.exit("plot_histories.py: %s: nothing to plot" % args.histories)
    for path in written:
        print("wrote %s" % path)


if __name__ == "__main__":
    main(sys.argv[1:])
