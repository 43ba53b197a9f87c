"""`shaftfe study`: design studies on Dask.distributed (``shaftfe.study``; docs/STUDIES.md).

Stdlib only at module level.
"""

from __future__ import annotations

import sys


def register(sub) -> None:
    p = sub.add_parser("study", help="design studies: sweep variant keys on Dask (run, report)",
                       description="Evaluate many designs of a base variant (a grid, a list or "
                       "a Latin hypercube of variant keys) on Dask.distributed, and report the "
                       "trade-offs. The study file is documented in docs/STUDIES.md.")
    ss = p.add_subparsers(dest="study_command", metavar="SUBCOMMAND", parser_class=type(p))
    pr = ss.add_parser("run", help="evaluate a study's designs (resumes an interrupted run)",
                       description="Evaluate every design of STUDY.toml that has no result in "
                       "the output folder yet; write results.parquet and results.csv (one row "
                       "per design) and the report page.")
    pr.add_argument("study", help="study file (TOML)")
    pr.add_argument("--out", default=None,
                    help="output folder (default reports/studies/<study name>)")
    pr.add_argument("--workers", type=int, default=None,
                    help="worker processes of the local cluster (default: as many as the "
                    "cores and the free memory allow)")
    pr.add_argument("--scheduler", default=None,
                    help="address of an existing Dask scheduler, e.g. tcp://host:8786 "
                    "(default: a local cluster)")
    pr.add_argument("--yes", action="store_true",
                    help="run a study with more designs than its max_designs")
    pr.add_argument("--no-report", action="store_true", help="write the tables only")
    pr.set_defaults(handler=run_run)
    pp = ss.add_parser("report", help="the HTML result page of a finished study folder")
    pp.add_argument("dir", help="the study's output folder")
    pp.set_defaults(handler=run_report)
    p.set_defaults(handler=lambda args: p.print_help() or 0)


def run_run(args) -> int:
    from pathlib import Path

    from shaftfe.errors import InputError
    from shaftfe.study import sampling
    from shaftfe.study.runner import run_study
    from shaftfe.study.spec import check_count, load_study

    if args.workers is not None and not 1 <= args.workers <= 1024:
        raise InputError("command line", "--workers", "an integer in [1, 1024]",
                         got=args.workers)
    if args.workers is not None and args.scheduler is not None:
        raise InputError("command line", "--workers with --scheduler", "one of them (an "
                         "existing cluster has its own workers)", reason="is given")
    spec = load_study(args.study)
    check_count(spec, sampling.count(spec), yes=args.yes)
    out = Path(args.out) if args.out else Path("reports") / "studies" / spec.name

    def announce(checked):                          # the cluster is there: before solving
        for line in checked.summary():
            print(f"shaftfe: {line}", file=sys.stderr)
    import signal

    def stop(signum, frame):             # a batch system's SIGTERM ends the run as Ctrl-C does
        raise KeyboardInterrupt
    previous = signal.signal(signal.SIGTERM, stop)
    try:
        run = run_study(spec, out, workers=args.workers, scheduler=args.scheduler,
                        announce=announce)
    except KeyboardInterrupt:
        done = len(list((out / "designs").glob("*.json"))) if (out / "designs").is_dir() else 0
        print(f"shaftfe: interrupted: {done} design results are saved in {out}; run the same "
              "command to compute the rest", file=sys.stderr)
        return 130
    finally:
        signal.signal(signal.SIGTERM, previous)
    page = None
    if not args.no_report:
        from shaftfe.study.report import write_report
        page = write_report(out)
    print(f"{len(run.rows)} designs: {run.computed} computed, {run.reused} from earlier runs, "
          f"{run.refused} refused, {run.failed} failed ({run.wall_seconds:.1f} s, "
          f"{run.workers or 0} workers)")
    print(f"results: {out / 'results.parquet'}, {out / 'results.csv'}")
    if page is not None:
        print(f"report: {page}")
    if run.failed:                  # an analysis that failed is not a result: say so, exit 1
        print(f"shaftfe: {run.failed} of {len(run.rows)} designs failed (reasons in "
              f"{out / 'results.csv'}, column error); run the same command to retry them",
              file=sys.stderr)
        return 1
    return 0


def run_report(args) -> int:
    from shaftfe.study.report import write_report
    print(f"report: {write_report(args.dir)}")
    return 0
