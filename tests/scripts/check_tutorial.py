#!/usr/bin/python3
"""Runs the commands of a tutorial page and checks the outputs it shows.

  /usr/bin/python3 tests/scripts/check_tutorial.py --plateball build/plateball docs/tutorials/PAGE.md

Every ```console block of the page holds commands ("$ COMMAND") each followed by the lines it shows.
The commands run in order, in one scratch directory (files written by one are read by the next)
holding a link to the repository's problems/, with the directory of --plateball first on the PATH,
through `bash -o pipefail`. Each must exit 0, and every line shown (but "...", which marks left-out
lines) must be a line of the command's real standard output, in the order shown. Prints each
command with its verdict; exits 1 when any failed.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
# One command of a tutorial runs in seconds (a MuJoCo replay of 12 s of motion: about 1 s of CPU).
COMMAND_TIMEOUT_S = 120


def console_examples(text):
    """(command, shown lines) of every "$ " line of the page's ```console blocks, in order."""
    examples, in_block = [], False
    for line in text.splitlines():
        if line.startswith("```"):
            in_block = line.strip() == "```console" if not in_block else False
            continue
        if not in_block:
            continue
        if line.startswith("$ "):
            examples.append((line[2:], []))
        elif examples:
            examples[-1][1].append(line)
    return examples


def missing_line(shown, real):
    """The first shown line that is not a line of real after the previous one's match; None if all are."""
    at = 0
    for line in shown:
        if line.strip() == "...":
            continue
        while at < len(real) and real[at] != line:
            at += 1
        if at == len(real):
            return line
        at += 1
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plateball", required=True, help="the built plateball tool")
    parser.add_argument("page", help="the tutorial page (Markdown)")
    args = parser.parse_args()
    with open(args.page) as f:
        examples = console_examples(f.read())
    if not examples:
        print(f"FAIL: {args.page}: no ```console block with a \"$ \" command")
        return 1
    env = dict(os.environ, PATH=os.path.dirname(os.path.abspath(args.plateball)) + os.pathsep + os.environ["PATH"])
    failures = 0
    with tempfile.TemporaryDirectory() as scratch:
        os.symlink(os.path.join(ROOT, "problems"), os.path.join(scratch, "problems"))
        for command, shown in examples:
            result = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=scratch, env=env,
                                    capture_output=True, text=True, timeout=COMMAND_TIMEOUT_S)
            if result.returncode != 0:
                verdict = f"FAIL: exit code {result.returncode}: {result.stderr.strip()[-500:]}"
            else:
                line = missing_line(shown, result.stdout.splitlines())
                verdict = "ok" if line is None else f"FAIL: the shown line {line!r} is not in the output (in order)"
            failures += verdict != "ok"
            print(f"{verdict}: $ {command} ({sum(1 for s in shown if s.strip() != '...')} lines shown)")
    print(f"{len(examples)} commands of {os.path.relpath(args.page, ROOT)}, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
