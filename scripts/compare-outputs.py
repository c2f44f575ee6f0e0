#!/usr/bin/env python3
"""Compares two folders written by scripts/capture-outputs.sh.

Every file must match: JSON documents key by key (numbers to REL relative,
1e-12 by default; provenance keys `tool_version` and `model_sha256`
skipped), other text token by token (numbers to REL, other tokens exactly),
exit codes exactly. Keys present on one side only are listed per
document kind (the JSON key changes); a key that is new and null on every
occurrence, or listed with --allow-new, is reported but not counted as a
difference.

    scripts/compare-outputs.py BEFORE AFTER [--rel 1e-12] [--allow-new KEY ...]
        [--allow-changed KEY ...]

For the typed results (issue 25):
    --allow-new complex_modes poisson_assumed damping_ratio --allow-changed shear_estimate
"""
import argparse
import json
import math
import os
import re
import sys

SKIP = {"tool_version", "model_sha256"}
NUM = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def close(a, b, rel):
    if a == b:
        return True
    if isinstance(a, bool) or isinstance(b, bool):
        return False
    if not all(isinstance(x, (int, float)) for x in (a, b)):
        return False
    if math.isnan(a) and math.isnan(b):
        return True
    return abs(a - b) <= rel * max(abs(a), abs(b))


ALLOW_CHANGED = set()


def walk(a, b, path, rel, diffs, added, removed, worst):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in a.keys() | b.keys():
            if k in SKIP:
                continue
            key = re.sub(r"\[\d+\]", "[]", f"{path}.{k}")
            if k not in b:
                removed.setdefault(key, 0)
                removed[key] += 1
            elif k not in a:
                added.setdefault(key, set()).add(json.dumps(b[k])[:40])
            else:
                walk(a[k], b[k], f"{path}.{k}", rel, diffs, added, removed, worst)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            diffs.append(f"{path}: length {len(a)} vs {len(b)}")
            return
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, f"{path}[{i}]", rel, diffs, added, removed, worst)
    else:
        if not close(a, b, rel):
            if path.rsplit(".", 1)[-1].split("[")[0] in ALLOW_CHANGED:
                return
            diffs.append(f"{path}: {json.dumps(a)[:60]} vs {json.dumps(b)[:60]}")
        elif a != b and isinstance(a, float):
            worst[0] = max(worst[0], abs(a - b) / max(abs(a), abs(b)))


def tokens(text):
    return re.split(r"[\s,;]+", text.strip())


def compare_text(a, b, rel, worst):
    ta, tb = tokens(a), tokens(b)
    if len(ta) != len(tb):
        return [f"{len(ta)} vs {len(tb)} tokens"]
    out = []
    for i, (x, y) in enumerate(zip(ta, tb)):
        if x == y:
            continue
        if NUM.match(x) and NUM.match(y) and close(float(x), float(y), rel):
            fx, fy = float(x), float(y)
            if fx != fy:
                worst[0] = max(worst[0], abs(fx - fy) / max(abs(fx), abs(fy)))
            continue
        out.append(f"token {i}: {x[:40]} vs {y[:40]}")
        if len(out) > 5:
            break
    return out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("before")
    p.add_argument("after")
    p.add_argument("--rel", type=float, default=1e-12)
    p.add_argument("--allow-new", nargs="*", default=[],
                   help="leaf keys that may be new with a non-null value")
    p.add_argument("--allow-changed", nargs="*", default=[],
                   help="leaf keys whose values may differ (a listed change)")
    args = p.parse_args()
    ALLOW_CHANGED.update(args.allow_changed)
    failures = 0
    added_all, removed_all = {}, {}
    worst = [0.0]
    files = 0
    for root, _, names in os.walk(args.before):
        for name in sorted(names):
            pa = os.path.join(root, name)
            rel_path = os.path.relpath(pa, args.before)
            pb = os.path.join(args.after, rel_path)
            if name.endswith(".err"):
                continue  # warnings and errors: the .rc and the JSON's warnings cover them
            files += 1
            if not os.path.exists(pb):
                print(f"MISSING {rel_path}")
                failures += 1
                continue
            ta = open(pa, encoding="utf-8", errors="replace").read()
            tb = open(pb, encoding="utf-8", errors="replace").read()
            diffs = []
            try:
                ja, jb = json.loads(ta), json.loads(tb)
            except ValueError:
                ja = jb = None
            if ja is not None and jb is not None:
                added, removed = {}, {}
                walk(ja, jb, "", args.rel, diffs, added, removed, worst)
                for k, v in added.items():
                    added_all.setdefault(k, set()).update(v)
                for k, v in removed.items():
                    removed_all[k] = removed_all.get(k, 0) + v
                    diffs.append(f"key {k} removed")
            else:
                diffs = compare_text(ta, tb, args.rel, worst)
            if diffs:
                failures += 1
                print(f"DIFF {rel_path}:")
                for d in diffs[:8]:
                    print(f"    {d}")
    for k in sorted(added_all):
        vals = added_all[k]
        tag = "new key (null everywhere)" if vals == {"null"} else "new key"
        print(f"{tag}: {k} = {', '.join(sorted(vals))[:80]}")
        if vals != {"null"} and k.rsplit(".", 1)[-1] not in args.allow_new:
            failures += 1
    print(f"{files} files compared, {failures} with differences; "
          f"largest relative difference of equal-within-tolerance numbers: {worst[0]:.1e}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
