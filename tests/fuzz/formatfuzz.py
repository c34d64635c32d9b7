#!/usr/bin/env python3
"""Mutation fuzzer of the input formats added after yamlfuzz.py: gmsh .msh files
with regions (fe-prep body.mesh.file), matrix files (fe-prep body.matrices:
CalculiX .sti/.mas/.dof/.inp, Matrix Market, Abaqus .mtx), the `units:` key of
every YAML input, and flexcomp-study's --sample expressions.

  formatfuzz.py --build BUILD --target msh|matrix|units|study --n N --seed S --work DIR --log LOG.jsonl

Seeds: seeds-formats/ (make_msh.py, make_matrices.py wrote them) and seeds/ for
the units of sections and scenes. Each case mutates one file of a seed (a number
token replaced by an extreme or malformed value, a line deleted, duplicated or
swapped, the file truncated, a header or type code changed, an index moved out
of range) or the YAML's units:, or writes one --sample option, runs the tool with
a timeout and a memory cap and classifies the outcome (common.py). A mutation
known to make the input wrong (a NaN, a count that no longer matches, an
unknown unit system, a node that does not exist) is `nonsense`: exit 0 on it
is `silent_accept`. For the study, a Python traceback is a crash and a plan
(study.json) left after an error is output_on_error.
"""
import argparse
import json
import os
import random
import re
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SEEDS = os.path.join(HERE, "seeds-formats")
NUM_RE = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w.])")
BAD_NUMS = ["nan", "inf", "-inf", "1e999", "abc", "", "0x1F", "1,5", "--1", "1e-400", "NaN"]
ODD_NUMS = ["0", "-1", "1e300", "-1e300", "1e-300", "2147483648", "9223372036854775808", "99999999",
            "3.5", "-0", "1e6", "7"]


def text_mutation(text, rng, ints_only=False):
    """One mutation of a text file: (new text, description, nonsense?)."""
    lines = text.split("\n")
    kind = rng.choice(["num_bad", "num_odd", "num_odd", "del_line", "dup_line", "swap_lines", "truncate",
                       "garbage_line", "empty", "blank_lines", "crlf", "tabs"])
    if kind in ("num_bad", "num_odd"):
        toks = list(NUM_RE.finditer(text))
        if not toks:
            return "garbage", "no number: garbage", True
        m = rng.choice(toks)
        v = rng.choice(BAD_NUMS if kind == "num_bad" else ODD_NUMS)
        line = text.count("\n", 0, m.start()) + 1
        return text[:m.start()] + v + text[m.end():], "line %d: number %r -> %r" % (line, m.group(), v), kind == "num_bad"
    if kind == "del_line":
        cand = [i for i, l in enumerate(lines) if l.strip()]
        i = rng.choice(cand)
        return "\n".join(lines[:i] + lines[i + 1:]), "line %d deleted: %r" % (i + 1, lines[i][:60]), None
    if kind == "dup_line":
        i = rng.randrange(len(lines))
        return "\n".join(lines[:i + 1] + [lines[i]] + lines[i + 1:]), "line %d duplicated: %r" % (i + 1, lines[i][:60]), None
    if kind == "swap_lines":
        i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
        return "\n".join(lines), "lines %d and %d swapped" % (i + 1, j + 1), None
    if kind == "truncate":
        k = rng.randrange(1, max(2, len(text) - 1))
        return text[:k], "truncated at byte %d of %d" % (k, len(text)), True
    if kind == "garbage_line":
        i = rng.randrange(len(lines))
        g = rng.choice(["\x00\x01\x02", "xyz", "1 2", "*", "$EndNodes", "% comment", "#", "1 2 3 4 5 6 7 8 9 10 11"])
        return "\n".join(lines[:i] + [g] + lines[i:]), "line %r inserted before line %d" % (g, i + 1), None
    if kind == "empty":
        return "", "empty file", True
    if kind == "blank_lines":
        i = rng.randrange(len(lines))
        return "\n".join(lines[:i] + ["", "   "] + lines[i:]), "blank lines before line %d" % (i + 1), False
    if kind == "crlf":
        return text.replace("\n", "\r\n"), "CRLF line ends", False
    return text.replace(" ", "\t"), "tabs for spaces", False


