#!/usr/bin/env python3
"""The sample output in README.md is what the pw85 program prints.

usage: check_readme_output.py README PROGRAM

Finds the first fenced code block of README whose lines include a command
running build/src/tools/pw85 with no arguments, takes the next fenced block
as the expected output, runs PROGRAM (no arguments) and fails on any
difference between its standard output and that block, or on a non-zero
exit status.
"""
import difflib
import re
import subprocess
import sys

COMMAND = re.compile(r"(^|[\s&;])build/src/tools/pw85\s*$")


def fenced_blocks(text):
    """(info string, lines) of each ``` block, in order."""
    blocks, current, info = [], None, None
    for line in text.splitlines():
        if line.startswith("```"):
            if current is None:
                current, info = [], line[3:].strip()
            else:
                blocks.append((info, current))
                current = None
        elif current is not None:
            current.append(line)
    return blocks


def main():
    readme, program = sys.argv[1], sys.argv[2]
    with open(readme) as f:
        blocks = fenced_blocks(f.read())
    for index, (_, lines) in enumerate(blocks):
        if any(COMMAND.search(l) for l in lines):
            break
    else:
        print(f"{readme}: no fenced block runs build/src/tools/pw85")
        return 1
    if index + 1 >= len(blocks):
        print(f"{readme}: no fenced block follows the one that runs the program")
        return 1
    expected = blocks[index + 1][1]
    run = subprocess.run([program], capture_output=True, text=True)
    actual = run.stdout.splitlines()
    if run.returncode != 0:
        print(f"{program} exited with status {run.returncode}: {run.stderr}")
        return 1
    if actual != expected:
        print(f"{readme} shows an output that {program} does not print:")
        sys.stdout.writelines(difflib.unified_diff(
            [l + "\n" for l in expected], [l + "\n" for l in actual],
            fromfile=f"{readme} (block {index + 2})", tofile=program))
        return 1
    print(f"{readme}: the {len(expected)} lines after the command are the output")
    return 0


if __name__ == "__main__":
    sys.exit(main())
