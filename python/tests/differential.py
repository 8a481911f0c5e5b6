"""The command line and the Python module run one pipeline: for the files of
the shared corpus (../shared/corpus, or $DELTAMESH_CORPUS) under switch
strings covering -p, -pq, -pqa, -pA, -c, -D, -Y, -r, -o2 and --adapt, the
CLI's output files and triangulate()/adapt()'s arrays must be identical:
vertices, markers, attributes, triangles, segments, edges and neighbours.
Every mesh also goes through the library's validator: -C on both sides
(the CLI exits 5, Python raises CheckError when it finds a problem).

Usage: differential.py CLI [CORPUS] ($DELTAMESH_CORPUS, when set, wins).
Exits 77 (skipped, with a message) without a corpus.
Cheap switch strings run on every file; costly ones on the files below a
size (the big ones take seconds each and add nothing the small ones miss).
"""
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

import deltamesh

SKIP = 77
CHEAP_SIZE = 4_000_000    # bytes: every file but the largest for -p -pA -pc
COSTLY_SIZE = 60_000      # refinement on the smaller files
ADAPT_SIZE = 20_000       # -r and --adapt on the smallest
WORKERS = 2


def read_table(path, cols):
    """The first `cols` columns after the index of a Triangle .edge/.neigh
    file written with -z (0-based; header: the count and one more number)."""
    with open(path) as f:
        text = re.sub(r"#[^\n]*", "", f.read())
    numbers = np.fromstring(text, dtype=np.int64, sep=" ")
    rows = int(numbers[0])
    return numbers[2:].reshape(rows, -1)[:, 1:1 + cols] if rows else np.zeros((0, cols), np.int64)


def cli_mesh(cli, work, name, switches, extra=()):
    """Runs the CLI in `work` on `name`; returns its next iteration as a dict."""
    args = [cli, switches + "zQneC", *extra, name]
    p = subprocess.run(args, cwd=work, capture_output=True, text=True, timeout=120)
    if p.returncode not in (0, 3):  # 3: a budget stopped refinement (a result, compared too)
        raise AssertionError(f"{' '.join(args)}: exit {p.returncode}: {p.stderr.strip()}")
    base = name.rsplit(".", 1)[0] if name.endswith((".poly", ".node")) else name
    stem, _, it = base.rpartition(".")
    out = os.path.join(work, f"{stem}.{int(it) + 1}" if stem and it.isdigit() else base + ".1")
    mesh = deltamesh.read(out + ".node")
    edges = read_table(out + ".edge", 3)
    mesh["edges"], mesh["edge_markers"] = edges[:, :2], edges[:, 2]
    mesh["neighbors"] = read_table(out + ".neigh", 3)
    return mesh, out, p.returncode


def compare(cli_m, py_m, label):
    """Same arrays in both (segments: the CLI writes them from its .poly)."""
    problems = []
    # Segments: the same edges with the same markers; Python lists them in
    # the input's order (Triangle's package), the CLI's .poly in triangle order.
    if cli_m.get("segments") is not None and py_m.get("segments") is not None:
        def edge_set(m):
            s = np.asarray(m["segments"]).reshape(-1, 2)
            mk = np.asarray(m.get("segment_markers", np.zeros(len(s)))).reshape(-1)
            return sorted((int(min(a, b)), int(max(a, b)), int(k)) for (a, b), k in zip(s, mk))
        if edge_set(cli_m) != edge_set(py_m):
            problems.append("segments: different edges or markers")
        cli_m = {k: v for k, v in cli_m.items() if k not in ("segments", "segment_markers")}
        py_m = {k: v for k, v in py_m.items() if k not in ("segments", "segment_markers")}
    # -A with no region point: the CLI's .ele has an all-zero attribute column
    # (Triangle's program), the module none (Triangle's Python package).
    if "triangle_attributes" in cli_m and "triangle_attributes" not in py_m and \
            not np.asarray(cli_m["triangle_attributes"]).any():
        cli_m = {k: v for k, v in cli_m.items() if k != "triangle_attributes"}
    for key in ("vertices", "vertex_markers", "vertex_attributes", "triangles", "triangle_attributes",
                "neighbors", "segments", "segment_markers", "edges", "edge_markers"):
        a, b = cli_m.get(key), py_m.get(key)
        if key == "segments" and a is not None and b is not None:
            a = a.reshape(-1, 2)
        if key in ("vertex_markers", "segment_markers", "edge_markers") and a is not None:
            a = a.reshape(-1)
            b = None if b is None else b.reshape(-1)
        if a is None and b is None:
            continue
        if a is None or b is None:
            # An empty array on one side, absent on the other, is the same.
            if (a if a is not None else b).size == 0:
                continue
            problems.append(f"{key}: {'CLI' if a is None else 'Python'} has none")
            continue
        if a.shape != b.shape or not np.array_equal(np.asarray(a, dtype=b.dtype), b):
            problems.append(f"{key}: CLI {a.shape} != Python {b.shape}")
    if problems:
        raise AssertionError(f"{label}: " + "; ".join(problems))