# ---- .msh
MSH_SPECIFIC = [
    ("type_quad4", r"^(\d+) 2 2 3 1 ", r"\1 3 2 3 1 ", False),
    ("type_tri6", r"^(\d+ )2( 2 3 1 )", r"\g<1>9\2", True),
    ("type_unknown", r"^(\d+ )2( 2 3 1 )", r"\g<1>99\2", True),
    ("version_3", r"^(2\.2|4\.1) 0 8", "3.0 0 8", True),
    ("version_5", r"^(2\.2|4\.1) 0 8", "5.0 0 8", True),
    ("binary_flag", r"^(2\.2|4\.1) 0 8", r"\1 1 8", True),
    ("phys_rename", r'"skin"', '"skim"', True),
    ("phys_empty", r'"stringer"', '""', True),
    ("phys_dup", r'"root"', '"skin"', True),
    ("no_physnames", r"\$PhysicalNames\n(.*\n)*?\$EndPhysicalNames\n", "", True),
    ("node_count_up", r"(\$Nodes\n)(\d+)\n", lambda m: m.group(1) + str(int(m.group(2)) + 5) + "\n", True),
    ("elem_bad_node", r"(\n\d+ 2 2 3 1 \d+ \d+ )(\d+)\n", r"\g<1>9999\n", True),
    ("elem_self", r"(\n\d+ 2 2 3 1 )(\d+) (\d+) (\d+)\n", r"\g<1>\2 \2 \4\n", True),
    ("no_end", r"\$EndElements\n?$", "", True),
]


def mutate_msh(work, rng):
    src = rng.choice(["plate22.msh", "plate41.msh"])
    text = open(os.path.join(SEEDS, src)).read()
    if rng.random() < 0.4:
        name, pat, rep, nonsense = rng.choice(MSH_SPECIFIC)
        new, n = re.subn(pat, rep, text, count=1, flags=re.M)
        desc = "%s: %s" % (src, name)
        if n == 0:
            new, desc2, nonsense = text_mutation(text, rng)
            desc = "%s: %s" % (src, desc2)
    else:
        new, d, nonsense = text_mutation(text, rng)
        desc = "%s: %s" % (src, d)
    open(os.path.join(work, "mesh.msh"), "w").write(new)
    y = open(os.path.join(SEEDS, "body_plate.yaml")).read().replace("plate41.msh", "mesh.msh")
    open(os.path.join(work, "body.yaml"), "w").write(y)
    return ["fe-prep", "body.yaml", "-o", "out.h5", "-q"], "out.h5", desc, nonsense, "mesh.msh"


# ---- matrices
MATRIX_FILES = {"calculix": ("body_ccx.yaml", ["tube.sti", "tube.mas", "tube.dof", "tube.inp"]),
                "matrix_market": ("body_mm.yaml", ["tube_k.mtx", "tube_m.mtx", "tube.dofs", "tube_nodes.txt"]),
                "abaqus": ("body_abq.yaml", ["tube_k_abq.mtx", "tube_m_abq.mtx", "tube.inp"])}
MM_HEADERS = ["%%MatrixMarket matrix coordinate real general", "%%MatrixMarket matrix coordinate complex symmetric",
              "%%MatrixMarket matrix array real symmetric", "%%MatrixMarket matrix coordinate pattern symmetric",
              "%%MatrixMarket matrix coordinate real skew-symmetric", "%%MatrixMarket vector coordinate real general",
              "%%MatrixMarket matrix coordinate integer symmetric", "%MatrixMarket", ""]


