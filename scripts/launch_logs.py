"""Real launch.log files for the tests: ros2/launch itself (a checkout of its `launch` package, run by a Python that
has its dependencies) starting real rclpy programs of ROS 2 Kilted, each run with a bring-up fault of
scripts/stack_faults.py, and writing its log folder as `ros2 launch` does.

Each run is one folder under --out, holding that launch's `launch.log`:
- params_file: a scan filter whose params file sets an integer parameter to a string (rclpy raises and the process
  exits 1), beside a healthy node, both with launch's default output ('log': stdout and stderr into launch.log);
- crash: the scan filter's timer callback raises after it started (output 'both');
- screen: the scan filter given a remap rule rcl cannot parse, with output 'screen', so launch.log keeps only
  launch's own lines (the process started, then died with its exit code).
This machine's folders are replaced by fixed names (/opt/venv, /home/robot/ws) so the files hold no local path.

    /tmp/lv/bin/python scripts/launch_logs.py --launch LAUNCH_CHECKOUT/launch --python .venv/bin/python --out DIR
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from pathlib import Path

HEALTHY = """\
import sys
import rclpy
from rclpy.node import Node

rclpy.init(args=sys.argv)
node = Node('odom_relay')
for n in range(3):
    node.get_logger().info(f'relayed odometry message {n}')
    rclpy.spin_once(node, timeout_sec=0.1)
node.destroy_node()
rclpy.shutdown()
"""


def run_launch(name: str, actions: list[tuple[str, list[str], str]], work: Path, out: Path, python: str) -> None:
    import launch
    import launch.logging
    from launch.actions import ExecuteProcess

    launch.logging.reset()
    folder = work / "log" / name
    folder.mkdir(parents=True)
    launch.logging.launch_config.log_dir = str(folder)
    described = [ExecuteProcess(cmd=[python, *cmd], name=proc, output=output, cwd=str(work))
                 for proc, cmd, output in actions]
    service = launch.LaunchService()
    service.include_launch_description(launch.LaunchDescription(described))
    service.run()
    target = out / name
    target.mkdir(parents=True, exist_ok=True)
    text = (folder / "launch.log").read_text(encoding="utf-8")
    for local, fixed in ((python.rsplit("/bin/", 1)[0], "/opt/venv"), (str(work.resolve()), "/home/robot/ws"),
                         (str(work), "/home/robot/ws")):
        text = text.replace(local, fixed)
    (target / "launch.log").write_text(text, encoding="utf-8")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--launch", type=Path, required=True, help="the `launch` package folder of ros2/launch")
    parser.add_argument("--python", required=True, help="a Python with rclpy (the project's .venv/bin/python)")
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    sys.path.insert(0, str(args.launch))
    sys.path.insert(0, str(Path(__file__).parent))
    from stack_faults import NODE, WRONG_TYPE

    python = str(Path(args.python).absolute())
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        (work / "scan_filter.py").write_text(NODE, encoding="utf-8")
        (work / "odom_relay.py").write_text(HEALTHY, encoding="utf-8")
        (work / "scan_filter.yaml").write_text(WRONG_TYPE, encoding="utf-8")
        run_launch("params_file", [
            ("odom_relay", ["odom_relay.py"], "log"),
            ("scan_filter", ["scan_filter.py", "--ros-args", "--params-file", "scan_filter.yaml"], "log")],
            work, args.out, python)
        run_launch("crash", [("scan_filter", ["scan_filter.py", "--crash"], "both")], work, args.out, python)
        run_launch("screen", [("scan_filter", ["scan_filter.py", "--ros-args", "-r", "__node:=front-lidar"],
                               "screen")], work, args.out, python)
        shutil.rmtree(work / "log")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
