"""Write the README's tables of the real-log suites from the reports under docs/eval/ (each set as measured once
before anything was tuned on it, `<suite>-before/report.json`, and as the code answers it now, `<suite>/`), or with
--check fail when the README says otherwise.

    .venv/bin/python scripts/real_logs_table.py            # print the tables
    .venv/bin/python scripts/real_logs_table.py --write    # put them into README.md between the markers
    .venv/bin/python scripts/real_logs_table.py --check    # exit 1 when README.md's tables are not these
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from hexar.evals.real_table import replace_block, table

ROOT = Path(__file__).resolve().parents[1]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--readme", type=Path, default=ROOT / "README.md")
    parser.add_argument("--docs", type=Path, default=ROOT / "docs" / "eval")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--write", action="store_true")
    mode.add_argument("--check", action="store_true")
    args = parser.parse_args(argv)
    block = table(args.docs)
    if not (args.write or args.check):
        print(block, end="")
        return 0
    try:
        text = args.readme.read_text(encoding="utf-8")
        wanted = replace_block(text, block)
    except (OSError, ValueError) as err:
        print(f"ERROR: {err}", file=sys.stderr)
        return 2
    if args.check:
        if wanted != text:
            print(f"ERROR: {args.readme.name}'s real-log tables differ from the reports under {args.docs}: "
                  "run scripts/real_logs_table.py --write", file=sys.stderr)
            return 1
        return 0
    args.readme.write_text(wanted, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