def mutate_matrix(work, rng):
    fmt = rng.choice(sorted(MATRIX_FILES))
    yaml_name, files = MATRIX_FILES[fmt]
    for f in files:
        shutil.copy(os.path.join(SEEDS, f), work)
    target = rng.choice(files)
    text = open(os.path.join(SEEDS, target)).read()
    r = rng.random()
    nonsense = None
    if target.endswith(".mtx") and not target.endswith("_abq.mtx") and r < 0.25:
        lines = text.split("\n")
        h = rng.choice(MM_HEADERS)
        lines[0] = h
        new, desc = "\n".join(lines), "header -> %r" % h
        nonsense = "general" not in h and "integer" not in h
    elif r < 0.45 and not target.endswith((".inp", ".txt", ".dof", ".dofs")):
        # An entry moved: out of range, into the other triangle, or made asymmetric by a duplicate.
        lines = [l for l in text.split("\n")]
        body = [i for i, l in enumerate(lines) if l and not l.startswith("%") and len(NUM_RE.findall(l)) >= 3]
        i = rng.choice(body[1:] if target.endswith("k.mtx") or target.endswith("m.mtx") else body)
        nums = NUM_RE.findall(lines[i])
        sep = "," if "," in lines[i] else " "
        choice = rng.choice(["out_of_range", "transpose_dup", "asym_dup", "zero_index", "negative_value_diag"])
        if choice == "out_of_range":
            nums[0] = "37" if not target.endswith("_abq.mtx") else "999"
            nonsense = True
        elif choice == "transpose_dup":
            if target.endswith("_abq.mtx"):
                nums = [nums[2], nums[3], nums[0], nums[1], nums[4]]
            else:
                nums = [nums[1], nums[0], nums[2]]
            lines.insert(i + 1, sep.join(nums))
            new = "\n".join(lines)
            desc = "%s line %d: entry repeated in the other triangle" % (target, i + 1)
            open(os.path.join(work, target), "w").write(new)
            return finish_matrix(work, yaml_name, fmt, desc, None, target)
        elif choice == "asym_dup":
            nums[-1] = repr(float(nums[-1]) * 1.5 + 1)
            lines.insert(i + 1, lines[i])
            nonsense = None
        elif choice == "zero_index":
            nums[0] = "0"
            nonsense = None
        else:
            nums[-1] = "-1e30"
            nonsense = None
        lines[i] = sep.join(nums) if choice != "asym_dup" else sep.join(nums)
        new, desc = "\n".join(lines), "line %d: %s" % (i + 1, choice)
    else:
        new, desc, nonsense = text_mutation(text, rng)
    open(os.path.join(work, target), "w").write(new)
    return finish_matrix(work, yaml_name, fmt, "%s: %s" % (target, desc), nonsense, target)


def finish_matrix(work, yaml_name, fmt, desc, nonsense, target):
    shutil.copy(os.path.join(SEEDS, yaml_name), os.path.join(work, "body.yaml"))
    return ["fe-prep", "body.yaml", "-o", "out.h5", "-q"], "out.h5", "%s %s" % (fmt, desc), nonsense, target


# ---- units:
UNITS_GOOD = ["m-kg-s", "mm-t-s", "mm-kg-ms", "mm-g-ms", "mm-kg-s", "cm-g-s", "m-t-s", "in-lbf-s", "in-lb-s", "ft-slug-s"]
UNITS_BAD = ["", "SI", "si", "MM-T-S", "mm-t-s ", "m-kg", "in-lbf", "m/kg/s", 0, 1, -1, None, True, [1, 2],
             ["m-kg-s"], {"length": "mm"}, {"length": 0}, {"length": -1e-3, "mass": 1, "time": 1},
             {"length": "nan"}, {"length": 1e-3, "mass": 1e3, "time": 1, "bogus": 2}, {"length": 1e308, "mass": 1e308, "time": 1e-308},
             {"system": "mm-t-s"}, "x" * 3000]
UNITS_SEEDS = [("fe-prep", "body_plate.yaml", SEEDS), ("fe-prep", "body_mm.yaml", SEEDS),
               ("section-prep", "sec_box.yaml", None), ("section-prep", "sec_circle.yaml", None),
               ("mbs-run", "scene_pend.yaml", None)]


