#!/usr/bin/env python3
"""Lists (or with --delete removes) corpus files that carry recognisable content of the shared
scenes: three or more data lines (12+ characters, comments stripped) found in a shared scene
and not in the project's own files. The shared scenes may seed a local fuzz run but may not be
copied into the repository.

    python3 fuzz/shared_filter.py [--delete] corpus/shp corpus/brs ...
"""
import os
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
SHARED = pathlib.Path(os.environ.get("RAYGINE_SHARED", HERE.parent.parent / "shared")) / "scenes"
OWN = [HERE.parent / "assets" / "scenes"]
MIN_LEN = 12
MAX_SHARED_LINES = 2


def lines(data):
    out = set()
    for raw in data.replace(b"\r", b"\n").split(b"\n"):
        line = b" ".join(raw.split(b";;")[0].split())
        if len(line) >= MIN_LEN:
            out.add(line)
    return out


def corpus_of(root):
    out = set()
    for path in root.rglob("*"):
        if path.is_file():
            out |= lines(path.read_bytes())
    return out


def main():
    delete = "--delete" in sys.argv
    dirs = [pathlib.Path(a) for a in sys.argv[1:] if a != "--delete"]
    if not SHARED.is_dir():
        print(f"shared_filter.py: {SHARED} is absent: nothing to compare with")
        return
    shared = corpus_of(SHARED)
    for own in OWN:
        shared -= corpus_of(own)
    flagged = 0
    for d in dirs:
        for path in sorted(d.iterdir()):
            hits = lines(path.read_bytes()) & shared
            if len(hits) > MAX_SHARED_LINES:
                flagged += 1
                if delete:
                    path.unlink()
                else:
                    print(f"{path}: {len(hits)} shared lines")
    print(f"shared_filter.py: {flagged} files {'removed' if delete else 'flagged'}")


main()
