"""``python -m amiro.ros2.msgbuild --package tf2_msgs [--out PREFIX]``: run by setup.

Prints what was built (or that it was already current) and how long it took; a missing
compiler or a bad definition is one line on stderr and exit status 2.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from amiro.core.config import ConfigError
from amiro.ros2.msgbuild import build_package
from amiro.ros2.msgbuild.package import shipped_packages


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m amiro.ros2.msgbuild",
        description="Build the ROS 2 interface packages shipped as .msg/.action files.",
    )
    parser.add_argument(
        "--package",
        action="append",
        help=f"package to build, repeatable (default: {', '.join(shipped_packages())})",
    )
    parser.add_argument("--out", type=Path, help="install prefix (default: this venv)")
    parser.add_argument("--force", action="store_true", help="rebuild even if up to date")
    parser.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    args = parser.parse_args(argv)
    results = []
    try:
        for name in args.package or shipped_packages():
            results.append(build_package(name, args.out, force=args.force))
    except ConfigError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    if args.json:
        print(
            json.dumps(
                {
                    "packages": [
                        {
                            "package": r.package,
                            "prefix": str(r.prefix),
                            "skipped": r.skipped,
                            "seconds": round(r.seconds, 2),
                            "libraries": [str(p) for p in r.libraries],
                        }
                        for r in results
                    ]
                }
            )
        )
    else:
        for r in results:
            state = "up to date" if r.skipped else f"built in {r.seconds:.1f} s"
            print(f"{r.package}: {state} in {r.prefix}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
