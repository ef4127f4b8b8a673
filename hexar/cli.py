"""The `hexar` command line. Every command returns an exit code and reports bad input as one line."""

from __future__ import annotations

import sys

import typer

from hexar.cli_batch import eval_, mcp, triage
from hexar.cli_recordings import annotate, ask, chat, inspect, runs, simulate, web
from hexar.cli_robot import listen, replay, serve

app = typer.Typer(
    add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
    help="Ask a robot why it did what it did.",
)
# in the order `hexar --help` lists them
for command in (simulate, inspect, runs, ask, chat, annotate, web, listen, serve, replay):
    app.command()(command)
app.command("eval")(eval_)
app.command()(mcp)
app.command()(triage)


def release_ros_start_mark() -> None:
    """Undo scripts/hexar_ros_lazy.pth's mark, so a Python program that hexar starts (a worker, a robot stand-in)
    runs the ROS wheels' bootstrap as usual; this process re-executes itself if it comes to need rclpy."""
    import os

    if os.environ.pop("_HEXAR_ROS_LAZY", None):
        os.environ.pop("_ROS_WHEELS_BOOTSTRAP_COMPLETE", None)


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit code (usage errors: 2, bad input: 2, success: 0)."""
    release_ros_start_mark()
    try:
        app(args=argv)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