def bbox_area(pslg):
    v = pslg["vertices"]
    if len(v) == 0:
        return 1.0
    span = v.max(axis=0) - v.min(axis=0)
    return float(max(span[0] * span[1], 1e-300))


def sizes_ramp(vertices):
    """Target edge lengths growing left to right over the bounding box."""
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    w = max(float(hi[0] - lo[0]), 1e-300)
    scale = max(float((hi - lo).max()), 1e-300)
    return scale * (0.01 + 0.05 * (vertices[:, 0] - lo[0]) / w)


def check_file(cli, corpus, f, size, work_root):
    """Every switch string for one corpus file; returns (runs, failure messages)."""
    poly = f.endswith(".poly")
    p = "p" if poly else ""
    src = os.path.join(corpus, f)
    pslg = deltamesh.read(src)
    # Digits and '.' only: a letter after the number is the next switch.
    area = np.format_float_positional(bbox_area(pslg) / 2000, unique=True, trim="-")
    plans = []
    if size <= CHEAP_SIZE:
        plans += [p, p + "A", p + "c"] if poly else ["", "c"]
    if size <= COSTLY_SIZE:
        plans += [p + "q30", p + "q33", p + "qa" + area, p + "D", p + "q30Y", p + "q30o2"]
    work = os.path.join(work_root, f)
    os.makedirs(work)
    shutil.copy(src, work)
    runs, failures = 0, []
    for sw in plans:
        label = f"{f} -{sw}"
        runs += 1
        for old in os.listdir(work):  # the previous run's outputs
            if old != f:
                os.remove(os.path.join(work, old))
        try:
            cli_m, out, _ = cli_mesh(cli, work, f, "-" + sw)
            py_m = deltamesh.triangulate(pslg, sw + "QneC")
            compare(cli_m, py_m, label)
            if not poly or size > ADAPT_SIZE or sw != p:
                continue
            # -r on the mesh just made (its .poly's segments and holes are
            # in again), and --adapt to sizes in a .mtr file.
            runs += 2
            stem = os.path.basename(out)
            mesh = deltamesh.read(out + ".node")
            cli_r, _, _ = cli_mesh(cli, work, stem, "-rpq30")
            py_r = deltamesh.triangulate(mesh, "rpq30QneC")
            compare(cli_r, py_r, f"{f} -p then -rpq30")
            h = sizes_ramp(mesh["vertices"])
            with open(out + ".mtr", "w") as m:
                m.write(f"{len(h)} 1\n" + "".join(repr(float(x)) + "\n" for x in h))
            cli_a, _, _ = cli_mesh(cli, work, stem, "-rpq30", ("--adapt",))
            py_a = deltamesh.adapt(mesh, h, "q30QneC")
            compare(cli_a, py_a, f"{f} -p then -rpq30 --adapt")
        except (AssertionError, deltamesh.Error, ValueError) as e:
            failures.append(f"FAIL {label}: {e}")
    shutil.rmtree(work, ignore_errors=True)
    return runs, failures


def main():
    cli = os.path.abspath(sys.argv[1])
    corpus = os.environ.get("DELTAMESH_CORPUS") or (sys.argv[2] if len(sys.argv) > 2 else "")
    if not corpus or not os.path.isdir(corpus):
        print(f"differential: no corpus at '{corpus}' (../shared/corpus or $DELTAMESH_CORPUS): skipped")
        return SKIP
    files = [f for f in os.listdir(corpus) if f.endswith((".poly", ".node"))]
    size = {f: os.path.getsize(os.path.join(corpus, f)) for f in files}
    files.sort(key=lambda f: -size[f])  # the big ones first: two workers end together
    runs = failures = 0
    t0 = time.perf_counter()
    work_root = tempfile.mkdtemp(prefix="dm_diff_")
    try:
        with concurrent.futures.ProcessPoolExecutor(max_workers=WORKERS) as pool:
            jobs = [pool.submit(check_file, cli, corpus, f, size[f], work_root) for f in files]
            for job in jobs:
                n, fails = job.result()
                runs += n
                failures += len(fails)
                for line in fails:
                    print(line)
    finally:
        shutil.rmtree(work_root, ignore_errors=True)
    print(f"differential: {runs} runs on {len(files)} files, {failures} failed, "
          f"{time.perf_counter() - t0:.1f} s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
