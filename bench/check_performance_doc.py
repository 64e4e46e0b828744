#!/usr/bin/python3
"""The tables of docs/performance.md are written from the benchmark CSVs.

    check_performance_doc.py DOCS_DIR            # check (the meson test)
    check_performance_doc.py DOCS_DIR --write    # rewrite the tables

Each table of performance.md that comes from a CSV sits between

    <!-- generated: NAME -->
    ...
    <!-- end generated -->

and is the output of the function NAME below applied to the CSV of that
benchmark in DOCS_DIR (a value printed with fewer digits than the CSV holds
is rounded, nothing else). The check fails when a table differs from what
the CSV gives, when a block names no known table, or when a number of the
cost column of guide.md's task table appears in none of the generated
tables (the guide quotes performance.md, it does not measure). After a new
run of a benchmark, copy its CSV into docs/ and run with --write.
"""
import csv
import io
import os
import re
import sys


def read_sections(path):
    """Rows of a CSV as dicts, grouped in sections: a section starts at a
    header line (no field is a number) or after a '#' comment line, whose
    text labels the section."""
    sections = []
    header = None
    label = ""
    with open(path) as fh:
        lines = fh.read().splitlines()
    for line in lines:
        if not line.strip():
            continue
        if line.startswith("#"):
            label = line[1:].strip()
            sections.append((label, header, []))
            continue
        fields = next(csv.reader(io.StringIO(line)))
        if not any(_is_number(f) for f in fields):  # a header
            header = fields
            sections.append((label, header, []))
            continue
        sections[-1][2].append(dict(zip(header, fields)))
    return [(lab, rows) for lab, _, rows in sections if rows]


def _is_number(s):
    try:
        float(s)
        return True
    except ValueError:
        return False


def rows_of(path):
    return [r for _, rows in read_sections(path) for r in rows]


def table(head, rows):
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(out)


def f1(x):
    return f"{float(x):.1f}"


def f2(x):
    return f"{float(x):.2f}"


def err(x):
    return f"{float(x):.1e}"


CLASSES = ["0 [0.5, 2]", "1 [0.1, 10]", "2 [0.01, 100]", "3 [0.001, 1000]"]


def contact_methods(docs):
    rows = rows_of(os.path.join(docs, "bench_contact.csv"))
    methods = []
    for r in rows:
        if r["method"] not in methods:
            methods.append(r["method"])
    out = []
    for m in methods:
        cells = [f"`{m}`" if m.startswith("pw85") else m]
        for c in range(4):
            r = next(r for r in rows if r["method"] == m and int(r["class"]) == c)
            cells.append(f"{f1(r['median_ns'])} / {err(r['max_rel_err'])} / {r['n_status_nonzero']}")
        out.append(cells)
    return table(["method"] + [f"class {c}" for c in CLASSES], out)


def overlap(docs):
    rows = rows_of(os.path.join(docs, "bench_overlap.csv"))
    scenes = []
    for r in rows:
        if r["scene"] not in scenes and not r["scene"].startswith("batch/"):
            scenes.append(r["scene"])
    out = []
    for s in scenes:
        by = {r["function"]: r for r in rows if r["scene"] == s}
        ov, de = by["pw85_overlap"], by["contact_function_DEFAULT"]
        fcl = by.get("fcl_collide")
        out.append([s, ov["n_pairs"], f1(ov["median_ns"]), f1(de["median_ns"]),
                    f1(fcl["median_ns"]) if fcl else "—",
                    f"{ov['wrong_verdicts']} / {fcl['wrong_verdicts'] if fcl else '—'}"])
    return table(["scene", "pairs", "`pw85_overlap` ns", "DEFAULT, μ² < 1, ns", "FCL ns",
                  "wrong verdicts pw85 / FCL"], out)


def dca(docs):
    rows = rows_of(os.path.join(docs, "bench_dca.csv"))
    out = []
    for c in range(4):
        by = {r["method"]: r for r in rows if int(r["class"]) == c}
        z, b, d = by["pw85_dca(ZHENG)"], by["pw85_dca(BRENT)"], by["pw85_dca(DEFAULT)"]
        t, cf = by["pw85_dca_2d"], by["1/sqrt(pw85_contact_function_2d)"]
        out.append([CLASSES[c], f"{f1(z['ns_median'])} ({z['evaluations_mean']})", f1(b["ns_median"]),
                    f1(d["ns_median"]), f1(t["ns_median"]), f1(cf["ns_median"]),
                    f"{err(z['rel_err_max'])} / {err(d['rel_err_max'])} / {err(t['rel_err_max'])}",
                    b["n_status_not_ok"]])
    return table(["class", "ZHENG ns (planes)", "BRENT route ns", "DEFAULT route ns",
                  "`pw85_dca_2d` ns", "2D contact function ns",
                  "max error ZHENG / DEFAULT / 2D", "BRENT route not OK"], out)