def mutate_units(work, rng):
    import yaml
    tool, seed, folder = rng.choice(UNITS_SEEDS)
    folder = folder or os.path.join(HERE, "seeds")
    for f in os.listdir(SEEDS):
        shutil.copy(os.path.join(SEEDS, f), work)
    doc = yaml.safe_load(open(os.path.join(folder, seed)))
    if rng.random() < 0.35:
        v = rng.choice(UNITS_GOOD)
        nonsense = False
    else:
        v = rng.choice(UNITS_BAD)
        nonsense = True
        if isinstance(v, dict) and set(v) <= {"length", "mass", "time"} and all(
                isinstance(x, (int, float)) and x > 0 and x < 1e300 for x in v.values()) and len(v) == 3:
            nonsense = None
    where = rng.choice(["top", "top", "nested", "twice"])
    text = yaml.safe_dump(doc, sort_keys=False)
    if where == "top":
        doc["units"] = v
        text = yaml.safe_dump(doc, sort_keys=False)
    elif where == "nested":
        key = next(iter(k for k in doc if isinstance(doc[k], dict)), None)
        if key is None:
            doc["units"] = v
        else:
            doc[key]["units"] = v
        text = yaml.safe_dump(doc, sort_keys=False)
        nonsense = None if key != "body" else nonsense  # units: inside body: is a documented place
    else:
        doc.pop("units", None)
        text = "units: m-kg-s\n" + yaml.safe_dump(doc, sort_keys=False) + "units: %s\n" % json.dumps(v)
        nonsense = True  # a key given twice
    name = "in.yaml"
    open(os.path.join(work, name), "w").write(text)
    out = "out.h5"
    return [tool, name, "-o", out, "-q"], out, "%s %s: units (%s) = %r" % (tool, seed, where, v), nonsense, name


# ---- flexcomp-study --sample
PATHS = ["forces.lin.stiffness", "forces.sp.damping", "simulation.rtol", "forces.gravity.g.2", "bodies.rod2.rod.density",
         "bodies.rod1.rigid.mass", "forces.sp.torque.value*", "joints.J2.initial_angle", "bodies.1.position.0",
         "nope", "forces.nope.stiffness", "forces.9.stiffness", "bodies.rod1.name", "simulation", "",
         "forces.gravity.g.7", "bodies..rod1", "events.0.time", "body:flex:modes", "forces.sp.torque.value.9"]
DISTS = ["normal(10, 1)", "uniform(5, 15)", "lognormal(2, 0.1)", "truncated(normal(10, 5), 1, 20)", "choice(1, 2, 3)",
         "normal(1,)", "normal(1, -1)", "uniform(2, 1)", "uniform(1, 1)", "lognormal(0, -1)", "truncated(normal(0, 1), 5, 4)",
         "truncated(normal(0, 1), 50, 60)", "choice()", "choice(a, b)", "normal(nan, 1)", "normal(inf, 1)",
         "uniform(-inf, inf)", "normal(1e308, 1e308)", "poisson(3)", "normal", "normal(1, 2, 3)",
         "__import__('os').system('id')", "1+1", "normal(1, 1))", "uniform(0, 1e-320)", "choice(" + ",".join(["1"] * 2000) + ")",
         "lognormal(800, 1)", "normal(-5, 0.1)"]


def mutate_study(work, rng):
    for f in ("scene_pend.yaml",):
        shutil.copy(os.path.join(HERE, "seeds", f), work)
    opts = []
    descs = []
    for _ in range(rng.choice([1, 1, 2])):
        p, d = rng.choice(PATHS), rng.choice(DISTS)
        op = rng.choice(["=", "=", "*="]) if not p.endswith("*") else "="
        if p.endswith("*"):
            p, op = p[:-1], "*="
        opts += ["--sample", p + op + d]
        descs.append(p + op + d[:60])
    n = rng.choice(["3", "3", "3", "0", "-2", "1", "100000000"])
    design = rng.choice(["random", "lhs", "sobol"])
    seed = rng.choice(["1", "7", "-1", "99999999999999999999"])
    cmd = ["flexcomp-study", "scene_pend.yaml", "--out", "study"] + opts + ["--samples", n, "--design", design,
                                                                          "--seed", seed, "--emit-makefile", "mk"]
    return cmd, "study/study.json", "%s samples=%s design=%s seed=%s" % (" ".join(descs), n, design, seed), None, "scene_pend.yaml"


