#!/usr/bin/env python3
"""Runs every `scripts/aesim` command shown in the README's and the guides' shell blocks, as
written, in a scratch folder that sees the repository's scenes, presets, receivers and scripts;
fails when one no longer runs (exit status other than 0). The documentation cannot rot unseen.

usage: doc_commands.py AESIM_BINARY SOURCE_DIR [--python-path DIR] [--list]
With --python-path (the folder of the built `aesim` module), `scripts/python` commands run too.
"""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

# Names the guides use for the reader's own files, each made here by a command of aesim's own.
PLACEHOLDERS = {
    "recording.aedat4": ["run", "--duration", "200ms", "--out", "recording.aedat4"],
}
# What the scratch folder holds of the repository: copies (3 MB), so that a command that writes
# beside its inputs (a guide regenerating a shipped preset) writes into the scratch folder.
SHARED = ["scenes", "models", "rtl", "tests", "scripts"]


def shell_blocks(path):
    """The lines of a Markdown file's ```sh blocks, continuation lines joined."""
    lines, inside, pending = [], False, ""
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            inside = line.strip() == "```sh" and not inside
            continue
        if not inside:
            continue
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        lines.append(pending + line)
        pending = ""
    return lines


def printed_example(source):
    """The README's copy of what `scripts/aesim` prints, or None."""
    text = (source / "README.md").read_text(encoding="utf-8")
    at = text.find("`scripts/aesim` prints")
    if at < 0:
        return None
    start = text.index("```\n", at) + 4
    return text[start:text.index("```\n", start)]


def without_wall_time(text):
    return re.sub(r"in [0-9.e+-]+ s wall time", "in (wall time) s wall time", text)


def commands(source):
    pages = [source / "README.md"] + sorted((source / "docs").glob("*.md"))
    seen, out = set(), []
    for page in pages:
        for line in shell_blocks(page):
            words = shlex.split(line, comments=True)
            if not words or words[0] not in ("scripts/aesim", "scripts/python"):
                continue
            if words[0] == "scripts/aesim":
                args = ["aesim"] + (words[1:] or ["run"])  # scripts/aesim alone runs `aesim run`
            else:
                args = ["python"] + words[1:]
            key = tuple(args)
            if key not in seen:
                seen.add(key)
                out.append((page.relative_to(source), args))
    return out


def main():
    binary, source = sys.argv[1], pathlib.Path(sys.argv[2]).resolve()
    python_path = sys.argv[sys.argv.index("--python-path") + 1] if "--python-path" in sys.argv else None
    found = [(page, args) for page, args in commands(source) if args[0] == "aesim" or python_path]
    if "--list" in sys.argv:
        for page, args in found:
            print(page, " ".join(args))
        return 0
    if len(found) < 10:
        print(f"only {len(found)} commands found: the extraction is broken", file=sys.stderr)
        return 1
    env = dict(os.environ, SYSTEMC_DISABLE_COPYRIGHT_MESSAGE="1")
    if python_path:
        env["PYTHONPATH"] = python_path
    failed = 0
    with tempfile.TemporaryDirectory(prefix="aesim-doc-commands-") as scratch:
        for name in SHARED:
            shutil.copytree(source / name, pathlib.Path(scratch) / name, symlinks=True)
        os.mkdir(pathlib.Path(scratch) / "docs")
        for page, args in found:
            for arg in args:
                if arg in PLACEHOLDERS and not (pathlib.Path(scratch) / arg).exists():
                    subprocess.run([binary] + PLACEHOLDERS[arg], cwd=scratch, env=env, check=True,
                                   stdout=subprocess.DEVNULL)
            program = [binary] if args[0] == "aesim" else [sys.executable]
            r = subprocess.run(program + args[1:], cwd=scratch, env=env, capture_output=True, text=True,
                               timeout=600)
            status = "ok" if r.returncode == 0 else f"FAILED (exit {r.returncode})"
            print(f"{page}: {' '.join(args)}: {status}")
            if r.returncode != 0:
                failed += 1
                print("  " + r.stderr.strip().replace("\n", "\n  "))
            if page.name == "README.md" and args == ["aesim", "run"]:
                shown = printed_example(source)
                if shown is None or without_wall_time(shown) != without_wall_time(r.stdout):
                    failed += 1
                    print("  the README's copy of its output differs from the program's:\n" + r.stdout)
    print(f"{len(found) - failed} of {len(found)} documented commands ran")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
