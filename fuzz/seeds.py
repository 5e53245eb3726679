#!/usr/bin/env python3
"""Builds local seed inputs for the fuzz targets from the shared scenes (../../shared/scenes or
$RAYGINE_SHARED/scenes) into fuzz/seeds/<target>/ (git-ignored: the shared scenes may not be
copied into the project). Big meshes become small valid files (their first vertices and the
triangles that use only those) and raw truncations of a few KB.

    python3 fuzz/seeds.py
"""
import os
import pathlib
import re

HERE = pathlib.Path(__file__).resolve().parent
SHARED = pathlib.Path(os.environ.get("RAYGINE_SHARED", HERE.parent.parent / "shared")) / "scenes"
OUT = HERE / "seeds"
TRUNCATE = 4096
KEEP_VERTICES = 60


def small_brep(lines, keep=KEEP_VERTICES):
    """The sections of one brep cut down to `keep` vertices, as lines (no define/enddef)."""
    data = [re.split(r";;", line)[0].strip() for line in lines]
    out, i = [], 0
    while i < len(data):
        words = data[i].split()
        if not words:
            i += 1
            continue
        key = words[0].lower()
        if key == "vertices":
            n = int(words[1])
            verts = data[i + 1 : i + 1 + n]
            i += 1 + n
        elif key == "triangles":
            n = int(words[1])
            tris = data[i + 1 : i + 1 + n]
            i += 1 + n
        elif key == "parts":
            nparts = int(words[1])
            values = []
            i += 1
            while len(values) < len(tris) and i < len(data):
                values += data[i].split()
                i += 1
        else:
            i += 1
    verts = verts[:keep]
    kept = [(t, p) for t, p in zip(tris, values or ["0"] * len(tris))
            if all(int(v) < len(verts) for v in t.split())][:2 * keep]
    out.append(f"vertices {len(verts)}")
    out += verts
    out.append(f"triangles {len(kept)}")
    out += [t for t, _ in kept]
    if values:
        out.append(f"parts {nparts}")
        parts = [p for _, p in kept]
        out += [" ".join(parts[k : k + 10]) for k in range(0, len(parts), 10)]
    return out


def write(target, name, data):
    path = OUT / target / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)


def main():
    if not SHARED.is_dir():
        print(f"seeds.py: {SHARED} is absent: no shared seeds")
        return
    for path in sorted(SHARED.rglob("*")):
        if not path.is_file() or path.name.endswith(".md"):
            continue
        raw = path.read_bytes()
        stem = path.relative_to(SHARED).as_posix().replace("/", "_")
        target = "brs" if path.suffix == ".brs" else "shp"
        if path.suffix in (".atr", ".prb", ".lgt", ".cam"):
            target = path.suffix[1:]
        if len(raw) <= 16384:
            write(target, stem, raw)
        if len(raw) > TRUNCATE:
            write(target, stem + ".head", raw[:TRUNCATE])
        text = raw.decode("utf-8", "replace").splitlines()
        if path.suffix == ".brs":
            write("brs", stem + ".small", ("\n".join(small_brep(text)) + "\nshading\n" + "1.0 " * 20 + "\n").encode())
        elif path.suffix == ".shp" and len(raw) > 16384:
            body = small_brep(text)
            head = text[: next(k for k, l in enumerate(text) if l.lower().startswith("define"))]
            small = head + ["define breps brs_0"] + body + ["enddef"]
            write("shp", stem + ".small", ("\r\n".join(small) + "\r\n").encode())
    print(f"seeds.py: wrote {sum(1 for _ in OUT.rglob('*') if _.is_file())} files under {OUT}")


main()
