"""Command line: ``corrugation-post {figures,compare,growth,speeds,mechanisms,sweep,speed-accuracy,accuracy-map,growth-accuracy,stability,grid-convergence,validity-map,track,spectrum,check}`` (or ``python -m corrugation_post``).

Exit status: 0 success; 1 some outputs could not be made (messages on stderr);
2 unusable input (missing file, not a run file, passage not stored) or bad usage.
"""

from __future__ import annotations

import argparse
import sys

import matplotlib

EXIT_OK, EXIT_PARTIAL, EXIT_BAD_INPUT = 0, 1, 2

# (command, help, manifest columns) of the study commands.
MANIFEST_COMMANDS = (
    ("speed-accuracy", "errors against a reference and CPU time per model and mesh",
     "scene, model, mesh, file, reference (1 for the reference run)"),
    ("accuracy-map", "the wear-error map of contact.model = auto (scripts/accuracy_map.sh)",
     "wavelength, model, mesh, file"),
    ("growth-accuracy", "growth-rate error per model and mesh (scripts/growth_accuracy.sh)", "model, mesh, file"),
    ("stability", "outcome table of scripts/stability_map.sh",
     "sweep, value, file, exit_code, message (one 'baseline' row)"),
    ("grid-convergence", "convergence of both discretisations of the exact model (scripts/grid_convergence.sh)",
     "scene, grid (fixed or adapted), size (contact.dx in m, or the adapted mesh n), file"),
    ("validity-map", "where the Hertz normal contact differs from the profile's (scripts/validity_map.sh)",
     "wavelength, amplitude, normal, file, exit_code, message, contact_loss"),
)


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="corrugation-post",
        description="Figures and comparisons from corrugation run files (HDF5).",
    )
    sub = parser.add_subparsers(dest="command", required=True)

    fig = sub.add_parser("figures", help="wear map, centre-line wear, loads, traction snapshots, growth, "
                         "roughness levels against the limit (both rails of a two-rail file)")
    fig.add_argument("run", help="run file (.h5)")
    fig.add_argument("--out", required=True, help="output folder (created if needed)")
    fig.add_argument("--pass", dest="pass_index", type=int, default=None,
                     help="passage N as the terminal counts them, from 1 (default: the last stored)")
    fig.add_argument("--levels-at", dest="levels_at", type=int, nargs="+", default=None, metavar="N",
                     help="passages (from 1) whose band levels levels.png draws (default: up to four spread "
                          "over the run)")

    cmp_ = sub.add_parser("compare", help="overlay several runs, table of relative differences")
    cmp_.add_argument("runs", nargs="+", help="run files; the first is the reference")
    cmp_.add_argument("--out", required=True, help="output folder (created if needed)")
    cmp_.add_argument("--pass", dest="pass_index", type=int, default=None,
                      help="passage N as the terminal counts them, from 1 (default: the last one stored in every "
                           "run)")

    grw = sub.add_parser("growth", help="compare growth studies: rms and one harmonic against traffic")
    grw.add_argument("runs", nargs="+", help="growth-study run files; the first is the reference")
    grw.add_argument("--out", required=True, help="output folder (created if needed)")
    grw.add_argument("--wavelength", type=float, default=None,
                     help="harmonic to follow (m; default: the one that grew most in the first run)")

    mech = sub.add_parser("mechanisms", help="the mechanism study side by side: each mechanism's growth rate against "
                          "frequency and wavelength at its speeds (scripts/mechanism_study.sh)")
    mech.add_argument("folders", nargs="+", help="one folder per mechanism, named after it, holding the speeds.csv "
                      "of `corrugation-post speeds`")
    mech.add_argument("--out", required=True, help="output folder")
    spd = sub.add_parser("speeds", help="growth rate against wavelength and frequency: studies at several speeds "
                         "and mixed traffic (scripts/discrete_speeds.sh)")
    spd.add_argument("runs", nargs="+", help="growth-study run files (single speeds, and mixes of them)")
    spd.add_argument("--track", default=None, help="`corrugation track` file whose resonances to mark")
    spd.add_argument("--out", required=True, help="output folder (created if needed)")

    swp = sub.add_parser("sweep", help="growth-rate map of a collected sweep (corrugation sweep collect)")
    swp.add_argument("file", help="collected sweep (.h5)")
    swp.add_argument("--x", default=None, help="axis along x (default: the first)")
    swp.add_argument("--y", default=None, help="axis along y (default: the second, if any; none: against --x alone)")
    swp.add_argument("--wavelength", type=float, default=None,
                     help="the rate of this harmonic (m; default: the fastest-growing one of each member)")
    swp.add_argument("--at", action="append", default=[], metavar="AXIS=INDEX",
                     help="hold a further axis at this index (default 0; repeatable)")
    swp.add_argument("--out", required=True, help="output folder (created if needed)")

    # The study commands: a manifest CSV from a script in, a table out.
    for name, help_, manifest in MANIFEST_COMMANDS:
        cmd = sub.add_parser(name, help=help_)
        cmd.add_argument("manifest", help=f"CSV: {manifest}")
        cmd.add_argument("--out", required=True, help="output folder (created if needed)")

    trk = sub.add_parser("track", help="receptance figure of a `corrugation track` file")
    trk.add_argument("file", help="track file (.h5)")
    trk.add_argument("--out", required=True, help="output folder (created if needed)")

    spc = sub.add_parser("spectrum", help="figures and table of a `corrugation spectrum` file: the modes' rates "
                         "against wavelength, the forced pattern, the fastest modes' envelopes")
    spc.add_argument("file", help="spectrum file (.h5)")
    spc.add_argument("--out", required=True, help="output folder (created if needed)")

    chk = sub.add_parser("check", help="check a run file against the layout contract")
    chk.add_argument("run", help="run file (.h5)")
    return parser


