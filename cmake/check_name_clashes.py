#!/usr/bin/python3
"""Counts name clashes in tirpol (one name for one thing across modules) at a revision (default: the working tree of the current folder).

1. Type names: a class/struct/enum defined at namespace scope (column 0) in two or more modules, or
   a using-alias of one name with different targets in two modules (same target = same meaning).
2. Fields named for two things: a public header of a module that has the roughness parameter
   `sigma` (MicrofacetParameter::sigma, "sigma" parameter names) and also a field `sigma` that is an
   uncertainty; and emissivity records in another shape than the CSV's eps_s0/eps_s0_std
   (e_s0/e_s0_sigma members, l_dw without units).
Usage: check_name_clashes.py [--source-dir DIR] [REV] — prints each clash and the total; exits 1
when there is one (CTest style.name_clashes runs it on the source tree; docs/architecture.md).
"""
import collections, os, re, subprocess, sys

args = sys.argv[1:]
if args[:1] == ["--source-dir"]:
    os.chdir(args[1])
    args = args[2:]
rev = args[0] if args else None
modules = "core materials simulation thermal acquisition calibration fitting report live twin sweep".split()

def files(paths):
    """The C++ files under `paths`: at REV from git, else as they are on disk (no git needed)."""
    if rev:
        cmd = ["git", "ls-tree", "-r", "--name-only", rev, "--"] + paths
        found = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout.split()
    else:
        found = [os.path.join(d, f) for p in paths for d, _, fs in os.walk(p) for f in fs]
    return sorted(f for f in found if f.endswith((".h", ".cpp")))

def text(path):
    if rev:
        return subprocess.run(["git", "show", f"{rev}:{path}"], capture_output=True, text=True).stdout
    return open(path, encoding="utf-8", errors="replace").read()

type_re = re.compile(r"^(?:class|struct|enum class|enum) ([A-Z]\w*)\s*(?:final\s*)?(?:\{|:[^:])", re.M)
alias_re = re.compile(r"^using ([A-Z]\w*) = ([^;]*);", re.M)
meanings = collections.defaultdict(lambda: collections.defaultdict(set))
for m in modules:
    for f in files([f"{m}/include", f"{m}/src"]):
        t = text(f)
        for name in type_re.findall(t):
            meanings[name][f"type in {m}"].add(m)
        for name, target in alias_re.findall(t):
            target = re.sub(r"\b(tirpol|fitting|std|chrono)::", "", target).strip()
            meanings[name][target].add(m)
clashes = []
for name, by in sorted(meanings.items()):
    mods = set().union(*by.values())
    if len(mods) > 1 and len(by) > 1:
        clashes.append(f"type {name}: " + "; ".join(f"{k} ({', '.join(sorted(v))})" for k, v in sorted(by.items())))
for m in modules:
    for f in files([f"{m}/include"]):
        t = text(f)
        roughness = re.search(r'MicrofacetParameter::sigma|"sigma"|\bsigma,\s*$|n and σ', t, re.M)
        uncertainty = re.search(r"\b(?:double|std::vector<double>) (?:[\w =.0,]*, )?sigma\b[^;]*;", t)
        if roughness and uncertainty:
            clashes.append(f"sigma is roughness and an uncertainty in {f}")
        for old in re.findall(r"\bdouble\s+(?:[\w =.0,]*,\s*)?(e_s[01](?:_sigma)?|l_dw)\b", t):
            clashes.append(f"emissivity record field {old} in {f} (the CSV's: eps_s0, eps_s0_std, l_dw_w_m2_sr)")
for c in clashes:
    print(c)
print(f"{len(clashes)} name clashes")
sys.exit(1 if clashes else 0)