TARGETS = {"msh": mutate_msh, "matrix": mutate_matrix, "units": mutate_units, "study": mutate_study}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", required=True)
    ap.add_argument("--src", default=os.path.normpath(os.path.join(HERE, "..", "..")))
    ap.add_argument("--target", required=True, choices=sorted(TARGETS))
    ap.add_argument("--n", type=int, default=50)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--work", required=True)
    ap.add_argument("--log", required=True)
    ap.add_argument("--timeout", type=float, default=30)
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    exe = {"fe-prep": os.path.join(build, "fe-prep", "fe-prep"), "section-prep": os.path.join(build, "section-prep", "section-prep"),
           "mbs-run": os.path.join(build, "mbs-run", "mbs-run"),
           "flexcomp-study": os.path.join(a.src, "tools", "flexcomp-study")}
    rng = random.Random(a.seed)
    keep = os.path.join(a.work, "keep")
    os.makedirs(keep, exist_ok=True)
    counts = {}
    with open(a.log, "w") as log:
        for i in range(a.n):
            case = os.path.join(a.work, "case")
            shutil.rmtree(case, ignore_errors=True)
            os.makedirs(case)
            cmd, out, desc, nonsense, input_name = TARGETS[a.target](case, rng)
            tool = cmd[0]
            if tool == "flexcomp-study":
                cmd = ["/usr/bin/python3", exe[tool]] + cmd[1:] + ["--tools", build]
            else:
                cmd = [exe[tool]] + cmd[1:]
            res = common.run(cmd, case, a.timeout)
            out_path = os.path.join(case, out)
            if tool == "flexcomp-study":
                rec = classify_study(res, case, out_path)
            else:
                rec = common.classify(res, out_path, bool(nonsense), tool, input_name)
                if nonsense is None and rec["outcome"] == "accepted":
                    rec["outcome"] = "accepted"  # not known to be wrong: reviewed by hand in the table
            rec.update({"case": i, "seed": a.seed, "target": a.target, "tool": tool, "desc": desc, "rc": res["rc"],
                        "elapsed": res["elapsed"]})
            log.write(json.dumps(rec) + "\n")
            log.flush()
            counts[rec["outcome"]] = counts.get(rec["outcome"], 0) + 1
            if rec["outcome"] in ("crash", "hang", "nan_output", "bad_output", "output_on_error", "silent_accept",
                                  "error_unlocated") or rec.get("tmp_left"):
                dst = os.path.join(keep, "%s-%d-%d" % (a.target, a.seed, i))
                shutil.rmtree(dst, ignore_errors=True)
                shutil.copytree(case, dst, ignore=shutil.ignore_patterns("*.h5", "mk", "study"))
                open(os.path.join(dst, "cmd.txt"), "w").write(" ".join(cmd) + "\n" + desc + "\n" + res["stderr"][-3000:])
    print("%s seed %d: %s" % (a.target, a.seed, json.dumps(counts, sort_keys=True)))


def classify_study(res, case, out_path):
    err = res["stderr"] + res["stdout"]
    rec = {}
    if res["hang"]:
        rec["outcome"] = "hang"
    elif res["rc"] < 0 or "Traceback (most recent call last)" in err:
        rec["outcome"] = "crash"
    elif res["rc"] == 0:
        rec["outcome"] = "accepted" if os.path.exists(out_path) else "bad_output"
        if rec["outcome"] == "accepted":
            plan = json.load(open(out_path))
            vals = [v for row in plan.get("values", []) for v in row]
            if any(isinstance(v, float) and (v != v or v in (float("inf"), float("-inf"))) for v in vals):
                rec["outcome"] = "nan_output"
    else:
        if os.path.exists(out_path) or os.path.exists(os.path.join(case, "mk", "Makefile")):
            rec["outcome"] = "output_on_error"
        elif re.search(r"--sample|--samples|--seed|scene_pend\.yaml", err):
            rec["outcome"] = "error_located"
        else:
            rec["outcome"] = "error_unlocated"
    msg = [l for l in err.splitlines() if "error" in l.lower()]
    rec["msg"] = (msg[0] if msg else (err.strip().splitlines() or [""])[-1])[:300]
    return rec


if __name__ == "__main__":
    main()