def _warn(problems) -> None:
    for msg in problems:
        print(f"warning: {msg}", file=sys.stderr)


def _figures(args) -> int:
    from .figures import make_figures

    paths, problems, notes = make_figures(args.run, args.out, args.pass_index, args.levels_at)
    for p in paths:
        print(p)
    for msg in notes:
        print(f"note: {msg}", file=sys.stderr)
    _warn(problems)
    return EXIT_PARTIAL if problems else EXIT_OK


def _compare(args) -> int:
    from .compare import compare_runs, format_table

    if len(args.runs) < 2:
        print("note: only one run given; relative differences are all zero", file=sys.stderr)
    rows, paths, problems = compare_runs(args.runs, args.out, args.pass_index)
    print(format_table(rows))
    for p in paths:
        print(p)
    _warn(problems)
    return EXIT_PARTIAL if problems else EXIT_OK


def _print_table(result, fmt) -> int:
    """Prints a table command's rows with ``fmt`` and the files it wrote."""
    rows, paths = result
    print(fmt(rows))
    for p in paths:
        print(p)
    return EXIT_OK


def _growth(args) -> int:
    from .growth import compare_growth, format_table

    return _print_table(compare_growth(args.runs, args.out, args.wavelength), format_table)


def _speeds(args) -> int:
    from .speeds import format_table, speed_study

    return _print_table(speed_study(args.runs, args.out, args.track), format_table)


def _mechanisms(args) -> int:
    from .mechanisms import format_table, mechanism_figure

    return _print_table(mechanism_figure(args.folders, args.out), format_table)


def _sweep(args) -> int:
    from .sweep import format_table, sweep_map

    at = {}
    for item in args.at:
        name, _, index = item.partition("=")
        if not index.isdigit():
            print(f"error: --at {item!r}: expected AXIS=INDEX", file=sys.stderr)
            return EXIT_BAD_INPUT
        at[name] = int(index)
    return _print_table(sweep_map(args.file, args.out, args.x, args.y, args.wavelength, at), format_table)


def _speed_accuracy(args) -> int:
    from .speed_accuracy import format_table, run

    return _print_table(run(args.manifest, args.out), format_table)


def _accuracy_map(args) -> int:
    from .accuracy_map import format_table, run

    return _print_table(run(args.manifest, args.out), format_table)


def _growth_accuracy(args) -> int:
    from .accuracy_map import format_growth, run_growth

    return _print_table(run_growth(args.manifest, args.out), format_growth)


def _stability(args) -> int:
    from .stability import markdown, run

    return _print_table(run(args.manifest, args.out), markdown)


def _grid_convergence(args) -> int:
    from .grid_convergence import format_table, run

    result, paths = run(args.manifest, args.out)
    print(format_table(result))
    for p in paths:
        print(p)
    return EXIT_OK


def _validity_map(args) -> int:
    from .validity_map import markdown, run

    return _print_table(run(args.manifest, args.out), markdown)


def _track(args) -> int:
    from .track import figure

    for p in figure(args.file, args.out):
        print(p)
    return EXIT_OK


def _spectrum(args) -> int:
    from .spectrum import figure

    for p in figure(args.file, args.out):
        print(p)
    return EXIT_OK


def _check(args) -> int:
    from .schema import check_file

    problems = check_file(args.run)
    for msg in problems:
        print(msg)
    print(f"{args.run}: {'OK' if not problems else f'{len(problems)} problem(s)'}")
    return EXIT_PARTIAL if problems else EXIT_OK


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    from .io import RunFileError

    matplotlib.use("Agg")
    args = _parser().parse_args(argv)
    handler = {"figures": _figures, "compare": _compare, "growth": _growth, "speeds": _speeds, "mechanisms": _mechanisms, "sweep": _sweep,
               "speed-accuracy": _speed_accuracy, "accuracy-map": _accuracy_map, "growth-accuracy": _growth_accuracy, "stability": _stability, "grid-convergence": _grid_convergence,
               "validity-map": _validity_map, "track": _track, "spectrum": _spectrum, "check": _check}[args.command]
    try:
        return handler(args)
    except RunFileError as err:
        print(f"error: {err}", file=sys.stderr)
        return EXIT_BAD_INPUT