def derivatives(docs):
    rows = rows_of(os.path.join(docs, "bench_derivatives.csv"))
    out = []
    for r in rows:
        c = int(r["class"])
        out.append([CLASSES[c], r["default_ns"], r["derivatives_ns"], r["ratio_derivatives_default"],
                    r["forces_ns"], r["ratio_forces_default"],
                    r["contact_ns"], r["pairs_default_ns"], r["pairs_derivatives_ns"], r["ratio_pairs"],
                    r["pairs_forces_ns"], r["ratio_pairs_forces"]])
    return table(["class", "DEFAULT", "`pw85_contact_derivatives`", "ratio", "FORCES", "ratio",
                  "`pw85_contact`", "`pw85_contact_function_pairs`",
                  "`pw85_contact_derivatives_pairs`", "ratio", "FORCES pairs", "ratio"], out)


def derivatives_callgrind(docs):
    rows = rows_of(os.path.join(docs, "bench_derivatives_callgrind.csv"))
    out = [[CLASSES[int(r["class"])], r["default_per_pair"], r["derivatives_per_pair"], r["ratio"],
            r["forces_per_pair"], r["ratio_forces"]] for r in rows]
    return table(["class", "DEFAULT", "`pw85_contact_derivatives`", "ratio", "FORCES", "ratio"],
                 out)


def _batch_sections(docs):
    return read_sections(os.path.join(docs, "bench_batch.csv"))


def batch(docs):
    label, rows = _batch_sections(docs)[0]
    out = []
    for r in rows:
        name = r["function"]
        out.append([name, f"{r['median_ns']} ({r['min_ns']}–{r['max_ns']})",
                    f"{f2(r['ratio_to_loop_median'])} ({f2(r['ratio_min'])}–{f2(r['ratio_max'])})"])
    return table(["call", "ns per pair (min–max)", "ratio to the loop above (min–max)"], out)


def batch_classes(docs):
    out = []
    for label, rows in _batch_sections(docs)[1:]:
        m = re.match(r"class (\d)", label)
        if not m:
            continue
        by = {r["function"]: r for r in rows}
        lo, po = by["loop pw85_overlap"], by["pw85_overlap_pairs"]
        ld, pd = by["loop pw85_contact_function_method DEFAULT"], by["pw85_contact_function_pairs DEFAULT"]
        out.append([CLASSES[int(m.group(1))], f"{lo['median_ns']} → {po['median_ns']}",
                    f2(po["ratio_to_loop_median"]), f"{ld['median_ns']} → {pd['median_ns']}",
                    f2(pd["ratio_to_loop_median"])])
    return table(["class", "overlap: loop → `pw85_overlap_pairs` ns", "ratio",
                  "DEFAULT: loop → `pw85_contact_function_pairs` ns", "ratio"], out)


def contact_time(docs):
    rows = rows_of(os.path.join(docs, "bench_contact_time.csv"))
    out = []
    for c in range(4):
        by = [r for r in rows if int(r["class"]) == c]
        out.append([CLASSES[c], " / ".join(f"{r['median_eval']} ({r['max_eval']})" for r in by),
                    " / ".join(r["ns_median"] for r in by), by[0]["ns_default"],
                    " / ".join(r["ns_per_eval_over_default"] for r in by)])
    kinds = " / ".join(r["kind"] for r in rows if int(r["class"]) == 0)
    return table(["class", f"evaluations, median (max): {kinds}", "ns per call", "DEFAULT ns",
                  "per evaluation ÷ DEFAULT"], out)


def scene(docs):
    rows = rows_of(os.path.join(docs, "bench_scene.csv"))
    out = []
    for n in dict.fromkeys(r["n"] for r in rows if r["name"] == "query_s1"):
        by = {r["name"]: r for r in rows if r["n"] == n and r["phi"] == "0.45"}
        q, o, ra = by["query_s1"], by["overlap_pairs"], by["ratio_query_to_overlap_pairs"]
        out.append([n, f"{f1(q['median'])} ({f1(q['min'])}–{f1(q['max'])})",
                    f"{f1(o['median'])} ({f1(o['min'])}–{f1(o['max'])})",
                    f"{f2(ra['median'])} ({f2(ra['min'])}–{f2(ra['max'])})",
                    f2(by["sphere_pairs_s1"]["median"]), f"{float(by['examined_s1']['median']):.4f}"])
    return table(["N", "query ns/particle", "`pw85_overlap_pairs` over the sphere pairs, ns/particle",
                  "ratio", "sphere pairs per particle", "pairs to the exact predicate per particle"], out)


def scene_shell(docs):
    rows = rows_of(os.path.join(docs, "bench_scene.csv"))
    out = []
    keys = dict.fromkeys((r["aspect"], r["n"]) for r in rows if r["name"] == "within_s1.2")
    for aspect, n in keys:
        by = {r["name"]: r for r in rows if r["n"] == n and r["aspect"] == aspect}
        out.append([aspect, n, f2(by["sphere_pairs_s1.2"]["median"]), f"{float(by['examined_s1.2']['median']):.3f}",
                    f"{float(by['within_s1.2']['median']):.3f}", f2(by["ratio_examined_to_within"]["median"])])
    return table(["aspect", "N", "sphere pairs", "to the exact predicate", "within s = 1.2",
                  "ratio"], out)


def lammps(docs):
    out = []
    for label, rows in read_sections(os.path.join(docs, "bench_lammps.csv")):
        if not rows or "rep" not in rows[0]:
            continue
        m = re.search(r"--phi ([0-9.]+)", label)
        res = {}
        for style in ("pw85/soft", "gayberne"):
            cpu = sorted(float(r["cpu_ns_per_pair"]) for r in rows if r["style"] == style)
            res[style] = (cpu[len(cpu) // 2], cpu[0], cpu[-1])
        p, g = res["pw85/soft"], res["gayberne"]
        out.append([m.group(1) if m else "?", rows[0]["neighbour_pairs"],
                    f"{p[0]} ({p[1]}–{p[2]})", f"{g[0]} ({g[1]}–{g[2]})", f2(p[0] / g[0])])
    return table(["φ", "neighbour pairs", "pw85/soft ns per pair (CPU)", "gayberne ns per pair (CPU)",
                  "ratio"], out)


GENERATORS = {f.__name__: f for f in (contact_methods, overlap, dca, derivatives,
                                      derivatives_callgrind, batch, batch_classes,
                                      contact_time, scene, scene_shell, lammps)}

BLOCK = re.compile(r"(<!-- generated: (\w+) -->\n)(.*?)(<!-- end generated -->)", re.S)
NUMBER = re.compile(r"\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def guide_cost_numbers(path):
    """Numbers of the cost column of guide.md's task table."""
    nums = []
    with open(path) as fh:
        lines = fh.read().splitlines()
    col = None
    for line in lines:
        if not line.startswith("|"):
            col = None
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if col is None:
            col = next((i for i, c in enumerate(cells) if c.startswith("cost")), -1)
            continue
        if col < 0 or set(line) <= set("|-: ") or col >= len(cells):
            continue
        cell = re.sub(r"\[[^\]]*\]\([^)]*\)", "", cells[col])  # drop links
        nums += [(line[:60], n) for n in NUMBER.findall(cell)]
    return nums


def main(argv):
    docs = argv[1]
    write = "--write" in argv[2:]
    path = os.path.join(docs, "performance.md")
    with open(path) as fh:
        text = fh.read()
    errors = []
    generated = []

    def replace(m):
        name = m.group(2)
        if name not in GENERATORS:
            errors.append(f"performance.md: no generator for table '{name}'")
            return m.group(0)
        want = GENERATORS[name](docs) + "\n"
        generated.append(want)
        if m.group(3) != want:
            errors.append(f"performance.md: table '{name}' differs from its CSV; expected:\n{want}")
        return m.group(1) + want + m.group(4)

    new = BLOCK.sub(replace, text)
    if not generated:
        errors.append("performance.md: no generated table")
    if write:
        with open(path, "w") as fh:
            fh.write(new)
        errors = [e for e in errors if "differs" not in e]
    known = set(NUMBER.findall("\n".join(generated)))
    guide = os.path.join(docs, "guide.md")
    for row, n in guide_cost_numbers(guide):
        if n not in known:
            errors.append(f"guide.md: cost {n} (row '{row}') is in no generated table of performance.md")
    for e in errors:
        print(e)
    print(f"{len(generated)} generated tables, {len(errors)} problems")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
